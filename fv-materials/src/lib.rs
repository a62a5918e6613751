//! fv-materials
