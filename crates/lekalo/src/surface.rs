//! Tensor-product Bezier, B-spline and NURBS surfaces.
