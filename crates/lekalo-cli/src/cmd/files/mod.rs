//! Files of other kinds: conversion, CAD files, Parquet batches.
//!
//! - `convert.rs`: `lekalo convert`;
//! - `cad.rs`: STEP and IGES in convert and the other commands;
//! - `parquet_batch.rs`: Parquet batches in interpolate, eval and convert.

pub(crate) mod cad;
pub(crate) mod convert;
pub(crate) mod parquet_batch;
