//! The report of what a CAD read left out: each skipped entity counted by kind (its type and
//! its reason, the entities the reason names masked), and the first of them, by id, listed
//! one by one. Memory is bounded by the kinds and the listing, not by the entities: a file
//! that is a chain of a million skipped trims keeps one kind and a thousand entries.

use std::collections::HashMap;

use super::{SkippedKind, StepSkipped};

/// How many skipped entities a read lists one by one by default (those of the smallest ids);
/// the others are counted by kind ([`Skips::kinds`]).
pub const SKIPPED_LISTED: usize = 1000;

/// How many kinds of skip are told apart; past them every further kind is counted in one
/// kind, [`OTHER_KINDS`]. Reasons that differ by more than the entities they name (numbers
/// that vary from entity to entity) would otherwise make a kind per entity.
pub const SKIPPED_KINDS: usize = 1000;

/// The entity type of the kind that counts the kinds past [`SKIPPED_KINDS`].
pub const OTHER_KINDS: &str = "(other types)";

/// The entities a read skipped: how many ([`Skips::len`]), counted by kind
/// ([`Skips::kinds`], the most frequent first), and the first of them by id
/// ([`Skips::listed`], at most the listing bound the read was given).
///
/// ```
/// use lekalo_io::{Skips, StepSkipped};
/// let s = |id, r: &str| StepSkipped { id, entity: "T".into(), reason: r.into() };
/// let mut k = Skips::new(2);
/// for id in (1..=5).rev() {
///     k.push(s(id, &format!("curve #{} is too deep", id + 1)));
/// }
/// k.finish();
/// assert_eq!(k.len(), 5);
/// assert_eq!(k.listed().iter().map(|s| s.id).collect::<Vec<_>>(), [1, 2]);
/// assert_eq!(k.unlisted(), 3);
/// assert_eq!((k.kinds().len(), k.kinds()[0].count, k.kinds()[0].first_id), (1, 5, 1));
/// assert_eq!(k.kinds()[0].reason, "curve #2 is too deep");
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Skips {
    listed: Vec<StepSkipped>,
    keep: usize,
    kinds: Vec<SkippedKind>,
    index: HashMap<(String, String), usize>,
    total: usize,
}

impl Skips {
    /// An empty report that lists at most `keep` entities (those of the smallest ids).
    #[must_use]
    pub fn new(keep: usize) -> Self {
        Skips {
            keep,
            ..Skips::default()
        }
    }

    /// Counts `s` by kind and keeps it when its id is among the `keep` smallest so far.
    /// Amortised O(log keep) per entity; memory O(keep + kinds).
    pub fn push(&mut self, s: StepSkipped) {
        self.total += 1;
        let mut key = (s.entity.clone(), reason_kind(&s.reason));
        if !self.index.contains_key(&key) && self.index.len() >= SKIPPED_KINDS {
            key = (OTHER_KINDS.to_string(), String::new());
        }
        let n = self.kinds.len();
        let k = *self.index.entry(key).or_insert(n);
        if k == n {
            let other = self.index.len() > SKIPPED_KINDS;
            self.kinds.push(SkippedKind {
                entity: if other {
                    OTHER_KINDS.into()
                } else {
                    s.entity.clone()
                },
                reason: if other {
                    format!(
                        "more than {SKIPPED_KINDS} kinds of skip; the first of these: {}: {}",
                        s.entity, s.reason
                    )
                } else {
                    s.reason.clone()
                },
                count: 0,
                first_id: s.id,
            });
        }
        let kind = &mut self.kinds[k];
        kind.count += 1;
        if s.id < kind.first_id && kind.entity != OTHER_KINDS {
            kind.first_id = s.id;
            kind.reason.clone_from(&s.reason);
        }
        if self.keep == 0 {
            return;
        }
        self.listed.push(s);
        if self.listed.len() >= self.keep.saturating_mul(2) {
            self.trim();
        }
    }

    /// Keeps the `keep` entries of the smallest ids, in id order.
    fn trim(&mut self) {
        self.listed.sort_by_key(|s| s.id);
        self.listed.truncate(self.keep);
    }

    /// Puts the listing in id order (and bounds it) and the kinds most frequent first (then by
    /// type): called once the read is done.
    pub fn finish(&mut self) {
        self.trim();
        self.kinds
            .sort_by(|a, b| b.count.cmp(&a.count).then_with(|| a.entity.cmp(&b.entity)));
        self.index.clear();
        self.index.shrink_to_fit();
    }

    /// How many entities were skipped, listed or not.
    #[must_use]
    pub fn len(&self) -> usize {
        self.total
    }

    /// Whether nothing was skipped.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.total == 0
    }

    /// The skipped entities of the smallest ids, in id order: all of them when
    /// [`Skips::unlisted`] is 0.
    #[must_use]
    pub fn listed(&self) -> &[StepSkipped] {
        &self.listed
    }

    /// How many skipped entities are counted in [`Skips::kinds`] but not listed.
    #[must_use]
    pub fn unlisted(&self) -> usize {
        self.total - self.listed.len()
    }

    /// The skipped entities by type and reason, the most frequent first (after
    /// [`Skips::finish`]); each kind keeps the reason of its first entity.
    #[must_use]
    pub fn kinds(&self) -> &[SkippedKind] {
        &self.kinds
    }

    /// The listed entities ([`Skips::listed`]).
    pub fn iter(&self) -> std::slice::Iter<'_, StepSkipped> {
        self.listed.iter()
    }
}

impl<'a> IntoIterator for &'a Skips {
    type Item = &'a StepSkipped;
    type IntoIter = std::slice::Iter<'a, StepSkipped>;
    fn into_iter(self) -> Self::IntoIter {
        self.listed.iter()
    }
}

impl FromIterator<StepSkipped> for Skips {
    /// Every entity listed and counted.
    fn from_iter<I: IntoIterator<Item = StepSkipped>>(iter: I) -> Self {
        let mut s = Skips::new(usize::MAX);
        for x in iter {
            s.push(x);
        }
        s.finish();
        s
    }
}

/// `reason` with its references to entities masked (`#123` and `D45` become `#…` and `D…`):
/// the reasons of a million trimmed curves each too deep below the next differ by the curve
/// they name only, and are one kind of skip.
pub(super) fn reason_kind(reason: &str) -> String {
    let mut out = String::with_capacity(reason.len());
    let mut prev: Option<char> = None;
    let mut chars = reason.chars().peekable();
    while let Some(c) = chars.next() {
        let at_word = prev.is_none_or(|p| !p.is_alphanumeric());
        let reference = c == '#' || (c == 'D' && at_word);
        out.push(c);
        prev = Some(c);
        if reference && chars.peek().is_some_and(char::is_ascii_digit) {
            while chars.next_if(char::is_ascii_digit).is_some() {}
            out.push('…');
            prev = Some('…');
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn skip(id: u64, entity: &str, reason: &str) -> StepSkipped {
        StepSkipped {
            id,
            entity: entity.into(),
            reason: reason.into(),
        }
    }

    #[test]
    fn a_million_skips_keep_the_listing_and_one_kind() {
        let mut s = Skips::new(SKIPPED_LISTED);
        for id in (0..1_000_000u64).rev() {
            s.push(skip(
                id,
                "TRIMMED_CURVE",
                &format!("curve #{} is too deep", id + 1),
            ));
            assert!(
                s.listed.len() < 2 * SKIPPED_LISTED,
                "the listing is bounded"
            );
        }
        s.finish();
        assert_eq!(
            (s.len(), s.unlisted()),
            (1_000_000, 1_000_000 - SKIPPED_LISTED)
        );
        assert_eq!(s.listed()[0].id, 0);
        assert_eq!(s.listed()[SKIPPED_LISTED - 1].id, SKIPPED_LISTED as u64 - 1);
        assert_eq!(s.kinds().len(), 1);
        assert_eq!((s.kinds()[0].count, s.kinds()[0].first_id), (1_000_000, 0));
        assert_eq!(s.kinds()[0].reason, "curve #1 is too deep");
    }

    #[test]
    fn kinds_past_the_bound_are_counted_together() {
        let mut s = Skips::new(0);
        for id in 0..(SKIPPED_KINDS as u64 + 500) {
            s.push(skip(id, "PLANE", &format!("its radius {id}.5 is negative")));
        }
        s.finish();
        assert_eq!(s.kinds().len(), SKIPPED_KINDS + 1);
        assert!(s.listed().is_empty() && s.unlisted() == SKIPPED_KINDS + 500);
        let other = s.kinds().iter().find(|k| k.entity == OTHER_KINDS).unwrap();
        assert_eq!((other.count, other.first_id), (500, SKIPPED_KINDS as u64));
        assert!(
            other.reason.contains("PLANE: its radius 1000.5"),
            "{}",
            other.reason
        );
        assert_eq!(s.kinds().iter().map(|k| k.count).sum::<usize>(), s.len());
    }

    #[test]
    fn an_unbounded_listing_keeps_every_entity_in_id_order() {
        let s: Skips = [skip(3, "A", "r"), skip(1, "B", "r"), skip(2, "A", "r")]
            .into_iter()
            .collect();
        assert_eq!(s.iter().map(|s| s.id).collect::<Vec<_>>(), [1, 2, 3]);
        assert_eq!(s.unlisted(), 0);
        assert_eq!((s.kinds()[0].entity.as_str(), s.kinds()[0].count), ("A", 2));
    }
}
