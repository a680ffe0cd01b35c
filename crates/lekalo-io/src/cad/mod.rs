//! CAD exchange files: STEP (ISO 10303-21, AP203/214/242) read and written, IGES 5.3.
//!
//! - `step.rs`: the STEP writer of curves and surfaces;
//! - `step_faces.rs`: the STEP writer of faces (boundary representations);
//! - `step_read/`: the STEP reader (a folder);
//! - `iges/`: IGES read and write;
//! - `motion.rs`: rigid (and, for IGES, affine) maps of coordinates, `x ↦ R x + t`: a STEP
//!   placement or an IGES transformation matrix, composed and inverted;
//! - `faces_write_tests.rs`: faces written to STEP and IGES and read back;
//! - `limits_tests.rs`: the readers' size limit (`--max-size`) on generated files.
//!
//! Both readers take a size limit ([`crate::read_step_limited`], [`crate::read_iges_limited`]):
//! the entities of a file, and the control points and knots of its B-splines together, checked
//! before they are allocated.

#[cfg(test)]
pub(crate) mod faces_write_tests;
pub(crate) mod iges;
#[cfg(test)]
mod limits_tests;
pub(crate) mod motion;
pub(crate) mod step;
mod step_faces;
pub(crate) mod step_read;
