//! The sweep against the definitions: every pair of segments compared (brute force), and
//! containment by point in polygon, on random rings with small integer coordinates (so
//! that shared points, touching and collinear overlaps are common).

use super::*;
use crate::geometry::{point_in_polygon, polygon_area};
use crate::shapes::comb;

struct Rng(u64);

impl Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.0 = mix(self.0);
        self.0 % n
    }
}

/// Every pair of segments that meet, by definition: closed segments that share a point,
/// except consecutive segments of a ring, which may share their common vertex only.
fn brute_force(rings: &[Vec<Point>]) -> Vec<[SegmentRef; 2]> {
    let segment = |(r, i): SegmentRef| (rings[r][i], rings[r][(i + 1) % rings[r].len()]);
    let all: Vec<SegmentRef> = (0..rings.len()).flat_map(|r| (0..rings[r].len()).map(move |i| (r, i))).collect();
    let mut pairs = Vec::new();
    for (k, &s) in all.iter().enumerate() {
        for &t in &all[k + 1..] {
            let ((a, b), (c, d)) = (segment(s), segment(t));
            let len = rings[s.0].len();
            let meets = if s.0 == t.0 && (s.1 + 1) % len == t.1 {
                // s ends where t starts: the far end of one lies on the other.
                segments_intersect(d, d, a, b) || segments_intersect(a, a, c, d)
            } else if s.0 == t.0 && (t.1 + 1) % len == s.1 {
                segments_intersect(b, b, c, d) || segments_intersect(c, c, a, b)
            } else {
                segments_intersect(a, b, c, d)
            };
            if meets {
                pairs.push([s, t]);
            }
        }
    }
    pairs
}

fn random_rings(rng: &mut Rng, grid: u64) -> Vec<Vec<Point>> {
    let count = 1 + rng.below(4) as usize;
    (0..count)
        .map(|_| {
            let m = 3 + rng.below(4) as usize;
            let mut ring: Vec<Point> = Vec::new();
            while ring.len() < m {
                let p = [rng.below(grid) as f64, rng.below(grid) as f64];
                if ring.last() != Some(&p) {
                    ring.push(p);
                }
            }
            ring
        })
        .collect()
}

#[test]
fn finds_a_meeting_exactly_when_there_is_one() {
    let mut rng = Rng(1);
    let (mut with, mut without) = (0, 0);
    for _ in 0..3000 {
        let grid = [4, 8, 30][rng.below(3) as usize];
        let rings = random_rings(&mut rng, grid);
        let expected = brute_force(&rings);
        let first = sweep(&rings, Find::First, usize::MAX).unwrap();
        assert_eq!(first.meetings.is_empty(), expected.is_empty(), "{rings:?}: {:?}", first.meetings);
        for pair in &first.meetings {
            assert!(expected.contains(pair), "{rings:?}: {pair:?} do not meet");
        }
        // Cover: every pair found meets, and every meeting pair shares a segment with one.
        let cover = sweep(&rings, Find::Cover, usize::MAX).unwrap();
        let reported: Vec<SegmentRef> = cover.meetings.iter().flatten().copied().collect();
        for pair in &cover.meetings {
            assert!(expected.contains(pair), "{rings:?}: {pair:?} do not meet");
        }
        for [s, t] in &expected {
            assert!(reported.contains(s) || reported.contains(t), "{rings:?}: {s:?} {t:?} not covered");
        }
        if expected.is_empty() {
            without += 1;
        } else {
            with += 1;
        }
    }
    assert!(with > 500 && without > 150, "{with} with meetings, {without} without");
}

#[test]
fn containment_matches_point_in_polygon() {
    let mut rng = Rng(2);
    let mut checked = 0;
    for _ in 0..8000 {
        // Several small rings and one large one, so that nesting happens.
        let mut rings = random_rings(&mut rng, 40);
        let (x, y, s) = (rng.below(10) as f64, rng.below(10) as f64, 20.0 + rng.below(20) as f64);
        rings.push(vec![[x - s, y - s], [x + s, y - s + 1.0], [x + s, y + s], [x - s + 2.0, y + s]]);
        if rng.below(2) == 0 {
            rings.last_mut().unwrap().reverse();
        }
        if !brute_force(&rings).is_empty() {
            continue;
        }
        checked += 1;
        let found = sweep(&rings, Find::First, usize::MAX).unwrap();
        assert!(found.meetings.is_empty());
        for (r, ring) in rings.iter().enumerate() {
            let area = |c: usize| polygon_area(&rings[c]).abs();
            let parent = (0..rings.len())
                .filter(|&c| c != r && point_in_polygon(ring[0], &rings[c]))
                .min_by(|&a, &b| area(a).total_cmp(&area(b)));
            assert_eq!(found.parents[r], parent, "ring {r} of {rings:?}");
            assert_eq!(found.counter_clockwise[r], polygon_area(ring) > 0.0);
        }
        let mut seen = vec![false; rings.len()];
        for &r in &found.order {
            assert!(found.parents[r].is_none_or(|p| seen[p]), "ring {r} before its container");
            seen[r] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }
    assert!(checked > 400, "{checked} valid sets");
}

#[test]
fn a_comb_takes_n_log_n_comparisons() {
    // 8000 segments, 4000 of them spanning the comb: a sweep by x ranges compares about
    // 8 million pairs; this one may compare at most 50 per segment.
    let teeth = 2000;
    let n = 4 * teeth;
    let mut rings = vec![comb(teeth, 1000.0)];
    let found = sweep(&rings, Find::First, 50 * n).expect("within n log n");
    assert!(found.meetings.is_empty());
    // No two vertices straight above one another within rounding: swept once.
    assert!(!found.close_in_a_column);
    // A hole in each tooth but the last, then one tooth bent onto the next.
    for i in 0..teeth - 1 {
        let (x, y) = (10.0 + (i % 900) as f64, 2.0 * i as f64 + 0.5);
        rings.push(vec![[x, y - 0.25], [x + 10.0, y], [x, y + 0.25]]);
    }
    let found = sweep(&rings, Find::First, 100 * n).expect("within n log n");
    assert!(found.meetings.is_empty());
    assert!(found.parents[1..].iter().all(|&p| p == Some(0)));
    rings[0][4 * 700 + 2][1] += 1.0;
    let found = sweep(&rings, Find::First, 100 * n).expect("within n log n");
    // The moved corner now lies on the next tooth's corner: the segments at those corners.
    let [(r0, s0), (r1, s1)] = found.meetings[0];
    assert_eq!((r0, r1), (0, 0));
    assert!([4 * 700 + 1, 4 * 700 + 2].contains(&s0) && [4 * 701, 4 * 701 + 1].contains(&s1), "{s0} {s1}");
}

#[test]
fn deep_nesting_and_shared_points() {
    // 300 nested squares, alternating direction, each inside the previous.
    let rings: Vec<Vec<Point>> = (0..300)
        .map(|k| {
            let (lo, hi) = (k as f64, 1000.0 - k as f64);
            let ring = vec![[lo, lo], [hi, lo], [hi, hi], [lo, hi]];
            if k % 2 == 0 {
                ring
            } else {
                ring.into_iter().rev().collect()
            }
        })
        .collect();
    let found = sweep(&rings, Find::First, usize::MAX).unwrap();
    for (k, parent) in found.parents.iter().enumerate() {
        assert_eq!(*parent, k.checked_sub(1));
    }
    // Two rings sharing a vertex, and a ring visiting a point twice.
    let touching = [vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[1.0, 0.0], [2.0, 0.0], [2.0, 1.0]]];
    assert_eq!(sweep(&touching, Find::First, usize::MAX).unwrap().meetings, vec![[(0, 1), (1, 0)]]);
    let pinched = [vec![[0.0, 0.0], [2.0, 0.0], [1.0, 1.0], [2.0, 2.0], [0.0, 2.0], [1.0, 1.0]]];
    assert_eq!(sweep(&pinched, Find::First, usize::MAX).unwrap().meetings.len(), 1);
    // -0.0 and 0.0 are one point.
    let signed_zero = [vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[-0.0, 0.0], [-1.0, 0.0], [0.0, -1.0]]];
    assert_eq!(sweep(&signed_zero, Find::First, usize::MAX).unwrap().meetings.len(), 1);
    // The budget runs out.
    assert!(sweep(&[comb(100, 1000.0)], Find::First, 100).is_none());
}

#[test]
fn near_touches_are_found_as_the_rule_defines_them() {
    // Rings on a small grid, each point moved by a few units in the last place: vertices lie
    // on other segments within rounding (but exactly off them) as often as exactly on them.
    let mut rng = Rng(3);
    let (mut near_only, mut checked) = (0, 0);
    for _ in 0..4000 {
        let mut rings = random_rings(&mut rng, 5);
        for ring in &mut rings {
            for p in ring.iter_mut() {
                for x in p.iter_mut() {
                    let ulps = rng.below(7) as i64 - 3;
                    *x = f64::from_bits((*x + 1.0).to_bits().wrapping_add_signed(ulps));
                }
            }
        }
        let expected = brute_force(&rings);
        let first = sweep(&rings, Find::First, usize::MAX).unwrap();
        assert_eq!(first.meetings.is_empty(), expected.is_empty(), "{rings:?}: {:?}", first.meetings);
        for pair in &first.meetings {
            assert!(expected.contains(pair), "{rings:?}: {pair:?} do not meet");
        }
        let cover = sweep(&rings, Find::Cover, usize::MAX).unwrap();
        let reported: Vec<SegmentRef> = cover.meetings.iter().flatten().copied().collect();
        for [s, t] in &expected {
            assert!(reported.contains(s) || reported.contains(t), "{rings:?}: {s:?} {t:?} not covered");
        }
        // Count the sets where only rounding makes some segments meet.
        let exact = |(a, b): (Point, Point), (c, d): (Point, Point)| {
            use Ordering::{Equal, Greater, Less};
            let (d1, d2, d3, d4) =
                (orientation(c, d, a), orientation(c, d, b), orientation(a, b, c), orientation(a, b, d));
            let opposite = |x, y| matches!((x, y), (Less, Greater) | (Greater, Less));
            let on = |o: Ordering, p: Point, q: Point, r: Point| {
                o == Equal
                    && r[0] >= p[0].min(q[0])
                    && r[0] <= p[0].max(q[0])
                    && r[1] >= p[1].min(q[1])
                    && r[1] <= p[1].max(q[1])
            };
            (opposite(d1, d2) && opposite(d3, d4))
                || on(d1, c, d, a)
                || on(d2, c, d, b)
                || on(d3, a, b, c)
                || on(d4, a, b, d)
        };
        let segment = |(r, i): SegmentRef| (rings[r][i], rings[r][(i + 1) % rings[r].len()]);
        let apart = |s: SegmentRef, t: SegmentRef| {
            let len = rings[s.0].len();
            s.0 != t.0 || ((s.1 + 1) % len != t.1 && (t.1 + 1) % len != s.1)
        };
        if expected.iter().any(|&[s, t]| apart(s, t) && !exact(segment(s), segment(t))) {
            near_only += 1;
        }
        checked += 1;
    }
    assert!(near_only > 1000, "in {near_only} of {checked} sets some segments meet only to double precision");
}
