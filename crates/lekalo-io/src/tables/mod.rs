//! Tables of samples out: parameters, points, derivatives, curvature, normals (CSV, JSON),
//! and the number format they share.
//!
//! - `samples.rs`: samples of curves (`sample_table`);
//! - `surface_samples.rs`: samples of surfaces;
//! - `numfmt.rs`: shortest round-trip numbers.

pub(crate) mod numfmt;
pub(crate) mod samples;
pub(crate) mod surface_samples;
