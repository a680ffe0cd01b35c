use super::grid_params::{chord_params, chord_params_body, line_params};
use super::*;

/// The bit patterns of `v`, for comparisons that must be exact.
#[cfg(target_arch = "x86_64")]
fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}
use crate::interpolate::collocation::solve_collocation;

/// A wavy `nu × nv` grid in `dim` dimensions, offset by `offset`, rows along the first
/// coordinate and columns along the second.
fn wavy(nu: usize, nv: usize, dim: usize, offset: f64) -> Vec<f64> {
    let mut data = Vec::with_capacity(nu * nv * dim);
    for k in 0..nu {
        for l in 0..nv {
            let (x, y) = (k as f64, l as f64);
            let i = (k * nv + l) as f64;
            let coords = [
                x + 0.3 * (1.7 * i).sin(),
                y + 0.2 * (0.9 * i).cos(),
                (0.5 * x).sin() * (0.3 * y).cos(),
                0.1 * x * y,
            ];
            data.extend((0..dim).map(|c| coords[c % 4] + offset));
        }
    }
    data
}

#[test]
fn one_pass_chord_parameters_equal_the_line_loops() {
    for (nu, nv, dim) in [(2, 2, 1), (5, 3, 3), (17, 11, 2), (40, 7, 3), (3, 9, 4)] {
        // scales whose squared steps are subnormal or overflow take the scaled distances
        for (offset, scale) in [(0.0, 1.0), (1e8, 1.0), (0.0, 1e-160), (0.0, 1e155)] {
            let data: Vec<f64> = wavy(nu, nv, dim, offset)
                .iter()
                .map(|x| x * scale)
                .collect();
            let (mut fu, mut fv) = (vec![0.0; nu], vec![0.0; nv]);
            assert!(
                chord_params(&data, nu, nv, dim, &mut fu, &mut fv),
                "{nu}×{nv}"
            );
            let (mut gu, mut gv) = (vec![0.0; nu], vec![0.0; nv]);
            line_params(&data, nu, nv, dim, 1.0, &mut gu, &mut gv).unwrap();
            assert_eq!(fu, gu, "ū sums, {nu}×{nv}×{dim}, scale {scale:e}");
            assert_eq!(fv, gv, "v̄ sums, {nu}×{nv}×{dim}, scale {scale:e}");
            #[cfg(target_arch = "x86_64")]
            if crate::numeric::isa::has_avx2() {
                let (mut base_u, mut base_v) = (vec![0.0; nu], vec![0.0; nv]);
                assert!(chord_params_body(
                    &data,
                    nu,
                    nv,
                    dim,
                    &mut base_u,
                    &mut base_v
                ));
                // `chord_params` took the AVX2 copy: the same bits as the baseline body
                assert_eq!(bits(&fu), bits(&base_u), "AVX2 ū, {nu}×{nv}×{dim}");
                assert_eq!(bits(&fv), bits(&base_v), "AVX2 v̄, {nu}×{nv}×{dim}");
            }
        }
    }
    // a zero step down a column, then along a row, declines (the line loops report it)
    let mut data = wavy(3, 2, 1, 0.0);
    data[4] = data[2];
    let (mut u, mut v) = (vec![0.0; 3], vec![0.0; 2]);
    assert!(!chord_params(&data, 3, 2, 1, &mut u, &mut v));
    let mut data = wavy(2, 3, 1, 0.0);
    data[2] = data[1];
    let (mut u, mut v) = (vec![0.0; 2], vec![0.0; 3]);
    assert!(!chord_params(&data, 2, 3, 1, &mut u, &mut v));
    // an infinite coordinate declines too
    let mut data = wavy(3, 3, 2, 0.0);
    data[7] = f64::INFINITY;
    let (mut u, mut v) = (vec![0.0; 3], vec![0.0; 3]);
    assert!(!chord_params(&data, 3, 3, 2, &mut u, &mut v));
}

/// The pass-by-pass solve of document 000 §5 (P&T A9.4 order): every column along `u`
/// (all `nv·dim` numbers of a row as right-hand sides), then every row along `v`, each by
/// [`solve_collocation`] with its own factorisation, on the grid centred on `q_00`.
fn pass_by_pass(
    s: &BSplineSurface,
    report: &SurfaceInterpolationReport,
    data: &[f64],
    dim: usize,
) -> Vec<f64> {
    let (nu, nv) = s.net_size();
    let reference = data[..dim].to_vec();
    let mut control: Vec<f64> = data
        .chunks_exact(dim)
        .flat_map(|q| q.iter().zip(&reference).map(|(x, r)| x - r))
        .collect();
    let (p, q) = s.degree();
    let (knots_u, knots_v) = s.knots();
    solve_collocation(
        knots_u,
        p,
        report.params_u(),
        0,
        &mut control,
        nv * dim,
        Factors::Discard,
    )
    .unwrap();
    for block in control.chunks_exact_mut(nv * dim).take(nu) {
        solve_collocation(
            knots_v,
            q,
            report.params_v(),
            0,
            block,
            dim,
            Factors::Discard,
        )
        .unwrap();
    }
    for c in control.chunks_exact_mut(dim) {
        for (x, r) in c.iter_mut().zip(&reference) {
            *x += r;
        }
    }
    control
}

#[test]
fn two_sweeps_agree_with_the_pass_by_pass_solve() {
    let cases = [
        (7, 5, 3, 3, 2),
        (40, 33, 3, 3, 3),
        (12, 9, 2, 2, 4),
        (9, 12, 4, 5, 1),
        (6, 8, 1, 1, 3),
        (30, 4, 3, 4, 3),
    ];
    for (nu, nv, dim, p, q) in cases {
        for (offset, param) in [
            (0.0, Parametrization::ChordLength),
            (1e6, Parametrization::ChordLength),
            (0.0, Parametrization::Centripetal),
            (0.0, Parametrization::Uniform),
        ] {
            let data = wavy(nu, nv, dim, offset);
            let grid = Points::from_flat(dim, data.clone()).unwrap();
            let (s, report) = SurfaceInterpolation::new(p, q)
                .parametrization(param)
                .interpolate_with_report(grid.as_view(), nu, nv)
                .unwrap();
            let reference = pass_by_pass(&s, &report, &data, dim);
            let scale = reference.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let worst = s
                .control_points()
                .as_slice()
                .iter()
                .zip(&reference)
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(
                worst <= 1e-14 * scale,
                "{nu}×{nv}×{dim}, degrees ({p}, {q}), offset {offset}, {param:?}: \
                 {worst:e} of {scale:e}"
            );
            // the interpolation took the AVX2 copy of the sweeps: the same bits as the
            // baseline body
            #[cfg(target_arch = "x86_64")]
            if crate::numeric::isa::has_avx2() {
                let (knots_u, knots_v) = s.knots();
                let lu_u =
                    factor_collocation(knots_u, p, report.params_u(), Factors::Keep).unwrap();
                let lu_v =
                    factor_collocation(knots_v, q, report.params_v(), Factors::Keep).unwrap();
                let base = solve_grid_body(&data, nu, nv, dim, &lu_u, &lu_v).unwrap();
                assert_eq!(
                    bits(s.control_points().as_slice()),
                    bits(&base),
                    "AVX2 net, {nu}×{nv}×{dim}, degrees ({p}, {q}), {param:?}"
                );
            }
        }
    }
}

#[test]
fn small_block_solve_equals_the_general_loop() {
    // BandedCrout::solve's fixed kernels against its general loop, bit for bit, on the
    // collocation factors of both directions of a grid
    let (nu, nv, dim) = (23, 19, 3);
    let data = wavy(nu, nv, dim, 0.0);
    let grid = Points::from_flat(dim, data.clone()).unwrap();
    for (p, nc) in [(3, 3), (2, 3), (3, 1), (2, 2), (3, 4), (5, 3)] {
        let (s, report) = SurfaceInterpolation::new(p, p)
            .interpolate_with_report(grid.as_view(), nu, nv)
            .unwrap();
        let lu = factor_collocation(s.knots_v(), p, report.params_v(), Factors::Keep).unwrap();
        let rhs: Vec<f64> = (0..nv * nc).map(|i| (0.37 * i as f64).sin()).collect();
        let mut fast = rhs.clone();
        lu.solve(&mut fast, nc);
        let mut general = rhs;
        lu.solve_general(&mut general, nc);
        assert_eq!(
            fast,
            general,
            "degree {p}, {nc} columns, band ({}, {})",
            lu.kl(),
            lu.ku()
        );
    }
}
