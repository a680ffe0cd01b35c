//! Divided differences and B-splines as divided differences (document 003).
