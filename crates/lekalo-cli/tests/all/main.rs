//! The end-to-end tests of the `lekalo` command, one test binary with one module per subject: every
//! integration test binary links the whole crate, so one binary builds much faster than one per
//! file. A file of this folder that is not declared below would be compiled nowhere;
//! `every_test_file_is_a_module` checks that none is left out.

mod cli;
mod cli_bezier;
mod cli_blend;
mod cli_blend_corners;
mod cli_faces;
mod cli_fit;
mod cli_fit_options;
mod cli_fit_shape_surface;
mod cli_fit_sphere;
mod cli_fit_tensor;
mod cli_gallery;
mod cli_grid_knots;
mod cli_grid_params;
mod cli_help_examples;
mod cli_interpolate;
mod cli_intersect_surfaces;
mod cli_json;
mod cli_knot_cad;
mod cli_mesh_faces;
mod cli_mesh_normals;
mod cli_mesh_tessellated;
mod cli_npy;
mod cli_parquet;
mod cli_pp;
mod cli_query;
mod cli_robustness;
mod cli_surfaces;
mod common;
mod figures;

#[test]
fn every_test_file_is_a_module() {
    lekalo_testkit::assert_every_test_file_is_a_module(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/all"
    ));
}
