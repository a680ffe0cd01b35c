//! The lexer and parser of the exchange structure (ISO 10303-21 §6–7): keywords, the six token
//! kinds, lists, typed parameters, simple and complex instances, with line numbers in errors.

use std::cell::Cell;
use std::collections::HashMap;

use super::progress::Meter;
use super::{Instance, Record, P};
use crate::error::{IoError, IoResult, Location};

/// Deepest nesting of parameter lists read. Geometry nests two or three deep (a surface's
/// control net, a typed measure in a list); a deeper file is refused with a syntax error instead
/// of building values whose walk and drop would recurse as deep as the file says.
pub(super) const MAX_NESTING: usize = 64;

struct Lexer<'a> {
    s: &'a [u8],
    pos: usize,
    source: &'a str,
    /// The last position whose line was counted, and its line: the count resumes there, so
    /// that asking the line of every instance costs one pass over the file, not one per instance.
    line_at: Cell<(usize, usize)>,
    /// Whether parameters are built; without, they are checked only (strings, enumerations
    /// and keywords of typed parameters are not copied, lists are not stored).
    keep: bool,
    /// The stack of lists open of [`Lexer::params`], kept between calls for its memory.
    stack: Vec<(Option<String>, Vec<P>)>,
}

impl<'a> Lexer<'a> {
    fn new(text: &'a str, source: &'a str, keep: bool) -> Self {
        Lexer {
            s: text.as_bytes(),
            pos: 0,
            source,
            line_at: Cell::new((0, 1)),
            keep,
            stack: Vec::new(),
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
        let k = self.keyword_span()?;
        Ok(String::from_utf8_lossy(k).to_ascii_uppercase())
    }

    /// The bytes of a keyword, as written (any case).
    fn keyword_span(&mut self) -> IoResult<&'a [u8]> {
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
        Ok(&self.s[start..self.pos])
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
        let n = d.iter().try_fold(0u64, |n, &c| {
            n.checked_mul(10)?.checked_add(u64::from(c - b'0'))
        });
        match n {
            Some(n) if !d.is_empty() => Ok(n),
            _ => self.err(format!(
                "entity instance name #{} is not a number below 2^64",
                String::from_utf8_lossy(d)
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
        let mut open = std::mem::take(&mut self.stack);
        open.clear();
        open.push((None, Vec::new()));
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
                        let word = self.keyword_span()?;
                        self.skip_ws()?;
                        if self.peek() != Some(b'(') {
                            // `NaN`, `inf`, `TRUE`: a bare word is no STEP value
                            let word = String::from_utf8_lossy(word);
                            return self.err(format!(
                                "{word} is not a value: a word in a parameter list starts a typed parameter NAME(…); numbers are written with digits (1.5, -2.E-3; NaN and infinities have no STEP form), enumerations between dots (.T.), strings in quotes"
                            ));
                        }
                        self.pos += 1;
                        let k = if self.keep {
                            String::from_utf8_lossy(word).to_ascii_uppercase()
                        } else {
                            String::new()
                        };
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
                if let Some((_, items)) = open.last_mut().filter(|_| self.keep) {
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
                    self.stack = open;
                    return Ok(items);
                };
                if self.keep {
                    parent.push(match kind {
                        None => P::List(items),
                        Some(k) => P::Typed(k, items),
                    });
                }
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
                    let rest = &self.s[self.pos..];
                    let Some(k) = memchr::memchr(b'\'', rest) else {
                        return self.err("string '… is never closed");
                    };
                    if self.keep {
                        text.extend_from_slice(&rest[..k]);
                    }
                    self.pos += k + 1;
                    if self.peek() == Some(b'\'') {
                        // '' stands for one quote
                        if self.keep {
                            text.push(b'\'');
                        }
                        self.pos += 1;
                    } else {
                        break;
                    }
                }
                if !self.keep {
                    return Ok(P::Unset);
                }
                Ok(P::Str(String::from_utf8_lossy(&text).into_owned()))
            }
            b'"' => {
                self.pos += 1;
                let start = self.pos;
                while self.peek().is_some_and(|c| c != b'"') {
                    self.pos += 1;
                }
                let end = self.pos;
                self.expect(b'"')?;
                if !self.keep {
                    return Ok(P::Unset);
                }
                Ok(P::Str(
                    String::from_utf8_lossy(&self.s[start..end]).into_owned(),
                ))
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
                let end = self.pos;
                self.expect(b'.')?;
                if !self.keep {
                    return Ok(P::Unset);
                }
                Ok(P::Enum(
                    String::from_utf8_lossy(&self.s[start..end]).to_ascii_uppercase(),
                ))
            }
            b'+' | b'-' | b'.' | b'0'..=b'9' => {
                let start = self.pos;
                while self.peek().is_some_and(|c| {
                    c.is_ascii_digit() || matches!(c, b'+' | b'-' | b'.' | b'E' | b'e')
                }) {
                    self.pos += 1;
                }
                let bytes = &self.s[start..self.pos];
                // Part 21 allows "1." (no fraction digits); fast_float2 reads it, correctly
                // rounded as Rust's parser, from the bytes without a copy
                match fast_float2::parse::<f64, _>(bytes) {
                    Ok(x) if x.is_finite() => Ok(P::Num(x)),
                    Ok(_) => self.err(format!(
                        "number {} is outside the range of a double",
                        String::from_utf8_lossy(bytes)
                    )),
                    Err(_) => self.err(format!(
                        "\"{}\" is not a number",
                        String::from_utf8_lossy(bytes)
                    )),
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
pub(super) struct Parsed<'a> {
    pub(super) instances: Instances<'a>,
    pub(super) schema: Option<String>,
}

/// The entity instances of a file, in id order, found by id in constant time: writers number
/// instances `#1, #2, …` with few gaps, so a table indexed by id holds the position of each
/// (when the largest id is at most [`DENSE_IDS`] times the count, plus 1024); sparser ids are
/// found by binary search. Either way no id is hashed and the table is linear in the count.
///
/// An instance is held as the offset of its text and its type (an index into the table of the
/// distinct type names of the file): 20 bytes, whatever its parameters. Its parameters are
/// parsed from the text when asked for ([`Instance::get`]), and dropped with the [`Instance`],
/// so that the memory of a read is the text, this table and what is converted, not a tree of
/// every parameter of the file.
pub(super) struct Instances<'a> {
    /// The text of the exchange structure.
    text: &'a str,
    /// The ids, ascending.
    ids: Vec<u64>,
    /// The offset of the `#` that starts the instance of each id of `ids`.
    at: Vec<usize>,
    /// The type of each instance of `ids`: an index into `kinds`.
    kind: Vec<u32>,
    /// The record names of each type: one for a simple instance, those of a complex one in
    /// the order written.
    kinds: Vec<Box<[String]>>,
    /// The position + 1 of id `k` at `dense[k]` (0: no instance), or empty for sparse ids.
    dense: Vec<u32>,
}

/// The largest id, over the number of instances, up to which [`Instances`] indexes by id.
const DENSE_IDS: u64 = 4;

/// The line (from 1) of the byte at `at` of `text`: one pass over the text before it, for
/// messages only.
pub(super) fn line_of(text: &str, at: usize) -> usize {
    let end = at.min(text.len());
    1 + memchr::memchr_iter(b'\n', &text.as_bytes()[..end]).count()
}

/// The records of the instance whose text starts at `at` (its `#`), parsed; the text was
/// checked by [`parse`], so nothing is refused here (a text that was not is read as no record).
pub(super) fn records_at(text: &str, at: usize) -> Vec<Record> {
    let mut lx = Lexer::new(text, "", true);
    lx.pos = at;
    let read = (|| {
        lx.expect(b'#')?;
        lx.entity_ref()?;
        lx.expect(b'=')?;
        lx.instance_body(None)
    })();
    read.unwrap_or_default()
}

/// The numbers of the list that is the second and last parameter of the simple instance whose
/// text starts at `at`, read straight from the text (`CARTESIAN_POINT('', (x, y, z))`,
/// `DIRECTION('', (x, y, z))`): no record is built. `None` when the instance is written
/// otherwise (other parameters, a typed number in the list), for the caller to read its
/// records.
pub(super) fn numbers_at(text: &str, at: usize) -> Option<Vec<f64>> {
    let mut lx = Lexer::new(text, "", false);
    lx.pos = at;
    lx.expect(b'#').ok()?;
    lx.entity_ref().ok()?;
    lx.expect(b'=').ok()?;
    lx.keyword_span().ok()?;
    lx.expect(b'(').ok()?;
    lx.scalar().ok()?;
    lx.expect(b',').ok()?;
    lx.expect(b'(').ok()?;
    let mut out = Vec::with_capacity(3);
    lx.skip_ws().ok()?;
    if lx.peek() == Some(b')') {
        lx.pos += 1;
    } else {
        loop {
            match lx.scalar().ok()? {
                P::Num(x) => out.push(x),
                _ => return None,
            }
            if !lx.separator().ok()? {
                break;
            }
        }
    }
    // the instance's parameters end here
    lx.expect(b')').ok()?;
    Some(out)
}

impl Lexer<'_> {
    /// The records after `#id =`: `NAME(…)`, or `(NAME(…) NAME(…) …)` for a complex
    /// instance, built when [`Lexer::keep`]; their names, upper case and separated by spaces,
    /// are left in `names` when given.
    fn instance_body(&mut self, mut names: Option<&mut Vec<u8>>) -> IoResult<Vec<Record>> {
        if let Some(n) = names.as_deref_mut() {
            n.clear();
        }
        let mut recs = Vec::new();
        let mut record = |lx: &mut Self, names: &mut Option<&mut Vec<u8>>| -> IoResult<()> {
            let k = lx.keyword_span()?;
            if let Some(names) = names.as_deref_mut() {
                if !names.is_empty() {
                    names.push(b' ');
                }
                names.extend(k.iter().map(u8::to_ascii_uppercase));
            }
            let params = lx.params()?;
            if lx.keep {
                recs.push((String::from_utf8_lossy(k).to_ascii_uppercase(), params));
            }
            Ok(())
        };
        self.skip_ws()?;
        if self.peek() == Some(b'(') {
            self.pos += 1;
            loop {
                self.skip_ws()?;
                if self.peek() == Some(b')') {
                    self.pos += 1;
                    break;
                }
                record(self, &mut names)?;
            }
        } else {
            record(self, &mut names)?;
        }
        Ok(recs)
    }
}

impl<'a> Instances<'a> {
    /// The instances of `text` at offsets `at` with ids `ids` and types `kind`, in any order; a
    /// repeated id is an error naming the line of its second definition.
    fn new(
        text: &'a str,
        mut ids: Vec<u64>,
        mut at: Vec<usize>,
        mut kind: Vec<u32>,
        kinds: Vec<Box<[String]>>,
        source: &str,
    ) -> IoResult<Self> {
        if !ids.windows(2).all(|w| w[0] < w[1]) {
            // stable: of two instances with one id, the one defined later stays after
            let mut order: Vec<usize> = (0..ids.len()).collect();
            order.sort_by_key(|&k| ids[k]);
            if let Some(w) = order.windows(2).find(|w| ids[w[0]] == ids[w[1]]) {
                let line = line_of(text, at[w[0]].max(at[w[1]]));
                return Err(IoError::syntax(
                    Location::new(source).at_line(line),
                    format!("entity instance #{} is defined twice", ids[w[0]]),
                ));
            }
            ids = order.iter().map(|&k| ids[k]).collect();
            at = order.iter().map(|&k| at[k]).collect();
            kind = order.iter().map(|&k| kind[k]).collect();
        }
        // grown by doubling while parsing: the capacity beyond the count is given back
        ids.shrink_to_fit();
        at.shrink_to_fit();
        kind.shrink_to_fit();
        let n = ids.len() as u64;
        let dense = match ids.last() {
            Some(&max)
                if n < u64::from(u32::MAX)
                    && max <= n.saturating_mul(DENSE_IDS).saturating_add(1024) =>
            {
                // max is below 4 · n + 1024 entries, n instances already held
                #[allow(clippy::cast_possible_truncation)]
                let mut t = vec![0u32; max as usize + 1];
                for (k, &id) in ids.iter().enumerate() {
                    #[allow(clippy::cast_possible_truncation)]
                    {
                        t[id as usize] = k as u32 + 1;
                    }
                }
                t
            }
            _ => Vec::new(),
        };
        Ok(Instances {
            text,
            ids,
            at,
            kind,
            kinds,
            dense,
        })
    }

    /// The instance at position `k` of the ids.
    fn nth(&self, k: usize) -> Instance<'_> {
        Instance::new(self.text, self.at[k], &self.kinds[self.kind[k] as usize])
    }

    /// The instance `#id`.
    pub(super) fn get(&self, id: &u64) -> Option<Instance<'_>> {
        let k = if self.dense.is_empty() {
            self.ids.binary_search(id).ok()?
        } else {
            let slot = *self.dense.get(usize::try_from(*id).ok()?)?;
            (slot as usize).checked_sub(1)?
        };
        (k < self.ids.len()).then(|| self.nth(k))
    }

    /// The instance `#id`, which must exist (an id taken from [`Instances::keys`]).
    pub(super) fn known(&self, id: &u64) -> Instance<'_> {
        match self.get(id) {
            Some(i) => i,
            None => unreachable!("instance #{id} looked up by an id not taken from the file"),
        }
    }

    /// How many instances the file holds.
    pub(super) fn len(&self) -> usize {
        self.ids.len()
    }

    /// The ids, ascending.
    pub(super) fn ids(&self) -> &[u64] {
        &self.ids
    }

    /// Whether an instance has a record named in `names` (a look at the types of the file,
    /// not at its instances).
    pub(super) fn any_of(&self, names: &[&str]) -> bool {
        self.kinds
            .iter()
            .any(|k| k.iter().any(|n| names.contains(&n.as_str())))
    }

    /// The instances, in id order.
    pub(super) fn values(&self) -> impl Iterator<Item = Instance<'_>> {
        (0..self.ids.len()).map(|k| self.nth(k))
    }
}

/// Bytes parsed between two reports to the progress hook (a fraction of a millisecond).
const REPORT_BYTES: usize = 1 << 16;

/// Parses the exchange structure; more than `max_entities` instances is
/// [`IoError::OverLimit`], refused before the next one is stored. `meter` is told the bytes
/// parsed every [`REPORT_BYTES`] and stops the parse when cancelled.
///
/// The whole text is checked here (every error of syntax is reported with its line), but only
/// the id, offset and type of each instance are kept ([`Instances`]).
pub(super) fn parse<'a>(
    text: &'a str,
    source: &str,
    max_entities: usize,
    meter: &Meter<'_>,
) -> IoResult<Parsed<'a>> {
    let mut lx = Lexer::new(text, source, true);
    let mut reported = 0;
    let mut ids: Vec<u64> = Vec::new();
    let mut offsets: Vec<usize> = Vec::new();
    let mut kind: Vec<u32> = Vec::new();
    // the types met, by their names ("NAME" or "NAME NAME …" for a complex instance)
    let mut kinds: Vec<Box<[String]>> = Vec::new();
    let mut kind_of: HashMap<Vec<u8>, u32> = HashMap::new();
    let mut names: Vec<u8> = Vec::new();
    // the type of the previous instance: runs of one type (the points of a net) are common
    let mut last: (Vec<u8>, u32) = (Vec::new(), u32::MAX);
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
            let start = lx.pos;
            lx.pos += 1;
            let id = lx.entity_ref()?;
            lx.expect(b'=')?;
            lx.keep = false;
            let body = lx.instance_body(Some(&mut names));
            lx.keep = true;
            body?;
            lx.expect(b';')?;
            if ids.len() >= max_entities {
                return Err(IoError::OverLimit {
                    what: format!(
                        "{source}: line {}: more than {max_entities} entity instances, above the size limit {max_entities}",
                        line_of(text, start)
                    ),
                    limit: crate::Limit::Size,
                    raise_to: None,
                });
            }
            let k = if last.1 != u32::MAX && last.0 == names {
                last.1
            } else {
                let k = match kind_of.get(names.as_slice()) {
                    Some(&k) => k,
                    None => {
                        let k = u32::try_from(kinds.len()).map_err(|_| IoError::TooLarge {
                            what: format!(
                                "{source}: line {}: more than 2^32 entity types",
                                line_of(text, start)
                            ),
                        })?;
                        // `#1 = ();` is a complex instance of no record
                        let split = names
                            .split(|&c| c == b' ')
                            .filter(|n| !n.is_empty())
                            .map(|n| String::from_utf8_lossy(n).into_owned())
                            .collect();
                        kinds.push(split);
                        kind_of.insert(names.clone(), k);
                        k
                    }
                };
                last = (names.clone(), k);
                k
            };
            ids.push(id);
            offsets.push(start);
            kind.push(k);
            if lx.pos - reported >= REPORT_BYTES {
                reported = lx.pos;
                meter.parsed(lx.pos)?;
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
    Ok(Parsed {
        instances: Instances::new(text, ids, offsets, kind, kinds, source)?,
        schema,
    })
}
