//! solver-app
