//! Subcommands that look at objects: information, evaluation and plots.
//!
//! - `info.rs`: `lekalo info`;
//! - `eval.rs`: `lekalo eval` of curves;
//! - `surface_eval.rs`: `lekalo eval` of surfaces;
//! - `plot.rs`: `lekalo plot`;
//! - `comb.rs`: the curvature comb of `lekalo plot --comb`;
//! - `shapes.rs`: surfaces and pp-forms in info, convert and plot.

pub(crate) mod comb;
pub(crate) mod eval;
pub(crate) mod info;
pub(crate) mod plot;
pub(crate) mod shapes;
pub(crate) mod surface_eval;
