//! Closed-form mechanics of the two seeds.
//!
//! - [`strip_load`]: stresses under a knife edge modelled as a strip on a
//!   half-space, normal (Boussinesq, seed 000 eq. 2) and tangential (Cerruti,
//!   eq. 3).
//! - [`principal_strain`]: Hooke's law and the maximum principal strain below
//!   the edge (seed 000 eqs. 4–5).
//! - [`slice_push`]: the slice-push ratio ξ and what follows from it: the force
//!   ratio F_t/F_n = ξ/(2(1+ν)), the normal-force ratio f_n^s/f_n^p and the
//!   toughness ratio r(ξ,ν) (seed 000 eq. 6, Fig. 3).
//! - [`line_load`]: the line-load stress field and its largest principal stress
//!   (seed 001 eqs. 1–4).
//! - [`nucleation`]: seed 001's scalings of the forces at crack nucleation.

pub mod line_load;
pub mod nucleation;
pub mod principal_strain;
pub mod slice_push;
pub mod strip_load;

pub use slice_push::{SlicePushRatio, force_ratio, normal_force_ratio, toughness_ratio};
