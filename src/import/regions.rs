//! From closed rings to outlines with holes, by containment and fill rule.
//!
//! The rings may come from several shapes (SVG elements), each with its own fill rule, and
//! must not cross or touch. Then they nest into a tree, every face of the tree (inside a
//! ring, outside its children) has one winding number per shape, and a face is filled when
//! any shape fills it. A ring with a filled face on one side and an empty one on the other
//! is a boundary: the outer boundary of a part, or a hole in one. Parts come out largest
//! first; a part inside a hole of another part is a part of its own. The crossing check and
//! the tree come from one sweep (`crate::sweep`), O(n log n) in the number of points; the
//! fill of the faces from one walk of the tree.

use crate::geometry::{bounding_box, distance, orient, polygon_area, Point};
use crate::import::vector::FillRule;
use crate::outline::Outline;
use crate::sweep::{sweep, Find, Sweep};

/// A closed ring (not repeating its first point) of one shape.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SourceRing {
    pub(crate) points: Vec<Point>,
    /// The shape it belongs to: an index into the fill rules.
    pub(crate) shape: usize,
}

/// Why rings could not be assembled.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum RegionError {
    /// The two rings (indices into the input) cross or touch (the same index twice: a ring
    /// meets itself).
    Crossing(usize, usize),
    /// The crossing check gave up after `max_segment_pairs` comparisons of segments.
    TooComplex,
}

/// Builds outlines from rings; `rules[shape]` is the fill rule of each shape. Rings with
/// fewer than three distinct points or no area are ignored, and so are parts with an area
/// below `min_area` (holes that small are filled).
pub(crate) fn assemble(
    rings: &[SourceRing],
    rules: &[FillRule],
    min_area: f64,
    max_segment_pairs: usize,
) -> Result<Vec<Outline>, RegionError> {
    // Clean rings, keeping their input indices and signed areas.
    let mut sources = Vec::new();
    let mut areas = Vec::new();
    let mut points: Vec<Vec<Point>> = Vec::new();
    for (index, ring) in rings.iter().enumerate() {
        let mut ring_points = ring.points.clone();
        ring_points.dedup();
        while ring_points.len() > 1 && ring_points.first() == ring_points.last() {
            ring_points.pop();
        }
        if ring_points.len() < 3 {
            continue;
        }
        // Rings along a line enclose nothing; a figure-eight has zero area too, but it
        // crosses itself, which the check below reports.
        let (lo, hi) = bounding_box(ring_points.iter().copied()).expect("ring has points");
        let diagonal2 = (hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2);
        let a = ring_points[0];
        let b = ring_points.iter().copied().max_by(|p, q| distance(a, *p).total_cmp(&distance(a, *q))).unwrap_or(a);
        if ring_points.iter().all(|&p| orient(a, b, p).abs() <= 1e-12 * diagonal2) {
            continue;
        }
        let area = polygon_area(&ring_points);
        sources.push(index);
        areas.push(area);
        points.push(ring_points);
    }
    let found = sweep(&points, Find::First, max_segment_pairs).ok_or(RegionError::TooComplex)?;
    if let Some([(ring_a, _), (ring_b, _)]) = found.meetings.first() {
        return Err(RegionError::Crossing(sources[*ring_a], sources[*ring_b]));
    }
    let n = points.len();
    let parent = &found.parents;
    let filled = filled_faces(&found, |i| rings[sources[i]].shape, rules);
    let outside_filled = |i: usize| parent[i].is_some_and(|p| filled[p]);
    let is_boundary = |i: usize| filled[i] != outside_filled(i);

    // Outer boundaries, then holes attached to the nearest enclosing outer boundary (the
    // nearest boundary at or above each ring, found containers first).
    let mut part_of: Vec<Option<usize>> = vec![None; n];
    let mut boundary_above = vec![usize::MAX; n];
    let mut parts: Vec<(Outline, f64)> = Vec::new();
    for &i in &found.order {
        boundary_above[i] = if is_boundary(i) { i } else { parent[i].map_or(usize::MAX, |p| boundary_above[p]) };
        if is_boundary(i) && filled[i] {
            part_of[i] = Some(parts.len());
            parts.push((Outline::new(points[i].clone()), areas[i].abs()));
        }
    }
    // Holes by decreasing area, as they are listed.
    let mut holes: Vec<usize> = (0..n).filter(|&i| is_boundary(i) && !filled[i]).collect();
    holes.sort_by(|&i, &j| areas[j].abs().total_cmp(&areas[i].abs()));
    for i in holes {
        let around = parent[i].map(|p| boundary_above[p]).expect("a hole has a filled face around it");
        let part = part_of[around].expect("the enclosing boundary is an outer one");
        if areas[i].abs() >= min_area {
            parts[part].0.holes.push(points[i].clone());
            parts[part].1 -= areas[i].abs();
        }
    }
    parts.retain(|(_, area)| *area >= min_area);
    parts.sort_by(|a, b| b.1.total_cmp(&a.1));
    Ok(parts.into_iter().map(|(outline, _)| outline).collect())
}

/// Whether the inner face of each ring is filled: some shape's winding number there is
/// one its rule fills. Walks the containment tree depth first, adding a ring's turn (+1
/// counter-clockwise, -1 clockwise) to its shape's winding number on the way in and
/// taking it off on the way out, with a count of the shapes that fill: O(n) however deep
/// the rings nest.
fn filled_faces(found: &Sweep, shape_of: impl Fn(usize) -> usize, rules: &[FillRule]) -> Vec<bool> {
    let n = found.parents.len();
    let mut start = vec![0; n + 1];
    for p in found.parents.iter().flatten() {
        start[p + 1] += 1;
    }
    for k in 0..n {
        start[k + 1] += start[k];
    }
    let mut children = vec![0; start[n]];
    let mut next = start.clone();
    for (i, p) in found.parents.iter().enumerate() {
        if let Some(p) = *p {
            children[next[p]] = i;
            next[p] += 1;
        }
    }
    let shapes = (0..n).map(&shape_of).max().map_or(0, |s| s + 1);
    let mut winding = vec![0i32; shapes];
    let mut filling = 0usize;
    let mut filled = vec![false; n];
    let mut stack: Vec<(usize, bool)> = (0..n).filter(|&i| found.parents[i].is_none()).map(|i| (i, true)).collect();
    while let Some((i, entering)) = stack.pop() {
        let shape = shape_of(i);
        let rule = rules.get(shape).copied().unwrap_or_default();
        let turn = if found.counter_clockwise[i] == entering { 1 } else { -1 };
        let before = rule.fills(winding[shape]);
        winding[shape] += turn;
        match (before, rule.fills(winding[shape])) {
            (false, true) => filling += 1,
            (true, false) => filling -= 1,
            _ => {}
        }
        if entering {
            filled[i] = filling > 0;
            stack.push((i, false));
            stack.extend(children[start[i]..start[i + 1]].iter().map(|&c| (c, true)));
        }
    }
    filled
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, s: f64, ccw: bool) -> Vec<Point> {
        let mut r = vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]];
        if !ccw {
            r.reverse();
        }
        r
    }

    fn ring(points: Vec<Point>, shape: usize) -> SourceRing {
        SourceRing { points, shape }
    }

    #[test]
    fn fill_rules_decide_holes() {
        // Two squares of one path running the same way: a hole under even-odd only.
        let rings = [ring(square(0.0, 0.0, 10.0, true), 0), ring(square(2.0, 2.0, 2.0, true), 0)];
        let even_odd = assemble(&rings, &[FillRule::EvenOdd], 0.0, usize::MAX).unwrap();
        assert_eq!(even_odd.len(), 1);
        assert_eq!(even_odd[0].holes.len(), 1);
        assert_eq!(even_odd[0].area(), 96.0);
        let non_zero = assemble(&rings, &[FillRule::NonZero], 0.0, usize::MAX).unwrap();
        assert_eq!(non_zero[0].holes.len(), 0);
        // Running the other way makes a hole under non-zero too.
        let rings = [ring(square(0.0, 0.0, 10.0, true), 0), ring(square(2.0, 2.0, 2.0, false), 0)];
        assert_eq!(assemble(&rings, &[FillRule::NonZero], 0.0, usize::MAX).unwrap()[0].holes.len(), 1);
    }

    #[test]
    fn a_shape_in_a_hole_is_a_part_and_other_shapes_fill_holes() {
        let rings = [
            ring(square(0.0, 0.0, 10.0, true), 0),
            ring(square(2.0, 2.0, 6.0, false), 0),
            ring(square(4.0, 4.0, 1.0, true), 1),
            ring(square(20.0, 0.0, 1.0, true), 2),
        ];
        let parts = assemble(&rings, &[FillRule::NonZero; 3], 0.0, usize::MAX).unwrap();
        let areas: Vec<f64> = parts.iter().map(Outline::area).collect();
        assert_eq!(areas, vec![64.0, 1.0, 1.0]);
        // A second shape covering the hole fills it: one part, no hole.
        let rings = [
            ring(square(0.0, 0.0, 10.0, true), 0),
            ring(square(2.0, 2.0, 6.0, false), 0),
            ring(square(1.0, 1.0, 8.0, true), 1),
        ];
        let parts = assemble(&rings, &[FillRule::NonZero; 2], 0.0, usize::MAX).unwrap();
        assert_eq!(parts.len(), 1);
        assert_eq!(parts[0].area(), 100.0);
        // Tiny parts and holes go.
        let rings = [ring(square(0.0, 0.0, 10.0, true), 0), ring(square(2.0, 2.0, 0.5, false), 0)];
        assert_eq!(assemble(&rings, &[FillRule::NonZero], 1.0, usize::MAX).unwrap()[0].holes.len(), 0);
    }

    #[test]
    fn crossing_rings_are_named() {
        let rings = [ring(square(0.0, 0.0, 2.0, true), 0), ring(square(1.0, 1.0, 2.0, true), 1)];
        assert_eq!(assemble(&rings, &[FillRule::NonZero; 2], 0.0, usize::MAX), Err(RegionError::Crossing(0, 1)));
    }
}
