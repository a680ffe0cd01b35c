//! `lekalo fit`: least squares, smoothing, tolerance, robust, surfaces.
//!
//! - `fit.rs`: the command and its modes;
//! - `fit_periodic.rs`: closed curves.

pub(crate) mod fit;
pub(crate) mod fit_periodic;
