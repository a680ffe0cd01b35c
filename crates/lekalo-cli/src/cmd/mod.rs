//! One module per subcommand: arguments (clap derive, with examples) and `run`.

pub(crate) mod convert;
pub(crate) mod eval;
pub(crate) mod info;
pub(crate) mod knots;
pub(crate) mod make;
pub(crate) mod plot;
// surfaces and pp-forms in info, convert and plot (issue 7)
pub(crate) mod shapes;
// construction subcommands (issues 3–6)
pub(crate) mod bezier;
pub(crate) mod blend;
pub(crate) mod interpolate;
pub(crate) mod pp;
// geometric queries
pub(crate) mod intersect;
pub(crate) mod measure;
pub(crate) mod mesh;
pub(crate) mod project;
