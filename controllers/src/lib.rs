//! shearcut-controllers.

pub mod trajectory;
