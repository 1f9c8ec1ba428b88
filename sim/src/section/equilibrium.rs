//! The section's equilibrium at a fixed configuration (seed 000 §III.C,
//! DESIGN §3.2): crack tip at y_tip, knife edge at y_edge, the edge's drag τ
//! along the cut. The contacts of the edge flat and the wedge faces are
//! solved by a primal-dual active set on the condensed line; the forces on
//! the knife, the strain energy and the friction for the step's knife
//! increments are read off the solution. A knife step evaluates this at its
//! start, at trial crack extensions and at its end.

use super::condensed::{MAX_STRIP, StripConstraint};
use super::contact::FaceSlip;
use super::simulation::{Model, Workspace};

/// Result of evaluating a configuration (full section, both halves).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Eval {
    /// Vertical force of the edge flat on the material, N/m.
    pub(super) f_edge: f64,
    /// Vertical force of the wedge faces' normal pressure, N/m (0 while the
    /// edge presses below the tip).
    pub(super) f_wedge: f64,
    /// Tangential force of the antiplane drag, N/m.
    pub(super) f_t: f64,
    /// Vertical friction force on the faces for the step's increments, N/m.
    pub(super) f_fric_n: f64,
    /// Tangential friction force on the faces for the step's increments, N/m.
    pub(super) f_fric_t: f64,
    /// Strain energy, in-plane plus antiplane, J/m.
    pub(super) energy: f64,
    /// Of which antiplane, J/m.
    pub(super) energy_anti: f64,
    /// Face nodes whose contact reaction is tensile.
    pub(super) tensile: usize,
    /// Fingerprint of the contact active sets (edge columns, released faces).
    pub(super) contacts: u64,
}

impl Eval {
    /// Elastic vertical force F_n without friction (edge plus wedge), N/m.
    pub(super) fn f_elastic_n(&self) -> f64 {
        self.f_edge + self.f_wedge
    }
}

/// Most active-set iterations of the face contact per evaluation.
const MAX_ACTIVE_SET_ITERATIONS: usize = 64;

/// The strip constraint of the edge at (y_tip, y_edge): the material at the
/// tip moved to the edge, u_y = y_edge − y_tip. It acts only where the edge
/// presses on the material (decided by `evaluate`).
pub(super) fn strip_of(model: &Model, y_tip: f64, y_edge: f64) -> StripConstraint {
    let d = y_tip - y_edge;
    let (row, phi) = tip_row(model, y_tip);
    StripConstraint {
        row,
        phi,
        value: -d,
        active: [true; MAX_STRIP],
    }
}

/// Row j and weight φ of the tip: y_tip = (j + φ)·h, 1 ≤ j ≤ R.
pub(super) fn tip_row(model: &Model, y_tip: f64) -> (usize, f64) {
    let t = y_tip / model.h;
    let mut j = t.floor();
    let mut phi = t - j;
    if phi > 1.0 - 1e-9 {
        j += 1.0;
        phi = 0.0;
    } else if phi < 1e-9 {
        phi = 0.0;
    }
    let j = (j as usize).clamp(1, model.n);
    if j == model.n {
        phi = 0.0;
    }
    (j, phi)
}

/// Solves the configuration (tip, edge, drag) and returns forces and energies
/// of the full section, with friction for knife increments (dn, dt ≥ 0).
/// Leaves the gaps in `ws.g`, the reactions in `ws.p`. Allocation-free.
pub(super) fn evaluate(
    model: &Model,
    ws: &mut Workspace,
    y_tip: f64,
    y_edge: f64,
    drag: f64,
    dn: f64,
    dt: f64,
) -> Eval {
    let key = [y_tip, y_edge, drag, dn, dt].map(f64::to_bits);
    if let Some((last, e)) = ws.last
        && last == key
    {
        return e;
    }
    ws.last = None;
    let h = model.h;
    let (j, _) = tip_row(model, y_tip);
    // Gaps: rows above the tip open to the blade, measured from the tip while
    // the edge presses below it, from the edge when the crack runs ahead.
    let y_ref = y_tip.max(y_edge);
    let first = j; // index of row j+1
    ws.g[..first].fill(0.0);
    for (i, g) in ws.g.iter_mut().enumerate().skip(first) {
        let y = (i + 1) as f64 * h;
        *g = if y <= y_tip {
            0.0
        } else {
            model.profile.width(y - y_ref)
        };
    }
    // Unilateral contacts, solved together by a primal-dual active set on the
    // condensed line:
    // - the wedge faces: a face row is released when its reaction would pull
    //   the face onto the blade (p < 0), and put back in contact when,
    //   released, it would penetrate the blade (g < ŵ);
    // - the edge flat, column by column: a strip column presses while its
    //   force on the material is compressive (λ_a ≤ 0) and is released when
    //   it would pull; a released column comes back when the material there
    //   would rise above the edge (u_a > value).
    // This is a convex obstacle problem (a strictly convex energy under
    // per-DOF inequality constraints), so the active sets are unique and the
    // stored energy is C¹ in the knife position across their changes: the
    // energy balance stays closed. (A strip switched on and off as a whole
    // is not of this kind: its two tests disagree in a band of positions and
    // the active set cycles there.) Warm-started from the last evaluation the
    // loop typically settles in one or two passes.
    let mut strip_c = strip_of(model, y_tip, y_edge);
    let k = model.line.k;
    strip_c.active = ws.strip_active;
    let tol = 1e-9 * model.material.fracture_toughness;
    let gap_tol = 1e-9 * h;
    ws.released[..first].fill(false);
    for (i, r) in ws.released.iter_mut().enumerate().skip(first) {
        let y = (i + 1) as f64 * h;
        if y > y_tip {
            break;
        }
        *r = false;
    }
    let mut ip = Default::default();
    let mut converged = false;
    for _ in 0..MAX_ACTIVE_SET_ITERATIONS {
        ws.solves += 1;
        let any = strip_c.active[..k].iter().any(|&a| a);
        ip = model.line.solve_released(
            &mut ws.g,
            first,
            &ws.released,
            None,
            any.then_some(&strip_c),
            &mut ws.p,
            &mut ws.lambda,
            &mut ws.mixed,
        );
        let mut changed = false;
        for i in first..model.n {
            let y = (i + 1) as f64 * h;
            if y <= y_tip {
                continue;
            }
            let w = model.profile.width(y - y_ref);
            if !ws.released[i] && ws.p[i] < -tol {
                ws.released[i] = true;
                changed = true;
            } else if ws.released[i] && ws.g[i] < w - gap_tol {
                ws.released[i] = false;
                ws.g[i] = w;
                changed = true;
            }
        }
        for a in 0..k {
            if strip_c.active[a] && ws.lambda[a] > tol {
                strip_c.active[a] = false;
                changed = true;
            } else if !strip_c.active[a]
                && model.line.strip_uy(a, &ws.g, first, &strip_c, &ws.lambda)
                    > strip_c.value + gap_tol
            {
                strip_c.active[a] = true;
                changed = true;
            }
        }
        if !changed {
            converged = true;
            break;
        }
    }
    ws.strip_active = strip_c.active;
    let mut contacts = strip_c.active[..k]
        .iter()
        .fold(0u64, |m, &a| (m << 1) | u64::from(a));
    // (No face row below `first` is released.)
    for (i, &r) in ws.released.iter().enumerate().skip(first) {
        if r {
            contacts = contacts.wrapping_mul(1_000_003) ^ (i as u64 + 1);
        }
    }
    let strip = strip_c.active[..k].iter().any(|&a| a).then_some(strip_c);
    // Antiplane drag: the whole flat holds the material along the edge while
    // any of it presses (seed 000 §III.C: the nodes in contact are fixed on
    // the edge). Switching columns one by one would drop their stored
    // antiplane energy without work, while the whole flat lets go only when
    // the indentation, and with it the drag τ = ξ·d, goes to 0.
    let (u_anti, f_anti) = match &strip {
        Some(s) if drag != 0.0 => model.line.solve_antiplane(&StripConstraint {
            value: drag,
            active: [true; MAX_STRIP],
            ..*s
        }),
        _ => (0.0, 0.0),
    };
    let mut e = Eval {
        f_edge: -2.0 * ip.strip_force,
        f_t: 2.0 * f_anti,
        energy: 2.0 * (ip.energy + u_anti),
        energy_anti: 2.0 * u_anti,
        contacts,
        ..Default::default()
    };
    face_terms(model, ws, y_tip, y_edge, dn, dt, &mut e);
    if converged {
        ws.last = Some((key, e));
    }
    e
}

/// The terms of `e` read off the face reactions left in `ws.p` by the
/// evaluation of (y_tip, y_edge): the wedge's vertical force, the tensile
/// count, and the friction for knife increments (dn, dt ≥ 0). Allocation-free.
pub(super) fn face_terms(
    model: &Model,
    ws: &Workspace,
    y_tip: f64,
    y_edge: f64,
    dn: f64,
    dt: f64,
    e: &mut Eval,
) {
    let h = model.h;
    let (first, _) = tip_row(model, y_tip);
    let y_ref = y_tip.max(y_edge);
    let edge_contact = y_tip > y_edge;
    let mu = model.material.friction_coefficient;
    e.f_wedge = 0.0;
    e.tensile = 0;
    e.f_fric_n = 0.0;
    e.f_fric_t = 0.0;
    // The face slope takes a few values along the faces (corner, bevel,
    // flank): the slip geometry and the normal's stretch factor are
    // computed once per run of equal slopes (the same expressions, so the
    // same values).
    let mut run: Option<(u64, FaceSlip, f64)> = None;
    for i in first..model.n {
        let y = (i + 1) as f64 * h;
        if y <= y_tip {
            continue;
        }
        let slope = model.profile.slope(y - y_ref);
        let (slip, stretch) = match run {
            Some((bits, slip, stretch)) if bits == slope.to_bits() => (slip, stretch),
            _ => {
                let slip = FaceSlip::new(slope, dn, dt);
                let stretch = (1.0 + slope * slope).sqrt();
                run = Some((slope.to_bits(), slip, stretch));
                (slip, stretch)
            }
        };
        let p = ws.p[i];
        // The knife's vertical force from the faces' pressure is the
        // derivative of the energy with respect to the knife position at a
        // fixed crack: nonzero only when the faces are measured from the edge.
        if !edge_contact {
            e.f_wedge += 2.0 * p * slope;
        }
        if p < -1e-9 * model.material.fracture_toughness {
            e.tensile += 1;
        }
        let normal = p.max(0.0) * stretch;
        let (fn_, ft) = slip.friction(mu, normal, dn, dt);
        e.f_fric_n += 2.0 * fn_;
        e.f_fric_t += 2.0 * ft;
    }
}
