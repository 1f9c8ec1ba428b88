//! Seed 001 in full: large-deformation indentation and slicing of a soft
//! periodic slab by a rigid wire, with crack nucleation where the largest
//! principal Cauchy stress on the surface reaches σ* = 2μ.
//!
//! Files, one concept each: `neo_hookean` (the seed's compressible
//! neo-Hookean energy, stresses and tangent), `element` (Q4 kinematics with
//! three displacement components, selectively reduced integration), `mesh`
//! (graded half-slab mesh), `system` (assembly and sparse Cholesky, faer),
//! `newton` (Newton's method with an energy line search), `wire_contact`
//! (penalty normal contact, regularised Coulomb friction along the wire),
//! `surface_stress` (σ₁ over the surface cells and over the slab),
//! `nucleation_envelope` (the nucleation loads scaled by μR, as the cutting
//! model's sections use them),
//! `seed_comparison` (the seed's observations side by side), `slab`
//! ([`WireSlab`]: load stepping, forces, nucleation), `sweep` (the kinematic
//! angles), `settings`, `error`.

mod element;
mod error;
mod mesh;
mod neo_hookean;
mod newton;
mod nucleation_envelope;
mod seed_comparison;
mod settings;
mod slab;
mod surface_stress;
mod sweep;
mod system;
mod wire_contact;

pub use error::FiniteStrainError;
pub use neo_hookean::{NeoHookean, largest_principal};
pub use newton::NewtonReport;
pub use nucleation_envelope::{ENVELOPE_POINTS, NucleationEnvelope};
pub use seed_comparison::SeedComparison;
pub use settings::{Indenter, SideSupport, WireSlabSettings};
pub use slab::{IndentationRun, Nucleation, SlabState, WireSlab, WireSlabError};
pub use surface_stress::{StressField, SurfaceStress};
pub use sweep::{AngleSweep, sweep_angles, sweep_angles_until};
