//! A cross section cut by a straight knife edge: the section simulation
//! driven by knife motion (seed 000 §III.C, DESIGN §3.2–3.2a).

use crate::blade::BladeSection;
use crate::material::Material;

use super::condensed::{CondensedLine, MAX_STRIP, ReleasedWorkspace, StripConstraint};
use super::contact::{FaceSlip, WedgeProfile};
use super::error::SectionError;
use super::fracture::{Extension, solve_extension, toughness_ratio};
use super::geometry::SectionGeometry;
use super::mesh::SectionMesh;
use super::settings::{FirstFracture, SectionSettings};
use crate::finite_strain::NucleationEnvelope;

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
struct Model {
    line: CondensedLine,
    profile: WedgeProfile,
    material: Material,
    settings: SectionSettings,
    /// Row spacing on the cut line, m.
    h: f64,
    /// Rows R of the line.
    n: usize,
    /// Height of the section at the cut, m.
    height: f64,
    /// Nodes and elements (kept for callers that inspect the mesh).
    elements: usize,
    /// μ·R with R the edge flat's width, N/m: the scale of the loads of
    /// seed 001's nucleation envelope ([`FirstFracture::SurfaceStress`]).
    nucleation_scale: f64,
}

/// Result of evaluating a configuration (full section, both halves).
#[derive(Debug, Clone, Copy, Default)]
struct Eval {
    f_edge: f64,
    f_wedge: f64,
    f_t: f64,
    f_fric_n: f64,
    f_fric_t: f64,
    energy: f64,
    energy_anti: f64,
    tensile: usize,
    /// Fingerprint of the contact active sets (edge columns, released faces).
    contacts: u64,
}

impl Eval {
    fn f_elastic_n(&self) -> f64 {
        self.f_edge + self.f_wedge
    }
}

/// Preallocated buffers of a section.
#[derive(Debug, Clone)]
struct Workspace {
    g: Vec<f64>,
    p: Vec<f64>,
    lambda: [f64; MAX_STRIP],
    /// Face rows released from the wedge (unilateral contact); kept between
    /// evaluations as the active set's warm start.
    released: Vec<bool>,
    /// Strip columns in contact with the edge (warm start, as `released`).
    strip_active: [bool; MAX_STRIP],
    mixed: ReleasedWorkspace,
    /// Linear solves of the condensed line so far (a cost counter).
    solves: u64,
    /// The last step's end configuration (y_tip, y_edge, drag) and its
    /// evaluation, whose face reactions are still in `p`: the next step
    /// starts there, so its start evaluation needs only the friction for
    /// the new increments (`face_terms`), not another active-set solve.
    end: Option<(f64, f64, f64, Eval)>,
    /// The arguments (y_tip, y_edge, drag, dn, dt, as bits) and result of
    /// the last evaluation, if its active sets converged; its gaps,
    /// reactions and strip forces are still in `g`, `p` and `lambda`. An
    /// evaluation of the same configuration is then this result (the first
    /// active-set pass would solve the same system and change nothing).
    last: Option<([u64; 5], Eval)>,
}

/// Most active-set iterations of the face contact per evaluation.
const MAX_ACTIVE_SET_ITERATIONS: usize = 64;

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
/// With [`FirstFracture::SurfaceStress`] (seed 001) the first fracture is
/// not R'_c's: before it the crack grows only in a step whose end load per
/// unit length (F_n, F_t), without growth, is on or beyond the
/// finite-strain slab's nucleation envelope scaled by μb (b the edge flat's
/// width, a wire's radius R); from that step on it grows by the balance with
/// r·R_c. The criterion reads the present load only: the envelope was
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
/// balance closes to round-off there too (`segment_work`).
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
        let model = &self.model;
        let ws = &mut self.ws;
        let st = self.state;
        let y_edge1 = st.y_edge - dn;
        if st.completed {
            let mut step = st.step;
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
            return Ok(step);
        }
        let dt_abs = dt.abs();
        let xi = if dn > 0.0 { dt_abs / dn } else { f64::INFINITY };
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
        let u0 = e0.energy;
        let d0 = st.y_tip - st.y_edge;
        let drag_at = |s: f64| -> f64 {
            let d1 = st.y_tip - s - y_edge1;
            if d1 <= 0.0 {
                0.0
            } else if d0 <= 0.0 {
                if dn > 0.0 { dt_abs * d1 / dn } else { 0.0 }
            } else {
                st.drag + dt_abs - xi.min(f64::MAX) * s
            }
        };
        // Drag at a knife advance t ∈ [0, dn] of a step without crack growth.
        let drag_mid = |t: f64| -> f64 {
            let d = st.y_tip - (st.y_edge - t);
            if d <= 0.0 {
                0.0
            } else if d0 <= 0.0 {
                xi.min(f64::MAX) * d
            } else {
                st.drag + xi.min(f64::MAX) * t
            }
        };
        // Seed 001's surface stress instead of R'_c: before the first
        // fracture the crack may grow only once the edge's load at the end of
        // the step, without growth, is on or beyond the nucleation envelope;
        // then, as after it, by the balance with R_c.
        let surface_stress =
            model.settings.first_fracture == FirstFracture::SurfaceStress && !st.fractured;
        let nucleated = surface_stress && {
            let e = evaluate(model, ws, st.y_tip, y_edge1, drag_at(0.0), dn, dt_abs);
            NucleationEnvelope::SEED_GEL.reached(
                e.f_elastic_n() + e.f_fric_n,
                e.f_t + e.f_fric_t,
                model.nucleation_scale,
            )
        };
        let mut release = |s: f64| -> f64 {
            let e = evaluate(model, ws, st.y_tip - s, y_edge1, drag_at(s), dn, dt_abs);
            let w =
                0.5 * (e0.f_elastic_n() + e.f_elastic_n()) * dn + 0.5 * (e0.f_t + e.f_t) * dt_abs;
            (w - (e.energy - u0)) / s
        };
        let mat = &model.material;
        let r = if xi.is_finite() {
            toughness_ratio(xi, mat.poisson_ratio)
        } else {
            f64::INFINITY
        };
        let (trigger, target) = if st.fractured || surface_stress {
            (r * mat.fracture_toughness, r * mat.fracture_toughness)
        } else {
            (
                r * mat.initial_fracture_toughness,
                r * mat.initial_fracture_toughness.min(mat.fracture_toughness),
            )
        };
        // With a skin layer (`Material::skin_thickness`) the toughness
        // depends on the depth: an extension s from the tip's depth a₀ pays
        // Γ(s) = R'_c·|[a₀, a₀+s] ∩ [0, t]| + R_c·(the rest), and balances
        // R(s) = r·Γ(s)/s. The root search then runs on R(s)/(r·Γ(s)/s)
        // against 1 (same relative tolerance).
        let skin = mat.skin_thickness.map(|t| (t, model.height - st.y_tip));
        let layered = |s: f64| -> f64 {
            match skin {
                Some((t, a0)) => {
                    let in_skin = (t - a0).clamp(0.0, s);
                    r * (mat.initial_fracture_toughness * in_skin
                        + mat.fracture_toughness * (s - in_skin))
                        / s
                }
                None => target,
            }
        };
        let (trigger, target) = if skin.is_some() {
            (1.0, 1.0)
        } else {
            (trigger, target)
        };
        let mut balance = |s: f64| -> f64 {
            if skin.is_some() {
                release(s) / layered(s)
            } else {
                release(s)
            }
        };
        let s_max = st.y_tip - model.h;
        let set = &model.settings;
        let ext = if surface_stress && !nucleated {
            Extension::None
        } else if dn > 0.0 && trigger.is_finite() && s_max > 0.0 {
            solve_extension(
                &mut balance,
                set.initial_crack_extension,
                (st.y_tip - y_edge1).max(0.0) + model.h,
                s_max,
                trigger,
                target,
                set.bisection_tolerance,
                set.max_bracket_doublings,
                set.max_bisection_iterations,
            )
        } else {
            Extension::None
        };
        // Back from the balance ratio to R(s) and the toughness paid.
        let to_rate = |s: f64, b: f64| if skin.is_some() { b * layered(s) } else { b };
        let (s, r_s, mut status) = match ext {
            Extension::None => (0.0, 0.0, StepStatus::Indenting),
            Extension::Balanced { s, r } => (s, to_rate(s, r), StepStatus::Cutting),
            Extension::RunsThrough { s, r } => (s, to_rate(s, r), StepStatus::CutThrough),
            Extension::Unbracketed { s, r } => (s, to_rate(s, r), StepStatus::Unbracketed),
        };
        let target_at = |s: f64| if skin.is_some() { layered(s) } else { target };
        // Knife work of a step without crack growth: trapezoids between the
        // positions where the force may jump, i.e. where a face node passes a
        // kink of the wedge profile (s = 0, the corner, the end of the bevel)
        // while the faces are measured from the edge, and where the edge
        // passes the tip. Between them the force is linear in the knife
        // position up to active-set changes (kinks of U, whose trapezoid
        // error is second order), so the work matches ΔU + friction.
        // (With crack growth the step's work is the same trapezoid as R(s)'s,
        // which the fracture term balances.)
        let (mut w_el, mut w_fric) = (0.0, 0.0);
        let mut prev = e0;
        let mut t_prev = 0.0;
        let xi_f = xi.min(f64::MAX);
        let eval_mid = |ws: &mut Workspace, t: f64| {
            evaluate(model, ws, st.y_tip, st.y_edge - t, drag_mid(t), dn, dt_abs)
        };
        if s == 0.0 && dn > 0.0 {
            let [corner, bevel] = model.profile.kinks();
            let h = model.h;
            loop {
                let y = st.y_edge - t_prev;
                // The next break below y: the grid y_i − c for c ∈ {0, corner,
                // bevel} with y_i = (i+1)·h (rows above the tip), and the tip.
                let mut next = y_edge1;
                for c in [0.0, corner, bevel] {
                    let k = ((y + c) / h - 1e-9).ceil() - 1.0;
                    let yb = k * h - c;
                    if yb > next && yb < y && yb > st.y_tip {
                        next = yb;
                    }
                }
                if st.y_tip < y && st.y_tip > next {
                    next = st.y_tip;
                }
                if next <= y_edge1 + 1e-12 * h {
                    break;
                }
                // The force jumps at the break: close the segment with its
                // left limit and open the next with the right limit.
                let t = st.y_edge - next;
                let eps = 1e-9 * h;
                let before = eval_mid(ws, t - eps);
                let after = eval_mid(ws, t + eps);
                let (we, wf) = segment_work(ws, &eval_mid, t_prev, &prev, t, &before, xi_f, 8);
                w_el += we;
                w_fric += wf;
                prev = after;
                t_prev = t;
            }
        }
        // Commit the end state.
        let y_tip1 = st.y_tip - s;
        let drag1 = drag_at(s);
        let e1 = evaluate(model, ws, y_tip1, y_edge1, drag1, dn, dt_abs);
        let d1 = y_tip1 - y_edge1;
        if d1 <= 0.0 && s == 0.0 {
            status = StepStatus::NoContact;
        }
        if s == 0.0 && dn > 0.0 {
            // segment_work evaluates inside the segment only if the contact
            // sets differ at its ends; then restore the end state's buffers
            // (the surface deflection below reads them).
            let evaluated_inside = prev.contacts != e1.contacts;
            let (we, wf) = segment_work(ws, &eval_mid, t_prev, &prev, dn, &e1, xi_f, 8);
            w_el += we;
            w_fric += wf;
            if evaluated_inside {
                let again = evaluate(model, ws, y_tip1, y_edge1, drag1, dn, dt_abs);
                debug_assert_eq!(again.energy.to_bits(), e1.energy.to_bits());
            }
        } else {
            w_el =
                0.5 * (e0.f_elastic_n() + e1.f_elastic_n()) * dn + 0.5 * (e0.f_t + e1.f_t) * dt_abs;
            w_fric =
                0.5 * (e0.f_fric_n + e1.f_fric_n) * dn + 0.5 * (e0.f_fric_t + e1.f_fric_t) * dt_abs;
        }
        let mut work = st.step.work;
        work.knife += w_el + w_fric;
        work.friction += w_fric;
        work.strain_energy = e1.energy;
        work.strain_energy_antiplane = e1.energy_anti;
        if s > 0.0 {
            // Fracture takes R(s)·s (= W − ΔU exactly); R = target within the
            // tolerance when balanced. A crack that runs through releases
            // more: the excess is reported as unstable release.
            let fracture = if matches!(status, StepStatus::Cutting) {
                r_s * s
            } else {
                target_at(s) * s
            };
            work.fracture += fracture;
            work.unstable += (w_el - (e1.energy - u0)) - fracture;
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

/// Knife work (elastic, friction) over knife advances t_a → t_b of a step
/// without crack growth (tangential advance ξ per unit vertical), from the
/// end states `ea`, `eb`. The forces are linear in t while the contact active
/// sets stay the same; where they change the force has a kink (continuous,
/// the energy being C¹). A segment whose ends differ in active sets is split
/// at the kink found from the two one-sided slopes (two extra evaluations);
/// if the sets on either side of it still differ from the ends' (several
/// changes), or the lines do not cross inside, the halves are split again,
/// up to `depth` times, then integrated by the trapezoid.
#[allow(clippy::too_many_arguments)]
fn segment_work(
    ws: &mut Workspace,
    eval_at: &impl Fn(&mut Workspace, f64) -> Eval,
    t_a: f64,
    ea: &Eval,
    t_b: f64,
    eb: &Eval,
    xi: f64,
    depth: u32,
) -> (f64, f64) {
    let power = |e: &Eval| e.f_elastic_n() + xi * e.f_t;
    let friction = |e: &Eval| e.f_fric_n + xi * e.f_fric_t;
    let len = t_b - t_a;
    let trapezoid = (
        0.5 * (power(ea) + power(eb)) * len,
        0.5 * (friction(ea) + friction(eb)) * len,
    );
    if ea.contacts == eb.contacts || len <= 0.0 || depth == 0 {
        return trapezoid;
    }
    let eps = 1e-4 * len;
    let (ea2, eb2) = (eval_at(ws, t_a + eps), eval_at(ws, t_b - eps));
    let ka = (power(&ea2) - power(ea)) / eps;
    let kb = (power(eb) - power(&eb2)) / eps;
    // Intersection of the two lines: power(ea) + ka (t − t_a) = power(eb) + kb (t − t_b).
    let ts = (power(eb) - power(ea) - kb * t_b + ka * t_a) / (ka - kb);
    let single = ts > t_a + eps && ts < t_b - eps && {
        let (l, r) = (eval_at(ws, ts - eps), eval_at(ws, ts + eps));
        l.contacts == ea.contacts && r.contacts == eb.contacts
    };
    if single {
        let part = |q: &dyn Fn(&Eval) -> f64| {
            let left = q(ea) + (q(&ea2) - q(ea)) / eps * (ts - t_a);
            let right = q(eb) + (q(eb) - q(&eb2)) / eps * (ts - t_b);
            0.5 * (q(ea) + left) * (ts - t_a) + 0.5 * (right + q(eb)) * (t_b - ts)
        };
        return (part(&power), part(&friction));
    }
    let tm = if ts > t_a + eps && ts < t_b - eps {
        ts
    } else {
        0.5 * (t_a + t_b)
    };
    let em = eval_at(ws, tm);
    let (w1, f1) = segment_work(ws, eval_at, t_a, ea, tm, &em, xi, depth - 1);
    let (w2, f2) = segment_work(ws, eval_at, tm, &em, t_b, eb, xi, depth - 1);
    (w1 + w2, f1 + f2)
}

/// The strip constraint of the edge at (y_tip, y_edge): the material at the
/// tip moved to the edge, u_y = y_edge − y_tip. It acts only where the edge
/// presses on the material (decided by `evaluate`).
fn strip_of(model: &Model, y_tip: f64, y_edge: f64) -> StripConstraint {
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
fn tip_row(model: &Model, y_tip: f64) -> (usize, f64) {
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
fn evaluate(
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
fn face_terms(
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
