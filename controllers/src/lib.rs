//! shearcut-controllers.
