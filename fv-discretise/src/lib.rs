//! fv-discretise
