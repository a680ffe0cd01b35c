//! Files of other kinds: conversion and CAD files.
//!
//! - `convert.rs`: `lekalo convert`;
//! - `cad.rs`: STEP and IGES in convert and the other commands.

pub(crate) mod cad;
pub(crate) mod convert;
