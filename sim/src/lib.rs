//! shearcut-sim: the cutting model.
