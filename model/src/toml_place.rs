//! Where a field is written in a scenario's TOML text: the line an error
//! about it points to. `tbgen` places the model's errors on a scenario's
//! lines with it, and the emulator library those of a configuration, so
//! both say `file:line: field ...` alike.

use toml::de::{DeTable, DeValue};

/// One step of a field path: a key or an array index.
enum Step<'a> {
    Key(&'a str),
    Index(usize),
}

/// `endat.commands[2].command` as steps.
fn steps(dotted: &str) -> Vec<Step<'_>> {
    let mut out = Vec::new();
    for part in dotted.split('.') {
        let mut pieces = part.split('[');
        if let Some(key) = pieces.next().filter(|k| !k.is_empty()) {
            out.push(Step::Key(key));
        }
        for index in pieces {
            match index.trim_end_matches(']').parse() {
                Ok(i) => out.push(Step::Index(i)),
                Err(_) => return out,
            }
        }
    }
    out
}

/// The byte offset of the deepest part of field path `dotted` written in
/// `text`: the key itself, or the array entry or table holding it.
pub fn locate(text: &str, dotted: &str) -> Option<usize> {
    deepest(text, dotted).map(|(offset, _)| offset)
}

/// The byte offset of field path `dotted` in `text` if the text writes
/// every part of it, else `None`.
pub fn find(text: &str, dotted: &str) -> Option<usize> {
    deepest(text, dotted)
        .filter(|&(_, whole)| whole)
        .map(|(offset, _)| offset)
}

/// The deepest part of `dotted` that `text` writes, and whether it is all of it.
fn deepest(text: &str, dotted: &str) -> Option<(usize, bool)> {
    let doc = DeTable::parse(text).ok()?;
    let mut table = Some(doc.get_ref());
    let mut value: Option<&DeValue> = None;
    let mut best = None;
    let steps = steps(dotted);
    let mut resolved = 0;
    for step in &steps {
        let found = match (step, table, value) {
            (Step::Key(k), Some(t), _) => t
                .iter()
                .find(|(key, _)| key.get_ref() == k)
                .map(|(key, v)| (key.span().start, v)),
            (&Step::Index(i), _, Some(DeValue::Array(a))) => a.get(i).map(|v| (v.span().start, v)),
            _ => None,
        };
        let Some((offset, v)) = found else { break };
        best = Some(offset);
        resolved += 1;
        value = Some(v.get_ref());
        table = match v.get_ref() {
            DeValue::Table(t) => Some(t),
            _ => None,
        };
    }
    best.map(|offset| (offset, resolved == steps.len()))
}

/// The 1-based line of `text` where field path `dotted` is set (see
/// [`locate`]), or `None` when the text writes no part of it.
pub fn line_of(text: &str, dotted: &str) -> Option<usize> {
    locate(text, dotted).map(|offset| line_column(text, offset).0)
}

/// The 1-based line and column of byte `offset` of `text`.
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before
        .rsplit('\n')
        .next()
        .map(|l| l.chars().count())
        .unwrap_or(0)
        + 1;
    (line, column)
}
