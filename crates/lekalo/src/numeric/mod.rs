//! Numerical building blocks (crate-private).
//!
//! - `linalg.rs`: banded linear systems (Crout elimination without pivoting, cyclic systems)
//!   and scaled norms.
//! - `tridiagonal.rs`: tridiagonal systems by LAPACK `dgtsv`'s elimination with partial pivoting.
//! - `twisted.rs`: tridiagonal systems eliminated from both ends at once, for one column.
//! - `partitioned.rs`: tridiagonal systems eliminated in eight checked partitions at once, for
//!   one column.
//! - `damped.rs`: Levenberg–Marquardt refinement of small least-squares problems on a box.
//! - `isa.rs`: run-time choice of the instruction set for kernels compiled twice.
//! - `large_buffer.rs`: zeroed buffers for large results, on huge pages where available.
//! - `progress.rs`: [`Progress`](crate::Progress), progress reports and cancellation of long
//!   computations.

pub(crate) mod damped;
pub(crate) mod isa;
pub(crate) mod large_buffer;
pub(crate) mod linalg;
pub(crate) mod partitioned;
pub(crate) mod progress;
pub(crate) mod tridiagonal;
pub(crate) mod twisted;
