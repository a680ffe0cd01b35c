//! Maps of 3-D coordinates, `x ↦ R x + t`: the placement of a STEP `AXIS2_PLACEMENT_3D`
//! (ISO 10303-42 §4.4.3) as the rigid map from its frame's coordinates to its space's,
//! composed and inverted to carry a part of an assembly into the file's frame
//! (`step_read/assembly.rs`); an IGES transformation matrix (entity 124, IGES 5.3 §4.21) as the
//! matrix the file gives, chained to the matrix that one points at (`iges/read.rs`). A B-spline
//! or NURBS follows an affine map of its control points (affine invariance, The NURBS Book
//! §4.2), so moving the points moves the curve or surface exactly.

/// A map `x ↦ R x + t` of 3-D coordinates: rigid for STEP placements (`R` orthonormal), as
/// written for IGES matrices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Motion {
    /// Rows of `R`.
    r: [[f64; 3]; 3],
    t: [f64; 3],
}

impl Motion {
    pub(crate) const IDENTITY: Motion = Motion {
        r: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        t: [0.0; 3],
    };

    /// The motion from a frame's coordinates to those of the space it is placed in: the
    /// columns of `R` are the frame's axes, `t` its origin.
    pub(crate) fn of(p: &lekalo::surface::Placement) -> Motion {
        let (x, y, z) = (p.x, p.y, p.z);
        Motion {
            r: [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]],
            t: p.origin,
        }
    }

    /// The map of the rows `r` of `R` and the translation `t`, as a file gives them.
    pub(crate) fn affine(r: [[f64; 3]; 3], t: [f64; 3]) -> Motion {
        Motion { r, t }
    }

    /// `x ↦ Rᵀ (x − t)`, for a rigid motion (`R` orthonormal).
    pub(crate) fn inverse(&self) -> Motion {
        let r = &self.r;
        let rt = [
            [r[0][0], r[1][0], r[2][0]],
            [r[0][1], r[1][1], r[2][1]],
            [r[0][2], r[1][2], r[2][2]],
        ];
        let t = rotate(&rt, self.t);
        Motion {
            r: rt,
            t: [-t[0], -t[1], -t[2]],
        }
    }

    /// `outer ∘ self`.
    pub(crate) fn then(&self, outer: &Motion) -> Motion {
        let mut r = [[0.0; 3]; 3];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (0..3).map(|k| outer.r[i][k] * self.r[k][j]).sum();
            }
        }
        let t = rotate(&outer.r, self.t);
        Motion {
            r,
            t: [t[0] + outer.t[0], t[1] + outer.t[1], t[2] + outer.t[2]],
        }
    }

    /// Moves a point (3-D; other dimensions are left alone).
    pub(crate) fn point(&self, p: &mut [f64]) {
        if let Ok(q) = <[f64; 3]>::try_from(&*p) {
            let m = rotate(&self.r, q);
            p.copy_from_slice(&[m[0] + self.t[0], m[1] + self.t[1], m[2] + self.t[2]]);
        }
    }

    /// Turns a direction (3-D; other dimensions are left alone).
    pub(crate) fn direction(&self, d: &mut [f64]) {
        if let Ok(q) = <[f64; 3]>::try_from(&*d) {
            d.copy_from_slice(&rotate(&self.r, q));
        }
    }
}

fn rotate(r: &[[f64; 3]; 3], x: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| r[i][0] * x[0] + r[i][1] * x[1] + r[i][2] * x[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn motions_compose_and_invert() {
        let p = lekalo::surface::Placement::new(
            [1.0, 2.0, 3.0],
            Some([0.0, 0.0, 1.0]),
            Some([0.0, 1.0, 0.0]),
        )
        .expect("placement");
        let m = Motion::of(&p);
        let mut x = [1.0, 0.0, 0.0];
        m.point(&mut x);
        // the frame's x axis is the space's y
        assert_eq!(x, [1.0, 3.0, 3.0]);
        m.inverse().point(&mut x);
        assert!(x
            .iter()
            .zip([1.0, 0.0, 0.0])
            .all(|(a, b)| (a - b).abs() < 1e-15));
        let twice = m.then(&m);
        let mut y = [0.0; 3];
        twice.point(&mut y);
        let mut z = [0.0; 3];
        m.point(&mut z);
        m.point(&mut z);
        assert_eq!(y, z);
    }
}
