//! Cutting one 2D cross section with a straight knife edge (seed 000 §III,
//! DESIGN §3.2): plane-strain and antiplane FEM condensed onto the cut line,
//! wedge contact with Coulomb friction, and fracture by the seed's energy
//! balance (eq. 1) with the slicing toughness r(ξ,ν)·R_c (eq. 6).
//!
//! Files: `geometry` (the section polygon), `mesh` (graded Q4 mesh of the half
//! section), `plane_strain` and `antiplane` (element stiffnesses), `condensed`
//! (factorisation and Schur complement onto the cut line), `factor_cache`
//! (stiffness pattern and symbolic factorisation per mesh shape, shared by
//! every build), `contact` (wedge
//! profile and friction), `equilibrium` (the contacts' active set and the
//! forces and energies at a fixed crack tip, edge and drag), `knife_step`
//! (one step's kinematics: the edge's end and the drag along the cut),
//! `crack_growth` (a step's energy release rate, first-fracture criterion
//! and balanced extension), `crack_arrest` (where a running crack stops
//! under seed 001's surface-stress option), `step_toughness` (the toughness an extension
//! pays, skin layer included), `knife_work` (the knife's work over a step),
//! `fracture` (toughness ratio, bracketing and regula falsi), `simulation`
//! ([`CrossSection`]), `settings`, `error`.

mod antiplane;
mod condensed;
mod contact;
mod crack_arrest;
mod crack_growth;
mod equilibrium;
mod error;
mod factor_cache;
mod fracture;
mod geometry;
mod knife_step;
mod knife_work;
mod mesh;
mod nested_dissection;
mod plane_strain;
mod settings;
mod simulation;
mod step_toughness;
#[cfg(test)]
mod verification;

pub use error::SectionError;
pub use geometry::SectionGeometry;
pub use settings::{FirstFracture, SURFACE_STRESS_MIN_POISSON_RATIO, SectionSettings};
pub use simulation::{CrossSection, SectionStep, StepStatus, WorkSplit};
