//! Versioned JSON format of every object.
