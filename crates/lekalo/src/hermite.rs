//! Cubic Hermite and natural cubic splines.
