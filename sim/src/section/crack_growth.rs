//! The crack growth of one knife step (seed 000 eq. 1, §III.C): the energy
//! release rate R(s) of a trial extension s, the first fracture's criterion
//! (R'_c, or seed 001's nucleation envelope), and the extension that
//! balances R(s) against the step's toughness (or, under seed 001's
//! surface-stress option, where the crack arrests: `crack_arrest`).

use crate::finite_strain::NucleationEnvelope;

use super::crack_arrest::solve_arrest;
use super::equilibrium::Eval;
use super::fracture::{Extension, solve_extension};
use super::knife_step::KnifeStep;
use super::knife_work::elastic_work;
use super::settings::FirstFracture;
use super::simulation::{Model, StepStatus, Workspace};
use super::step_toughness::StepToughness;

/// How far the crack grew in one knife step and what that extension paid.
#[derive(Debug, Clone, Copy)]
pub(super) struct CrackGrowth {
    /// Crack extension s ≥ 0, m.
    pub(super) extension: f64,
    /// Energy release rate R(s) at the extension, N/m (0 without growth);
    /// for an arrested crack, the toughness r·Γ(s)/s it pays.
    rate: f64,
    /// `Indenting` without growth, else `Cutting` (balanced), `CutThrough`
    /// or `Unbracketed` (as [`Extension`]).
    pub(super) status: StepStatus,
    /// The toughness the extension pays.
    toughness: StepToughness,
}

impl CrackGrowth {
    /// Solves the crack extension of `step` from its start equilibrium
    /// `start`; `fractured` is the section's first-fracture flag.
    ///
    /// For a trial extension s the end state has the tip at y_tip − s and
    /// the edge at y_edge − dn; the knife's elastic work over the step is
    /// W(s) = ½(F_n⁰ + F_n(s))·dn + ½(F_t⁰ + F_t(s))·|dt| and
    /// R(s) = (W(s) − ΔU(s))/s. With [`FirstFracture::SurfaceStress`] before
    /// the first fracture the crack may grow only once the edge's load at
    /// the end of the step, without growth, is on or beyond the nucleation
    /// envelope scaled by μb; then, as after it, by the balance with R_c.
    /// The extension is [`solve_extension`]'s on the [`StepToughness`]
    /// balance, at most down to one row above the board; with
    /// [`FirstFracture::SurfaceStress`] it is [`solve_arrest`]'s instead:
    /// the crack runs while its release rate, resolved over one row, is at
    /// least the toughness and stops where it falls below, the energy
    /// released beyond the toughness being the step's unstable release.
    /// Allocation-free.
    pub(super) fn solve(
        model: &Model,
        ws: &mut Workspace,
        step: &KnifeStep,
        start: &Eval,
        fractured: bool,
    ) -> Self {
        let dn = step.dn;
        let surface_stress =
            model.settings.first_fracture == FirstFracture::SurfaceStress && !fractured;
        let nucleated = surface_stress && {
            let e = step.at_extension(model, ws, 0.0);
            NucleationEnvelope::SEED_GEL.reached(
                e.f_elastic_n() + e.f_fric_n,
                e.f_t + e.f_fric_t,
                model.nucleation_scale,
            )
        };
        let toughness = StepToughness::new(
            &model.material,
            step.xi,
            fractured || surface_stress,
            model.height - step.y_tip,
        );
        let mut balance = |s: f64| -> f64 {
            let e = step.at_extension(model, ws, s);
            let release = (elastic_work(step, start, &e) - (e.energy - start.energy)) / s;
            toughness.balance(release, s)
        };
        let s_max = step.y_tip - model.h;
        let set = &model.settings;
        let arrest = model.settings.first_fracture == FirstFracture::SurfaceStress;
        let ext = if surface_stress && !nucleated {
            Extension::None
        } else if arrest && dn > 0.0 && toughness.trigger.is_finite() && s_max > 0.0 {
            let released = |s: f64| {
                let e = step.at_extension(model, ws, s);
                elastic_work(step, start, &e) - (e.energy - start.energy)
            };
            solve_arrest(
                released,
                |s| toughness.target_at(s) * s,
                set.initial_crack_extension,
                (step.y_tip - step.y_edge1).max(0.0) + model.h,
                s_max,
                model.h,
                set.bisection_tolerance,
                set.max_bracket_doublings,
                set.max_bisection_iterations,
            )
        } else if dn > 0.0 && toughness.trigger.is_finite() && s_max > 0.0 {
            solve_extension(
                &mut balance,
                set.initial_crack_extension,
                (step.y_tip - step.y_edge1).max(0.0) + model.h,
                s_max,
                toughness.trigger,
                toughness.target,
                set.bisection_tolerance,
                set.max_bracket_doublings,
                set.max_bisection_iterations,
            )
        } else {
            Extension::None
        };
        let (extension, rate, status) = match ext {
            Extension::None => (0.0, 0.0, StepStatus::Indenting),
            // An arrested crack pays the toughness; what it released beyond
            // is the step's unstable release.
            Extension::Balanced { s, .. } if arrest => {
                (s, toughness.target_at(s), StepStatus::Cutting)
            }
            Extension::Balanced { s, r } => (s, toughness.rate(s, r), StepStatus::Cutting),
            Extension::RunsThrough { s, r } => (s, toughness.rate(s, r), StepStatus::CutThrough),
            Extension::Unbracketed { s, r } => (s, toughness.rate(s, r), StepStatus::Unbracketed),
        };
        Self {
            extension,
            rate,
            status,
            toughness,
        }
    }

    /// Energy the extension spends on fracture, J/m: R(s)·s (= W − ΔU
    /// exactly) when balanced, R = target within the tolerance; the
    /// toughness's r·Γ(s) for a crack that runs through or is unbracketed,
    /// or is arrested, whose excess release is unstable.
    pub(super) fn fracture_energy(&self) -> f64 {
        let s = self.extension;
        if matches!(self.status, StepStatus::Cutting) {
            self.rate * s
        } else {
            self.toughness.target_at(s) * s
        }
    }
}
