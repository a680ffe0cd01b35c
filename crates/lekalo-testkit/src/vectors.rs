//! Test vectors of the documents, written once for every crate's tests.

/// Interpolation through the five points of P&T Example 9.1 (document 000 has no numeric
/// example; docs/theory/interpolation.md#test-vectors): the points, their chord-length
/// parameters and the reference interpolants. Irrational values have six decimals: compare them
/// with [`example_9_1::DECIMALS`].
pub mod example_9_1 {
    /// Tolerance of the six-decimal reference values.
    pub const DECIMALS: f64 = 1e-6;

    /// The points `q = (0,0), (3,4), (-1,4), (-4,0), (-4,-3)`; their chords have lengths 5, 4, 5,
    /// 3 (total 17).
    pub const POINTS: [[f64; 2]; 5] = [
        [0.0, 0.0],
        [3.0, 4.0],
        [-1.0, 4.0],
        [-4.0, 0.0],
        [-4.0, -3.0],
    ];

    /// [`POINTS`] coordinate after coordinate, point after point.
    pub const POINTS_FLAT: [f64; 10] = [0.0, 0.0, 3.0, 4.0, -1.0, 4.0, -4.0, 0.0, -4.0, -3.0];

    /// [`POINTS`] as a whitespace-separated text file, one point a line.
    pub const POINTS_TEXT: &str = "0 0\n3 4\n-1 4\n-4 0\n-4 -3\n";

    /// Chord-length parameters `0, 5/17, 9/17, 14/17, 1`.
    pub const CHORD_PARAMETERS: [f64; 5] = [0.0, 5.0 / 17.0, 9.0 / 17.0, 14.0 / 17.0, 1.0];

    /// Free-end quadratic on the chord-length parameters: averaged knots `0³, 7/17, 23/34, 1³`.
    pub const QUADRATIC_CHORD_KNOTS: [f64; 8] =
        [0.0, 0.0, 0.0, 7.0 / 17.0, 23.0 / 34.0, 1.0, 1.0, 1.0];

    /// Free-end quadratic on the chord-length parameters: its control points.
    pub const QUADRATIC_CHORD_CONTROL: [[f64; 2]; 5] = [
        [0.0, 0.0],
        [5.767270, 4.323172],
        [-1.627371, 4.418936],
        [-4.616510, -0.163975],
        [-4.0, -3.0],
    ];

    /// Free-end cubic on the chord-length parameters: its values `r(t)` at `t = 1/4, 1/2, 3/4`.
    pub const CUBIC_CHORD_VALUES: [(f64, [f64; 2]); 3] = [
        (0.25, [3.407028, 3.663345]),
        (0.5, [-0.474156, 4.175193]),
        (0.75, [-3.627509, 1.253884]),
    ];
}
