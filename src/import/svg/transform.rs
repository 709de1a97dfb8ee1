//! Affine transforms and the SVG `transform` attribute: `matrix`, `translate`, `scale`,
//! `rotate` (with an optional centre), `skewX` and `skewY`, composed left to right.

use crate::geometry::Point;
use crate::import::svg::path_data::{Scanner, SyntaxError};

/// An affine map `(x, y) -> (a x + c y + e, b x + d y + f)`, stored `[a, b, c, d, e, f]` as
/// in SVG's `matrix(a b c d e f)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine(pub [f64; 6]);

impl Affine {
    /// The identity.
    pub const IDENTITY: Self = Self([1.0, 0.0, 0.0, 1.0, 0.0, 0.0]);

    /// A translation.
    pub fn translate(x: f64, y: f64) -> Self {
        Self([1.0, 0.0, 0.0, 1.0, x, y])
    }

    /// A scaling about the origin.
    pub fn scale(x: f64, y: f64) -> Self {
        Self([x, 0.0, 0.0, y, 0.0, 0.0])
    }

    /// A rotation about the origin by `degrees` (from the x axis towards the y axis).
    pub fn rotate(degrees: f64) -> Self {
        let (s, c) = degrees.to_radians().sin_cos();
        Self([c, s, -s, c, 0.0, 0.0])
    }

    /// `self` after `other`: the map `p -> self(other(p))`.
    pub fn then_apply_to(self, other: Self) -> Self {
        let [a, b, c, d, e, f] = self.0;
        let [a2, b2, c2, d2, e2, f2] = other.0;
        Self([
            a * a2 + c * b2,
            b * a2 + d * b2,
            a * c2 + c * d2,
            b * c2 + d * d2,
            a * e2 + c * f2 + e,
            b * e2 + d * f2 + f,
        ])
    }

    /// Maps a point.
    pub fn apply(&self, p: Point) -> Point {
        let [a, b, c, d, e, f] = self.0;
        [a * p[0] + c * p[1] + e, b * p[0] + d * p[1] + f]
    }

    /// Whether the map reverses orientation.
    pub fn is_mirror(&self) -> bool {
        self.0[0] * self.0[3] - self.0[1] * self.0[2] < 0.0
    }
}

/// Parses a transform list such as `translate(10 20) rotate(45, 5 5) scale(2)`.
pub fn parse_transform(text: &str) -> Result<Affine, SyntaxError> {
    let mut s = Scanner::new(text);
    let mut total = Affine::IDENTITY;
    s.skip_whitespace();
    while !s.at_end() {
        // A byte position: the character offset is counted only for an error.
        let name_start = s.position();
        let mut name = String::new();
        while let Some(c) = s.peek().filter(u8::is_ascii_alphabetic) {
            name.push(c as char);
            s.bump();
        }
        s.skip_whitespace();
        if s.peek() != Some(b'(') {
            return Err(s.error(format!("expected `(` after a transform name, {}", s.found())));
        }
        s.bump();
        s.skip_whitespace();
        let mut args = Vec::new();
        while s.peek() != Some(b')') {
            if args.len() == 6 {
                return Err(s.error("a transform takes at most 6 numbers"));
            }
            args.push(s.number()?);
            s.skip_separator();
        }
        s.bump();
        let bad = || {
            let plural = if args.len() == 1 { "" } else { "s" };
            SyntaxError::new(s.offset_at(name_start), format!("{name}() does not take {} number{plural}", args.len()))
        };
        let step = match (name.as_str(), args.as_slice()) {
            ("matrix", &[a, b, c, d, e, f]) => Affine([a, b, c, d, e, f]),
            ("translate", &[x]) => Affine::translate(x, 0.0),
            ("translate", &[x, y]) => Affine::translate(x, y),
            ("scale", &[x]) => Affine::scale(x, x),
            ("scale", &[x, y]) => Affine::scale(x, y),
            ("rotate", &[a]) => Affine::rotate(a),
            ("rotate", &[a, x, y]) => {
                Affine::translate(x, y).then_apply_to(Affine::rotate(a)).then_apply_to(Affine::translate(-x, -y))
            }
            ("skewX", &[a]) => Affine([1.0, 0.0, a.to_radians().tan(), 1.0, 0.0, 0.0]),
            ("skewY", &[a]) => Affine([1.0, a.to_radians().tan(), 0.0, 1.0, 0.0, 0.0]),
            ("matrix" | "translate" | "scale" | "rotate" | "skewX" | "skewY", _) => return Err(bad()),
            _ => {
                return Err(SyntaxError::new(s.offset_at(name_start), format!("unknown transform `{name}`")));
            }
        };
        total = total.then_apply_to(step);
        s.skip_separator();
    }
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Point, b: Point) -> bool {
        (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12
    }

    #[test]
    fn transforms_compose_left_to_right() {
        // translate then scale: the scale acts first on the point.
        let t = parse_transform("translate(10,20) scale(2 3)").unwrap();
        assert_eq!(t.apply([1.0, 1.0]), [12.0, 23.0]);
        // Rotation about a centre keeps the centre fixed and turns x towards y.
        let r = parse_transform("rotate(90 5 5)").unwrap();
        assert!(close(r.apply([5.0, 5.0]), [5.0, 5.0]));
        assert!(close(r.apply([6.0, 5.0]), [5.0, 6.0]));
        let k = parse_transform("skewX(45)").unwrap();
        assert!(close(k.apply([0.0, 2.0]), [2.0, 2.0]));
        let m = parse_transform(" matrix(1,2,3,4,5,6)\n").unwrap();
        assert_eq!(m.apply([1.0, 1.0]), [9.0, 12.0]);
        assert!(parse_transform("scale(-1 1)").unwrap().is_mirror());
        assert_eq!(parse_transform("").unwrap(), Affine::IDENTITY);
    }

    #[test]
    fn bad_transforms_are_errors() {
        assert_eq!(parse_transform("rotate(1 2)").unwrap_err().message, "rotate() does not take 2 numbers");
        assert_eq!(parse_transform("spin(3)").unwrap_err().message, "unknown transform `spin`");
        assert!(parse_transform("scale(1").is_err());
        assert!(parse_transform("matrix(1 2 3 4 5 6 7)").is_err());
    }
}
