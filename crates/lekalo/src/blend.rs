//! Jump-smoothing polynomials and C^k blending of curves (document 001).
