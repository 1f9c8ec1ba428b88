//! The periodic slab of seed 001 indented and sheared by a rigid wire.
//!
//! The slab's cross section normal to the wire, L wide and B deep, is meshed
//! with Q4 elements carrying three displacement components (see `element`);
//! fields do not vary along the wire (the seed's periodicity in the thickness
//! direction). Base clamped; sides move only vertically (or are free); top
//! free except where the wire touches. The wire's plane X = 0 is a plane of
//! symmetry of the whole problem, also under slicing (u_x is odd in X, u_y and
//! u_z even), so only X ≥ 0 is meshed, with u_x = 0 on X = 0.
//!
//! The kinematic angle θ = atan(V_t/V_n) drives the wire: at depth d (below
//! the undeformed surface) its axis is at Y = B + R − d and it has travelled
//! w = d·tan θ along its axis. The model is quasi-static: each load step in d
//! minimises the total energy (`newton`).
//!
//! Forces are those the slab exerts on the wire, resistance positive: the
//! normal force F_n against the indentation and the tangential F_t against the
//! travel, per unit length × the wire length h (N).

use super::error::FiniteStrainError;
use super::mesh::SlabMesh;
use super::neo_hookean::NeoHookean;
use super::newton::{NewtonReport, minimise};
use super::settings::{Indenter, SideSupport, WireSlabSettings};
use super::surface_stress::{
    StressField, SurfaceStress, stress_field, surface_maximum, surface_profile,
};
use super::system::{NoSurface, SurfacePotential, System};
use super::wire_contact::WireContact;
use crate::invalid_setting::InvalidSetting;

/// Most halvings of a load step where Newton's method fails.
const MAX_HALVINGS: u32 = 6;

/// The state after a load step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlabState {
    /// Wire depth d below the undeformed surface, m.
    pub depth: f64,
    /// Wire travel along its axis w = d tan θ, m.
    pub travel: f64,
    /// Normal force F_n on the wire (resisting the indentation), N.
    pub force_normal: f64,
    /// Tangential force F_t on the wire (resisting its travel), N.
    pub force_tangential: f64,
    /// Largest principal Cauchy stress at the top surface, averaged over the
    /// nucleation criterion's surface cell, at the cell where it is largest,
    /// Pa.
    pub surface_stress: f64,
    /// Where that cell sits: reference distance of its centre from the
    /// wire's plane, m.
    pub surface_stress_position: f64,
    /// Reference distance from the wire's plane of the outermost node in
    /// contact, m (0 without contact).
    pub contact_extent: f64,
    /// Contact half width from the normal contact forces f_i at reference
    /// positions X_i: a = 2 √(Σ f_i X_i² / Σ f_i), exact for Hertz's
    /// elliptical pressure, m.
    pub contact_half_width: f64,
    /// Newton iterations of the last load step (all its solves).
    pub newton_iterations: usize,
}

impl SlabState {
    /// Whether the surface σ₁ maximum lies under the wire: within the
    /// central half of the contact (|X| < contact extent / 2), rather than on
    /// the wings of the contact or beyond.
    pub fn maximum_under_wire(&self) -> bool {
        self.contact_extent > 0.0 && self.surface_stress_position < 0.5 * self.contact_extent
    }
}

/// Where and at what forces the surface reached σ*.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nucleation {
    /// Wire depth at nucleation, m (linear interpolation between the two
    /// load steps around σ₁ = σ*).
    pub depth: f64,
    /// Normal force at nucleation, N.
    pub force_normal: f64,
    /// Tangential force at nucleation, N.
    pub force_tangential: f64,
    /// Reference distance from the wire's plane of the σ₁ maximum, m.
    pub position: f64,
    /// Whether the maximum lies under the wire (see
    /// [`SlabState::maximum_under_wire`]) rather than on the contact's wings.
    pub under_wire: bool,
}

/// One indentation at one kinematic angle, from first touch to nucleation.
#[derive(Debug, Clone, PartialEq)]
pub struct IndentationRun {
    /// Kinematic angle θ, rad.
    pub angle: f64,
    /// The states after each load step.
    pub states: Vec<SlabState>,
    /// Nucleation, if σ* was reached before the largest depth.
    pub nucleation: Option<Nucleation>,
    /// Surface σ₁ profile at the last state.
    pub surface_profile: Vec<SurfaceStress>,
    /// The deformed slab with σ₁ at the last state.
    pub field: StressField,
    /// Whether a stop request ended the indentation before nucleation and
    /// before the largest depth ([`WireSlab::indent_until`]).
    pub stopped: bool,
}

/// The finite-strain slab and wire (seed 001).
///
/// # Memory allocation
/// [`WireSlab::new`] allocates the mesh, the sparse pattern and the symbolic
/// factorisation; each Newton iteration allocates its numeric factor.
pub struct WireSlab {
    settings: WireSlabSettings,
    system: System,
    contact: WireContact,
    /// u_y DOFs of the top nodes under a flat punch.
    punch: Vec<usize>,
    u: Vec<f64>,
    depth: f64,
    angle: f64,
    tolerance: f64,
    /// Newton's report of the step's first solve (the one that carries the
    /// load increment).
    last: NewtonReport,
    /// Newton iterations of the last step, over all its solves.
    step_iterations: usize,
    /// The last step's displacement increment and depth increment (m), for
    /// the next step's predictor.
    increment: Option<(Vec<f64>, f64)>,
}

/// Why a slab could not be set up or run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WireSlabError {
    /// A setting is out of range.
    #[error("{0}")]
    Setting(#[from] InvalidSetting),
    /// The model failed.
    #[error("{0}")]
    Model(#[from] FiniteStrainError),
}

impl WireSlab {
    /// Validates the settings, meshes the half slab and builds the system.
    pub fn new(settings: &WireSlabSettings) -> Result<Self, WireSlabError> {
        settings.validate()?;
        let s = settings;
        let r = s.wire_radius;
        let fine = r / s.elements_per_radius as f64;
        let mesh = SlabMesh::half_slab(
            0.5 * s.slab_width,
            s.slab_depth,
            fine,
            s.fine_zone_radii * r,
            s.grading_ratio,
            s.max_element_size,
            s.column_refinement,
        );
        let half_width = 0.5 * s.slab_width;
        let mut prescribed = vec![false; 3 * mesh.nodes.len()];
        let mut punch = Vec::new();
        for (n, p) in mesh.nodes.iter().enumerate() {
            if p[1] == 0.0 {
                prescribed[3 * n..3 * n + 3].fill(true);
            }
            if p[0] == 0.0 {
                prescribed[3 * n] = true;
            }
            if p[0] == half_width && s.sides == SideSupport::Roller {
                prescribed[3 * n] = true;
                prescribed[3 * n + 2] = true;
            }
            if s.indenter == Indenter::FlatPunch && p[1] == s.slab_depth && p[0] <= r * (1.0 + 1e-9)
            {
                prescribed[3 * n + 1] = true;
                punch.push(3 * n + 1);
            }
        }
        let surface: Vec<usize> = match s.indenter {
            Indenter::Wire => mesh.top.clone(),
            Indenter::FlatPunch => Vec::new(),
        };
        let mu = s.shear_modulus;
        let stiffness = (0..surface.len())
            .map(|k| s.contact_penalty * mu * mesh.top_tributary(k) / r)
            .collect();
        let mut contact = WireContact::new(r, s.friction_coefficient, stiffness);
        contact.centre = [0.0, s.slab_depth + r];
        let material = NeoHookean {
            shear_modulus: mu,
            bulk_modulus: s.bulk_modulus_ratio * mu,
        };
        let n_dofs = prescribed.len();
        let system = System::new(mesh, material, &prescribed, surface)?;
        Ok(Self {
            settings: *s,
            system,
            contact,
            punch,
            u: vec![0.0; n_dofs],
            depth: 0.0,
            angle: 0.0,
            tolerance: s.newton_tolerance * mu * r,
            last: NewtonReport::default(),
            step_iterations: 0,
            increment: None,
        })
    }

    /// The settings the slab was built with.
    pub fn settings(&self) -> &WireSlabSettings {
        &self.settings
    }

    /// Number of elements of the half slab.
    pub fn element_count(&self) -> usize {
        self.system.mesh.elements.len()
    }

    /// Number of unknowns (free DOFs).
    pub fn unknowns(&self) -> usize {
        self.system.free_count()
    }

    /// Back to the undeformed slab with the wire touching its surface, and
    /// the kinematic angle `angle` (rad, in [0, π/2)).
    pub fn reset(&mut self, angle: f64) {
        self.u.fill(0.0);
        self.depth = 0.0;
        self.angle = angle;
        self.contact.release();
        self.contact.centre[1] = self.settings.slab_depth + self.settings.wire_radius;
        self.increment = None;
    }

    /// Newton's report of the last load step's first solve (its residual
    /// history).
    pub fn last_newton(&self) -> &NewtonReport {
        &self.last
    }

    fn surface_positions(&self) -> (Vec<[f64; 2]>, Vec<f64>) {
        let nodes = self.system.surface_nodes();
        let pos = nodes
            .iter()
            .map(|&n| {
                let p = self.system.mesh.nodes[n];
                [p[0] + self.u[3 * n], p[1] + self.u[3 * n + 1]]
            })
            .collect();
        let uz = nodes.iter().map(|&n| self.u[3 * n + 2]).collect();
        (pos, uz)
    }

    /// One load step to depth `depth` (m): the last increment scaled as a
    /// predictor, then Newton's method, repeated while the contact sets
    /// change (at most `contact_passes` solves). On failure the state is left
    /// as it was and `false` returned.
    fn try_step(&mut self, depth: f64) -> Result<bool, FiniteStrainError> {
        let saved_u = self.u.clone();
        let saved_contact = self.contact.clone();
        let r = self.settings.wire_radius;
        let dd = depth - self.depth;
        if let Some((du, last)) = &self.increment {
            let scale = dd / last;
            for (u, d) in self.u.iter_mut().zip(du) {
                *u += scale * d;
            }
        }
        self.contact.centre[1] = self.settings.slab_depth + r - depth;
        self.contact.travel = depth * self.angle.tan();
        for &d in &self.punch {
            self.u[d] = -depth;
        }
        let (pos, _) = self.surface_positions();
        self.contact.activate(&pos);
        let passes = self.settings.contact_passes;
        let mut iterations = 0;
        for pass in 0..passes {
            let surface: &dyn SurfacePotential = match self.settings.indenter {
                Indenter::Wire => &self.contact,
                Indenter::FlatPunch => &NoSurface,
            };
            let report = minimise(
                &mut self.system,
                &mut self.u,
                surface,
                self.tolerance,
                self.settings.max_newton_iterations,
            );
            let converged = matches!(&report, Ok(r) if r.converged);
            if let Ok(report) = report {
                iterations += report.residuals.len() - 1;
                if pass == 0 {
                    self.last = report;
                }
            }
            if !converged {
                self.u = saved_u;
                self.contact = saved_contact;
                return Ok(false);
            }
            let (pos, uz) = self.surface_positions();
            if !self.contact.update(&pos, &uz) {
                break;
            }
        }
        let (_, uz) = self.surface_positions();
        self.contact.commit(&uz);
        let du = self.u.iter().zip(&saved_u).map(|(a, b)| a - b).collect();
        self.increment = Some((du, dd));
        self.depth = depth;
        self.step_iterations = iterations;
        Ok(true)
    }

    /// Presses on to depth `depth` (m) in load steps of at most
    /// `depth_step`, halving a step where Newton's method fails.
    pub fn advance_to(&mut self, depth: f64) -> Result<SlabState, FiniteStrainError> {
        let step = self.settings.depth_step;
        while self.depth < depth - 1e-12 * step {
            let mut dd = step.min(depth - self.depth);
            let mut halvings = 0;
            while !self.try_step(self.depth + dd)? {
                halvings += 1;
                if halvings > MAX_HALVINGS {
                    return Err(FiniteStrainError::NotConverged {
                        depth_um: ((self.depth + dd) * 1e6).round() as u32,
                    });
                }
                dd *= 0.5;
            }
        }
        Ok(self.state())
    }

    /// The present state.
    pub fn state(&self) -> SlabState {
        let s = &self.settings;
        let h = s.wire_length;
        let (mut f_n, mut f_t, mut extent) = (0.0, 0.0, 0.0f64);
        let (mut m0, mut m2) = (0.0, 0.0);
        match s.indenter {
            Indenter::Wire => {
                let (pos, uz) = self.surface_positions();
                for (slot, &n) in self.system.surface_nodes().iter().enumerate() {
                    let c = self.contact.normal(pos[slot]);
                    let f = self.contact.normal_force(slot, pos[slot]);
                    if f > 0.0 {
                        // Force on the wire: f along −normal (towards the
                        // wire's axis); its upward part resists.
                        f_n -= f * c.normal[1];
                        let x = self.system.mesh.nodes[n][0];
                        extent = extent.max(x);
                        m0 += f;
                        m2 += f * x * x;
                    }
                    if let Some(st) = self.contact.stretch(slot, uz[slot]) {
                        // The wire drags the node along +z with this force;
                        // the node holds the wire back by as much.
                        f_t += self.contact.friction_force(slot, st);
                    }
                }
            }
            Indenter::FlatPunch => {
                f_n = -self.system.internal_force(&self.u, &self.punch);
                extent = s.wire_radius;
            }
        }
        let sigma = surface_maximum(&self.surface_profile());
        SlabState {
            depth: self.depth,
            travel: self.depth * self.angle.tan(),
            force_normal: 2.0 * f_n * h,
            force_tangential: 2.0 * f_t * h,
            surface_stress: sigma.stress,
            surface_stress_position: sigma.position,
            contact_extent: extent,
            contact_half_width: if m0 > 0.0 {
                2.0 * (m2 / m0).sqrt()
            } else {
                0.0
            },
            newton_iterations: self.step_iterations,
        }
    }

    /// σ₁ averaged over the nucleation criterion's surface cells now (see
    /// [`SurfaceStress`]).
    pub fn surface_profile(&self) -> Vec<SurfaceStress> {
        surface_profile(&self.system, &self.u, self.settings.nucleation_cell())
    }

    /// The deformed half slab with σ₁ per element now.
    pub fn stress_field(&self) -> StressField {
        stress_field(&self.system, &self.u)
    }

    /// Indents at kinematic angle `angle` (rad) from first touch until the
    /// surface σ₁ reaches σ* or the depth reaches `max_depth`.
    pub fn indent(&mut self, angle: f64) -> Result<IndentationRun, FiniteStrainError> {
        self.indent_until(angle, &|| false)
    }

    /// [`indent`](Self::indent), asking `stop` after each load step: `true`
    /// ends the indentation there ([`IndentationRun::stopped`]), with at
    /// least one state.
    pub fn indent_until(
        &mut self,
        angle: f64,
        stop: &dyn Fn() -> bool,
    ) -> Result<IndentationRun, FiniteStrainError> {
        self.reset(angle);
        let s = self.settings;
        let target = s.nucleation_stress();
        let mut states: Vec<SlabState> = Vec::new();
        let mut nucleation = None;
        let mut previous: Option<SlabState> = None;
        let mut stopped = false;
        while self.depth < s.max_depth * (1.0 - 1e-12) {
            let next = (self.depth + s.depth_step).min(s.max_depth);
            let st = self.advance_to(next)?;
            states.push(st);
            if st.surface_stress >= target {
                let prev = previous.unwrap_or(SlabState {
                    depth: 0.0,
                    force_normal: 0.0,
                    force_tangential: 0.0,
                    surface_stress: 0.0,
                    ..st
                });
                let t = ((target - prev.surface_stress)
                    / (st.surface_stress - prev.surface_stress))
                    .clamp(0.0, 1.0);
                let lerp = |a: f64, b: f64| a + t * (b - a);
                nucleation = Some(Nucleation {
                    depth: lerp(prev.depth, st.depth),
                    force_normal: lerp(prev.force_normal, st.force_normal),
                    force_tangential: lerp(prev.force_tangential, st.force_tangential),
                    position: st.surface_stress_position,
                    under_wire: st.maximum_under_wire(),
                });
                break;
            }
            previous = Some(st);
            if stop() {
                stopped = self.depth < s.max_depth * (1.0 - 1e-12);
                break;
            }
        }
        Ok(IndentationRun {
            angle,
            states,
            nucleation,
            surface_profile: self.surface_profile(),
            field: self.stress_field(),
            stopped,
        })
    }
}
