//! Piecewise polynomials and their B-spline bases (document 003).
