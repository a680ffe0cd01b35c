//! A linear function of the coefficients of a shape-constrained fit and of the auxiliary
//! variables of its cones, local to a knot span: the rows of the cone program
//! (`docs/theory/fitting.md#shape-constraints`; crate-private).

/// A linear function of the variables, `g(x) = Σ coef_i x_{first+i} + aux_coef·x_aux + constant`.
#[derive(Debug, Clone)]
pub(crate) struct Row {
    pub(crate) first: usize,
    pub(crate) coef: Vec<f64>,
    /// An auxiliary variable (index among the auxiliaries) and its coefficient.
    pub(crate) aux: Option<(usize, f64)>,
    pub(crate) constant: f64,
}

impl Row {
    /// `f·g`.
    pub(super) fn scale(&mut self, f: f64) {
        self.coef.iter_mut().for_each(|v| *v *= f);
        if let Some((_, a)) = &mut self.aux {
            *a *= f;
        }
        self.constant *= f;
    }

    /// The largest coefficient in absolute value (the auxiliary's included).
    pub(crate) fn max_abs(&self) -> f64 {
        let a = self.aux.map_or(0.0, |(_, a)| a.abs());
        self.coef.iter().fold(a, |m, v| m.max(v.abs()))
    }

    /// `g(x)` at the variables `x` (coefficients, then auxiliaries from `n`).
    pub(crate) fn eval(&self, x: &[f64], n: usize) -> f64 {
        let mut s = self.constant;
        for (i, c) in self.coef.iter().enumerate() {
            s += c * x[self.first + i];
        }
        if let Some((k, a)) = self.aux {
            s += a * x[n + k];
        }
        s
    }
}

/// `a + f·b` for two rows of the same columns (no auxiliary).
pub(crate) fn add_rows(a: &Row, b: &Row, f: f64) -> Row {
    Row {
        first: a.first,
        coef: a.coef.iter().zip(&b.coef).map(|(x, y)| x + f * y).collect(),
        aux: None,
        constant: a.constant + f * b.constant,
    }
}
