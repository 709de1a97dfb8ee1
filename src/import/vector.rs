//! Vector paths (move, line, quadratic and cubic Béziers, close) as the SVG importer keeps
//! them: in output coordinates, for flattening into outlines and for exporting the art
//! deformed (map [`VectorPath::points`] through the mesh, then write them back with
//! [`VectorPath::to_path_data`]).

use std::fmt::Write;

use crate::geometry::Point;
use crate::message::Number;

/// A path command; each takes a fixed number of points from [`VectorPath::points`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verb {
    /// Starts a subpath at one point.
    Move,
    /// A line to one point.
    Line,
    /// A quadratic Bézier: control point, end point.
    Quad,
    /// A cubic Bézier: two control points, end point.
    Cubic,
    /// Closes the subpath (no point).
    Close,
}

impl Verb {
    /// How many points the verb takes.
    pub fn point_count(self) -> usize {
        match self {
            Self::Move | Self::Line => 1,
            Self::Quad => 2,
            Self::Cubic => 3,
            Self::Close => 0,
        }
    }

    /// The verb of an SVG path-data letter in absolute form (`M`, `L`, `Q`, `C`, `Z`).
    pub fn from_letter(letter: char) -> Option<Self> {
        [Self::Move, Self::Line, Self::Quad, Self::Cubic, Self::Close].into_iter().find(|v| v.letter() == letter)
    }

    /// The SVG path-data letter (absolute form).
    pub fn letter(self) -> char {
        match self {
            Self::Move => 'M',
            Self::Line => 'L',
            Self::Quad => 'Q',
            Self::Cubic => 'C',
            Self::Close => 'Z',
        }
    }
}

/// How overlapping subpaths of one path fill (SVG `fill-rule`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FillRule {
    /// Inside where the winding number is not zero (the SVG default).
    #[default]
    NonZero,
    /// Inside where the winding number is odd.
    EvenOdd,
}

impl FillRule {
    /// Whether a point with this winding number is filled.
    pub fn fills(self, winding: i32) -> bool {
        match self {
            Self::NonZero => winding != 0,
            Self::EvenOdd => winding % 2 != 0,
        }
    }
}

/// A path of straight and curved segments. Every subpath starts with [`Verb::Move`]; arcs
/// have been converted to cubics.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VectorPath {
    /// The commands.
    pub verbs: Vec<Verb>,
    /// Their points, in order (see [`Verb::point_count`]).
    pub points: Vec<Point>,
}

impl VectorPath {
    /// Applies `f` to every point (transforms are affine, so curves stay exact).
    pub fn map_points(&mut self, f: impl Fn(Point) -> Point) {
        for p in &mut self.points {
            *p = f(*p);
        }
    }

    /// The path of SVG path-data letters (`commands`, absolute M, L, Q, C, Z) and their
    /// points. Fails, saying why, for another letter or a number of points other than the
    /// commands take.
    pub fn from_commands(commands: &str, points: Vec<Point>) -> Result<Self, String> {
        let verbs = (commands.chars())
            .map(|c| {
                Verb::from_letter(c)
                    .ok_or_else(|| format!("unknown path command {c:?}: the commands are M, L, Q, C, Z"))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let needed: usize = verbs.iter().map(|v| v.point_count()).sum();
        if points.len() != needed {
            return Err(format!("the commands take {needed} points, but {} were given", points.len()));
        }
        Ok(Self { verbs, points })
    }

    /// SVG path data with absolute commands for these verbs and the given points (for
    /// example the path's own points mapped through a deformed mesh): the one writer of
    /// path data, in JavaScript too (`pathData`). Numbers are written in their shortest
    /// exact form, in exponent form outside 1e-6 to 1e21, and `-0` as `0`. `points` must
    /// have the length of [`VectorPath::points`]; extra points are ignored and missing ones
    /// end the output early.
    pub fn to_path_data(&self, points: &[Point]) -> String {
        let mut out = String::new();
        let mut next = 0;
        for &verb in &self.verbs {
            let count = verb.point_count();
            let Some(chunk) = points.get(next..next + count) else { break };
            next += count;
            if !out.is_empty() {
                out.push(' ');
            }
            out.push(verb.letter());
            for p in chunk {
                // Adding +0 turns -0 into 0 and changes nothing else.
                let _ = write!(out, " {} {}", Number(p[0] + 0.0), Number(p[1] + 0.0));
            }
        }
        out
    }

    /// The subpaths as closed polylines, curves replaced by chords that stay within
    /// `tolerance` of them. Subpaths are closed implicitly (filling closes them), and the
    /// closing point is not repeated. Fails with the number of points that would be needed
    /// (at least; NaN when a curve's size is not finite) when that exceeds `max_points`
    /// (counting `already` points made before), as a float: it may be far beyond `usize`.
    pub fn flatten(&self, tolerance: f64, already: usize, max_points: usize) -> Result<Vec<Vec<Point>>, f64> {
        let mut rings: Vec<Vec<Point>> = Vec::new();
        let mut ring: Vec<Point> = Vec::new();
        let mut total = already;
        let mut next = 0;
        let mut current = [0.0, 0.0];
        for &verb in &self.verbs {
            let p = &self.points[next..next + verb.point_count()];
            next += verb.point_count();
            let pieces = match verb {
                Verb::Move | Verb::Close => 0.0,
                Verb::Line => 1.0,
                // Uniform steps: a curve with second derivative at most D deviates from its
                // n-segment chord polyline by at most D / (8 n^2).
                Verb::Quad => {
                    let d = 2.0 * second_difference(current, p[0], p[1]);
                    (d / (8.0 * tolerance)).sqrt().ceil().max(1.0)
                }
                Verb::Cubic => {
                    let d = 6.0 * second_difference(current, p[0], p[1]).max(second_difference(p[0], p[1], p[2]));
                    (d / (8.0 * tolerance)).sqrt().ceil().max(1.0)
                }
            };
            // NaN (from infinite control points) fails this too.
            let budget = max_points.saturating_sub(total) as f64;
            if pieces.is_nan() || pieces > budget {
                return Err(total as f64 + pieces);
            }
            let n = pieces as usize;
            match verb {
                Verb::Move => {
                    if !ring.is_empty() {
                        rings.push(std::mem::take(&mut ring));
                    }
                    current = p[0];
                    ring.push(current);
                    total += 1;
                }
                Verb::Close => {
                    if !ring.is_empty() {
                        current = ring[0];
                        rings.push(std::mem::take(&mut ring));
                    }
                }
                Verb::Line | Verb::Quad | Verb::Cubic => {
                    if ring.is_empty() {
                        // After a close, drawing continues from the subpath's start.
                        ring.push(current);
                        total += 1;
                    }
                    let end = *p.last().expect("a drawing verb has points");
                    for i in 1..n {
                        let t = i as f64 / n as f64;
                        ring.push(match verb {
                            Verb::Quad => quad_at(current, p[0], p[1], t),
                            _ => cubic_at(current, p[0], p[1], p[2], t),
                        });
                    }
                    ring.push(end);
                    total += n;
                    current = end;
                }
            }
        }
        if !ring.is_empty() {
            rings.push(ring);
        }
        for ring in &mut rings {
            ring.dedup();
            while ring.len() > 1 && ring.first() == ring.last() {
                ring.pop();
            }
        }
        Ok(rings)
    }
}

/// `|a - 2b + c|`: the size of a second difference of control points.
fn second_difference(a: Point, b: Point, c: Point) -> f64 {
    (a[0] - 2.0 * b[0] + c[0]).hypot(a[1] - 2.0 * b[1] + c[1])
}

fn quad_at(p0: Point, p1: Point, p2: Point, t: f64) -> Point {
    let s = 1.0 - t;
    let (a, b, c) = (s * s, 2.0 * s * t, t * t);
    [a * p0[0] + b * p1[0] + c * p2[0], a * p0[1] + b * p1[1] + c * p2[1]]
}

fn cubic_at(p0: Point, p1: Point, p2: Point, p3: Point, t: f64) -> Point {
    let s = 1.0 - t;
    let (a, b, c, d) = (s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t);
    [a * p0[0] + b * p1[0] + c * p2[0] + d * p3[0], a * p0[1] + b * p1[1] + c * p2[1] + d * p3[1]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flattened_quarter_circle_stays_within_tolerance() {
        // The standard cubic for a quarter of the unit circle (radius error below 3e-4).
        let k = 4.0 / 3.0 * (std::f64::consts::PI / 8.0).tan();
        let path = VectorPath {
            verbs: vec![Verb::Move, Verb::Cubic, Verb::Line, Verb::Close],
            points: vec![[1.0, 0.0], [1.0, k], [k, 1.0], [0.0, 1.0], [0.0, 0.0]],
        };
        let tolerance = 1e-3;
        let rings = path.flatten(tolerance, 0, 1000).unwrap();
        assert_eq!(rings.len(), 1);
        let ring = &rings[0];
        assert_eq!(ring[0], [1.0, 0.0]);
        assert_eq!(*ring.last().unwrap(), [0.0, 0.0]);
        // Chord midpoints stay within tolerance (plus the cubic's own error) of the circle.
        for w in ring[..ring.len() - 1].windows(2) {
            let m = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
            assert!((1.0 - m[0].hypot(m[1])).abs() < tolerance + 3e-4, "{m:?}");
        }
        assert!(path.flatten(tolerance, 0, 5).is_err());
        assert_eq!(path.to_path_data(&path.points), format!("M 1 0 C 1 {k} {k} 1 0 1 L 0 0 Z"));
    }
}
