//! Bezier degree elevation and reduction (document 004).
