//! From closed rings to outlines with holes, by containment and fill rule.
//!
//! The rings may come from several shapes (SVG elements), each with its own fill rule, and
//! must not cross or touch. Then they nest into a tree, every face of the tree (inside a
//! ring, outside its children) has one winding number per shape, and a face is filled when
//! any shape fills it. A ring with a filled face on one side and an empty one on the other
//! is a boundary: the outer boundary of a part, or a hole in one. Parts come out largest
//! first; a part inside a hole of another part is a part of its own.

use crate::geometry::{bounding_box, distance, orient, point_in_polygon, polygon_area, Point};
use crate::import::vector::FillRule;
use crate::outline::{meeting_segments, Outline};

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
    /// The crossing check gave up after `max_segment_pairs` comparisons.
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
    match meeting_segments(&points, true, max_segment_pairs).as_deref() {
        None => return Err(RegionError::TooComplex),
        Some([[(ring_a, _), (ring_b, _)], ..]) => {
            return Err(RegionError::Crossing(sources[*ring_a], sources[*ring_b]))
        }
        Some([]) => {}
    }
    let n = points.len();
    let (order, parent) = containment(&points);

    // Winding numbers per shape of each ring's inner face, parents before children.
    let mut windings: Vec<Vec<(usize, i32)>> = vec![Vec::new(); n];
    let mut filled = vec![false; n];
    for &i in &order {
        let mut w = parent[i].map(|p| windings[p].clone()).unwrap_or_default();
        let shape = rings[sources[i]].shape;
        let turn = if areas[i] > 0.0 { 1 } else { -1 };
        match w.iter_mut().find(|(s, _)| *s == shape) {
            Some(entry) => entry.1 += turn,
            None => w.push((shape, turn)),
        }
        filled[i] = w.iter().any(|&(s, k)| rules.get(s).copied().unwrap_or_default().fills(k));
        windings[i] = w;
    }
    let outside_filled = |i: usize| parent[i].is_some_and(|p| filled[p]);
    let is_boundary = |i: usize| filled[i] != outside_filled(i);

    // Outer boundaries, then holes attached to the nearest enclosing outer boundary.
    let mut part_of: Vec<Option<usize>> = vec![None; n];
    let mut parts: Vec<(Outline, f64)> = Vec::new();
    for &i in &order {
        if is_boundary(i) && filled[i] {
            part_of[i] = Some(parts.len());
            parts.push((Outline::new(points[i].clone()), areas[i].abs()));
        }
    }
    for &i in &order {
        if !is_boundary(i) || filled[i] {
            continue;
        }
        let mut a = parent[i].expect("a hole has a filled face around it");
        while !is_boundary(a) {
            a = parent[a].expect("filled faces end at an outer boundary");
        }
        let part = part_of[a].expect("the enclosing boundary is an outer one");
        if areas[i].abs() >= min_area {
            parts[part].0.holes.push(points[i].clone());
            parts[part].1 -= areas[i].abs();
        }
    }
    parts.retain(|(_, area)| *area >= min_area);
    parts.sort_by(|a, b| b.1.total_cmp(&a.1));
    Ok(parts.into_iter().map(|(outline, _)| outline).collect())
}

/// The containment tree of rings that neither cross nor touch: the rings ordered by
/// decreasing area (so parents come first), and each ring's parent, the smallest ring
/// around it.
pub(crate) fn containment(rings: &[Vec<Point>]) -> (Vec<usize>, Vec<Option<usize>>) {
    let areas: Vec<f64> = rings.iter().map(|r| polygon_area(r).abs()).collect();
    let mut order: Vec<usize> = (0..rings.len()).collect();
    order.sort_by(|&i, &j| areas[j].total_cmp(&areas[i]));
    let boxes: Vec<(Point, Point)> =
        rings.iter().map(|r| bounding_box(r.iter().copied()).unwrap_or(([0.0; 2], [0.0; 2]))).collect();
    let mut parent = vec![None; rings.len()];
    for (rank, &i) in order.iter().enumerate() {
        let Some(&p) = rings[i].first() else { continue };
        // Smallest first: the first container found is the immediate parent.
        parent[i] = order[..rank].iter().rev().copied().find(|&j| {
            let (lo, hi) = boxes[j];
            p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] && point_in_polygon(p, &rings[j])
        });
    }
    (order, parent)
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
