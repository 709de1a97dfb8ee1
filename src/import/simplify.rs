//! Simplifying closed rings to a tolerance without breaking topology.
//!
//! Each ring is simplified on its own (Douglas-Peucker: keep the point farthest from a
//! chord while it is farther than the tolerance). Simplified rings may then cross
//! themselves or each other, or a small ring may end up on the other side of a simplified
//! neighbour; every segment involved gets back the original point farthest from it, and a
//! ring that changed sides is restored whole, until the rings are as valid as the input.
//! That terminates: each round restores points, and the input rings themselves are valid.
//! Each round's check is one sweep (`crate::sweep`), O(n log n): it reports enough meeting
//! pairs that every crossing involves a reported segment, and when nothing crosses it gives
//! the containment tree to compare with the input's.

use crate::geometry::{orient, Point};
use crate::sweep::{sweep, Find};

/// Simplifies rings that neither cross nor touch, keeping it so. `parents[r]` is the ring
/// that immediately contains ring `r` (if any), which must stay so. `None` when the
/// crossing checks, all rounds together, would compare more than `max_segment_pairs`
/// segments.
pub(crate) fn simplify_rings(
    rings: &[Vec<Point>],
    parents: &[Option<usize>],
    tolerance: f64,
    max_segment_pairs: usize,
) -> Option<Vec<Vec<Point>>> {
    // Per ring, which original points are kept.
    let mut keep: Vec<Vec<bool>> = rings.iter().map(|r| douglas_peucker(r, tolerance)).collect();
    let mut budget = max_segment_pairs;
    loop {
        let simplified: Vec<Vec<Point>> = rings
            .iter()
            .zip(&keep)
            .map(|(r, k)| r.iter().zip(k).filter(|(_, &k)| k).map(|(p, _)| *p).collect())
            .collect();
        let found = sweep(&simplified, Find::Cover, budget)?;
        budget -= found.comparisons;
        // The points to restore, found before any is restored (restoring renumbers the
        // simplified segments).
        let mut restore = Vec::new();
        for [a, b] in &found.meetings {
            for &(ring, segment) in [a, b] {
                restore.extend(refine(&rings[ring], &keep[ring], segment).map(|k| (ring, k)));
            }
        }
        let mut changed = false;
        for (ring, k) in restore {
            changed |= !keep[ring][k];
            keep[ring][k] = true;
        }
        if found.meetings.is_empty() {
            // Nothing crosses, so the sweep's containment is exact: a ring whose container
            // changed is restored whole, with its old and its new container.
            for (r, &parent) in parents.iter().enumerate() {
                if found.parents[r] != parent {
                    for ring in [Some(r), parent, found.parents[r]].into_iter().flatten() {
                        if keep[ring].iter().any(|k| !k) {
                            keep[ring].fill(true);
                            changed = true;
                        }
                    }
                }
            }
        }
        if !changed {
            return Some(simplified);
        }
    }
}

/// Douglas-Peucker on a closed ring: which points to keep (at least three).
fn douglas_peucker(ring: &[Point], tolerance: f64) -> Vec<bool> {
    let n = ring.len();
    let mut keep = vec![false; n];
    if n <= 3 {
        keep.fill(true);
        return keep;
    }
    // Anchors far apart: the point farthest from point 0, and the point farthest from that.
    let farthest_from = |a: Point| {
        (0..n).max_by(|&i, &j| distance2(a, ring[i]).total_cmp(&distance2(a, ring[j]))).expect("ring has points")
    };
    let first = farthest_from(ring[0]);
    let second = farthest_from(ring[first]);
    // Rotate the indices so that the first anchor is point 0.
    let ring: Vec<Point> = ring[first..].iter().chain(&ring[..first]).copied().collect();
    let far = (second + n - first) % n;
    let ring = ring.as_slice();
    keep[0] = true;
    keep[far] = true;
    let mut stack = vec![(0, far), (far, n)];
    while let Some((i, j)) = stack.pop() {
        if let Some((k, d)) = farthest(ring, i, j) {
            if d > tolerance {
                keep[k] = true;
                stack.push((i, k));
                stack.push((k, j));
            }
        }
    }
    // A ring needs a third point: the one farthest from the chord between the two anchors.
    if keep.iter().filter(|&&k| k).count() < 3 {
        let k = [farthest(ring, 0, far), farthest(ring, far, n)]
            .into_iter()
            .flatten()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .expect("more than three points");
        keep[k.0] = true;
    }
    // Back to the caller's numbering.
    keep.rotate_right(first);
    keep
}

/// The point strictly between `i` and `j` (indices modulo the ring) farthest from the chord
/// `i j`, and its distance.
fn farthest(ring: &[Point], i: usize, j: usize) -> Option<(usize, f64)> {
    let n = ring.len();
    let (a, b) = (ring[i % n], ring[j % n]);
    (i + 1..j).map(|k| (k, distance_to_segment(ring[k % n], a, b))).max_by(|x, y| x.1.total_cmp(&y.1))
}

/// The original point farthest from simplified segment `segment` of a ring (the segment
/// from its `segment`-th kept point to the next), if the segment dropped any.
fn refine(ring: &[Point], keep: &[bool], segment: usize) -> Option<usize> {
    let kept: Vec<usize> = (0..ring.len()).filter(|&k| keep[k]).collect();
    let i = kept[segment];
    let j = if segment + 1 < kept.len() { kept[segment + 1] } else { kept[0] + ring.len() };
    farthest(ring, i, j).map(|(k, _)| k % ring.len())
}

fn distance2(a: Point, b: Point) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}

/// Distance from `p` to the closed segment `a b`.
fn distance_to_segment(p: Point, a: Point, b: Point) -> f64 {
    let len2 = distance2(a, b);
    if len2 == 0.0 {
        return distance2(p, a).sqrt();
    }
    let t = ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) / len2;
    if t <= 0.0 {
        distance2(p, a).sqrt()
    } else if t >= 1.0 {
        distance2(p, b).sqrt()
    } else {
        orient(a, b, p).abs() / len2.sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::point_in_polygon;
    use crate::outline::check_no_intersections;

    #[test]
    fn a_noisy_square_becomes_its_corners() {
        let mut ring = Vec::new();
        for i in 0..40 {
            let wiggle = if i % 2 == 0 { 0.1 } else { -0.1 };
            let t = i as f64 / 10.0;
            ring.push(match i / 10 {
                0 => [t, wiggle],
                1 => [1.0 + wiggle, t - 1.0],
                2 => [3.0 - t, 1.0 + wiggle],
                _ => [wiggle, 4.0 - t],
            });
        }
        let out = simplify_rings(&[ring], &[None], 0.25, usize::MAX).unwrap();
        assert_eq!(out[0].len(), 4, "{:?}", out[0]);
    }

    #[test]
    fn the_closing_segment_refines_across_the_ring_start() {
        let ring = [[0.0, 0.0], [1.0, -0.1], [2.0, 0.0], [2.0, 1.0], [1.0, 1.1], [0.0, 1.0]];
        let keep = [true, false, true, false, true, false];
        // Kept points 0, 2, 4: the last segment runs from point 4 back to point 0.
        assert_eq!(refine(&ring, &keep, 2), Some(5));
        assert_eq!(refine(&ring, &keep, 0), Some(1));
        assert_eq!(refine(&ring, &[true; 6], 5), None);
    }

    #[test]
    fn a_close_neighbour_keeps_rings_apart() {
        // A zigzag outer ring whose simplified edge (y = 0.4) would pass over a small hole
        // in one of its valleys.
        let mut outer: Vec<Point> = (0..=20).map(|i| [i as f64, if i % 2 == 0 { 0.4 } else { 0.0 }]).collect();
        outer.extend([[20.0, 10.0], [0.0, 10.0]]);
        let hole = vec![[10.8, 0.15], [11.2, 0.15], [11.0, 0.3]];
        let rings = vec![outer, hole];
        assert!(point_in_polygon(rings[1][0], &rings[0]));
        let out = simplify_rings(&rings, &[None, Some(0)], 0.5, usize::MAX).unwrap();
        assert!(check_no_intersections(&out).is_ok());
        assert!(point_in_polygon(out[1][0], &out[0]));
    }
}
