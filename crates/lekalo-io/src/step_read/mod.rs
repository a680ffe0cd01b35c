//! Reading B-spline and NURBS curves and surfaces from STEP files (ISO 10303-21 exchange
//! structures of AP203, AP214 and AP242).
//!
//! Read: `B_SPLINE_CURVE_WITH_KNOTS` and `B_SPLINE_SURFACE_WITH_KNOTS`, plain or as the complex
//! instances that Open CASCADE and FreeCAD write for rational geometry
//! (`(BOUNDED_CURVE() B_SPLINE_CURVE(…) B_SPLINE_CURVE_WITH_KNOTS(…) … RATIONAL_B_SPLINE_CURVE(…)
//! …)`, and the surface analogue), and `TRIMMED_CURVE` over a B-spline basis trimmed by
//! `PARAMETER_VALUE`s (ISO 10303-42 §4.4.7, §4.4.13–15, §4.4.29, §4.4.35–37). The length unit
//! comes from the unit context: 3-D coordinates are converted to millimetres, the unit
//! [`crate::StepWriter`] declares, so that a file read and written again describes the same
//! geometry. A conversion factor of 1 (files in millimetres) leaves every coordinate bit for bit
//! as written. Curves of dimension 2 (parameter-space curves of faces) are not scaled.
//!
//! Everything else that is geometry (lines, conics, elementary and swept surfaces, implicit-knot
//! B-splines such as `BEZIER_CURVE`, trims by points) is listed in [`StepRead::skipped`] with the
//! reason, so a caller can tell the user what was left out.
//!
//! The exchange structure is tokenized here rather than with `ruststep`'s parser: that parser
//! panics on integers and exponents beyond the range of `i64` (`1.0E99999999999999999999`),
//! which a reader of user files must report as an error, and its errors carry no line numbers.
//! The grammar needed (ISO 10303-21 §6–7: keywords, the six token kinds, lists, typed
//! parameters, simple and complex instances) is small.

use std::cell::Cell;
use std::collections::{HashMap, HashSet};

use lekalo::{BSplineCurve, BSplineSurface, NurbsCurve, NurbsSurface, Points};

use crate::error::{IoError, IoResult, Location};
use crate::object::Object;
use crate::shape::{Shape, Surface};

/// A geometric entity of the file that was not read.
#[derive(Debug, Clone, PartialEq)]
pub struct StepSkipped {
    /// Entity instance id (`#id`).
    pub id: u64,
    /// Entity type, e.g. `CIRCLE`.
    pub entity: String,
    /// Why it was skipped.
    pub reason: String,
}

/// What [`read_step`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRead {
    /// The curves and surfaces read, with the id of their entity instance, in id order.
    pub shapes: Vec<(u64, Shape)>,
    /// Geometric entities that were not read, in id order.
    pub skipped: Vec<StepSkipped>,
    /// The schema named in the header's `FILE_SCHEMA`, e.g. `AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }`.
    pub schema: Option<String>,
    /// The length unit of the unit context, e.g. `millimetre`, `metre`, `INCH (25.4 mm)`;
    /// `millimetre (assumed)` when the file declares none.
    pub length_unit: String,
    /// The factor that converted 3-D coordinates to millimetres (1 for files in millimetres).
    pub scale_to_mm: f64,
}

/// A parameter of an entity instance (ISO 10303-21 §6.3, §7.3).
#[derive(Debug, Clone, PartialEq)]
enum P {
    Num(f64),
    Str(String),
    Enum(String),
    Ref(u64),
    Unset,
    Derived,
    List(Vec<P>),
    Typed(String, Vec<P>),
}

/// One record `NAME(params)`.
type Record = (String, Vec<P>);

#[derive(Debug, Clone)]
struct Instance {
    records: Vec<Record>,
    line: usize,
}

impl Instance {
    fn get(&self, name: &str) -> Option<&[P]> {
        self.records
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, p)| p.as_slice())
    }

    fn has(&self, name: &str) -> bool {
        self.records.iter().any(|(n, _)| n == name)
    }

    /// The type name for reports: the record's name, or the most specific of a complex one.
    fn type_name(&self) -> String {
        if self.records.len() == 1 {
            return self.records[0].0.clone();
        }
        let names: Vec<&str> = self.records.iter().map(|(n, _)| n.as_str()).collect();
        format!("({})", names.join(" "))
    }
}

/// Deepest nesting of parameter lists read. Geometry nests two or three deep (a surface's
/// control net, a typed measure in a list); a deeper file is refused with a syntax error instead
/// of building values whose walk and drop would recurse as deep as the file says.
const MAX_NESTING: usize = 64;

struct Lexer<'a> {
    s: &'a [u8],
    pos: usize,
    source: &'a str,
    /// The last position whose line was counted, and its line: the count resumes there, so
    /// that asking the line of every instance costs one pass over the file, not one per instance.
    line_at: Cell<(usize, usize)>,
}

impl<'a> Lexer<'a> {
    fn new(text: &'a str, source: &'a str) -> Self {
        Lexer {
            s: text.as_bytes(),
            pos: 0,
            source,
            line_at: Cell::new((0, 1)),
        }
    }

    fn line(&self) -> usize {
        let pos = self.pos.min(self.s.len());
        let (at, line) = self.line_at.get();
        let (from, base) = if pos >= at { (at, line) } else { (0, 1) };
        let line = base + memchr::memchr_iter(b'\n', &self.s[from..pos]).count();
        self.line_at.set((pos, line));
        line
    }

    fn err<T>(&self, msg: impl Into<String>) -> IoResult<T> {
        Err(IoError::syntax(
            Location::new(self.source).at_line(self.line()),
            msg.into(),
        ))
    }

    fn peek(&self) -> Option<u8> {
        self.s.get(self.pos).copied()
    }

    fn skip_ws(&mut self) -> IoResult<()> {
        loop {
            match self.peek() {
                Some(b) if b.is_ascii_whitespace() => self.pos += 1,
                Some(b'/') if self.s.get(self.pos + 1) == Some(&b'*') => {
                    let start = self.line();
                    match self.s[self.pos + 2..].windows(2).position(|w| w == b"*/") {
                        Some(k) => self.pos += k + 4,
                        None => {
                            return Err(IoError::syntax(
                                Location::new(self.source).at_line(start),
                                "comment /* … is never closed with */",
                            ))
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    fn expect(&mut self, c: u8) -> IoResult<()> {
        self.skip_ws()?;
        if self.peek() == Some(c) {
            self.pos += 1;
            Ok(())
        } else {
            let found = self.peek().map_or_else(
                || "the end of the file".to_string(),
                |b| format!("'{}'", b as char),
            );
            self.err(format!("expected '{}', found {found}", c as char))
        }
    }

    fn keyword(&mut self) -> IoResult<String> {
        self.skip_ws()?;
        let start = self.pos;
        while let Some(b) = self.peek() {
            if b.is_ascii_alphanumeric()
                || b == b'_'
                || b == b'-'
                || (b == b'!' && self.pos == start)
            {
                self.pos += 1;
            } else {
                break;
            }
        }
        if start == self.pos {
            return self.err("expected a keyword (an entity name such as CARTESIAN_POINT)");
        }
        Ok(String::from_utf8_lossy(&self.s[start..self.pos]).to_ascii_uppercase())
    }

    fn digits(&mut self) -> &'a [u8] {
        let start = self.pos;
        while self.peek().is_some_and(|b| b.is_ascii_digit()) {
            self.pos += 1;
        }
        &self.s[start..self.pos]
    }

    fn entity_ref(&mut self) -> IoResult<u64> {
        // after '#'
        let d = self.digits();
        let text = String::from_utf8_lossy(d);
        match text.parse::<u64>() {
            Ok(n) => Ok(n),
            Err(_) => self.err(format!(
                "entity instance name #{text} is not a number below 2^64"
            )),
        }
    }

    /// A parameter list `( … )` with its nested lists and typed parameters, read with an
    /// explicit stack of the lists open (no recursion, so the file's nesting cannot exhaust the
    /// thread's stack), at most [`MAX_NESTING`] deep.
    fn params(&mut self) -> IoResult<Vec<P>> {
        self.expect(b'(')?;
        // the lists open, innermost last: the keyword of a typed parameter (`None` for a plain
        // list) and the parameters read in it so far
        let mut open: Vec<(Option<String>, Vec<P>)> = vec![(None, Vec::new())];
        let mut just_opened = true;
        'param: loop {
            self.skip_ws()?;
            if just_opened && self.peek() == Some(b')') {
                self.pos += 1;
            } else {
                let kind = match self.peek() {
                    Some(b'(') => {
                        self.pos += 1;
                        Some(None)
                    }
                    Some(b) if b.is_ascii_alphabetic() || b == b'!' => {
                        let k = self.keyword()?;
                        self.expect(b'(')?;
                        Some(Some(k))
                    }
                    _ => None,
                };
                if let Some(kind) = kind {
                    if open.len() >= MAX_NESTING {
                        return self.err(format!(
                            "parameter lists nested more than {MAX_NESTING} deep; no STEP entity nests lists that deep"
                        ));
                    }
                    open.push((kind, Vec::new()));
                    just_opened = true;
                    continue;
                }
                let p = self.scalar()?;
                if let Some((_, items)) = open.last_mut() {
                    items.push(p);
                }
                if self.separator()? {
                    just_opened = false;
                    continue;
                }
            }
            // a ')' closed the innermost list
            loop {
                let Some((kind, items)) = open.pop() else {
                    return self.err("unbalanced parentheses in a parameter list");
                };
                let Some((_, parent)) = open.last_mut() else {
                    return Ok(items);
                };
                parent.push(match kind {
                    None => P::List(items),
                    Some(k) => P::Typed(k, items),
                });
                if self.separator()? {
                    just_opened = false;
                    continue 'param;
                }
            }
        }
    }

    /// After a parameter: `true` for a `,` (another parameter follows), `false` for a `)` (the
    /// list ends), both consumed.
    fn separator(&mut self) -> IoResult<bool> {
        self.skip_ws()?;
        match self.peek() {
            Some(b',') => {
                self.pos += 1;
                Ok(true)
            }
            Some(b')') => {
                self.pos += 1;
                Ok(false)
            }
            _ => self.err("expected ',' or ')' in a parameter list"),
        }
    }

    /// A parameter that is not a list: `$`, `*`, a reference, a string, an enumeration or a
    /// number.
    fn scalar(&mut self) -> IoResult<P> {
        self.skip_ws()?;
        let Some(b) = self.peek() else {
            return self.err("the file ends inside a parameter list");
        };
        match b {
            b'$' => {
                self.pos += 1;
                Ok(P::Unset)
            }
            b'*' => {
                self.pos += 1;
                Ok(P::Derived)
            }
            b'#' => {
                self.pos += 1;
                Ok(P::Ref(self.entity_ref()?))
            }
            b'\'' => {
                self.pos += 1;
                let mut text = Vec::new();
                loop {
                    match self.peek() {
                        None => return self.err("string '… is never closed"),
                        Some(b'\'') if self.s.get(self.pos + 1) == Some(&b'\'') => {
                            text.push(b'\'');
                            self.pos += 2;
                        }
                        Some(b'\'') => {
                            self.pos += 1;
                            break;
                        }
                        Some(c) => {
                            text.push(c);
                            self.pos += 1;
                        }
                    }
                }
                Ok(P::Str(String::from_utf8_lossy(&text).into_owned()))
            }
            b'"' => {
                self.pos += 1;
                let start = self.pos;
                while self.peek().is_some_and(|c| c != b'"') {
                    self.pos += 1;
                }
                let text = String::from_utf8_lossy(&self.s[start..self.pos]).into_owned();
                self.expect(b'"')?;
                Ok(P::Str(text))
            }
            b'.' if self
                .s
                .get(self.pos + 1)
                .is_some_and(u8::is_ascii_alphabetic) =>
            {
                self.pos += 1;
                let start = self.pos;
                while self
                    .peek()
                    .is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_')
                {
                    self.pos += 1;
                }
                let text = String::from_utf8_lossy(&self.s[start..self.pos]).to_ascii_uppercase();
                self.expect(b'.')?;
                Ok(P::Enum(text))
            }
            b'+' | b'-' | b'.' | b'0'..=b'9' => {
                let start = self.pos;
                while self.peek().is_some_and(|c| {
                    c.is_ascii_digit() || matches!(c, b'+' | b'-' | b'.' | b'E' | b'e')
                }) {
                    self.pos += 1;
                }
                let text = String::from_utf8_lossy(&self.s[start..self.pos]);
                // Part 21 allows "1." (no fraction digits); Rust's parser accepts it too
                match text.parse::<f64>() {
                    Ok(x) if x.is_finite() => Ok(P::Num(x)),
                    Ok(_) => self.err(format!("number {text} is outside the range of a double")),
                    Err(_) => self.err(format!("\"{text}\" is not a number")),
                }
            }
            _ => self.err(format!(
                "unexpected character '{}' in a parameter",
                b as char
            )),
        }
    }
}

/// The parsed exchange structure: instances by id, and the header's schema.
struct Parsed {
    instances: HashMap<u64, Instance>,
    schema: Option<String>,
}

fn parse(text: &str, source: &str) -> IoResult<Parsed> {
    let mut lx = Lexer::new(text, source);
    let mut instances = HashMap::new();
    let mut schema = None;
    let mut in_data = false;
    let mut seen_data = false;
    loop {
        lx.skip_ws()?;
        let Some(b) = lx.peek() else { break };
        if b == b'#' {
            if !in_data {
                return lx.err("entity instance outside a DATA section");
            }
            let line = lx.line();
            lx.pos += 1;
            let id = lx.entity_ref()?;
            lx.expect(b'=')?;
            lx.skip_ws()?;
            let records = if lx.peek() == Some(b'(') {
                lx.pos += 1;
                let mut recs = Vec::new();
                loop {
                    lx.skip_ws()?;
                    if lx.peek() == Some(b')') {
                        lx.pos += 1;
                        break;
                    }
                    let k = lx.keyword()?;
                    recs.push((k, lx.params()?));
                }
                recs
            } else {
                let k = lx.keyword()?;
                vec![(k, lx.params()?)]
            };
            lx.expect(b';')?;
            if instances.insert(id, Instance { records, line }).is_some() {
                return Err(IoError::syntax(
                    Location::new(source).at_line(line),
                    format!("entity instance #{id} is defined twice"),
                ));
            }
            continue;
        }
        let k = lx.keyword()?;
        match k.as_str() {
            "ISO-10303-21" | "HEADER" | "END-ISO-10303-21" => lx.expect(b';')?,
            "ENDSEC" => {
                in_data = false;
                lx.expect(b';')?;
            }
            "DATA" => {
                lx.skip_ws()?;
                if lx.peek() == Some(b'(') {
                    lx.params()?;
                }
                lx.expect(b';')?;
                in_data = true;
                seen_data = true;
            }
            _ => {
                let params = lx.params()?;
                lx.expect(b';')?;
                if k == "FILE_SCHEMA" {
                    if let Some(P::List(l)) = params.first() {
                        if let Some(P::Str(s)) = l.first() {
                            schema = Some(s.clone());
                        }
                    }
                }
            }
        }
        if k == "END-ISO-10303-21" {
            break;
        }
    }
    if !seen_data {
        return Err(IoError::syntax(
            Location::new(source),
            "no DATA section: this is not an ISO 10303-21 (STEP) exchange structure",
        ));
    }
    Ok(Parsed { instances, schema })
}

/// Curve and surface entities that are geometry but not read, reported as skipped.
const OTHER_GEOMETRY: &[&str] = &[
    "LINE",
    "CIRCLE",
    "ELLIPSE",
    "PARABOLA",
    "HYPERBOLA",
    "POLYLINE",
    "OFFSET_CURVE_2D",
    "OFFSET_CURVE_3D",
    "PLANE",
    "CYLINDRICAL_SURFACE",
    "CONICAL_SURFACE",
    "SPHERICAL_SURFACE",
    "TOROIDAL_SURFACE",
    "SURFACE_OF_REVOLUTION",
    "SURFACE_OF_LINEAR_EXTRUSION",
    "OFFSET_SURFACE",
    "RECTANGULAR_TRIMMED_SURFACE",
    "BEZIER_CURVE",
    "UNIFORM_CURVE",
    "QUASI_UNIFORM_CURVE",
    "BEZIER_SURFACE",
    "UNIFORM_SURFACE",
    "QUASI_UNIFORM_SURFACE",
];

struct Reader<'a> {
    p: &'a Parsed,
    source: &'a str,
    scale: f64,
}

type Why = String;

fn num(p: &P) -> Option<f64> {
    match p {
        P::Num(x) => Some(*x),
        P::Typed(_, inner) if inner.len() == 1 => num(&inner[0]),
        _ => None,
    }
}

fn int(p: &P) -> Option<usize> {
    let x = num(p)?;
    // a count: integral and far below any size the library accepts
    if x >= 0.0 && x.fract() == 0.0 && x < 1e15 {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Some(x as usize)
    } else {
        None
    }
}

fn list(p: &P) -> Option<&[P]> {
    match p {
        P::List(l) => Some(l),
        _ => None,
    }
}

fn numbers(p: &P, what: &str) -> Result<Vec<f64>, Why> {
    list(p)
        .and_then(|l| l.iter().map(num).collect::<Option<Vec<f64>>>())
        .ok_or_else(|| format!("{what} is not a list of numbers"))
}

/// The knots of one direction, each repeated by its multiplicity, for `n` control points of
/// degree `degree` (`dir` is `""`, `"u "` or `"v "` in messages). Those need `n + degree + 1`
/// knots: a degree or a sum of multiplicities that does not fit is refused before anything is
/// allocated, so that a multiplicity of 2^31 in a 300-byte file asks for no memory, and a sum
/// beyond the range of the integers is an error rather than a wrap.
fn expand_knots(mults: &P, knots: &P, n: usize, degree: usize, dir: &str) -> Result<Vec<f64>, Why> {
    let m: Vec<usize> = list(mults)
        .and_then(|l| l.iter().map(int).collect::<Option<Vec<_>>>())
        .ok_or_else(|| {
            format!("{dir}knot_multiplicities is not a list of non-negative integers")
        })?;
    let k = numbers(knots, &format!("{dir}knots"))?;
    if m.len() != k.len() {
        return Err(format!(
            "{} {dir}knot multiplicities for {} knots",
            m.len(),
            k.len()
        ));
    }
    if degree >= n {
        return Err(format!(
            "{dir}degree {degree} needs at least {} control points, there are {n}",
            degree.saturating_add(1)
        ));
    }
    // n and degree < n come from lists of the file, so this sum is far below usize::MAX
    let expected = n + degree + 1;
    let total = m.iter().try_fold(0usize, |sum, &x| sum.checked_add(x));
    match total {
        Some(t) if t == expected => {}
        Some(t) => {
            return Err(format!(
                "the {dir}knot multiplicities add up to {t} knots; {n} control points of degree {degree} need {expected}"
            ))
        }
        None => {
            return Err(format!(
                "the {dir}knot multiplicities add up to more than 2^64 knots; {n} control points of degree {degree} need {expected}"
            ))
        }
    }
    let mut out = Vec::with_capacity(expected);
    for (x, n) in k.iter().zip(&m) {
        out.extend(std::iter::repeat_n(*x, *n));
    }
    Ok(out)
}

impl Reader<'_> {
    fn at(&self, id: u64) -> Location {
        let mut loc = Location::new(self.source);
        if let Some(i) = self.p.instances.get(&id) {
            loc = loc.at_line(i.line);
        }
        loc
    }

    fn point(&self, p: &P) -> Result<Vec<f64>, Why> {
        let P::Ref(id) = p else {
            return Err("a control point is not a reference to a CARTESIAN_POINT".into());
        };
        let inst = self
            .p
            .instances
            .get(id)
            .ok_or_else(|| format!("control point #{id} is not defined"))?;
        let c = inst.get("CARTESIAN_POINT").ok_or_else(|| {
            format!(
                "control point #{id} is a {}, not a CARTESIAN_POINT",
                inst.type_name()
            )
        })?;
        let coords = c
            .get(1)
            .ok_or_else(|| format!("CARTESIAN_POINT #{id} has no coordinates"))
            .and_then(|c| numbers(c, &format!("the coordinates of #{id}")))?;
        Ok(coords)
    }

    fn points(&self, p: &P) -> Result<Points, Why> {
        let rows = list(p)
            .ok_or("control_points_list is not a list")?
            .iter()
            .map(|q| self.point(q))
            .collect::<Result<Vec<_>, _>>()?;
        let mut pts = Points::from_rows(&rows).map_err(|e| e.to_string())?;
        if pts.dim() == 3 && self.scale != 1.0 {
            let s = self.scale;
            pts = Points::from_flat(3, pts.as_slice().iter().map(|x| x * s).collect())
                .map_err(|e| e.to_string())?;
        }
        Ok(pts)
    }

    /// A B-spline curve instance (simple or complex, rational or not).
    fn curve(&self, inst: &Instance) -> Result<Object, Why> {
        let (degree, ctrl, mults, knots, weights) = if let Some(r) = inst
            .get("B_SPLINE_CURVE_WITH_KNOTS")
            .filter(|r| r.len() >= 9)
        {
            (&r[1], &r[2], &r[6], &r[7], None)
        } else {
            let b = inst
                .get("B_SPLINE_CURVE")
                .filter(|r| r.len() >= 2)
                .ok_or("no B_SPLINE_CURVE record with degree and control points")?;
            let k = inst
                .get("B_SPLINE_CURVE_WITH_KNOTS")
                .filter(|r| r.len() >= 2)
                .ok_or("implicit knots (only B_SPLINE_CURVE_WITH_KNOTS is read)")?;
            let w = inst.get("RATIONAL_B_SPLINE_CURVE").and_then(|r| r.first());
            (&b[0], &b[1], &k[0], &k[1], w)
        };
        let degree = int(degree).ok_or("degree is not a non-negative integer")?;
        let ctrl = self.points(ctrl)?;
        let knots = expand_knots(mults, knots, ctrl.len(), degree, "")?;
        let obj = match weights {
            None => {
                Object::BSpline(BSplineCurve::new(degree, knots, ctrl).map_err(|e| e.to_string())?)
            }
            Some(w) => {
                let w = numbers(w, "weights_data")?;
                Object::Nurbs(NurbsCurve::new(degree, knots, ctrl, w).map_err(|e| e.to_string())?)
            }
        };
        Ok(obj)
    }

    /// A B-spline surface instance (simple or complex, rational or not).
    fn surface(&self, inst: &Instance) -> Result<Surface, Why> {
        let simple = inst
            .get("B_SPLINE_SURFACE_WITH_KNOTS")
            .filter(|r| r.len() >= 13);
        let (du, dv, net, um, vm, uk, vk, weights) = if let Some(r) = simple {
            (&r[1], &r[2], &r[3], &r[8], &r[9], &r[10], &r[11], None)
        } else {
            let b = inst
                .get("B_SPLINE_SURFACE")
                .filter(|r| r.len() >= 3)
                .ok_or("no B_SPLINE_SURFACE record with degrees and control points")?;
            let k = inst
                .get("B_SPLINE_SURFACE_WITH_KNOTS")
                .filter(|r| r.len() >= 4)
                .ok_or("implicit knots (only B_SPLINE_SURFACE_WITH_KNOTS is read)")?;
            let w = inst
                .get("RATIONAL_B_SPLINE_SURFACE")
                .and_then(|r| r.first());
            (&b[0], &b[1], &b[2], &k[0], &k[1], &k[2], &k[3], w)
        };
        let du = int(du).ok_or("u_degree is not a non-negative integer")?;
        let dv = int(dv).ok_or("v_degree is not a non-negative integer")?;
        let rows = list(net).ok_or("control_points_list is not a list of lists")?;
        let nu = rows.len();
        let mut nv = 0;
        let mut flat: Vec<f64> = Vec::new();
        let mut dim = 0;
        for (i, row) in rows.iter().enumerate() {
            let pts = self.points(row)?;
            if i == 0 {
                nv = pts.len();
                dim = pts.dim();
            } else if pts.len() != nv || pts.dim() != dim {
                return Err(format!(
                    "row {i} of the control net has {} points of dimension {}, row 0 has {nv} of dimension {dim}",
                    pts.len(),
                    pts.dim()
                ));
            }
            flat.extend_from_slice(pts.as_slice());
        }
        let ctrl = Points::from_flat(dim.max(1), flat).map_err(|e| e.to_string())?;
        let ku = expand_knots(um, uk, nu, du, "u ")?;
        let kv = expand_knots(vm, vk, nv, dv, "v ")?;
        Ok(match weights {
            None => Surface::BSpline(
                BSplineSurface::new(du, dv, ku, kv, ctrl, (nu, nv)).map_err(|e| e.to_string())?,
            ),
            Some(w) => {
                let mut ws = Vec::with_capacity(nu * nv);
                for row in list(w).ok_or("weights_data is not a list of lists")? {
                    ws.extend(numbers(row, "a row of weights_data")?);
                }
                Surface::Nurbs(
                    NurbsSurface::new(du, dv, ku, kv, ctrl, ws, (nu, nv))
                        .map_err(|e| e.to_string())?,
                )
            }
        })
    }

    /// A `TRIMMED_CURVE` over a B-spline curve, trimmed by parameter values. `budget` is the
    /// number of basis control points trims may still read: a basis is read once per trim, so
    /// without it a file of many short trims of one long curve would be read in quadratic time.
    fn trimmed(&self, r: &[P], budget: &mut usize) -> Result<(u64, Object), Why> {
        if r.len() < 5 {
            return Err(
                "TRIMMED_CURVE needs name, basis_curve, trim_1, trim_2, sense_agreement".into(),
            );
        }
        let P::Ref(basis) = &r[1] else {
            return Err("basis_curve is not a reference".into());
        };
        let inst = self
            .p
            .instances
            .get(basis)
            .ok_or_else(|| format!("basis curve #{basis} is not defined"))?;
        if !is_bspline_curve(inst) {
            return Err(format!(
                "the basis curve #{basis} is a {} (only B-spline bases are read)",
                inst.type_name()
            ));
        }
        let size = ["B_SPLINE_CURVE_WITH_KNOTS", "B_SPLINE_CURVE"]
            .iter()
            .find_map(|name| {
                let r = inst.get(name)?;
                let at = usize::from(*name == "B_SPLINE_CURVE_WITH_KNOTS") + 1;
                r.get(at).and_then(list).map(<[P]>::len)
            })
            .unwrap_or(0);
        *budget = budget.checked_sub(size).ok_or_else(|| {
            format!(
                "the basis curve #{basis} ({size} control points) is one of bases trimmed more often than the file's size allows to read"
            )
        })?;
        let curve = self.curve(inst)?;
        let trim = |p: &P| -> Option<f64> {
            list(p)?.iter().find_map(|x| match x {
                P::Typed(k, v) if k == "PARAMETER_VALUE" => v.first().and_then(num),
                _ => None,
            })
        };
        let (Some(t1), Some(t2)) = (trim(&r[2]), trim(&r[3])) else {
            return Err("trimmed by points, not by PARAMETER_VALUE".into());
        };
        let sense = match &r[4] {
            P::Enum(e) => e == "T",
            _ => return Err("sense_agreement is not .T. or .F.".into()),
        };
        if sense != (t1 <= t2) {
            return Err(format!(
                "trims {t1} → {t2} with sense_agreement {} wrap around a closed curve",
                if sense { ".T." } else { ".F." }
            ));
        }
        let (a, b) = (t1.min(t2), t1.max(t2));
        let piece = restrict(&curve, a, b).map_err(|e| e.to_string())?;
        let piece = if sense {
            piece
        } else {
            reverse(&piece).map_err(|e| e.to_string())?
        };
        Ok((*basis, piece))
    }
}

fn split(o: &Object, t: f64) -> lekalo::Result<(Object, Object)> {
    Ok(match o {
        Object::Nurbs(c) => {
            let (a, b) = c.split_at(t)?;
            (Object::Nurbs(a), Object::Nurbs(b))
        }
        Object::BSpline(c) => {
            let (a, b) = c.split_at(t)?;
            (Object::BSpline(a), Object::BSpline(b))
        }
        Object::Bezier(c) => {
            let (a, b) = c.to_bspline().split_at(t)?;
            (Object::BSpline(a), Object::BSpline(b))
        }
    })
}

/// The piece of `o` over `[a, b]` (the curve itself where a trim is at its end).
fn restrict(o: &Object, a: f64, b: f64) -> lekalo::Result<Object> {
    let (lo, hi) = o.domain();
    let mut c = o.clone();
    if a > lo {
        c = split(&c, a)?.1;
    }
    if b < hi {
        c = split(&c, b)?.0;
    }
    Ok(c)
}

fn reverse(o: &Object) -> lekalo::Result<Object> {
    Ok(match o {
        Object::Nurbs(c) => Object::Nurbs(c.reverse()?),
        Object::BSpline(c) => Object::BSpline(c.reverse()?),
        Object::Bezier(c) => Object::BSpline(c.to_bspline().reverse()?),
    })
}

fn is_bspline_curve(i: &Instance) -> bool {
    i.has("B_SPLINE_CURVE_WITH_KNOTS") || i.has("B_SPLINE_CURVE")
}

fn is_bspline_surface(i: &Instance) -> bool {
    i.has("B_SPLINE_SURFACE_WITH_KNOTS") || i.has("B_SPLINE_SURFACE")
}

/// The length unit of the file and its factor to millimetres.
///
/// # Errors
/// [`IoError::Syntax`] naming the unit's entity when its factor is zero, negative or beyond the
/// range of a double: such a unit would turn every point into the origin, mirror the geometry
/// or make it infinite.
fn length_unit(p: &Parsed, source: &str) -> IoResult<(String, f64)> {
    // the unit assigned by the (first) global unit context, else any length unit of the file
    let mut ids: Vec<u64> = p.instances.keys().copied().collect();
    ids.sort_unstable();
    let from_context = ids.iter().find_map(|id| {
        let refs = p.instances[id]
            .get("GLOBAL_UNIT_ASSIGNED_CONTEXT")?
            .first()?;
        list(refs)?.iter().find_map(|r| match r {
            P::Ref(u) if p.instances.get(u).is_some_and(|i| i.has("LENGTH_UNIT")) => Some(*u),
            _ => None,
        })
    });
    let unit = from_context.or_else(|| {
        ids.iter()
            .copied()
            .find(|id| p.instances[id].has("LENGTH_UNIT"))
    });
    let Some((u, (name, mm))) = unit.and_then(|u| Some((u, unit_factor(p, u, 0)?))) else {
        return Ok(("millimetre (assumed)".to_string(), 1.0));
    };
    if !(mm.is_finite() && mm > 0.0) {
        let mut at = Location::new(source);
        if let Some(i) = p.instances.get(&u) {
            at = at.at_line(i.line);
        }
        return Err(IoError::syntax(
            at,
            format!(
                "entity #{u}: the length unit {name} is {} mm; a unit must be a positive finite length, correct its conversion factor",
                crate::fmt_number(mm)
            ),
        ));
    }
    Ok((name, mm))
}

fn unit_factor(p: &Parsed, id: u64, depth: usize) -> Option<(String, f64)> {
    let inst = p.instances.get(&id)?;
    if let Some(si) = inst.get("SI_UNIT") {
        let prefix = match si.first() {
            Some(P::Enum(e)) => Some(e.as_str()),
            _ => None,
        };
        let f = match prefix {
            None => 1000.0,
            Some("EXA") => 1e21,
            Some("PETA") => 1e18,
            Some("TERA") => 1e15,
            Some("GIGA") => 1e12,
            Some("MEGA") => 1e9,
            Some("KILO") => 1e6,
            Some("HECTO") => 1e5,
            Some("DECA") => 1e4,
            Some("DECI") => 100.0,
            Some("CENTI") => 10.0,
            Some("MILLI") => 1.0,
            Some("MICRO") => 1e-3,
            Some("NANO") => 1e-6,
            Some("PICO") => 1e-9,
            Some("FEMTO") => 1e-12,
            Some("ATTO") => 1e-15,
            Some(_) => return None,
        };
        let name = prefix.map_or_else(
            || "metre".to_string(),
            |p| format!("{}metre", p.to_ascii_lowercase()),
        );
        return Some((name, f));
    }
    if depth > 4 {
        return None;
    }
    let cb = inst.get("CONVERSION_BASED_UNIT")?;
    let name = match cb.first() {
        Some(P::Str(s)) => s.clone(),
        _ => "conversion-based unit".to_string(),
    };
    let P::Ref(m) = cb.get(1)? else { return None };
    let measure = p.instances.get(m)?.records.first()?;
    let value = num(measure.1.first()?)?;
    let P::Ref(base) = measure.1.get(1)? else {
        return None;
    };
    let (_, f) = unit_factor(p, *base, depth + 1)?;
    let mm = value * f;
    Some((format!("{name} ({} mm)", crate::fmt_number(mm)), mm))
}

/// Reads the B-spline and NURBS curves and surfaces of a STEP file. `source` names the file in
/// errors.
///
/// ```
/// use lekalo_io::{read_step, Object, Shape, StepWriter};
/// let c = lekalo::NurbsCurve::circle(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 1.0)?;
/// let mut w = StepWriter::new("circle");
/// w.add_object(&Object::Nurbs(c.clone()))?;
/// let r = read_step(&w.finish("2000-01-01T00:00:00"), "circle.step")?;
/// assert_eq!(r.shapes.len(), 1);
/// assert_eq!(r.shapes[0].1, Shape::Curve(Object::Nurbs(c)));   // bit for bit
/// assert_eq!(r.length_unit, "millimetre");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`IoError::Syntax`] (with the line) when the text is not an exchange structure;
/// [`IoError::Syntax`] naming the entity when a B-spline entity is malformed or rejected by the
/// library's constructor (unsorted knots, wrong counts, non-positive weights).
pub fn read_step(text: &str, source: &str) -> IoResult<StepRead> {
    let parsed = parse(text, source)?;
    let (length_unit, scale) = length_unit(&parsed, source)?;
    let rd = Reader {
        p: &parsed,
        source,
        scale,
    };
    let mut ids: Vec<u64> = parsed.instances.keys().copied().collect();
    ids.sort_unstable();
    let mut shapes = Vec::new();
    let mut skipped = Vec::new();
    let mut trimmed_bases = HashSet::new();
    let mut trimmed = Vec::new();
    // the basis control points all trims may read: four times the instances of the file (each
    // control point is an instance), so that reading stays linear in the file's size
    let mut budget = parsed.instances.len().saturating_mul(4);
    for &id in &ids {
        let inst = &parsed.instances[&id];
        if let Some(r) = inst.get("TRIMMED_CURVE") {
            match rd.trimmed(r, &mut budget) {
                Ok((basis, piece)) => {
                    trimmed_bases.insert(basis);
                    trimmed.push((id, Shape::Curve(piece)));
                }
                Err(reason) => skipped.push(StepSkipped {
                    id,
                    entity: "TRIMMED_CURVE".into(),
                    reason,
                }),
            }
        }
    }
    for &id in &ids {
        let inst = &parsed.instances[&id];
        let bad = |why: Why| {
            IoError::syntax(
                rd.at(id),
                format!("entity #{id} {}: {why}", inst.type_name()),
            )
        };
        if is_bspline_curve(inst) {
            if trimmed_bases.contains(&id) {
                continue;
            }
            match rd.curve(inst) {
                Ok(c) => shapes.push((id, Shape::Curve(c))),
                Err(why) if why.starts_with("implicit knots") => skipped.push(StepSkipped {
                    id,
                    entity: inst.type_name(),
                    reason: why,
                }),
                Err(why) => return Err(bad(why)),
            }
        } else if is_bspline_surface(inst) {
            match rd.surface(inst) {
                Ok(s) => shapes.push((id, Shape::Surface(s))),
                Err(why) if why.starts_with("implicit knots") => skipped.push(StepSkipped {
                    id,
                    entity: inst.type_name(),
                    reason: why,
                }),
                Err(why) => return Err(bad(why)),
            }
        } else if let Some((name, _)) = inst
            .records
            .iter()
            .find(|(n, _)| OTHER_GEOMETRY.contains(&n.as_str()))
        {
            skipped.push(StepSkipped {
                id,
                entity: name.clone(),
                reason: "not a B-spline (lekalo reads B-spline and NURBS curves and surfaces)"
                    .into(),
            });
        }
    }
    shapes.extend(trimmed);
    shapes.sort_by_key(|(id, _)| *id);
    skipped.sort_by_key(|s| s.id);
    Ok(StepRead {
        shapes,
        skipped,
        schema: parsed.schema,
        length_unit,
        scale_to_mm: scale,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::StepWriter;

    const OCC_STYLE: &str = "ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('Open CASCADE Model'),'2;1');
FILE_NAME('x','2024-01-01T00:00:00',('Author'),(''),'Open CASCADE STEP processor 7.7','Open CASCADE 7.7','Unknown');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));
ENDSEC;
DATA;
#1 = CARTESIAN_POINT('',(0.,0.,0.));
#2 = CARTESIAN_POINT('',(1.,2.,0.));
#3 = CARTESIAN_POINT('',(3.,2.,0.));
#4 = CARTESIAN_POINT('',(4.,0.,0.));
/* a comment */
#5 = B_SPLINE_CURVE_WITH_KNOTS('',2,(#1,#2,#3,#4),.UNSPECIFIED.,.F.,.F.,(3,1,3),(0.,0.5,1.),
  .UNSPECIFIED.);
#6 = ( BOUNDED_CURVE() B_SPLINE_CURVE(2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.)
B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,1.),.PIECEWISE_BEZIER_KNOTS.) CURVE()
GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE((1.,0.5,1.)) REPRESENTATION_ITEM('') );
#7 = TRIMMED_CURVE('',#8,(PARAMETER_VALUE(0.25)),(PARAMETER_VALUE(0.75)),.T.,.PARAMETER.);
#8 = B_SPLINE_CURVE_WITH_KNOTS('',1,(#1,#4),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#9 = CIRCLE('',#10,2.);
#10 = AXIS2_PLACEMENT_3D('',#1,$,$);
#11 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) );
#12 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#11)) REPRESENTATION_CONTEXT('',''));
ENDSEC;
END-ISO-10303-21;
";

    #[test]
    fn reads_occ_style_entities_with_units_and_trims() {
        let r = read_step(OCC_STYLE, "occ.step").unwrap();
        assert_eq!(r.length_unit, "metre");
        assert_eq!(r.scale_to_mm, 1000.0);
        assert_eq!(
            r.schema.as_deref(),
            Some("AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }")
        );
        let ids: Vec<u64> = r.shapes.iter().map(|(i, _)| *i).collect();
        assert_eq!(ids, [5, 6, 7]);
        let Shape::Curve(Object::BSpline(c)) = &r.shapes[0].1 else {
            panic!("#5 is a B-spline curve")
        };
        assert_eq!(c.knots().as_slice(), &[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]);
        assert_eq!(c.control_points().point(1), &[1000.0, 2000.0, 0.0]);
        let Shape::Curve(Object::Nurbs(n)) = &r.shapes[1].1 else {
            panic!("#6 is a NURBS curve")
        };
        assert_eq!(n.weights(), vec![1.0, 0.5, 1.0]);
        let Shape::Curve(t) = &r.shapes[2].1 else {
            panic!("#7 is a curve")
        };
        assert_eq!(t.domain(), (0.25, 0.75));
        assert_eq!(t.control_points().point(0), &[1000.0, 0.0, 0.0]);
        assert_eq!(r.skipped.len(), 1);
        assert_eq!(r.skipped[0].entity, "CIRCLE");
    }

    #[test]
    fn our_own_files_round_trip_bit_for_bit() {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let ctrl =
            Points::from_3d(&[[1.0, 0.0, 0.1], [1.0, 1.0, 1.0 / 3.0], [0.0, 1.0, 1e-300]]).unwrap();
        let curve = Object::Nurbs(
            NurbsCurve::new(
                2,
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                ctrl,
                vec![1.0, w, 1.0],
            )
            .unwrap(),
        );
        let net = Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.7],
            [1.0, 0.0, -0.3],
            [1.0, 1.0, 1.0 / 7.0],
        ])
        .unwrap();
        let surf = BSplineSurface::new(
            1,
            1,
            vec![0.0, 0.0, 2.0, 2.0],
            vec![0.0, 0.0, 1.0, 1.0],
            net,
            (2, 2),
        )
        .unwrap();
        let nurbs = NurbsSurface::new(
            1,
            1,
            vec![0.0, 0.0, 2.0, 2.0],
            vec![0.0, 0.0, 1.0, 1.0],
            surf.control_points().clone(),
            vec![1.0, 0.3, 2.5, 1.0],
            (2, 2),
        )
        .unwrap();
        let mut wr = StepWriter::new("t");
        wr.add_object(&curve).unwrap();
        wr.add_any_surface(&Surface::BSpline(surf.clone())).unwrap();
        wr.add_any_surface(&Surface::Nurbs(nurbs.clone())).unwrap();
        let r = read_step(&wr.finish("2000-01-01T00:00:00"), "t.step").unwrap();
        let got: Vec<Shape> = r.shapes.into_iter().map(|(_, s)| s).collect();
        assert_eq!(
            got,
            vec![
                Shape::Curve(curve),
                Shape::Surface(Surface::BSpline(surf)),
                Shape::Surface(Surface::Nurbs(nurbs))
            ]
        );
        assert!(r.skipped.is_empty(), "{:?}", r.skipped);
        assert_eq!(r.scale_to_mm, 1.0);
    }

    #[test]
    fn errors_name_the_line_and_never_panic() {
        let e = read_step(
            "ISO-10303-21;\nDATA;\n#1=FOO(1.0E99999999999999999999);\nENDSEC;",
            "x",
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("x:3:"), "{e}");
        let e = read_step("hello", "x").unwrap_err().to_string();
        assert!(e.starts_with("x:1:"), "{e}");
        let e = read_step("ISO-10303-21;\nDATA;\n#1=FOO('abc);\n", "x")
            .unwrap_err()
            .to_string();
        assert!(e.contains("never closed"), "{e}");
        let bad = OCC_STYLE.replace("(3,1,3),(0.,0.5,1.)", "(3,1,3),(0.,1.5,1.)");
        let e = read_step(&bad, "b.step").unwrap_err().to_string();
        assert!(e.starts_with("b.step:13: entity #5"), "{e}");
        let e = read_step(
            "ISO-10303-21;\nDATA;\n#1=A(#99999999999999999999999);\n",
            "x",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("#99999999999999999999999"), "{e}");
        for cut in [10, 200, 600, 900] {
            let _ = read_step(&OCC_STYLE[..cut], "cut");
        }
    }

    /// `text` with its message, for the tests of hostile files below.
    fn refused(text: &str) -> String {
        read_step(text, "h.step").unwrap_err().to_string()
    }

    #[test]
    fn deep_nesting_is_refused_without_recursion() {
        // a million '(' overflowed the stack of a recursive reader (abort, exit 134)
        let deep = format!(
            "ISO-10303-21;\nDATA;\n#1=FOO({}1{});\nENDSEC;\n",
            "(".repeat(1_000_000),
            ")".repeat(1_000_000)
        );
        let e = refused(&deep);
        assert!(
            e.starts_with("h.step:3:") && e.contains("nested more than"),
            "{e}"
        );
        // as deep as the limit is still read, typed parameters included
        let ok = format!(
            "ISO-10303-21;\nDATA;\n#1=FOO({}1{},A(B((2))));\nENDSEC;\n",
            "(".repeat(MAX_NESTING - 2),
            ")".repeat(MAX_NESTING - 2)
        );
        assert!(read_step(&ok, "ok.step").is_ok());
        // unbalanced or unterminated lists are syntax errors, not panics
        for bad in [
            "#1=FOO((1,2);",
            "#1=FOO(1,(2)));",
            "#1=FOO(A(",
            "#1=FOO(,);",
        ] {
            let e = refused(&format!("ISO-10303-21;\nDATA;\n{bad}\nENDSEC;\n"));
            assert!(e.starts_with("h.step:"), "{bad}: {e}");
        }
    }

    #[test]
    fn knot_counts_are_checked_before_allocation() {
        let with = |mults: &str, knots: &str, degree: &str| {
            OCC_STYLE.replace(
                "2,(#1,#2,#3,#4),.UNSPECIFIED.,.F.,.F.,(3,1,3),(0.,0.5,1.)",
                &format!("{degree},(#1,#2,#3,#4),.UNSPECIFIED.,.F.,.F.,{mults},{knots}"),
            )
        };
        // one multiplicity of 2^31 - 3 asked for 16 GiB and aborted
        let e = refused(&with("(3,2147483645,3)", "(0.,0.5,1.)", "2"));
        assert!(
            e.starts_with("h.step:13: entity #5") && e.contains("add up to 2147483651 knots"),
            "{e}"
        );
        // multiplicities whose sum overflows 64 bits (8e15 bytes were asked for)
        let n = 20_000;
        let mults = format!("({})", vec!["999999999999999"; n].join(","));
        let knots = format!(
            "({})",
            (0..n)
                .map(|i| format!("{i}."))
                .collect::<Vec<_>>()
                .join(",")
        );
        let e = refused(&with(&mults, &knots, "2"));
        assert!(e.contains("more than 2^64 knots"), "{e}");
        // a degree far beyond the control points
        let e = refused(&with("(3,1,3)", "(0.,0.5,1.)", "99999999999999"));
        assert!(e.contains("degree 99999999999999 needs at least"), "{e}");
        // the same for a surface's two directions
        let surface = "ISO-10303-21;\nDATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=B_SPLINE_SURFACE_WITH_KNOTS('',1,1,((#1,#1),(#1,#1)),.UNSPECIFIED.,.F.,.F.,.F.,(2,2),(2,4294967295),(0.,1.),(0.,1.),.UNSPECIFIED.);
ENDSEC;\n";
        let e = refused(surface);
        assert!(
            e.starts_with("h.step:4: entity #2") && e.contains("v knot multiplicities add up to"),
            "{e}"
        );
    }

    #[test]
    fn many_trims_of_one_long_basis_are_read_in_linear_time() {
        // 20,000 trims of one curve of 20,000 control points: each trim read the whole basis
        let n = 20_000;
        let mut text = String::from("ISO-10303-21;\nDATA;\n");
        let mut refs = Vec::with_capacity(n);
        for i in 0..n {
            text += &format!("#{}=CARTESIAN_POINT('',({i}.,0.,0.));\n", i + 1);
            refs.push(format!("#{}", i + 1));
        }
        let basis = n + 1;
        text += &format!(
            "#{basis}=B_SPLINE_CURVE_WITH_KNOTS('',1,({}),.UNSPECIFIED.,.F.,.F.,(2,{}2),(0.,{}1.),.UNSPECIFIED.);\n",
            refs.join(","),
            "1,".repeat(n - 2),
            (1..n - 1).map(|k| format!("{k}e-5,")).collect::<String>()
        );
        for k in 0..n {
            text += &format!(
                "#{}=TRIMMED_CURVE('',#{basis},(PARAMETER_VALUE(0.1)),(PARAMETER_VALUE(0.2)),.T.,.PARAMETER.);\n",
                basis + 1 + k
            );
        }
        text += "ENDSEC;\n";
        let start = std::time::Instant::now();
        let r = read_step(&text, "trims.step").unwrap();
        assert!(start.elapsed().as_secs() < 20, "{:?}", start.elapsed());
        // the first trims are read, the rest are listed as skipped with the reason
        let read = r.shapes.len();
        assert!(read > 0 && read < 10, "{read} trims read");
        assert_eq!(r.skipped.len(), n - read, "every other trim is listed");
        assert!(
            r.skipped[0].reason.contains("trimmed more often"),
            "{:?}",
            r.skipped[0]
        );
    }

    #[test]
    fn units_that_are_not_positive_lengths_are_refused() {
        let with_unit = |factor: &str| {
            OCC_STYLE.replace(
                "#11 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) );",
                &format!(
                    "#11 = ( CONVERSION_BASED_UNIT('INCH',#13) LENGTH_UNIT() NAMED_UNIT(*) );
#13 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE({factor}),#14);
#14 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );"
                ),
            )
        };
        let r = read_step(&with_unit("25.4"), "in.step").unwrap();
        assert_eq!(
            (r.length_unit.as_str(), r.scale_to_mm),
            ("INCH (25.4 mm)", 25.4)
        );
        // 0 turned every point into the origin, a negative unit mirrored the geometry
        for (factor, shown) in [("0.", "0 mm"), ("-25.4", "-25.4 mm"), ("1.E308", "inf mm")] {
            let text = with_unit(factor);
            let text = if factor == "1.E308" {
                // a finite factor whose product with the base unit is not
                text.replace("SI_UNIT(.MILLI.,.METRE.)", "SI_UNIT(.KILO.,.METRE.)")
            } else {
                text
            };
            let e = refused(&text);
            assert!(
                e.starts_with("h.step:22: entity #11") && e.contains("positive finite length"),
                "{factor}: {e}"
            );
            assert!(e.contains(shown), "{factor}: {e}");
        }
    }
}
