//! Point sets in: CSV and whitespace text, JSON, NumPy `.npy` and `.npz`.
//!
//! - `points_in.rs`: the readers and their options (`read_points`);
//! - `text_points.rs`: the one-pass parallel text parser;
//! - `npy.rs`: NumPy `.npy` arrays in and out;
//! - `npz.rs`: NumPy `.npz` archives of curves.
//! - `tensor_npz.rs`: NumPy `.npz` archives of tensor splines in `N` parameters.

pub(crate) mod npy;
pub(crate) mod npz;
pub(crate) mod points_in;
pub(crate) mod tensor_npz;
pub(crate) mod text_points;
