//! One module per subcommand: arguments (clap derive, with examples) and `run`.

pub(crate) mod convert;
pub(crate) mod eval;
pub(crate) mod info;
pub(crate) mod knots;
pub(crate) mod make;
pub(crate) mod plot;
// surfaces and pp-forms in info, convert and plot
pub(crate) mod shapes;
// construction subcommands
pub(crate) mod bezier;
pub(crate) mod blend;
pub(crate) mod interpolate;
pub(crate) mod pp;
// knot operations, surfaces in make/eval, CAD files in convert
pub(crate) mod cad;
pub(crate) mod deprecated;
pub(crate) mod explicit;
pub(crate) mod jump;
pub(crate) mod knot;
pub(crate) mod make_surface;
pub(crate) mod surface_eval;
pub(crate) mod tensor;
// fitting: least squares, smoothing, tolerance
pub(crate) mod fit;
pub(crate) mod fit_periodic;
// geometric queries
pub(crate) mod comb;
pub(crate) mod intersect;
pub(crate) mod measure;
pub(crate) mod mesh;
pub(crate) mod offset;
// Parquet batches in interpolate, eval and convert
pub(crate) mod parquet_batch;
pub(crate) mod project;
// the browser editor
pub(crate) mod serve;
