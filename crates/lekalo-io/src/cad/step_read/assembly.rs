//! The placements of parts in assemblies (ISO 10303-44 product structure, as AP203, AP214 and
//! AP242 write it): a `NEXT_ASSEMBLY_USAGE_OCCURRENCE` makes a part (its `PRODUCT_DEFINITION`)
//! an occurrence in a parent; the `CONTEXT_DEPENDENT_SHAPE_REPRESENTATION` of that occurrence
//! relates the two parts' shape representations by a `REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION`
//! whose `ITEM_DEFINED_TRANSFORMATION` names a frame (`AXIS2_PLACEMENT_3D`) in each: the
//! child's geometry goes to the parent's coordinates by the rigid motion that takes the child's
//! frame onto the parent's, `A₂ ∘ A₁⁻¹` where `Aᵢ` maps a frame's coordinates to its
//! representation's (ISO 10303-43 §4.4.8, `item_defined_transformation`). Chained up to the
//! root, these give each part's occurrences in the file's frame; a part used twice is read twice,
//! once at each placement, as Open CASCADE's reader places it.
//!
//! A part's geometry is what its shape representations (with those related to them by a
//! `SHAPE_REPRESENTATION_RELATIONSHIP` without transformation, such as the B-rep of a part)
//! reach through their items. Files without an assembly are read unchanged.

use std::collections::{HashMap, HashSet};

use super::entities::Reader;
use super::P;
use crate::cad::motion::Motion;

/// Most occurrences of parts an assembly may place (a nesting that multiplies beyond this is
/// read at the first occurrences only).
const MAX_OCCURRENCES: usize = 1 << 16;
/// Deepest nesting of assemblies followed (a cycle of occurrences ends there).
const MAX_DEPTH: usize = 64;

/// The parts an assembly places, and which instances of the file are whose geometry.
#[derive(Debug, Default)]
pub(super) struct Assembly {
    /// The placed part of each instance of its geometry (an index of `occurrences`).
    owner: HashMap<u64, usize>,
    /// Each placed part's occurrences: the motions from its coordinates to the file's.
    occurrences: Vec<Vec<Motion>>,
}

impl Assembly {
    /// How many times the file's instances are read: the most occurrences of a part.
    pub(super) fn passes(&self) -> usize {
        self.occurrences
            .iter()
            .map(Vec::len)
            .max()
            .unwrap_or(1)
            .max(1)
    }

    /// How the instance `id` is read in pass `pass`: `None` not at all (its part has fewer
    /// occurrences), `Some(None)` as written, `Some(Some(m))` moved by `m`.
    pub(super) fn motion(&self, id: u64, pass: usize) -> Option<Option<Motion>> {
        match self.owner.get(&id) {
            Some(&part) => self.occurrences[part].get(pass).map(|m| Some(*m)),
            None => (pass == 0).then_some(None),
        }
    }
}

fn reference(p: Option<&P>) -> Option<u64> {
    match p {
        Some(P::Ref(id)) => Some(*id),
        _ => None,
    }
}

fn references(p: &P, out: &mut Vec<u64>) {
    match p {
        P::Ref(id) => out.push(*id),
        P::List(v) | P::Typed(_, v) => v.iter().for_each(|q| references(q, out)),
        _ => {}
    }
}

/// A set of representations joined by relationships without transformation (union–find).
#[derive(Default)]
struct Groups(HashMap<u64, u64>);

impl Groups {
    fn root(&mut self, a: u64) -> u64 {
        let mut x = a;
        while let Some(&p) = self.0.get(&x).filter(|&&p| p != x) {
            x = p;
        }
        self.0.insert(a, x);
        x
    }

    fn join(&mut self, a: u64, b: u64) {
        let (ra, rb) = (self.root(a), self.root(b));
        if ra != rb {
            self.0.insert(ra, rb);
        }
    }
}

/// The file's assembly, or `None` when it places no part (no `NEXT_ASSEMBLY_USAGE_OCCURRENCE`,
/// or every occurrence where the file's frame is).
pub(super) fn assembly(rd: &Reader<'_>) -> Option<Assembly> {
    let instances = &rd.p.instances;
    if !instances.any_of(&["NEXT_ASSEMBLY_USAGE_OCCURRENCE"]) {
        return None;
    }
    // (parent, child) product definitions of each occurrence
    let mut usage: HashMap<u64, (u64, u64)> = HashMap::new();
    // what each PRODUCT_DEFINITION_SHAPE defines (a product definition or an occurrence)
    let mut defines: HashMap<u64, u64> = HashMap::new();
    // (product definition shape, representation)
    let mut shape_of: Vec<(u64, u64)> = Vec::new();
    let mut groups = Groups::default();
    // (relationship, product definition shape of the occurrence)
    let mut placed: Vec<(u64, u64)> = Vec::new();
    for &id in instances.ids() {
        let inst = instances.known(&id);
        if let Some(r) = inst.get("NEXT_ASSEMBLY_USAGE_OCCURRENCE") {
            if let (Some(a), Some(b)) = (reference(r.get(3)), reference(r.get(4))) {
                usage.insert(id, (a, b));
            }
        } else if let Some(r) = inst.get("PRODUCT_DEFINITION_SHAPE") {
            if let Some(d) = reference(r.get(2)) {
                defines.insert(id, d);
            }
        } else if let Some(r) = inst.get("SHAPE_DEFINITION_REPRESENTATION") {
            if let (Some(a), Some(b)) = (reference(r.first()), reference(r.get(1))) {
                shape_of.push((a, b));
            }
        } else if let Some(r) = inst.get("CONTEXT_DEPENDENT_SHAPE_REPRESENTATION") {
            if let (Some(a), Some(b)) = (reference(r.first()), reference(r.get(1))) {
                placed.push((a, b));
            }
        } else if !inst.has("REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION") {
            let r = inst
                .get("SHAPE_REPRESENTATION_RELATIONSHIP")
                .filter(|r| r.len() >= 4)
                .or_else(|| inst.get("REPRESENTATION_RELATIONSHIP"));
            if let Some((a, b)) = r.and_then(|r| Some((reference(r.get(2))?, reference(r.get(3))?)))
            {
                groups.join(a, b);
            }
        }
    }
    // the representations of each product definition
    let mut reps: HashMap<u64, Vec<u64>> = HashMap::new();
    for &(pds, rep) in &shape_of {
        if let Some(&pd) = defines.get(&pds) {
            reps.entry(pd).or_default().push(rep);
        }
    }
    let group_of = |groups: &mut Groups, pd: u64| -> HashSet<u64> {
        let roots: HashSet<u64> = reps
            .get(&pd)
            .into_iter()
            .flatten()
            .map(|&r| groups.root(r))
            .collect();
        let mut all: HashSet<u64> = groups
            .0
            .keys()
            .copied()
            .collect::<Vec<_>>()
            .into_iter()
            .filter(|&r| roots.contains(&groups.root(r)))
            .collect();
        all.extend(reps.get(&pd).into_iter().flatten().copied());
        all
    };
    // each occurrence's motion, child to parent
    let mut parents: HashMap<u64, Vec<(u64, Motion)>> = HashMap::new();
    for &(rel, pds) in &placed {
        let Some(&(parent, child)) = defines.get(&pds).and_then(|n| usage.get(n)) else {
            continue;
        };
        let Some(motion) = occurrence_motion(rd, rel, &group_of(&mut groups, child)) else {
            continue;
        };
        parents.entry(child).or_default().push((parent, motion));
    }
    // each part's occurrences in the file's frame
    let mut memo: HashMap<u64, Vec<Motion>> = HashMap::new();
    let mut assembly = Assembly::default();
    let mut parts: Vec<u64> = parents.keys().copied().collect();
    parts.sort_unstable();
    for pd in parts {
        let occ = occurrences(pd, &parents, &mut memo, 0);
        if occ.iter().all(|m| *m == Motion::IDENTITY) && occ.len() == 1 {
            continue;
        }
        // the part's geometry: everything its representations' items reach
        let part = assembly.occurrences.len();
        assembly.occurrences.push(occ);
        let mut seen = HashSet::new();
        let mut stack: Vec<u64> = Vec::new();
        for rep in group_of(&mut groups, pd) {
            if let Some(items) = instances
                .get(&rep)
                .and_then(|i| i.records().first().and_then(|(_, p)| p.get(1).cloned()))
            {
                references(&items, &mut stack);
            }
        }
        while let Some(id) = stack.pop() {
            if !seen.insert(id) {
                continue;
            }
            assembly.owner.entry(id).or_insert(part);
            if let Some(inst) = instances.get(&id) {
                for (_, params) in inst.records() {
                    params.iter().for_each(|p| references(p, &mut stack));
                }
            }
        }
    }
    (!assembly.occurrences.is_empty()).then_some(assembly)
}

/// The motion from the child's coordinates to the parent's of the relationship `rel`
/// (`REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION` by an `ITEM_DEFINED_TRANSFORMATION`):
/// `A₂ ∘ A₁⁻¹` when the first representation is the child's (one of `child_reps`), the inverse
/// otherwise.
fn occurrence_motion(rd: &Reader<'_>, rel: u64, child_reps: &HashSet<u64>) -> Option<Motion> {
    let inst = rd.p.instances.get(&rel)?;
    let r = inst.get("REPRESENTATION_RELATIONSHIP")?;
    let rep1 = reference(r.get(2))?;
    let op = reference(
        inst.get("REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION")?
            .first(),
    )?;
    let op = rd.p.instances.get(&op)?;
    let t = op.get("ITEM_DEFINED_TRANSFORMATION")?;
    let a1 = Motion::of(&rd.placement(t.get(2)?).ok()?);
    let a2 = Motion::of(&rd.placement(t.get(3)?).ok()?);
    Some(if child_reps.contains(&rep1) || child_reps.is_empty() {
        a1.inverse().then(&a2)
    } else {
        a2.inverse().then(&a1)
    })
}

/// The motions of every occurrence of the part `pd` in the file's frame: the part's own
/// motions into each parent, then the parent's occurrences (at most [`MAX_OCCURRENCES`],
/// followed [`MAX_DEPTH`] levels up).
fn occurrences(
    pd: u64,
    parents: &HashMap<u64, Vec<(u64, Motion)>>,
    memo: &mut HashMap<u64, Vec<Motion>>,
    depth: usize,
) -> Vec<Motion> {
    if let Some(m) = memo.get(&pd) {
        return m.clone();
    }
    let Some(ps) = parents.get(&pd).filter(|_| depth < MAX_DEPTH) else {
        return vec![Motion::IDENTITY];
    };
    let mut out = Vec::new();
    for (parent, m) in ps {
        for outer in occurrences(*parent, parents, memo, depth + 1) {
            if out.len() < MAX_OCCURRENCES {
                out.push(m.then(&outer));
            }
        }
    }
    memo.insert(pd, out.clone());
    out
}
