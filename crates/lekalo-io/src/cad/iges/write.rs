//! Writing IGES: curves (entity 126) and surfaces (entity 128) as Directory Entry and Parameter
//! Data records of 80 columns (IGES 5.3 §2.2, §4.23, §4.24).

use std::fmt::Write as _;

use crate::error::{IoError, IoResult};
use crate::object::Object;
use crate::shape::Surface;
use crate::step::step_real;

/// Builds one IGES file from curves and surfaces.
#[derive(Debug, Clone, Default)]
pub struct IgesWriter {
    /// `(entity type, form, parameter text, status number)` per entity.
    pub(super) entities: Vec<(u32, u32, Vec<String>, &'static str)>,
}

/// The status number of an independent entity (IGES 5.3 §2.2.4.4.9: visible, independent,
/// geometry use, top-down).
pub(super) const INDEPENDENT: &str = "00000000";

fn pad3(p: &[f64]) -> [f64; 3] {
    let mut c = [0.0; 3];
    c[..p.len()].copy_from_slice(p);
    c
}

fn check_dim(dim: usize) -> IoResult<()> {
    if dim == 0 || dim > 3 {
        return Err(IoError::Unsupported {
            what: format!(
                "IGES holds points in 1 to 3 dimensions, these have {dim}; project the data first"
            ),
        });
    }
    Ok(())
}

impl IgesWriter {
    /// An empty file.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a curve as entity 126.
    ///
    /// # Errors
    /// [`IoError::Unsupported`] for points of dimension above 3.
    pub fn add_object(&mut self, obj: &Object) -> IoResult<()> {
        let t = Self::curve_params(obj)?;
        self.push(126, t, INDEPENDENT);
        Ok(())
    }

    /// Appends an entity of form 0; returns its directory entry's sequence number.
    pub(crate) fn push(&mut self, ty: u32, params: Vec<String>, status: &'static str) -> usize {
        self.entities.push((ty, 0, params, status));
        2 * self.entities.len() - 1
    }

    /// The parameters of entity 126 for `obj`.
    pub(crate) fn curve_params(obj: &Object) -> IoResult<Vec<String>> {
        check_dim(obj.dim())?;
        let p = obj.degree();
        let knots = obj.knots();
        let ctrl = obj.control_points();
        let n = ctrl.len();
        let weights = obj.weights();
        let (a, b) = obj.domain();
        let mut t: Vec<String> = vec!["126".into(), (n - 1).to_string(), p.to_string()];
        let planar = ctrl.dim() < 3 || ctrl.iter().all(|q| q[2] == 0.0);
        t.extend(
            [usize::from(planar), 0, usize::from(weights.is_none()), 0].map(|x| x.to_string()),
        );
        t.extend(knots.as_slice().iter().map(|&x| step_real(x)));
        match &weights {
            Some(w) => t.extend(w.iter().map(|&x| step_real(x))),
            None => t.extend(std::iter::repeat_n("1.".to_string(), n)),
        }
        for q in ctrl.iter() {
            t.extend(pad3(q).iter().map(|&x| step_real(x)));
        }
        t.extend([step_real(a), step_real(b)]);
        t.extend(["0.", "0.", if planar { "1." } else { "0." }].map(String::from));
        Ok(t)
    }

    /// Adds a surface as entity 128.
    ///
    /// # Errors
    /// [`IoError::Unsupported`] for points of dimension above 3.
    pub fn add_surface(&mut self, s: &Surface) -> IoResult<()> {
        let t = Self::surface_params(s)?;
        self.push(128, t, INDEPENDENT);
        Ok(())
    }

    /// The parameters of entity 128 for `s`.
    pub(crate) fn surface_params(s: &Surface) -> IoResult<Vec<String>> {
        check_dim(s.dim())?;
        let (pu, pv) = s.degrees();
        let (nu, nv) = s.net_size();
        let (ku, kv) = s.knots();
        let ctrl = s.control_points();
        let weights = s.weights();
        let ((u0, u1), (v0, v1)) = s.domain();
        let mut t: Vec<String> = vec!["128".into()];
        t.extend(
            [
                nu - 1,
                nv - 1,
                pu,
                pv,
                0,
                0,
                usize::from(weights.is_none()),
                0,
                0,
            ]
            .map(|x| x.to_string()),
        );
        t.extend(
            ku.as_slice()
                .iter()
                .chain(kv.as_slice())
                .map(|&x| step_real(x)),
        );
        // u varies fastest
        for j in 0..nv {
            for i in 0..nu {
                t.push(
                    weights
                        .as_ref()
                        .map_or_else(|| "1.".to_string(), |w| step_real(w[i * nv + j])),
                );
            }
        }
        for j in 0..nv {
            for i in 0..nu {
                t.extend(pad3(ctrl.point(i * nv + j)).iter().map(|&x| step_real(x)));
            }
        }
        t.extend([u0, u1, v0, v1].map(step_real));
        Ok(t)
    }

    /// The complete file; `name` is the file name in the Global section, `timestamp` its date
    /// (`YYYYMMDD.HHNNSS`; pass a fixed value for reproducible files).
    #[must_use]
    pub fn finish(&self, name: &str, timestamp: &str) -> String {
        let mut out = String::new();
        let line = |out: &mut String, text: &str, section: char, seq: usize| {
            let _ = writeln!(out, "{text:<72}{section}{seq:>7}");
        };
        line(&mut out, "lekalo spline export", 'S', 1);
        let h = |s: &str| hollerith(s);
        let max_coord = self
            .entities
            .iter()
            .flat_map(|(_, _, t, _)| t.iter().filter_map(|x| x.parse::<f64>().ok()))
            .fold(0.0_f64, |m, x| m.max(x.abs()));
        let global = [
            h(","),
            h(";"),
            h(name),
            h(name),
            h("lekalo"),
            h(env!("CARGO_PKG_VERSION")),
            "32".into(),
            "308".into(),
            "15".into(),
            "308".into(),
            "15".into(),
            h(name),
            "1.".into(),
            "2".into(),
            h("MM"),
            "1".into(),
            "1.".into(),
            h(timestamp),
            "1.E-10".into(),
            step_real(max_coord),
            h("lekalo"),
            h(""),
            "11".into(),
            "0".into(),
            h(timestamp),
        ];
        let glines = pack(&global, 72);
        for (k, g) in glines.iter().enumerate() {
            line(&mut out, g, 'G', k + 1);
        }
        // parameter lines first (to know the pointers), then the directory
        let mut dir = String::new();
        let mut par = String::new();
        let mut pseq = 1;
        for (k, (ty, form, t, status)) in self.entities.iter().enumerate() {
            let de = 2 * k + 1;
            let lines = pack(t, 64);
            let start = pseq;
            for l in &lines {
                let _ = writeln!(par, "{l:<64}{de:>8}P{pseq:>7}");
                pseq += 1;
            }
            let _ = writeln!(
                dir,
                "{ty:>8}{start:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{status:>8}D{de:>7}",
                0, 0, 0, 0, 0, 0
            );
            let _ = writeln!(
                dir,
                "{ty:>8}{:>8}{:>8}{:>8}{form:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}",
                0,
                0,
                lines.len(),
                "",
                "",
                "",
                0,
                de + 1
            );
        }
        out.push_str(&dir);
        out.push_str(&par);
        let t = format!(
            "S{:>7}G{:>7}D{:>7}P{:>7}",
            1,
            glines.len(),
            2 * self.entities.len(),
            pseq - 1
        );
        line(&mut out, &t, 'T', 1);
        out
    }
}

/// Tokens joined by `,` (the last followed by `;`), packed into lines of at most `width`
/// characters without splitting a token.
/// A Hollerith string `nHtext` of printable ASCII: the count is of bytes and the file's columns
/// are bytes, so any other character (non-ASCII, a control such as a newline) is written `?`,
/// as STEP strings are ([`crate::cad::step`]).
fn hollerith(s: &str) -> String {
    let clean: String = s
        .chars()
        .map(|c| {
            if c.is_ascii() && !c.is_ascii_control() {
                c
            } else {
                '?'
            }
        })
        .collect();
    format!("{}H{clean}", clean.len())
}

/// Tokens joined by `,` and ended by `;`, in lines of at most `width` bytes; a token longer
/// than a line (a long Hollerith name) continues on the next lines, as the section's
/// columns 1 to `width` are read as one stream.
fn pack(tokens: &[String], width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut cur = String::new();
    for (k, t) in tokens.iter().enumerate() {
        let piece = format!("{t}{}", if k + 1 == tokens.len() { ';' } else { ',' });
        if !cur.is_empty() && cur.len() + piece.len() > width {
            lines.push(std::mem::take(&mut cur));
        }
        cur.push_str(&piece);
        // tokens are ASCII: cutting at a byte count keeps characters whole
        while cur.len() > width {
            let rest = cur.split_off(width);
            lines.push(std::mem::replace(&mut cur, rest));
        }
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}
