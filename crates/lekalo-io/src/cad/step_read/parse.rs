//! The lexer and parser of the exchange structure (ISO 10303-21 §6–7): keywords, the six token
//! kinds, lists, typed parameters, simple and complex instances, with line numbers in errors.

use std::cell::Cell;

use super::progress::Meter;
use super::{Instance, P};
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
pub(super) struct Parsed {
    pub(super) instances: Instances,
    pub(super) schema: Option<String>,
}

/// The entity instances of a file, in id order, found by id in constant time: writers number
/// instances `#1, #2, …` with few gaps, so a table indexed by id holds the position of each
/// (when the largest id is at most [`DENSE_IDS`] times the count, plus 1024); sparser ids are
/// found by binary search. Either way no id is hashed and the table is linear in the count.
pub(super) struct Instances {
    /// The ids, ascending.
    ids: Vec<u64>,
    /// The instance of each id of `ids`, at the same position.
    items: Vec<Instance>,
    /// The position + 1 of id `k` at `dense[k]` (0: no instance), or empty for sparse ids.
    dense: Vec<u32>,
}

/// The largest id, over the number of instances, up to which [`Instances`] indexes by id.
const DENSE_IDS: u64 = 4;

impl Instances {
    /// The instances of `(id, instance)` pairs in any order; a repeated id is an error naming
    /// the line of its second definition.
    fn new(mut pairs: Vec<(u64, Instance)>, source: &str) -> IoResult<Self> {
        if !pairs.windows(2).all(|w| w[0].0 < w[1].0) {
            // stable: of two instances with one id, the one defined later stays after
            pairs.sort_by_key(|(id, _)| *id);
            if let Some(w) = pairs.windows(2).find(|w| w[0].0 == w[1].0) {
                let (id, line) = (w[1].0, w[1].1.line.max(w[0].1.line));
                return Err(IoError::syntax(
                    Location::new(source).at_line(line),
                    format!("entity instance #{id} is defined twice"),
                ));
            }
        }
        let (ids, items): (Vec<u64>, Vec<Instance>) = pairs.into_iter().unzip();
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
        Ok(Instances { ids, items, dense })
    }

    /// The instance `#id`.
    pub(super) fn get(&self, id: &u64) -> Option<&Instance> {
        let k = if self.dense.is_empty() {
            self.ids.binary_search(id).ok()?
        } else {
            let slot = *self.dense.get(usize::try_from(*id).ok()?)?;
            (slot as usize).checked_sub(1)?
        };
        self.items.get(k)
    }

    /// How many instances the file holds.
    pub(super) fn len(&self) -> usize {
        self.ids.len()
    }

    /// The ids, ascending.
    pub(super) fn keys(&self) -> std::slice::Iter<'_, u64> {
        self.ids.iter()
    }

    /// The instances, in id order.
    pub(super) fn values(&self) -> std::slice::Iter<'_, Instance> {
        self.items.iter()
    }
}

impl std::ops::Index<&u64> for Instances {
    type Output = Instance;

    /// The instance `#id`, which must exist (an id taken from [`Instances::keys`]).
    fn index(&self, id: &u64) -> &Instance {
        match self.get(id) {
            Some(i) => i,
            None => unreachable!("instance #{id} looked up by an id not taken from the file"),
        }
    }
}

/// Bytes parsed between two reports to the progress hook (a fraction of a millisecond).
const REPORT_BYTES: usize = 1 << 16;

/// Parses the exchange structure; more than `max_entities` instances is
/// [`IoError::TooLarge`], refused before the next one is stored. `meter` is told the bytes
/// parsed every [`REPORT_BYTES`] and stops the parse when cancelled.
pub(super) fn parse(
    text: &str,
    source: &str,
    max_entities: usize,
    meter: &Meter<'_>,
) -> IoResult<Parsed> {
    let mut lx = Lexer::new(text, source);
    let mut reported = 0;
    let mut instances: Vec<(u64, Instance)> = Vec::new();
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
            if instances.len() >= max_entities {
                return Err(IoError::TooLarge {
                    what: format!(
                        "{source}: line {line}: more than {max_entities} entity instances, above the size limit {max_entities}; raise the limit with --max-size if the machine has the memory"
                    ),
                });
            }
            instances.push((id, Instance { records, line }));
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
        instances: Instances::new(instances, source)?,
        schema,
    })
}
