//! How messages and files write numbers and lists of words: [`Number`] and [`one_of`].
//! A leaf: it imports nothing of the crate, so every area's error can use it and the
//! crate's top-level [`crate::Error`] can hold every area's error without an import circle.

use std::fmt;

/// A number in messages and files as a person (and JavaScript) writes it: plain decimals
/// from 1e-6 to 1e21 (`100`, `0.25`), exponents outside (`1e308`, `1e-7`), never a run of
/// 300 zeros; always the shortest digits that read back to the same double.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Number(pub(crate) f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() || (1e-6..1e21).contains(&x.abs()) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// `"a", "b" or "c"`.
pub(crate) fn one_of(words: &[&str]) -> String {
    let quoted: Vec<String> = words.iter().map(|w| format!("\"{w}\"")).collect();
    match quoted.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => "nothing".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::Number;

    #[test]
    fn numbers_read_as_written() {
        let shown = |x: f64| Number(x).to_string();
        assert_eq!(shown(100.0), "100");
        assert_eq!(shown(0.25), "0.25");
        assert_eq!(shown(-1.5), "-1.5");
        assert_eq!(shown(1e308), "1e308");
        assert_eq!(shown(1e-300), "1e-300");
        assert_eq!(shown(1.5e-8), "1.5e-8");
        assert_eq!(shown(1e-7), "1e-7");
        assert_eq!(shown(1e-6), "0.000001");
        assert_eq!(shown(f64::NAN), "NaN");
        assert_eq!(shown(f64::NEG_INFINITY), "-inf");
        assert_eq!(shown(4294967295.0), "4294967295");
    }
}
