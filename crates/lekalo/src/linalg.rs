//! Banded and tridiagonal solvers.
