//! Interpolation of curves and surfaces through points (document 000).
