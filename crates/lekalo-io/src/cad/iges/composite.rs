//! Independent composite curves (IGES entity 102, IGES 5.3 §4.4) as one curve: the members
//! read from the file, joined by the core's [`lekalo::Curve::composite`]. Composites that
//! another entity uses (a face's boundary) are read with the faces (`faces.rs`).

use std::collections::{HashMap, HashSet};

use lekalo::Curve;

use crate::cad::motion::Motion;
use crate::{Shape, StepSkipped};

/// Why a composite curve (102) that another entity uses is not read as a curve.
pub(super) const SUBORDINATE_COMPOSITE: &str = "a composite curve that another entity uses (a face's boundary, read with --faces); its member curves are read one by one";

/// A composite curve of the file: its sequence number, its members' directory pointers and
/// its placement.
pub(super) type Composite = (u64, Vec<usize>, Option<Motion>);

/// Builds every composite of `composites` that stands alone from the curves in `shapes` and
/// adds it there, or lists it in `skipped` with the reason. A composite that a boundary
/// (`used`) or another composite points at is part of that entity and is not built alone; a
/// composite among the members of another is built once (nested at most [`MAX_NESTING`]
/// deep). Members meet within the file's resolution `resolution_mm` (global field 19) or
/// [`Curve::composite_tolerance`], whichever is larger. The control points of
/// all composites built together stay below `max_size`.
pub(super) fn build(
    composites: Vec<Composite>,
    used: &HashSet<u64>,
    shapes: &mut Vec<(u64, Shape)>,
    skipped: &mut Vec<StepSkipped>,
    (resolution_mm, max_size): (f64, usize),
    place: impl Fn(Shape, Option<&Motion>) -> Result<Shape, String>,
) {
    let members: HashSet<u64> = composites
        .iter()
        .flat_map(|c| c.1.iter().map(|&m| m as u64))
        .collect();
    let mut ctx = Context {
        by_id: composites.iter().map(|c| (c.0, c)).collect(),
        curves: shapes
            .iter()
            .enumerate()
            .filter(|(_, (_, s))| matches!(s, Shape::Curve(_)))
            .map(|(k, (id, _))| (*id, k))
            .collect(),
        shapes,
        memo: HashMap::new(),
        resolution_mm,
        budget: max_size,
    };
    let mut built = Vec::new();
    for (seq, _, motion) in &composites {
        let reason = if used.contains(seq) || members.contains(seq) {
            Err(SUBORDINATE_COMPOSITE.to_string())
        } else {
            ctx.joined(*seq, 0)
                .and_then(|c| place(Shape::Curve(c), motion.as_ref()))
        };
        match reason {
            Ok(shape) => built.push((*seq, shape)),
            Err(reason) => skipped.push(StepSkipped {
                id: *seq,
                entity: "IGES entity 102".into(),
                reason,
            }),
        }
    }
    shapes.extend(built);
}

/// The deepest nesting of composite curves read, as for the faces' boundaries.
const MAX_NESTING: usize = 8;

/// What [`build`] joins from: the composites by sequence number, the curves read and the
/// composites joined so far.
struct Context<'a> {
    by_id: HashMap<u64, &'a Composite>,
    curves: HashMap<u64, usize>,
    shapes: &'a [(u64, Shape)],
    memo: HashMap<u64, Result<Curve, String>>,
    resolution_mm: f64,
    /// Control points the composites may still hold together.
    budget: usize,
}

impl Context<'_> {
    /// The members of composite `seq` joined into one curve, `depth` composites down.
    fn joined(&mut self, seq: u64, depth: usize) -> Result<Curve, String> {
        if let Some(done) = self.memo.get(&seq) {
            return done.clone();
        }
        let result = self.join_members(seq, depth);
        self.memo.insert(seq, result.clone());
        result
    }

    fn join_members(&mut self, seq: u64, depth: usize) -> Result<Curve, String> {
        if depth >= MAX_NESTING {
            return Err(format!(
                "composite curves nested more than {MAX_NESTING} deep, or leading back to \
                 themselves (D{seq})"
            ));
        }
        let Some((_, members, motion)) = self.by_id.get(&seq).copied() else {
            return Err(format!("D{seq} is not a composite curve"));
        };
        if members.is_empty() {
            return Err("it has no member curves (N = 0)".into());
        }
        if depth > 0 && motion.is_some() {
            return Err(format!(
                "its member D{seq}, a composite curve, has a transformation matrix of its own, \
                 which lekalo does not apply to members"
            ));
        }
        let mut list = Vec::with_capacity(members.len());
        for &m in members {
            let m = m as u64;
            if self.by_id.contains_key(&m) {
                list.push(self.joined(m, depth + 1)?);
                continue;
            }
            match self.curves.get(&m).map(|&k| &self.shapes[k].1) {
                Some(Shape::Curve(c)) => list.push(c.clone()),
                _ => {
                    return Err(format!(
                        "its member D{m} is not a curve lekalo read (skipped, not a curve, or not \
                         in the file)"
                    ))
                }
            }
        }
        let points: usize = list.iter().map(|c| c.control_points().len()).sum();
        if points > self.budget {
            return Err(format!(
                "its members hold {points} control points, above what the size limit leaves \
                 ({}); raise --max-size",
                self.budget
            ));
        }
        self.budget -= points;
        let tolerance = self.resolution_mm.max(Curve::composite_tolerance(&list));
        Curve::composite(&list, tolerance).map_err(|e| e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use crate::cad::iges::read_iges;
    use crate::Shape;

    /// An IGES file of `entities` (type, parameter text), each its own D and P records;
    /// `subordinate` marks the entities (by index) whose directory entry says another entity
    /// uses them.
    fn iges(entities: &[(u32, &str)], subordinate: &[usize]) -> String {
        let mut s = format!("{:<72}S{:>7}\n", "composite curves", 1);
        let g = "1H,,1H;,,,,,,,,,,,1.,2,2HMM,,,,,,,,,,,;";
        s.push_str(&format!("{g:<72}G{:>7}\n", 1));
        let (mut d, mut p) = (String::new(), String::new());
        let mut pline = 1;
        for (k, (ty, params)) in entities.iter().enumerate() {
            let seq = 2 * k + 1;
            let status = if subordinate.contains(&k) {
                "00010000"
            } else {
                "00000000"
            };
            d.push_str(&format!(
                "{ty:>8}{pline:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{status}D{seq:>7}\n",
                0, 0, 0, 0, 0, 0
            ));
            let lines: Vec<&str> = params
                .as_bytes()
                .chunks(64)
                .map(|c| std::str::from_utf8(c).unwrap())
                .collect();
            d.push_str(&format!(
                "{ty:>8}{:>8}{:>8}{:>8}{:>8}{:>32}D{:>7}\n",
                0,
                0,
                lines.len(),
                0,
                "",
                seq + 1
            ));
            for l in lines {
                p.push_str(&format!("{l:<64}{seq:>8}P{pline:>7}\n"));
                pline += 1;
            }
        }
        s + &d + &p
    }

    #[test]
    fn an_independent_composite_is_one_curve_through_its_members() {
        // a line from (0, 0) to (1, 0), a quarter circle on to (2, 1), a line on to (2, 3)
        let text = iges(
            &[
                (110, "110,0.,0.,0.,1.,0.,0.;"),
                (100, "100,0.,1.,1.,1.,0.,2.,1.;"),
                (110, "110,2.,1.,0.,2.,3.,0.;"),
                (102, "102,3,1,3,5;"),
            ],
            &[0, 1, 2],
        );
        let r = read_iges(&text, "t.igs").unwrap();
        let (_, Shape::Curve(c)) = r.shapes.iter().find(|(id, _)| *id == 7).unwrap() else {
            panic!("the composite is a curve")
        };
        assert!(c.is_rational(), "the arc makes it rational");
        let (a, b) = c.domain();
        assert_eq!(c.eval(a).unwrap(), vec![0.0, 0.0, 0.0]);
        let end = c.eval(b).unwrap();
        assert!(
            (end[0] - 2.0).abs() < 1e-14 && (end[1] - 3.0).abs() < 1e-14,
            "{end:?}"
        );
        // the arc's middle lies on the circle about (1, 1)
        let m = c.eval(a + (b - a) * 0.5).unwrap();
        let r1 = (m[0] - 1.0).hypot(m[1] - 1.0);
        assert!((r1 - 1.0).abs() < 1e-14, "{m:?}");
        // the members are read as well, one by one
        assert_eq!(r.shapes.len(), 4);
    }

    #[test]
    fn composites_that_cannot_be_built_are_listed_with_the_reason() {
        let text = iges(
            &[
                (110, "110,0.,0.,0.,1.,0.,0.;"),
                (110, "110,1.,0.5,0.,2.,0.,0.;"),
                (102, "102,2,1,3;"),
                (102, "102,2,1,99;"),
                (102, "102,1,1;"),
            ],
            &[0, 1, 4],
        );
        let r = read_iges(&text, "t.igs").unwrap();
        let why = |id: u64| {
            r.skipped
                .listed()
                .iter()
                .find(|s| s.id == id)
                .map(|s| s.reason.clone())
                .unwrap_or_default()
        };
        assert!(why(5).contains("member 2 starts 5e-1"), "{}", why(5));
        assert!(why(7).contains("D99"), "{}", why(7));
        assert!(why(9).contains("another entity uses"), "{}", why(9));
        assert!(r.shapes.iter().all(|(id, _)| *id < 5));
    }

    #[test]
    fn nested_composites_are_built_once_and_within_the_size_limit() {
        // D5 = (line D1, line D3), D7 = (D5, line D9): one curve of three lines; D5 is part
        let text = iges(
            &[
                (110, "110,0.,0.,0.,1.,0.,0.;"),
                (110, "110,1.,0.,0.,1.,1.,0.;"),
                (102, "102,2,1,3;"),
                (102, "102,2,5,9;"),
                (110, "110,1.,1.,0.,0.,1.,0.;"),
            ],
            &[],
        );
        let r = read_iges(&text, "t.igs").unwrap();
        let (_, Shape::Curve(c)) = r.shapes.iter().find(|(id, _)| *id == 7).unwrap() else {
            panic!("the outer composite is a curve")
        };
        assert_eq!(c.domain(), (0.0, 3.0));
        assert_eq!(c.eval(3.0).unwrap(), vec![0.0, 1.0, 0.0]);
        assert!(r.shapes.iter().all(|(id, _)| *id != 5));
        assert!(r.skipped.listed().iter().any(|s| s.id == 5));
        // each composite lists the next one 20 times, 7 deep (20^7 copies of a full circle,
        // which ends where it starts): each is joined once, and the copies count against the
        // size limit
        let mut entities = vec![(100, "100,0.,0.,0.,1.,0.,1.,0.;".to_string())];
        for k in 0..7 {
            let next = if k == 6 { 1 } else { 5 + 2 * k };
            let list = vec![next.to_string(); 20].join(",");
            entities.push((102, format!("102,20,{list};")));
        }
        let refs: Vec<(u32, &str)> = entities.iter().map(|(t, p)| (*t, p.as_str())).collect();
        let start = std::time::Instant::now();
        let r = crate::cad::iges::read_iges_limited(&iges(&refs, &[]), "t.igs", 1_000_000).unwrap();
        let why = &r
            .skipped
            .listed()
            .iter()
            .find(|s| s.id == 3)
            .unwrap()
            .reason;
        assert!(why.contains("size limit"), "{why}");
        assert!(start.elapsed().as_secs() < 10, "{:?}", start.elapsed());
    }
}
