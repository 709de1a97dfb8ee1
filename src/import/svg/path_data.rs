//! SVG path data (the `d` attribute): every command (M L H V C S Q T A Z, absolute and
//! relative, with implicit repeats), and the number lists of `points`, `viewBox` and
//! `transform`. Elliptical arcs become cubic Béziers, converted to centre form as the SVG
//! implementation notes (F.6.5, F.6.6) describe.

use std::f64::consts::{FRAC_PI_4, TAU};

use crate::geometry::Point;
use crate::import::vector::{VectorPath, Verb};

/// A syntax error in an attribute value: what, and at which character (from 0).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SyntaxError {
    /// Character offset in the value.
    pub offset: usize,
    /// What was expected or found.
    pub message: String,
    /// Whether the value is well-formed so far but makes more points (or numbers) than the
    /// limit it was parsed with: a size limit met, not a syntax error.
    pub too_many: bool,
}

impl SyntaxError {
    pub(crate) fn new(offset: usize, message: impl Into<String>) -> Self {
        Self { offset, message: message.into(), too_many: false }
    }

    fn too_many(offset: usize, message: String) -> Self {
        Self { offset, message, too_many: true }
    }
}

/// A cursor over an attribute value: numbers, flags, separators.
pub(crate) struct Scanner<'a> {
    text: &'a str,
    pos: usize,
}

impl<'a> Scanner<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        Self { text, pos: 0 }
    }

    fn bytes(&self) -> &'a [u8] {
        self.text.as_bytes()
    }

    /// The character offset of the cursor (the text is ASCII up to any error). Counts
    /// from the start: for errors only, or parsing would be quadratic.
    pub(crate) fn offset(&self) -> usize {
        self.offset_at(self.pos)
    }

    /// The cursor's byte position, for [`Self::offset_at`] if an error needs it later.
    pub(crate) fn position(&self) -> usize {
        self.pos
    }

    /// The character offset of byte position `pos`.
    pub(crate) fn offset_at(&self, pos: usize) -> usize {
        self.text[..pos].chars().count()
    }

    pub(crate) fn peek(&self) -> Option<u8> {
        self.bytes().get(self.pos).copied()
    }

    pub(crate) fn at_end(&self) -> bool {
        self.pos >= self.text.len()
    }

    pub(crate) fn bump(&mut self) {
        self.pos += 1;
    }

    pub(crate) fn skip_whitespace(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\n' | b'\r' | b'\x0c')) {
            self.pos += 1;
        }
    }

    /// Skips whitespace, at most one comma, and whitespace.
    pub(crate) fn skip_separator(&mut self) {
        self.skip_whitespace();
        if self.peek() == Some(b',') {
            self.pos += 1;
            self.skip_whitespace();
        }
    }

    /// Whether a number can start here.
    pub(crate) fn number_ahead(&self) -> bool {
        matches!(self.peek(), Some(b'0'..=b'9' | b'+' | b'-' | b'.'))
    }

    pub(crate) fn error(&self, message: impl Into<String>) -> SyntaxError {
        SyntaxError::new(self.offset(), message)
    }

    /// Describes what is at the cursor, for error messages.
    pub(crate) fn found(&self) -> String {
        match self.text[self.pos..].chars().next() {
            Some(c) => format!("found `{c}`"),
            None => "found the end".to_string(),
        }
    }

    /// A number: sign, digits, fraction, exponent (`-1.5e3`, `.5`; `1.5.5` is two numbers).
    pub(crate) fn number(&mut self) -> Result<f64, SyntaxError> {
        let start = self.pos;
        let b = self.bytes();
        let mut i = self.pos;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let digits = |i: &mut usize| {
            let s = *i;
            while matches!(b.get(*i), Some(b'0'..=b'9')) {
                *i += 1;
            }
            *i - s
        };
        let mut count = digits(&mut i);
        if b.get(i) == Some(&b'.') {
            i += 1;
            count += digits(&mut i);
        }
        if count == 0 {
            return Err(self.error(format!("expected a number, {}", self.found())));
        }
        if matches!(b.get(i), Some(b'e' | b'E')) {
            // An exponent needs digits; otherwise the `e` belongs to what follows (as in
            // units like `em`).
            let mut j = i + 1;
            if matches!(b.get(j), Some(b'+' | b'-')) {
                j += 1;
            }
            if digits(&mut j) > 0 {
                i = j;
            }
        }
        self.pos = i;
        let value: f64 = self.text[start..i].parse().map_err(|_| SyntaxError::new(start, "invalid number"))?;
        if !value.is_finite() {
            return Err(SyntaxError::new(self.text[..start].chars().count(), "number out of range"));
        }
        Ok(value)
    }

    /// An arc flag: a single `0` or `1`.
    fn flag(&mut self) -> Result<bool, SyntaxError> {
        match self.peek() {
            Some(b'0') => {
                self.pos += 1;
                Ok(false)
            }
            Some(b'1') => {
                self.pos += 1;
                Ok(true)
            }
            _ => Err(self.error(format!("expected an arc flag (0 or 1), {}", self.found()))),
        }
    }
}

/// A list of numbers separated by whitespace and/or commas (as in `viewBox` and `points`).
pub(crate) fn parse_number_list(text: &str, max: usize) -> Result<Vec<f64>, SyntaxError> {
    let mut s = Scanner::new(text);
    let mut numbers = Vec::new();
    s.skip_whitespace();
    while !s.at_end() {
        if numbers.len() >= max {
            return Err(SyntaxError::too_many(s.offset(), format!("more than {max} numbers")));
        }
        numbers.push(s.number()?);
        s.skip_separator();
    }
    Ok(numbers)
}

/// Parses path data into a path in the same (user) coordinates. At most `max_points`
/// points are made; more is an error.
///
/// ```
/// use akap::import::svg::parse_path_data;
/// let path = parse_path_data("M0 0 h2 v1 H0 z", 100).unwrap();
/// assert_eq!(path.points, vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]);
/// ```
pub fn parse_path_data(data: &str, max_points: usize) -> Result<VectorPath, SyntaxError> {
    let mut s = Scanner::new(data);
    let mut path = VectorPath::default();
    let mut current: Point = [0.0, 0.0];
    let mut start: Point = [0.0, 0.0];
    // The control point a following S or T reflects, if the previous command was a curve
    // of the same kind.
    let mut last_cubic: Option<Point> = None;
    let mut last_quad: Option<Point> = None;
    let mut command: Option<u8> = None;
    s.skip_whitespace();
    while !s.at_end() {
        if path.points.len() > max_points {
            return Err(SyntaxError::too_many(s.offset(), format!("the path has more than {max_points} points")));
        }
        // A byte position: character offsets are counted only for an error.
        let command_start = s.position();
        let letter = match s.peek() {
            Some(c) if c.is_ascii_alphabetic() => {
                s.bump();
                s.skip_whitespace();
                c
            }
            // A number repeats the previous command; after a moveto, as a lineto.
            Some(_) if s.number_ahead() => match command {
                Some(b'M') => b'L',
                Some(b'm') => b'l',
                Some(b'Z' | b'z') => return Err(s.error("a number after a closepath (z) needs a command")),
                Some(c) => c,
                None => return Err(s.error("path data must start with a moveto (M or m)")),
            },
            _ => return Err(s.error(format!("expected a path command or a number, {}", s.found()))),
        };
        if command.is_none() && !matches!(letter, b'M' | b'm') {
            return Err(SyntaxError::new(s.offset_at(command_start), "path data must start with a moveto (M or m)"));
        }
        command = Some(letter);
        let relative = letter.is_ascii_lowercase();
        let base = if relative { current } else { [0.0, 0.0] };
        let point = |s: &mut Scanner| -> Result<Point, SyntaxError> {
            let x = s.number()?;
            s.skip_separator();
            let y = s.number()?;
            s.skip_separator();
            Ok([base[0] + x, base[1] + y])
        };
        let (mut next_cubic, mut next_quad) = (None, None);
        match letter.to_ascii_uppercase() {
            b'M' => {
                current = point(&mut s)?;
                start = current;
                path.verbs.push(Verb::Move);
                path.points.push(current);
            }
            b'L' => {
                current = point(&mut s)?;
                path.verbs.push(Verb::Line);
                path.points.push(current);
            }
            b'H' | b'V' => {
                let value = s.number()?;
                s.skip_separator();
                let axis = usize::from(letter.eq_ignore_ascii_case(&b'V'));
                current[axis] = if relative { current[axis] + value } else { value };
                path.verbs.push(Verb::Line);
                path.points.push(current);
            }
            b'C' | b'S' => {
                let c1 = if letter.eq_ignore_ascii_case(&b'C') {
                    point(&mut s)?
                } else {
                    last_cubic.map_or(current, |c| reflect(c, current))
                };
                let c2 = point(&mut s)?;
                let end = point(&mut s)?;
                path.verbs.push(Verb::Cubic);
                path.points.extend([c1, c2, end]);
                next_cubic = Some(c2);
                current = end;
            }
            b'Q' => {
                let c = point(&mut s)?;
                let end = point(&mut s)?;
                path.verbs.push(Verb::Quad);
                path.points.extend([c, end]);
                next_quad = Some(c);
                current = end;
            }
            b'T' => {
                let c = last_quad.map_or(current, |c| reflect(c, current));
                let end = point(&mut s)?;
                path.verbs.push(Verb::Quad);
                path.points.extend([c, end]);
                next_quad = Some(c);
                current = end;
            }
            b'A' => {
                let rx = s.number()?;
                s.skip_separator();
                let ry = s.number()?;
                s.skip_separator();
                let rotation = s.number()?;
                s.skip_separator();
                let large_arc = s.flag()?;
                s.skip_separator();
                let sweep = s.flag()?;
                s.skip_separator();
                let end = point(&mut s)?;
                arc_to(&mut path, current, rx, ry, rotation, large_arc, sweep, end);
                current = end;
            }
            b'Z' => {
                path.verbs.push(Verb::Close);
                current = start;
                s.skip_separator();
            }
            _ => {
                let offset = s.offset_at(command_start);
                return Err(SyntaxError::new(offset, format!("unknown path command `{}`", letter as char)));
            }
        }
        last_cubic = next_cubic;
        last_quad = next_quad;
    }
    if path.points.len() > max_points {
        return Err(SyntaxError::too_many(s.offset(), format!("the path has more than {max_points} points")));
    }
    Ok(path)
}

/// `c` reflected about `about`.
fn reflect(c: Point, about: Point) -> Point {
    [2.0 * about[0] - c[0], 2.0 * about[1] - c[1]]
}

/// Appends an elliptical arc from `from` to `to` as cubics of at most 45 degrees each
/// (radius error below 5e-6 of the radius).
#[allow(clippy::too_many_arguments)]
fn arc_to(path: &mut VectorPath, from: Point, rx: f64, ry: f64, degrees: f64, large: bool, sweep: bool, to: Point) {
    if from == to {
        return; // F.6.2: an arc between equal points is omitted.
    }
    let (mut rx, mut ry) = (rx.abs(), ry.abs());
    if rx == 0.0 || ry == 0.0 {
        path.verbs.push(Verb::Line);
        path.points.push(to);
        return;
    }
    let (sin_phi, cos_phi) = (degrees % 360.0).to_radians().sin_cos();
    // F.6.5 step 1: the start point in the ellipse's axes, relative to the chord midpoint.
    let (dx, dy) = ((from[0] - to[0]) / 2.0, (from[1] - to[1]) / 2.0);
    let x1 = cos_phi * dx + sin_phi * dy;
    let y1 = -sin_phi * dx + cos_phi * dy;
    // F.6.6: radii too small to reach are scaled up until the chord is a diameter.
    let lambda = (x1 / rx).powi(2) + (y1 / ry).powi(2);
    if lambda > 1.0 {
        rx *= lambda.sqrt();
        ry *= lambda.sqrt();
    }
    // Step 2: the centre in those axes.
    let (rx2, ry2, x12, y12) = (rx * rx, ry * ry, x1 * x1, y1 * y1);
    let denominator = rx2 * y12 + ry2 * x12;
    let mut root = ((rx2 * ry2 - denominator) / denominator).max(0.0).sqrt();
    if !root.is_finite() {
        root = 0.0;
    }
    if large == sweep {
        root = -root;
    }
    let (cx1, cy1) = (root * rx * y1 / ry, -root * ry * x1 / rx);
    // Step 3: the centre in user space.
    let cx = cos_phi * cx1 - sin_phi * cy1 + (from[0] + to[0]) / 2.0;
    let cy = sin_phi * cx1 + cos_phi * cy1 + (from[1] + to[1]) / 2.0;
    // Step 4: start angle and sweep.
    let theta1 = ((y1 - cy1) / ry).atan2((x1 - cx1) / rx);
    let theta2 = ((-y1 - cy1) / ry).atan2((-x1 - cx1) / rx);
    let mut delta = (theta2 - theta1) % TAU;
    if sweep && delta < 0.0 {
        delta += TAU;
    } else if !sweep && delta > 0.0 {
        delta -= TAU;
    }
    let pieces = (delta.abs() / FRAC_PI_4).ceil().clamp(1.0, 8.0) as usize;
    let step = delta / pieces as f64;
    let k = 4.0 / 3.0 * (step / 4.0).tan();
    let on_ellipse = |x: f64, y: f64| -> Point {
        [cx + rx * cos_phi * x - ry * sin_phi * y, cy + rx * sin_phi * x + ry * cos_phi * y]
    };
    for i in 0..pieces {
        let (a, b) = (theta1 + step * i as f64, theta1 + step * (i + 1) as f64);
        let ((sa, ca), (sb, cb)) = (a.sin_cos(), b.sin_cos());
        let end = if i + 1 == pieces { to } else { on_ellipse(cb, sb) };
        path.verbs.push(Verb::Cubic);
        path.points.extend([on_ellipse(ca - k * sa, sa + k * ca), on_ellipse(cb + k * sb, sb - k * cb), end]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(d: &str) -> Vec<Point> {
        parse_path_data(d, 1000).unwrap().points
    }

    #[test]
    fn numbers_run_together_as_the_grammar_allows() {
        assert_eq!(points("M1.5.5-2e1-.5"), vec![[1.5, 0.5], [-20.0, -0.5]]);
        assert_eq!(points("m1,2 3,4"), vec![[1.0, 2.0], [4.0, 6.0]]);
        // Arc flags need no separators.
        let arc = parse_path_data("M0 0a1 1 0 00 2 0", 100).unwrap();
        assert_eq!(arc.verbs[1], Verb::Cubic);
        assert_eq!(*arc.points.last().unwrap(), [2.0, 0.0]);
    }

    #[test]
    fn errors_say_where() {
        let e = |d: &str| parse_path_data(d, 100).unwrap_err();
        assert_eq!(e("L1 1").offset, 0);
        assert_eq!(e("M1 1 L2").message, "expected a number, found the end");
        assert_eq!(e("M1 1 X2").offset, 5);
        assert_eq!(e("M1 1 A1 1 0 2 0 3 3").message, "expected an arc flag (0 or 1), found `2`");
        assert_eq!(e("M1 1e999").message, "number out of range");
        assert_eq!(e("M0 0 z 1 1").offset, 7);
        let many = e(&"M0 0 ".repeat(200));
        assert!(many.too_many && many.message.contains("more than 100 points"), "{many:?}");
        assert!(!e("M1 1 L2").too_many);
    }
}
