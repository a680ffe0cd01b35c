//! CAD exchange files: STEP (ISO 10303-21, AP203/214/242) read and written, IGES 5.3.
//!
//! - `step.rs`: the STEP writer;
//! - `step_read/`: the STEP reader (a folder);
//! - `iges.rs`: IGES read and write.

pub(crate) mod iges;
pub(crate) mod step;
pub(crate) mod step_read;
