//! Functions `f(x)` typed as text, with exact derivatives of any order, for quasi-interpolation
//! of a user's function (`docs/theory/pp.md#quasi-interpolation`: the de Boor–Fix functionals
//! need `f^(r)(τ)`, `r < k`).
//!
//! The text is parsed into a tree (no code is ever executed); derivatives come from Taylor
//! arithmetic ("automatic differentiation" in Taylor mode: Griewank & Walther, *Evaluating
//! Derivatives*, 2nd ed., §13.2, Table 13.1 recurrences), exact up to rounding, unlike divided
//! differences whose error grows with the order. Hand-written because the grammar is small and
//! the recurrences are the point: no well-kept crate both parses and differentiates to order k.
//!
//! Grammar: numbers (`2`, `0.5`, `1e-3`), the variable `x` (or `t`), constants `pi` and `e`,
//! `+ - * /`, powers `^` (or `**`, right-associative), unary minus, parentheses and the
//! functions `sin cos tan exp ln log sqrt abs atan sinh cosh tanh`.

use crate::error::readable;
use crate::error::{Error, Result};
use crate::{Arg, What};

/// Longest expression text accepted.
pub const MAX_EXPRESSION_LEN: usize = 1000;
/// Deepest nesting of parentheses and operators accepted.
const MAX_DEPTH: usize = 64;
/// Highest derivative order [`Expression::derivatives`] computes.
pub const MAX_EXPRESSION_ORDER: usize = 32;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Func {
    Sin,
    Cos,
    Tan,
    Exp,
    Ln,
    Sqrt,
    Abs,
    Atan,
    Sinh,
    Cosh,
    Tanh,
}

const FUNCS: [(&str, Func); 12] = [
    ("sin", Func::Sin),
    ("cos", Func::Cos),
    ("tan", Func::Tan),
    ("exp", Func::Exp),
    ("ln", Func::Ln),
    ("log", Func::Ln),
    ("sqrt", Func::Sqrt),
    ("abs", Func::Abs),
    ("atan", Func::Atan),
    ("sinh", Func::Sinh),
    ("cosh", Func::Cosh),
    ("tanh", Func::Tanh),
];

#[derive(Debug, Clone, PartialEq)]
enum Node {
    Num(f64),
    X,
    Neg(Box<Node>),
    Bin(char, Box<Node>, Box<Node>),
    Call(Func, Box<Node>),
}

/// A parsed function of one variable `x`.
///
/// ```
/// use lekalo::Expression;
/// let f = Expression::parse("x*cos(x)")?;
/// // f, f', f'' at x = 0: 0, 1, 0; f''' = −3 at 0 (x cos x = x − x³/2 + …)
/// let d = f.derivatives(0.0, 3)?;
/// assert!((d[1] - 1.0).abs() < 1e-15 && (d[3] + 3.0).abs() < 1e-14);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Expression {
    root: Node,
}

fn syntax(reason: String) -> Error {
    Error::InvalidArgument {
        what: Arg::Expression.into(),
        reason,
    }
}

struct Parser<'a> {
    chars: Vec<char>,
    pos: usize,
    depth: usize,
    text: &'a str,
}

impl Parser<'_> {
    fn skip(&mut self) {
        while self.chars.get(self.pos).is_some_and(|c| c.is_whitespace()) {
            self.pos += 1;
        }
    }

    fn peek(&mut self) -> Option<char> {
        self.skip();
        self.chars.get(self.pos).copied()
    }

    fn eat(&mut self, c: char) -> bool {
        if self.peek() == Some(c) {
            self.pos += 1;
            true
        } else {
            false
        }
    }

    fn error(&self, what: &str) -> Error {
        syntax(format!(
            "{what} at character {} of \"{}\"; write e.g. x*cos(x), exp(-x^2), 1/(1+x^2)",
            self.pos + 1,
            self.text
        ))
    }

    fn enter(&mut self) -> Result<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(syntax(format!(
                "nested more than {MAX_DEPTH} levels deep; simplify the expression"
            )));
        }
        Ok(())
    }

    fn sum(&mut self) -> Result<Node> {
        self.enter()?;
        let mut left = self.product()?;
        while let Some(op @ ('+' | '-')) = self.peek() {
            self.pos += 1;
            let right = self.product()?;
            left = Node::Bin(op, Box::new(left), Box::new(right));
        }
        self.depth -= 1;
        Ok(left)
    }

    fn product(&mut self) -> Result<Node> {
        let mut left = self.unary()?;
        loop {
            self.skip();
            let op = match self.chars.get(self.pos..self.pos + 2) {
                Some(['*', '*']) => break,
                _ => match self.peek() {
                    Some(c @ ('*' | '/')) => c,
                    _ => break,
                },
            };
            self.pos += 1;
            let right = self.unary()?;
            left = Node::Bin(op, Box::new(left), Box::new(right));
        }
        Ok(left)
    }

    fn unary(&mut self) -> Result<Node> {
        self.enter()?;
        let node = if self.eat('-') {
            Node::Neg(Box::new(self.unary()?))
        } else if self.eat('+') {
            self.unary()?
        } else {
            self.power()?
        };
        self.depth -= 1;
        Ok(node)
    }

    fn power(&mut self) -> Result<Node> {
        let base = self.atom()?;
        self.skip();
        let is_pow = if self.chars.get(self.pos..self.pos + 2) == Some(&['*', '*']) {
            self.pos += 2;
            true
        } else {
            self.eat('^')
        };
        if is_pow {
            // right-associative, and -x^2 = -(x^2) while 2^-1 is allowed
            let exponent = self.unary()?;
            return Ok(Node::Bin('^', Box::new(base), Box::new(exponent)));
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Node> {
        match self.peek() {
            Some('(') => {
                self.pos += 1;
                let inner = self.sum()?;
                if !self.eat(')') {
                    return Err(self.error("missing \")\""));
                }
                Ok(inner)
            }
            Some(c) if c.is_ascii_digit() || c == '.' => self.number(),
            Some(c) if c.is_ascii_alphabetic() => {
                let start = self.pos;
                while self
                    .chars
                    .get(self.pos)
                    .is_some_and(|c| c.is_ascii_alphanumeric() || *c == '_')
                {
                    self.pos += 1;
                }
                let name: String = self.chars[start..self.pos].iter().collect();
                match name.as_str() {
                    "x" | "t" => return Ok(Node::X),
                    "pi" => return Ok(Node::Num(std::f64::consts::PI)),
                    "e" => return Ok(Node::Num(std::f64::consts::E)),
                    _ => {}
                }
                let Some(&(_, f)) = FUNCS.iter().find(|(n, _)| *n == name) else {
                    self.pos = start;
                    return Err(self.error(&format!(
                        "unknown name \"{name}\" (the variable is x; functions: sin cos tan exp ln sqrt abs atan sinh cosh tanh; constants: pi e)"
                    )));
                };
                if !self.eat('(') {
                    return Err(
                        self.error(&format!("\"{name}\" needs its argument in parentheses"))
                    );
                }
                let arg = self.sum()?;
                if !self.eat(')') {
                    return Err(self.error("missing \")\""));
                }
                Ok(Node::Call(f, Box::new(arg)))
            }
            Some(c) => Err(self.error(&format!("unexpected \"{c}\""))),
            None => Err(self.error("unexpected end")),
        }
    }

    fn number(&mut self) -> Result<Node> {
        let start = self.pos;
        let mut prev = ' ';
        while let Some(&c) = self.chars.get(self.pos) {
            let exp_sign = (c == '+' || c == '-') && (prev == 'e' || prev == 'E');
            if c.is_ascii_digit() || c == '.' || c == 'e' || c == 'E' || exp_sign {
                // `2e` followed by a non-digit is 2 times the constant e: stop before the `e`
                if (c == 'e' || c == 'E')
                    && !self
                        .chars
                        .get(self.pos + 1)
                        .is_some_and(|n| n.is_ascii_digit() || *n == '+' || *n == '-')
                {
                    break;
                }
                prev = c;
                self.pos += 1;
            } else {
                break;
            }
        }
        let text: String = self.chars[start..self.pos].iter().collect();
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Node::Num(v)),
            _ => {
                self.pos = start;
                Err(self.error(&format!("\"{text}\" is not a finite number")))
            }
        }
    }
}

impl Expression {
    /// Parses `text` (grammar in the module documentation).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] (about [`Arg::Expression`](crate::Arg::Expression)) naming the character where the text
    /// stops making sense, an unknown name, a text longer than [`MAX_EXPRESSION_LEN`] or nested
    /// too deeply.
    pub fn parse(text: &str) -> Result<Expression> {
        if text.len() > MAX_EXPRESSION_LEN {
            return Err(syntax(format!(
                "{} characters; at most {MAX_EXPRESSION_LEN}",
                text.len()
            )));
        }
        let mut p = Parser {
            chars: text.chars().collect(),
            pos: 0,
            depth: 0,
            text,
        };
        if p.peek().is_none() {
            return Err(syntax("empty; type a function of x, e.g. x*cos(x)".into()));
        }
        let root = p.sum()?;
        if p.peek().is_some() {
            let c = p.chars[p.pos];
            return Err(p.error(&format!("unexpected \"{c}\"")));
        }
        Ok(Expression { root })
    }

    /// `f(x)`.
    ///
    /// # Errors
    /// As [`Expression::derivatives`].
    pub fn eval(&self, x: f64) -> Result<f64> {
        Ok(self.derivatives(x, 0)?[0])
    }

    /// `f^(r)(x)` for `r = 0 ..= order`, by Taylor arithmetic (exact up to rounding).
    ///
    /// # Errors
    /// [`Error::NonFinite`] when `x` is NaN or infinite; [`Error::InvalidArgument`] (about
    /// [`Arg::Expression`], naming `x`) where the function or a derivative is undefined (a pole,
    /// `ln` of a non-positive number, `sqrt` of a negative one, `sqrt` or `abs` at 0 with a
    /// derivative, a power of 0 with a non-integer exponent) or beyond the range of `f64`;
    /// [`Error::TooLarge`] for `order > MAX_EXPRESSION_ORDER`.
    pub fn derivatives(&self, x: f64, order: usize) -> Result<Vec<f64>> {
        if order > MAX_EXPRESSION_ORDER {
            return Err(Error::TooLarge {
                what: What::of(Arg::Expression, "derivative order of an expression"),
                size: order,
                max: MAX_EXPRESSION_ORDER,
            });
        }
        if !x.is_finite() {
            return Err(Error::NonFinite {
                what: What::of(Arg::Expression, "x of the expression"),
                index: 0,
                value: x,
            });
        }
        let mut seed = vec![0.0; order + 1];
        seed[0] = x;
        if order > 0 {
            seed[1] = 1.0;
        }
        let jet = eval(&self.root, &seed).map_err(|e| undefined_at(x, e))?;
        let mut factorial = 1.0;
        let mut out = Vec::with_capacity(order + 1);
        for (r, c) in jet.iter().enumerate() {
            if r > 0 {
                factorial *= r as f64;
            }
            let v = c * factorial;
            if !v.is_finite() {
                let which = if r == 0 {
                    "its value".to_string()
                } else {
                    format!("its derivative of order {r}")
                };
                return Err(undefined_at(
                    x,
                    Error::InvalidArgument {
                        what: Arg::Expression.into(),
                        reason: format!("{which} is {v} (beyond the range of f64)"),
                    },
                ));
            }
            out.push(v);
        }
        Ok(out)
    }
}

/// An error of the expression's arithmetic at `x` as the argument's refusal naming `x` (`undefined
/// at x = 0: ln of 0 ...`), so that the caller's message says where the function fails.
fn undefined_at(x: f64, e: Error) -> Error {
    match e {
        Error::InvalidArgument { reason, .. } => Error::InvalidArgument {
            what: Arg::Expression.into(),
            reason: format!("undefined at x = {}: {reason}", readable(&x)),
        },
        other => other,
    }
}

/// Taylor coefficients `a_k = f^(k)(x₀)/k!` of a node, given those of `x`.
fn eval(node: &Node, x: &[f64]) -> Result<Vec<f64>> {
    let n = x.len();
    Ok(match node {
        Node::Num(v) => {
            let mut c = vec![0.0; n];
            c[0] = *v;
            c
        }
        Node::X => x.to_vec(),
        Node::Neg(a) => eval(a, x)?.iter().map(|v| -v).collect(),
        Node::Bin(op, a, b) => {
            let (a, b) = (eval(a, x)?, eval(b, x)?);
            match op {
                '+' => a.iter().zip(&b).map(|(p, q)| p + q).collect(),
                '-' => a.iter().zip(&b).map(|(p, q)| p - q).collect(),
                '*' => mul(&a, &b),
                '/' => div(&a, &b)?,
                _ => pow(&a, &b)?,
            }
        }
        Node::Call(f, a) => call(*f, &eval(a, x)?)?,
    })
}

fn mul(a: &[f64], b: &[f64]) -> Vec<f64> {
    (0..a.len())
        .map(|k| (0..=k).map(|j| a[j] * b[k - j]).sum())
        .collect()
}

fn div(a: &[f64], b: &[f64]) -> Result<Vec<f64>> {
    if b[0] == 0.0 {
        return Err(Error::InvalidArgument {
            what: Arg::Expression.into(),
            reason: "division by zero".into(),
        });
    }
    let mut c = vec![0.0; a.len()];
    for k in 0..a.len() {
        let s: f64 = (1..=k).map(|j| b[j] * c[k - j]).sum();
        c[k] = (a[k] - s) / b[0];
    }
    Ok(c)
}

fn is_const(a: &[f64]) -> bool {
    a[1..].iter().all(|&v| v == 0.0)
}

fn pow(a: &[f64], b: &[f64]) -> Result<Vec<f64>> {
    let n = a.len();
    if is_const(b) {
        let e = b[0];
        // small non-negative integer powers by products: exact, and defined at a = 0
        if let Some(times) = (0..=64u32).find(|&m| f64::from(m) == e) {
            let mut r = vec![0.0; n];
            r[0] = 1.0;
            for _ in 0..times {
                r = mul(&r, a);
            }
            return Ok(r);
        }
        if a[0] == 0.0 {
            if n == 1 && e > 0.0 {
                return Ok(vec![0.0]);
            }
            return Err(Error::InvalidArgument {
                what: Arg::Expression.into(),
                reason: format!(
                    "0^{e} has no derivative here; move the point off 0",
                    e = readable(&e)
                ),
            });
        }
        // p = a^e: k a₀ p_k = Σ_{j=1..k} ((e + 1) j − k) a_j p_{k−j}  (Griewank–Walther Table 13.1)
        let mut p = vec![0.0; n];
        p[0] = a[0].powf(e);
        for k in 1..n {
            let s: f64 = (1..=k)
                .map(|j| ((e + 1.0) * j as f64 - k as f64) * a[j] * p[k - j])
                .sum();
            p[k] = s / (k as f64 * a[0]);
        }
        return Ok(p);
    }
    // a^b = exp(b ln a)
    Ok(exp(&mul(b, &ln(a)?)))
}

fn exp(a: &[f64]) -> Vec<f64> {
    let mut e = vec![0.0; a.len()];
    e[0] = a[0].exp();
    for k in 1..a.len() {
        let s: f64 = (1..=k).map(|j| j as f64 * a[j] * e[k - j]).sum();
        e[k] = s / k as f64;
    }
    e
}

fn ln(a: &[f64]) -> Result<Vec<f64>> {
    if a[0] <= 0.0 {
        return Err(Error::InvalidArgument {
            what: Arg::Expression.into(),
            reason: format!(
                "ln of {} (a logarithm needs a positive argument)",
                readable(&a[0])
            ),
        });
    }
    let mut l = vec![0.0; a.len()];
    l[0] = a[0].ln();
    for k in 1..a.len() {
        let s: f64 = (1..k).map(|j| j as f64 * l[j] * a[k - j]).sum();
        l[k] = (a[k] - s / k as f64) / a[0];
    }
    Ok(l)
}

/// `(sin a, cos a)` together (each recurrence needs the other).
fn sin_cos(a: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = a.len();
    let (mut s, mut c) = (vec![0.0; n], vec![0.0; n]);
    (s[0], c[0]) = a[0].sin_cos();
    for k in 1..n {
        let (mut ss, mut cc) = (0.0, 0.0);
        for j in 1..=k {
            ss += j as f64 * a[j] * c[k - j];
            cc += j as f64 * a[j] * s[k - j];
        }
        s[k] = ss / k as f64;
        c[k] = -cc / k as f64;
    }
    (s, c)
}

/// `∫ q` with value `v0` at the point: coefficients `t_k = q_{k−1}/k`.
fn integrate(v0: f64, q: &[f64]) -> Vec<f64> {
    let mut t = vec![v0];
    t.extend(q.iter().enumerate().map(|(k, v)| v / (k + 1) as f64));
    t
}

/// Derivative's coefficients `a'_k = (k + 1) a_{k+1}` (one order fewer).
fn derivative(a: &[f64]) -> Vec<f64> {
    (1..a.len()).map(|k| k as f64 * a[k]).collect()
}

fn call(f: Func, a: &[f64]) -> Result<Vec<f64>> {
    let n = a.len();
    Ok(match f {
        Func::Sin => sin_cos(a).0,
        Func::Cos => sin_cos(a).1,
        Func::Tan => {
            let (s, c) = sin_cos(a);
            div(&s, &c)?
        }
        Func::Exp => exp(a),
        Func::Ln => ln(a)?,
        Func::Sqrt => {
            if a[0] < 0.0 || (a[0] == 0.0 && n > 1) {
                return Err(Error::InvalidArgument {
                    what: Arg::Expression.into(),
                    reason: format!(
                        "sqrt of {} has no {}; keep its argument positive",
                        a[0],
                        if a[0] < 0.0 {
                            "real value"
                        } else {
                            "derivative"
                        }
                    ),
                });
            }
            let mut r = vec![0.0; n];
            r[0] = a[0].sqrt();
            for k in 1..n {
                let s: f64 = (1..k).map(|j| r[j] * r[k - j]).sum();
                r[k] = (a[k] - s) / (2.0 * r[0]);
            }
            r
        }
        Func::Abs => {
            if a[0] == 0.0 && n > 1 {
                return Err(Error::InvalidArgument {
                    what: Arg::Expression.into(),
                    reason: "abs has no derivative where its argument is 0; put the breakpoints there or move the function".into(),
                });
            }
            let s = a[0].signum();
            a.iter().map(|v| s * v).collect()
        }
        Func::Atan => {
            // atan' = a'/(1 + a²)
            if n == 1 {
                return Ok(vec![a[0].atan()]);
            }
            let short = &a[..n - 1];
            let mut one_plus = mul(short, short);
            one_plus[0] += 1.0;
            integrate(a[0].atan(), &div(&derivative(a), &one_plus)?)
        }
        Func::Sinh | Func::Cosh | Func::Tanh => {
            let ep = exp(a);
            let neg: Vec<f64> = a.iter().map(|v| -v).collect();
            let em = exp(&neg);
            let sinh: Vec<f64> = ep.iter().zip(&em).map(|(p, m)| (p - m) / 2.0).collect();
            let cosh: Vec<f64> = ep.iter().zip(&em).map(|(p, m)| (p + m) / 2.0).collect();
            match f {
                Func::Sinh => sinh,
                Func::Cosh => cosh,
                _ => div(&sinh, &cosh)?,
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * (1.0 + b.abs())
    }

    #[test]
    fn derivatives_match_closed_forms() {
        let x = 0.7_f64;
        let cases: Vec<(&str, Vec<f64>)> = vec![
            ("x*cos(x)", {
                // (x cos x)^(r) = x cos(x + rπ/2) + r cos(x + (r−1)π/2)
                let h = std::f64::consts::FRAC_PI_2;
                (0..6)
                    .map(|r| {
                        let rf = r as f64;
                        x * (x + rf * h).cos() + rf * (x + (rf - 1.0) * h).cos()
                    })
                    .collect()
            }),
            (
                "exp(2*x)",
                (0..6).map(|r| 2f64.powi(r) * (2.0 * x).exp()).collect(),
            ),
            (
                "ln(x)",
                vec![
                    x.ln(),
                    1.0 / x,
                    -1.0 / (x * x),
                    2.0 / x.powi(3),
                    -6.0 / x.powi(4),
                ],
            ),
            (
                "sqrt(x)",
                vec![
                    x.sqrt(),
                    0.5 / x.sqrt(),
                    -0.25 * x.powf(-1.5),
                    0.375 * x.powf(-2.5),
                ],
            ),
            (
                "x^3 - 2*x",
                vec![x.powi(3) - 2.0 * x, 3.0 * x * x - 2.0, 6.0 * x, 6.0, 0.0],
            ),
            ("1/(1+x^2)", {
                let q = 1.0 + x * x;
                vec![1.0 / q, -2.0 * x / (q * q), (6.0 * x * x - 2.0) / q.powi(3)]
            }),
            ("atan(x)", {
                let q = 1.0 + x * x;
                vec![x.atan(), 1.0 / q, -2.0 * x / (q * q)]
            }),
            ("tan(x)", {
                let t = x.tan();
                vec![t, 1.0 + t * t, 2.0 * t * (1.0 + t * t)]
            }),
            ("x^x", vec![x.powf(x), x.powf(x) * (x.ln() + 1.0)]),
            (
                "cosh(x) - sinh(x)",
                (0..5).map(|r| (-1f64).powi(r) * (-x).exp()).collect(),
            ),
            ("-x^2", vec![-x * x, -2.0 * x, -2.0]),
            (
                "2^-1 + e - pi",
                vec![0.5 + std::f64::consts::E - std::f64::consts::PI, 0.0],
            ),
        ];
        for (text, want) in cases {
            let f = Expression::parse(text).unwrap();
            let got = f.derivatives(x, want.len() - 1).unwrap();
            for (r, (g, w)) in got.iter().zip(&want).enumerate() {
                assert!(close(*g, *w), "{text}: derivative {r} = {g}, expected {w}");
            }
        }
    }

    #[test]
    fn bad_texts_are_named_errors() {
        for (text, needle) in [
            ("", "empty"),
            ("x +", "unexpected end"),
            ("foo(x)", "unknown name \"foo\""),
            ("sin x", "parentheses"),
            ("(x", "missing"),
            ("x $ 2", "unexpected \"$\""),
            ("1e999", "not a finite number"),
        ] {
            let e = Expression::parse(text).unwrap_err().to_string();
            assert!(e.contains(needle), "{text:?}: {e}");
        }
        let deep = format!("{}x{}", "(".repeat(200), ")".repeat(200));
        let e = Expression::parse(&deep).unwrap_err().to_string();
        assert!(e.contains("nested"), "{e}");
        assert!(Expression::parse(&"x+".repeat(600)).is_err(), "too long");
    }

    #[test]
    fn domain_errors_are_reported() {
        // each names x, the operation and why, about the expression
        let e = Expression::parse("1/x").unwrap().eval(0.0).unwrap_err();
        assert_eq!(
            (e.to_string(), e.arg()),
            (
                "invalid expression: undefined at x = 0: division by zero".into(),
                Some(Arg::Expression)
            )
        );
        let e = Expression::parse("ln(x)").unwrap().eval(-1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid expression: undefined at x = -1: ln of -1 (a logarithm needs a positive argument)"
        );
        let e = Expression::parse("sqrt(x)")
            .unwrap()
            .derivatives(0.0, 1)
            .unwrap_err();
        assert!(e.to_string().contains("sqrt"), "{e}");
        let f = Expression::parse("x").unwrap();
        assert!(f.eval(f64::NAN).is_err(), "NaN x");
        assert!(
            f.derivatives(0.0, MAX_EXPRESSION_ORDER + 1).is_err(),
            "order limit"
        );
    }
}
