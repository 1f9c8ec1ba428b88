//! The object as the knife's plane cuts it: its silhouette in that plane,
//! the arc of edge that meets it, and the cross sections normal to the
//! edge's segments (seed 000 §IV, assumption A2).

pub mod contact_arc;
pub mod section_shape;

pub use contact_arc::{EdgeSegment, contact_arc, knife_plane_silhouette, segments};
