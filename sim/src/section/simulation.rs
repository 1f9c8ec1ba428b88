//! A cross section cut by a straight knife edge: the section simulation
//! driven by knife motion (seed 000 §III.C, DESIGN §3.2–3.2a).

use crate::blade::BladeSection;
use crate::material::Material;

use super::condensed::{CondensedLine, MAX_STRIP, ReleasedWorkspace};
use super::contact::WedgeProfile;
use super::crack_growth::CrackGrowth;
use super::equilibrium::{Eval, evaluate, face_terms, strip_of};
use super::error::SectionError;
use super::geometry::SectionGeometry;
use super::knife_step::KnifeStep;
use super::knife_work::{PiecewiseWork, elastic_work, friction_work};
use super::mesh::SectionMesh;
use super::settings::SectionSettings;

/// What a knife step did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepStatus {
    /// The edge is not touching the material below the crack tip.
    NoContact,
    /// The knife pressed on without the crack growing (R(δ₀) < R_c^s).
    Indenting,
    /// The crack grew, balanced: R = R_c^s within the bisection tolerance.
    Cutting,
    /// The crack reached the board: the section is cut through.
    CutThrough,
    /// R(s) stayed above R_c^s for every trial extension allowed by
    /// `max_bracket_doublings`; the step took the largest one.
    Unbracketed,
}

/// Cumulative energies of a section, per unit length of edge, J/m (= N).
///
/// Balance (seed 000 eq. 1 with friction): `knife + inherited = fracture +
/// strain_energy + friction + unstable` after every step (`inherited` is 0
/// unless the section took over a predecessor's cut).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WorkSplit {
    /// Work done by the knife: ∫ F_n dn + F_t dt (trapezoidal per step), J/m.
    pub knife: f64,
    /// Energy spent on crack growth, Σ R·ds with R = R_c^s (to the bisection
    /// tolerance), J/m.
    pub fracture: f64,
    /// Strain energy stored now, in-plane plus antiplane, J/m.
    pub strain_energy: f64,
    /// Of which antiplane (tangential) strain energy, J/m.
    pub strain_energy_antiplane: f64,
    /// Energy dissipated by friction on the wedge faces, J/m.
    pub friction: f64,
    /// Energy released in excess of R_c^s by a crack running unstably through
    /// the section (status `CutThrough` or `Unbracketed`), J/m.
    pub unstable: f64,
    /// Strain energy the section started with when it took over a
    /// predecessor's cut ([`CrossSection::take_over`]): the predecessor's
    /// elastic state, paid for by the predecessor's knife work, J/m (0 for a
    /// section cut from its intact state).
    pub inherited: f64,
}

/// The state of a section after a knife step. Forces are those the material
/// exerts on the knife per unit length of edge (N/m), resistance positive
/// (seed 000's plot convention).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionStep {
    /// Knife displacement since the edge first touched the top surface, m.
    pub knife_displacement: f64,
    /// Height of the knife edge above the board, m.
    pub edge_height: f64,
    /// Height of the crack tip above the board, m.
    pub crack_tip_height: f64,
    /// Depth of the crack below the top surface on the cut line, m.
    pub crack_depth: f64,
    /// Indentation: how far the edge is below the crack tip's reference
    /// position, m (0 when not in contact).
    pub indentation: f64,
    /// How far the top surface next to the blade (on the cut line) is pushed
    /// down, m.
    pub surface_deflection: f64,
    /// Vertical force F_n, N/m: edge + wedge normal pressure + friction.
    pub force_vertical: f64,
    /// Horizontal force along the edge F_t, N/m: antiplane shear + friction.
    pub force_tangential: f64,
    /// Part of F_n from the wedge faces' normal pressure when the crack runs
    /// ahead of the edge, N/m. While the edge presses below the tip the faces
    /// next to it ride down with it, and the work of opening them reaches the
    /// knife through the edge force (energy balance), so this part is 0.
    pub force_vertical_wedge: f64,
    /// Part of F_n from friction, N/m.
    pub force_vertical_friction: f64,
    /// Part of F_t from friction, N/m.
    pub force_tangential_friction: f64,
    /// Crack extension in this step, m.
    pub crack_extension: f64,
    /// Whether the first fracture has happened. Without a skin layer the
    /// toughness is then R_c, not R'_c; with one
    /// ([`Material::skin_thickness`]) the crack depth decides.
    pub fractured: bool,
    /// What the step did.
    pub status: StepStatus,
    /// Cumulative energies.
    pub work: WorkSplit,
    /// Face nodes whose contact reaction is tensile, a quality indicator: the
    /// face contact is unilateral (faces that would be pulled onto the blade
    /// are released), so this is 0 unless the active-set iteration failed.
    pub tensile_contacts: usize,
}

/// Immutable model of a section: mesh data and the condensed stiffness.
#[derive(Debug, Clone)]
pub(super) struct Model {
    pub(super) line: CondensedLine,
    pub(super) profile: WedgeProfile,
    pub(super) material: Material,
    pub(super) settings: SectionSettings,
    /// Row spacing on the cut line, m.
    pub(super) h: f64,
    /// Rows R of the line.
    pub(super) n: usize,
    /// Height of the section at the cut, m.
    pub(super) height: f64,
    /// Nodes and elements (kept for callers that inspect the mesh).
    pub(super) elements: usize,
    /// μ·R with R the edge flat's width, N/m: the scale of the loads of
    /// seed 001's nucleation envelope ([`FirstFracture::SurfaceStress`](super::FirstFracture::SurfaceStress)).
    pub(super) nucleation_scale: f64,
}

/// Preallocated buffers of a section.
#[derive(Debug, Clone)]
pub(super) struct Workspace {
    pub(super) g: Vec<f64>,
    pub(super) p: Vec<f64>,
    pub(super) lambda: [f64; MAX_STRIP],
    /// Face rows released from the wedge (unilateral contact); kept between
    /// evaluations as the active set's warm start.
    pub(super) released: Vec<bool>,
    /// Strip columns in contact with the edge (warm start, as `released`).
    pub(super) strip_active: [bool; MAX_STRIP],
    pub(super) mixed: ReleasedWorkspace,
    /// Linear solves of the condensed line so far (a cost counter).
    pub(super) solves: u64,
    /// The last step's end configuration (y_tip, y_edge, drag) and its
    /// evaluation, whose face reactions are still in `p`: the next step
    /// starts there, so its start evaluation needs only the friction for
    /// the new increments (`face_terms`), not another active-set solve.
    pub(super) end: Option<(f64, f64, f64, Eval)>,
    /// The arguments (y_tip, y_edge, drag, dn, dt, as bits) and result of
    /// the last evaluation, if its active sets converged; its gaps,
    /// reactions and strip forces are still in `g`, `p` and `lambda`. An
    /// evaluation of the same configuration is then this result (the first
    /// active-set pass would solve the same system and change nothing).
    pub(super) last: Option<([u64; 5], Eval)>,
}

/// Mutable state between steps.
#[derive(Debug, Clone, Copy, PartialEq)]
struct State {
    y_edge: f64,
    y_tip: f64,
    drag: f64,
    fractured: bool,
    completed: bool,
    step: SectionStep,
}

/// One cross section normal to a straight knife edge, cut by the knife's
/// motion (seed 000 §III; DESIGN §3.2, §3.2a).
///
/// # Formulation
/// Half model x ≥ 0 of a [`SectionGeometry`], plane strain (E, ν) for the
/// in-plane response and antiplane shear (G) for the tangential one
/// (generalised plane strain, seed 000 assumption A1), bottom fixed on the
/// board, meshed with graded Q4 elements and condensed once onto the cut line
/// ([`condensed`](super) module docs). On the cut line below the crack tip the
/// symmetry condition u_x = 0 holds; above it the crack faces are pushed out to
/// at least the blade's half-thickness (unilateral wedge contact, `contact`
/// module), and the edge flat presses column by column where it touches
/// (unilateral too); both by a primal-dual active set on the condensed line.
///
/// The edge flat (width b = `edge_width`) is a rigid strip: the material
/// at the crack tip's reference height (interpolated between the two rows
/// around the tip, so the tip moves continuously) is moved down by the
/// indentation d = y_tip − y_edge and along the edge by the drag τ. The drag
/// follows the seed's "nodes in contact are fixed on the edge": it grows by
/// the knife's tangential increment while the edge indents, and is kept while
/// the edge follows the crack (τ = ξ·d for a constant ξ).
///
/// # Fracture (seed 000 eq. 1, §III.C)
/// A step moves the knife by (dn, dt), ξ = dt/dn. For a trial crack extension
/// s the end state has the tip at y_tip − s and the edge at y_edge − dn; the
/// knife's elastic work over the step is W(s) = ½(F_n⁰ + F_n(s))·dn +
/// ½(F_t⁰ + F_t(s))·dt and the energy release rate R(s) = (W(s) − ΔU(s))/s
/// (dW = F_n·δ + F_t·ξδ while the edge follows the tip, DESIGN §3.2a; the
/// classical −∂U/∂a at a held knife is not used). The crack grows when
/// R(δ₀) ≥ r(ξ,ν)·R'_c before the first fracture, r(ξ,ν)·R_c after it (r of
/// seed 000 eq. 6); the extension solves R(s) = r·R_c by bracketing (δ doubled)
/// and a safeguarded regula falsi on the bracket. In steady cutting of a deep section ΔU → 0, so
/// F_n + ξ·F_t → r·R_c: the knife work per unit cut area is r·R_c.
///
/// With [`FirstFracture::SurfaceStress`](super::FirstFracture::SurfaceStress) (seed 001) the first fracture is
/// not R'_c's: before it the crack grows only in a step whose end load per
/// unit length (F_n, F_t), without growth, is on or beyond the
/// finite-strain slab's nucleation envelope scaled by μb (b the edge flat's
/// width, a wire's radius R); from that step on it grows while its release
/// rate, resolved over a row, is at least r·R_c and arrests where it falls
/// below (`crack_arrest`: Griffith's balance along the crack's path, which
/// stops the crack at the wire instead of spending the stored energy of the
/// nucleation on crack). The criterion reads the present load only: the envelope was
/// measured along straight paths at fixed θ, and a path that turns is judged
/// by where its load stands, not by how it got there.
///
/// With a skin layer of thickness t ([`Material::skin_thickness`]) the
/// toughness is R'_c for crack depths below t and R_c deeper, whatever the
/// first-fracture flag says: an extension s from depth a₀ balances
/// R(s) = r·Γ(s)/s, Γ the toughness integrated over [a₀, a₀ + s], so the
/// fracture energy of a cut to depth a > t is r·(R'_c·t + R_c·(a − t)).
///
/// The step is energy-consistent: knife work = fracture + strain energy +
/// friction (+ unstable release), with fracture = Σ R(s)·s and |R − r·R_c| ≤
/// tol·r·R_c.
///
/// In a step without crack growth the knife work is integrated piecewise
/// between the positions where the force has a kink or a jump (a face node
/// passing a kink of the blade profile, a contact set changing), so the
/// balance closes to round-off there too (`knife_work`).
///
/// # Memory allocation
/// [`CrossSection::new`] allocates the mesh, the condensed matrices and a
/// workspace (including R² doubles for the released faces' dense factor);
/// [`CrossSection::advance`] allocates nothing.
#[derive(Debug, Clone)]
pub struct CrossSection {
    model: Model,
    ws: Workspace,
    state: State,
    initial: State,
}

impl CrossSection {
    /// Builds the section: validates, meshes, assembles, factorises and
    /// condenses. The knife starts with its edge on the top surface at the cut
    /// line, not yet pressing.
    pub fn new(
        geometry: &SectionGeometry,
        material: &Material,
        blade: &BladeSection,
        settings: &SectionSettings,
    ) -> Result<Self, SectionError> {
        material
            .validate_domain()
            .map_err(|e| e.prefixed("material"))?;
        blade.validate().map_err(|e| e.prefixed("blade"))?;
        settings
            .validate_for(material)
            .map_err(|e| e.prefixed("section"))?;
        let mesh = SectionMesh::new(geometry, blade.edge_width, settings)?;
        let line = CondensedLine::new(&mesh, material.youngs_modulus, material.poisson_ratio)?;
        let n = mesh.rows;
        let model = Model {
            line,
            profile: WedgeProfile::new(blade, mesh.h),
            material: *material,
            settings: *settings,
            h: mesh.h,
            n,
            height: geometry.height_at_cut(),
            elements: mesh.elements.len(),
            nucleation_scale: material.shear_modulus() * blade.edge_width,
        };
        let h = model.height;
        let step = SectionStep {
            knife_displacement: 0.0,
            edge_height: h,
            crack_tip_height: h,
            crack_depth: 0.0,
            indentation: 0.0,
            surface_deflection: 0.0,
            force_vertical: 0.0,
            force_tangential: 0.0,
            force_vertical_wedge: 0.0,
            force_vertical_friction: 0.0,
            force_tangential_friction: 0.0,
            crack_extension: 0.0,
            fractured: false,
            status: StepStatus::NoContact,
            work: WorkSplit::default(),
            tensile_contacts: 0,
        };
        let state = State {
            y_edge: h,
            y_tip: h,
            drag: 0.0,
            fractured: false,
            completed: false,
            step,
        };
        Ok(Self {
            ws: Workspace {
                g: vec![0.0; n],
                p: vec![0.0; n],
                lambda: [0.0; MAX_STRIP],
                released: vec![false; n],
                strip_active: [true; MAX_STRIP],
                mixed: ReleasedWorkspace::new(n),
                solves: 0,
                end: None,
                last: None,
            },
            model,
            state,
            initial: state,
        })
    }

    /// Back to the state right after construction (keeps the factorisation).
    pub fn reset(&mut self) {
        self.state = self.initial;
        // Active-set warm starts: reset too, so a rerun is bit-identical.
        self.ws.released.fill(false);
        self.ws.end = None;
        self.ws.last = None;
        self.ws.strip_active = [true; MAX_STRIP];
    }

    /// Restarts the section with a crack already cut `crack_depth` (m) below
    /// its top, the edge at the crack tip with no indentation, and the first
    /// fracture done if `fractured` (so the toughness is R_c, not R'_c).
    ///
    /// This is how the plant hands a cut over to the successor of a moving
    /// cross section (seed 000 §IV, Fig. 4(b)): [`Self::reset`], then the tip
    /// at `height − crack_depth`, clamped to leave at least one row of the
    /// cut line (`crack_depth` ∈ [0, height − row_spacing]). The state then
    /// reads knife_displacement = crack_depth (the edge is at the tip),
    /// crack_depth, crack_tip_height = edge_height = height − crack_depth,
    /// and the `fractured` flag.
    ///
    /// Only the crack is carried: the predecessor's elastic state (the
    /// indentation, the drag of the edge along the cut, the stored strain
    /// energy) is not, and the energies restart at zero, so the caller keeps
    /// the predecessor's totals. Allocates nothing.
    pub fn restart_with_crack(&mut self, crack_depth: f64, fractured: bool) {
        self.reset();
        let model = &self.model;
        let max_depth = (model.height - model.h).max(0.0);
        let depth = if crack_depth.is_finite() {
            crack_depth.clamp(0.0, max_depth)
        } else {
            0.0
        };
        let y = model.height - depth;
        let st = &mut self.state;
        st.y_edge = y;
        st.y_tip = y;
        st.drag = 0.0;
        st.fractured = fractured;
        st.completed = false;
        st.step.knife_displacement = depth;
        st.step.edge_height = y;
        st.step.crack_tip_height = y;
        st.step.crack_depth = depth;
        st.step.fractured = fractured;
    }

    /// Takes over the cut of `predecessor`, the section this one succeeds as
    /// a moving cross section (seed 000 §IV, Fig. 4(b)): the crack cut
    /// `crack_depth` (m) below this section's top with the predecessor's
    /// first-fracture flag, as [`Self::restart_with_crack`], *and the knife
    /// where it is*: the edge at `edge_height` (m above the board on this
    /// section's cut line, kept between the board and the top), with the
    /// predecessor's drag along the edge if the edge presses below the tip.
    ///
    /// Re-choosing a section moves the plane that models the material around
    /// a segment, not the knife: an edge pressing d below an intact skin
    /// (R(δ₀) < r·R'_c, seed 000 eqs. 1 and 6) keeps pressing there on the
    /// successor, so the indentation builds up to the first fracture across
    /// re-choices instead of restarting from zero at each.
    ///
    /// The elastic state (forces, surface deflection, strain energy) is
    /// evaluated on this section's geometry for that configuration. The
    /// energies restart at zero except the strain energy, which is the
    /// predecessor's elastic state re-established here and is booked as
    /// [`WorkSplit::inherited`], so the balance reads knife + inherited =
    /// fracture + strain energy + friction + unstable. (The caller keeps the
    /// predecessor's knife work, which paid for it.) Allocates nothing.
    pub fn take_over(&mut self, predecessor: &CrossSection, crack_depth: f64, edge_height: f64) {
        let pred = predecessor.state;
        self.restart_with_crack(crack_depth, pred.fractured);
        let model = &self.model;
        let y_tip = self.state.y_tip;
        let y_edge = if edge_height.is_finite() {
            edge_height.clamp(0.0, model.height)
        } else {
            y_tip
        };
        let drag = if y_tip > y_edge && pred.y_tip > pred.y_edge {
            pred.drag
        } else {
            0.0
        };
        let e = evaluate(model, &mut self.ws, y_tip, y_edge, drag, 0.0, 0.0);
        let strip = strip_of(model, y_tip, y_edge);
        let surface = -model
            .line
            .line_uy(model.n, &self.ws.g, Some(&strip), &self.ws.lambda);
        let st = &mut self.state;
        st.y_edge = y_edge;
        st.drag = drag;
        let step = &mut st.step;
        step.knife_displacement = model.height - y_edge;
        step.edge_height = y_edge;
        step.indentation = (y_tip - y_edge).max(0.0);
        step.surface_deflection = surface;
        step.force_vertical = e.f_elastic_n();
        step.force_tangential = e.f_t;
        step.force_vertical_wedge = e.f_wedge;
        step.tensile_contacts = e.tensile;
        step.status = if y_tip > y_edge {
            StepStatus::Indenting
        } else {
            StepStatus::NoContact
        };
        step.work.strain_energy = e.energy;
        step.work.strain_energy_antiplane = e.energy_anti;
        step.work.inherited = e.energy;
        // The next step evaluates its start afresh (friction for its own
        // increments).
        self.ws.end = None;
    }

    /// The state after the last step (or the initial state).
    pub fn state(&self) -> &SectionStep {
        &self.state.step
    }

    /// Number of linear solves of the condensed line since construction
    /// (each configuration evaluated costs one per active-set pass): the
    /// section's cost counter, for profiling without a clock.
    pub fn solves(&self) -> u64 {
        self.ws.solves
    }

    /// Height of the section at the cut line, m.
    pub fn height(&self) -> f64 {
        self.model.height
    }

    /// Row spacing of the mesh on the cut line, m.
    pub fn row_spacing(&self) -> f64 {
        self.model.h
    }

    /// Number of elements of the half-section mesh.
    pub fn element_count(&self) -> usize {
        self.model.elements
    }

    /// Number of condensed in-plane degrees of freedom (cut line and strip).
    pub fn condensed_dofs(&self) -> usize {
        self.model.n * (self.model.line.k + 1)
    }

    /// Whether the section is cut through.
    pub fn is_cut_through(&self) -> bool {
        self.state.completed
    }

    /// Moves the knife down by `dn` ≥ 0 (m) and along the edge by `dt` (m);
    /// the slice-push ratio of the step is ξ = |dt|/dn. Returns the new state.
    pub fn advance(&mut self, dn: f64, dt: f64) -> Result<SectionStep, SectionError> {
        if !(dn.is_finite() && dn >= 0.0) {
            return Err(SectionError::InvalidStep(
                "the vertical increment must be finite and >= 0",
            ));
        }
        if !dt.is_finite() {
            return Err(SectionError::InvalidStep(
                "the tangential increment must be finite",
            ));
        }
        if self.state.completed {
            return Ok(self.advance_cut_through(dn));
        }
        let model = &self.model;
        let ws = &mut self.ws;
        let st = self.state;
        let step = KnifeStep::new(st.y_tip, st.y_edge, st.drag, dn, dt);
        let (y_edge1, dt_abs) = (step.y_edge1, step.dt_abs);
        // Start of the step: elastic part from the state, friction for this direction.
        let e0 = match ws.end.take() {
            Some((y_tip, y_edge, drag, mut e))
                if y_tip == st.y_tip && y_edge == st.y_edge && drag == st.drag =>
            {
                face_terms(model, ws, st.y_tip, st.y_edge, dn, dt_abs, &mut e);
                e
            }
            _ => evaluate(model, ws, st.y_tip, st.y_edge, st.drag, dn, dt_abs),
        };
        let growth = CrackGrowth::solve(model, ws, &step, &e0, st.fractured);
        let s = growth.extension;
        let mut status = growth.status;
        // Knife work of a step without crack growth: piecewise up to the
        // last break, closed below once the end state is known. (With crack
        // growth the step's work is the same trapezoid as R(s)'s, which the
        // fracture term balances.)
        let pieces =
            (s == 0.0 && dn > 0.0).then(|| PiecewiseWork::up_to_last_break(model, ws, &step, e0));
        // Commit the end state.
        let y_tip1 = st.y_tip - s;
        let drag1 = step.drag_at(s);
        let e1 = step.at_extension(model, ws, s);
        let d1 = y_tip1 - y_edge1;
        if d1 <= 0.0 && s == 0.0 {
            status = StepStatus::NoContact;
        }
        let (w_el, w_fric) = match pieces {
            Some(pieces) => pieces.close(model, ws, &step, &e1),
            None => (
                elastic_work(&step, &e0, &e1),
                friction_work(&step, &e0, &e1),
            ),
        };
        let mut work = st.step.work;
        work.knife += w_el + w_fric;
        work.friction += w_fric;
        work.strain_energy = e1.energy;
        work.strain_energy_antiplane = e1.energy_anti;
        if s > 0.0 {
            // A crack that runs through releases more than the fracture
            // takes: the excess is reported as unstable release.
            let fracture = growth.fracture_energy();
            work.fracture += fracture;
            work.unstable += (w_el - (e1.energy - e0.energy)) - fracture;
        }
        let completed = matches!(status, StepStatus::CutThrough);
        let strip = strip_of(model, y_tip1, y_edge1);
        let surface = -model.line.line_uy(model.n, &ws.g, Some(&strip), &ws.lambda);
        let step = SectionStep {
            knife_displacement: st.step.knife_displacement + dn,
            edge_height: y_edge1,
            crack_tip_height: y_tip1,
            crack_depth: model.height - y_tip1,
            indentation: d1.max(0.0),
            surface_deflection: surface,
            force_vertical: e1.f_elastic_n() + e1.f_fric_n,
            force_tangential: e1.f_t + e1.f_fric_t,
            force_vertical_wedge: e1.f_wedge,
            force_vertical_friction: e1.f_fric_n,
            force_tangential_friction: e1.f_fric_t,
            crack_extension: s,
            fractured: st.fractured || s > 0.0,
            status,
            work,
            tensile_contacts: e1.tensile,
        };
        self.ws.end = Some((y_tip1, y_edge1, drag1, e1));
        self.state = State {
            y_edge: y_edge1,
            y_tip: y_tip1,
            drag: drag1,
            fractured: step.fractured,
            completed,
            step,
        };
        Ok(step)
    }

    /// A knife step on a section already cut through: the knife moves on
    /// without force, the work is unchanged.
    fn advance_cut_through(&mut self, dn: f64) -> SectionStep {
        let y_edge1 = self.state.y_edge - dn;
        let mut step = self.state.step;
        step.knife_displacement += dn;
        step.edge_height = y_edge1;
        step.status = StepStatus::CutThrough;
        step.crack_extension = 0.0;
        step.force_vertical = 0.0;
        step.force_tangential = 0.0;
        step.force_vertical_wedge = 0.0;
        step.force_vertical_friction = 0.0;
        step.force_tangential_friction = 0.0;
        self.state.y_edge = y_edge1;
        self.state.step = step;
        step
    }

    /// Moves the knife edge down to `edge_depth` (m below the top surface at
    /// the cut) in steps of at most `max_step` (m), with `xi` tangential
    /// displacement per unit vertical; returns the last state. Convenience
    /// for sweeps; the plant calls [`Self::advance`] per tick.
    pub fn advance_to(
        &mut self,
        edge_depth: f64,
        xi: f64,
        max_step: f64,
    ) -> Result<SectionStep, SectionError> {
        if !(max_step.is_finite() && max_step > 0.0) {
            return Err(SectionError::InvalidStep(
                "the step size must be finite and > 0",
            ));
        }
        let mut last = self.state.step;
        while last.knife_displacement < edge_depth - 1e-15 {
            let dn = max_step.min(edge_depth - last.knife_displacement);
            last = self.advance(dn, xi * dn)?;
        }
        Ok(last)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::MaterialPreset;

    /// Knife travel until the crack first grows, and the state then.
    fn travel_to_first_growth(s: &mut CrossSection, step: f64) -> (f64, SectionStep) {
        let start = s.state().knife_displacement;
        for _ in 0..4000 {
            let st = s.advance(step, 0.0).unwrap();
            if st.crack_extension > 0.0 {
                return (st.knife_displacement - start, st);
            }
        }
        panic!("the crack never grew");
    }

    #[test]
    fn restart_with_crack_cuts_on_from_the_carried_depth() {
        // Eggplant cuboid: R'_c = 275 N/m > R_c = 140 N/m, so whether the
        // first fracture is carried over is visible in the knife travel to
        // the first crack growth.
        let material = MaterialPreset::EggplantCuboid.material();
        let geometry = SectionGeometry::rectangle(0.03, 0.02).unwrap();
        let settings = SectionSettings {
            row_spacing: 5e-4,
            ..SectionSettings::default()
        };
        let mut s =
            CrossSection::new(&geometry, &material, &BladeSection::default(), &settings).unwrap();
        let step = 6.25e-6;
        // A cut to a few millimetres, so the section has a history to discard.
        for _ in 0..800 {
            s.advance(step, 0.0).unwrap();
        }
        assert!(s.state().fractured && s.state().crack_depth > 1e-3);

        let depth = 0.006;
        s.restart_with_crack(depth, true);
        let st = *s.state();
        let y = 0.02 - depth;
        assert_eq!(st.knife_displacement, depth);
        assert_eq!(st.crack_depth, depth);
        assert!((st.crack_tip_height - y).abs() < 1e-15);
        assert_eq!(st.edge_height, st.crack_tip_height);
        assert_eq!(st.indentation, 0.0);
        assert!(st.fractured);
        assert_eq!(st.work, WorkSplit::default(), "energies restart at zero");
        // Cutting goes on from the carried depth, never above it.
        let (travel_fractured, first) = travel_to_first_growth(&mut s, step);
        // The edge starts at the tip of an open crack: it cuts on at once.
        assert!(travel_fractured <= 2.0 * step, "{travel_fractured}");
        assert!(first.fractured);
        assert!(first.crack_depth > depth);
        assert!(matches!(first.status, StepStatus::Cutting));
        for _ in 0..400 {
            let st = s.advance(step, 0.0).unwrap();
            assert!(st.crack_depth >= depth);
        }
        assert!(s.state().crack_depth > depth + 1e-3, "the cut went on");

        // The flag is what the caller says, not re-derived from the depth.
        s.restart_with_crack(depth, false);
        assert!(!s.state().fractured);
        assert_eq!(s.state().crack_depth, depth);

        // Clamped to leave one row; a negative depth is the intact section.
        s.restart_with_crack(1.0, true);
        assert!((s.state().crack_tip_height - s.row_spacing()).abs() < 1e-15);
        s.restart_with_crack(-1.0, false);
        assert_eq!(
            *s.state(),
            *CrossSection::new(&geometry, &material, &BladeSection::default(), &settings)
                .unwrap()
                .state()
        );
    }

    #[test]
    fn take_over_on_the_same_shape_continues_the_cut_unchanged() {
        // Eggplant with skin (R'_c = 650 N/m): an edge pressing 2 mm into
        // the intact skin, then handed over to a successor of the same shape
        // with the knife where it is. Nothing physical changes: the same
        // elastic state, the first fracture at the same knife travel as
        // without the hand-over, and the balance closes with the inherited
        // strain energy. (A restart at the crack tip would need the whole
        // indentation again.)
        let material = MaterialPreset::EggplantWhole.material();
        let geometry = SectionGeometry::rectangle(0.03, 0.02).unwrap();
        let settings = SectionSettings {
            row_spacing: 5e-4,
            ..SectionSettings::default()
        };
        let new = || {
            CrossSection::new(&geometry, &material, &BladeSection::default(), &settings).unwrap()
        };
        let (step, xi) = (2e-5, 0.3);
        let mut reference = new();
        let mut pred = new();
        for _ in 0..100 {
            reference.advance(step, xi * step).unwrap();
            pred.advance(step, xi * step).unwrap();
        }
        let p = *pred.state();
        assert!(!p.fractured && p.indentation > 1.9e-3, "{p:?}");
        let mut succ = new();
        succ.take_over(&pred, p.crack_depth, p.edge_height);
        let s = *succ.state();
        assert_eq!(s.edge_height, p.edge_height);
        assert_eq!(s.crack_tip_height, p.crack_tip_height);
        assert_eq!(s.indentation, p.indentation);
        assert!(!s.fractured);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
        // The elastic parts (the predecessor's forces include its last
        // step's friction; a hand-over moves nothing).
        assert!(close(
            s.force_vertical,
            p.force_vertical - p.force_vertical_friction
        ));
        assert!(close(s.surface_deflection, p.surface_deflection));
        assert!(close(s.work.strain_energy, p.work.strain_energy));
        assert_eq!(s.work.inherited, s.work.strain_energy);
        assert_eq!(s.work.knife, 0.0);
        // On to the first fracture: at the same travel as the uninterrupted
        // reference.
        let first = |c: &mut CrossSection| -> usize {
            for k in 0..2000 {
                if c.advance(step, xi * step).unwrap().fractured {
                    return k;
                }
            }
            panic!("never fractured");
        };
        let k_ref = first(&mut reference);
        let k_succ = first(&mut succ);
        assert!(k_ref.abs_diff(k_succ) <= 1, "{k_ref} vs {k_succ}");
        for _ in 0..200 {
            succ.advance(step, xi * step).unwrap();
        }
        let w = succ.state().work;
        let closure =
            w.knife + w.inherited - (w.fracture + w.strain_energy + w.friction + w.unstable);
        assert!(
            closure.abs() <= 1e-6 * (w.knife + w.inherited),
            "balance off by {closure}"
        );
        // The old hand-over (edge restarted at the tip) indents from zero.
        let mut restarted = new();
        restarted.restart_with_crack(p.crack_depth, p.fractured);
        let k_restart = first(&mut restarted);
        assert!(k_restart > k_ref + 50, "{k_restart} vs {k_ref}");
    }
}
