//! `lekalo fit`: least squares, smoothing, tolerance, robust, surfaces, closed curves.
//!
//! - `fit.rs`: the command and its modes, closed curves and periodic functions among them.

pub(crate) mod fit;
