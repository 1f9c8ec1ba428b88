//! shearcut application.
