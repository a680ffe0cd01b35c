//! The subcommands, grouped by subject; each module holds one subcommand's arguments (clap
//! derive, with examples) and its `run`.
//!
//! - `construct/`: building objects (make, interpolate, bezier, blend, pp, knots, knot, slice,
//!   sweep);
//! - `inspect/`: looking at objects (info, eval, plot);
//! - `fitting/`: `lekalo fit`;
//! - `queries/`: geometric queries (measure, project, intersect, offset, mesh);
//! - `files/`: conversion, CAD files;
//! - `deprecated.rs`: the older spellings of options; `serve.rs`: `lekalo serve`.

mod construct;
pub(crate) mod deprecated;
mod files;
mod fitting;
mod inspect;
mod queries;
pub(crate) mod serve;

// each subcommand keeps its short path (`crate::cmd::make`)
pub(crate) use construct::{
    bezier, blend, explicit, interpolate, jump, knot, knots, make, make_surface, make_tensor, pp,
    slice, sweep, tensor,
};
pub(crate) use files::{cad, convert};
pub(crate) use fitting::args as fit_args;
pub(crate) use fitting::fit;
pub(crate) use inspect::{comb, eval, info, plot, shapes, surface_eval};
pub(crate) use queries::{intersect, measure, mesh, offset, project};
