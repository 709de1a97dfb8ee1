//! The SVG text itself, outside the XML parser: line and column of elements met in
//! document order without counting from the top each time (as `Document::text_pos_at`
//! does, which made documents of many elements quadratic), and a count of every start
//! tag's attributes before the parser sees them (it compares each pair of an element's
//! attributes to find duplicates, so an element of n attributes costs it n(n-1)/2).

use std::ops::Range;

/// Line and column (from 1; columns in characters) of byte positions, met mostly in
/// increasing order.
pub(super) struct Cursor<'a> {
    text: &'a str,
    pos: usize,
    line: u32,
    column: u32,
}

impl<'a> Cursor<'a> {
    pub(super) fn new(text: &'a str) -> Self {
        Self { text, pos: 0, line: 1, column: 1 }
    }

    /// The line and column of byte `pos` (a character boundary): counted on from the last
    /// position asked for, or from the top when `pos` lies before it. Linear in the text
    /// over any number of calls in increasing order.
    pub(super) fn at(&mut self, pos: usize) -> (u32, u32) {
        let pos = pos.min(self.text.len());
        if pos < self.pos {
            (self.pos, self.line, self.column) = (0, 1, 1);
        }
        for c in self.text[self.pos..pos].chars() {
            if c == '\n' {
                self.line += 1;
                self.column = 1;
            } else {
                self.column += 1;
            }
        }
        self.pos = pos;
        (self.line, self.column)
    }
}

/// A start tag whose attributes take the document beyond the limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct TooManyAttributes {
    /// Byte position of the tag's `<`.
    pub(super) tag: usize,
    /// Its attributes.
    pub(super) attributes: usize,
}

/// Checks that the XML parser's duplicate checks, an element of n attributes costing
/// n(n-1)/2 comparisons, stay within `limit` comparisons for the whole document. Counts
/// the attributes of every start tag in the raw text (an attribute value cannot hold a
/// `<`, so a tag's attributes end before the next `<`: one pass). Tags inside the DTD's
/// internal subset (in entity values) may be copied wherever the entity is referenced,
/// so the largest of them counts `copies` times (the parser's node limit).
pub(super) fn check_attributes(text: &str, copies: usize, limit: usize) -> Result<(), TooManyAttributes> {
    let bytes = text.as_bytes();
    let dtd = internal_subset(bytes);
    let pairs = |n: usize| (n as u128) * (n.saturating_sub(1) as u128) / 2;
    let (mut body, mut largest_in_dtd) = (0u128, 0u128);
    let mut i = 0;
    while let Some(offset) = bytes[i..].iter().position(|&b| b == b'<') {
        let tag = i + offset;
        i = tag + 1;
        if matches!(bytes.get(i), None | Some(b'!' | b'?' | b'/')) {
            continue;
        }
        let (attributes, end) = count_attributes(bytes, i);
        i = end;
        if dtd.as_ref().is_some_and(|d| d.contains(&tag)) {
            largest_in_dtd = largest_in_dtd.max(pairs(attributes));
        } else {
            body += pairs(attributes);
        }
        if body + largest_in_dtd * copies as u128 > limit as u128 {
            return Err(TooManyAttributes { tag, attributes });
        }
    }
    Ok(())
}

fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\r' | b'\n')
}

/// The attributes of the start tag whose name begins at `i` (`name="value"` or with single
/// quotes), and where the count stopped: at the end of the tag, at anything that is not an
/// attribute (the parser will refuse the tag), or at the next `<`, whichever comes first.
fn count_attributes(b: &[u8], mut i: usize) -> (usize, usize) {
    let stops = |c: u8| is_space(c) || matches!(c, b'>' | b'/' | b'<' | b'=');
    let skip_spaces = |i: &mut usize| {
        while b.get(*i).is_some_and(|&c| is_space(c)) {
            *i += 1;
        }
    };
    while b.get(i).is_some_and(|&c| !stops(c)) {
        i += 1;
    }
    let mut count = 0;
    loop {
        skip_spaces(&mut i);
        let start = i;
        while b.get(i).is_some_and(|&c| !stops(c)) {
            i += 1;
        }
        if i == start {
            return (count, i);
        }
        skip_spaces(&mut i);
        if b.get(i) != Some(&b'=') {
            return (count, i);
        }
        i += 1;
        skip_spaces(&mut i);
        let Some(&quote @ (b'"' | b'\'')) = b.get(i) else { return (count, i) };
        i += 1;
        while b.get(i).is_some_and(|&c| c != quote && c != b'<') {
            i += 1;
        }
        if b.get(i) != Some(&quote) {
            return (count, i);
        }
        i += 1;
        count += 1;
    }
}

/// The DTD's internal subset (between `<!DOCTYPE ... [` and `]`), if the prolog has one:
/// the prolog is read as XML allows (declaration, processing instructions, comments and
/// white space, then the DOCTYPE); quoted strings, comments and processing instructions
/// inside are skipped whole. An unterminated subset runs to the end of the text.
fn internal_subset(b: &[u8]) -> Option<Range<usize>> {
    let find = |from: usize, what: &[u8]| b.get(from..)?.windows(what.len()).position(|w| w == what).map(|k| from + k);
    let mut i = if b.starts_with("\u{feff}".as_bytes()) { 3 } else { 0 };
    loop {
        while b.get(i).is_some_and(|&c| is_space(c)) {
            i += 1;
        }
        let rest = b.get(i..)?;
        if rest.starts_with(b"<?") {
            i = find(i, b"?>")? + 2;
        } else if rest.starts_with(b"<!--") {
            i = find(i, b"-->")? + 3;
        } else if rest.starts_with(b"<!DOCTYPE") {
            break;
        } else {
            return None;
        }
    }
    // The DOCTYPE's name and external identifier, up to `[` or `>`.
    i += "<!DOCTYPE".len();
    loop {
        match *b.get(i)? {
            quote @ (b'"' | b'\'') => i = b[i + 1..].iter().position(|&c| c == quote).map(|k| i + 1 + k + 1)?,
            b'[' => break,
            b'>' => return None,
            _ => i += 1,
        }
    }
    let open = i + 1;
    i = open;
    loop {
        let skipped = match b.get(i) {
            None => return Some(open..b.len()),
            Some(b']') => return Some(open..i),
            Some(&quote @ (b'"' | b'\'')) => b[i + 1..].iter().position(|&c| c == quote).map(|k| i + 1 + k + 1),
            Some(b'<') if b[i..].starts_with(b"<!--") => find(i, b"-->").map(|k| k + 3),
            Some(b'<') if b[i..].starts_with(b"<?") => find(i, b"?>").map(|k| k + 2),
            Some(_) => Some(i + 1),
        };
        match skipped {
            Some(next) => i = next,
            None => return Some(open..b.len()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cursor_agrees_with_counting_from_the_top() {
        let text = "<svg>\n  <g>\n\t<path d=\"é\"/>\n</g></svg>";
        let mut cursor = Cursor::new(text);
        let expected = |pos: usize| {
            let before = &text[..pos];
            let line = before.matches('\n').count() as u32 + 1;
            let column = before.rsplit('\n').next().unwrap().chars().count() as u32 + 1;
            (line, column)
        };
        for pos in (0..=text.len()).filter(|&p| text.is_char_boundary(p)).chain([3, 20, 0, text.len()]) {
            assert_eq!(cursor.at(pos), expected(pos), "at {pos}");
        }
    }

    #[test]
    fn attributes_are_counted_per_tag() {
        let b = br#"<path d="M0 0" fill = 'red' x="a>b"/><g/>"#;
        assert_eq!(count_attributes(b, 1), (3, 35));
        // A malformed tag stops the count; a `<` ends it.
        assert_eq!(count_attributes(b"<a x=1 y='2'>", 1).0, 0);
        assert_eq!(count_attributes(b"<a x='1<b y='2'>", 1).0, 0);
        let many: String = (0..100).map(|k| format!(" a{k}=\"\"")).collect();
        let text = format!("<svg><!-- <c x='1' y='1'> --><path{many}/><g a='1' b='1'/></svg>");
        // 100 attributes: 4950 pairs, plus the comment's tag (1) and the g (1).
        assert_eq!(check_attributes(&text, 1000, 4952), Ok(()));
        assert_eq!(
            check_attributes(&text, 1000, 4951),
            Err(TooManyAttributes { tag: text.rfind("<g").unwrap(), attributes: 2 })
        );
        assert_eq!(
            check_attributes(&text, 1000, 4000),
            Err(TooManyAttributes { tag: text.find("<path").unwrap(), attributes: 100 })
        );
    }

    #[test]
    fn tags_in_the_dtd_count_once_per_copy() {
        let text = r#"<?xml version="1.0"?><!-- a [ --><!DOCTYPE svg PUBLIC "a]" "b" [
            <!ENTITY e "<g a='1' b='2' c='3'/>"> <!-- ] --> <?pi ]?> ]><svg><g x="1" y="2"/>&e;</svg>"#;
        let subset = internal_subset(text.as_bytes()).unwrap();
        assert!(text[subset.clone()].contains("ENTITY") && text[subset].ends_with("?> "));
        // The entity's tag: 3 pairs, 10 copies; the body's g: 1 pair.
        assert_eq!(check_attributes(text, 10, 31), Ok(()));
        assert!(check_attributes(text, 10, 30).is_err());
        assert_eq!(internal_subset(b"<svg><!DOCTYPE x [ ]>"), None);
        assert_eq!(internal_subset(b"<!DOCTYPE svg>"), None);
    }
}
