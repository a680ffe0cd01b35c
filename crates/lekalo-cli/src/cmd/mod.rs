//! One module per subcommand: arguments (clap derive, with examples) and `run`.

pub(crate) mod convert;
pub(crate) mod eval;
pub(crate) mod info;
pub(crate) mod knots;
pub(crate) mod make;
pub(crate) mod plot;
