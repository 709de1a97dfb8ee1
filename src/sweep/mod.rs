//! Closed rings swept left to right (Shamos and Hoey 1976): whether any two of their
//! segments meet (cross, touch or overlap; consecutive segments of a ring may share their
//! common point and nothing more), and, when none do, which ring immediately contains
//! each. O(n log n) for n segments, whatever their layout.
//!
//! Two predicates, as in [`crate::geometry`]: the sweep's order comes from exact
//! orientation tests ([`orientation`]), so that it is consistent whatever the rounding;
//! whether two segments meet is [`segments_intersect`]'s "to double precision" (they share
//! a point exactly, or an end lies on the other segment within rounding), the outline
//! checks' one notion of touching. The rings are swept scaled by a power of two (exact), as
//! that rule wants.
//!
//! Points are swept in lexicographic order (by x, then y), which handles vertical segments
//! like any other. A point shared by two vertices is a meeting found by sorting, so
//! afterwards only the two segments of one vertex share an end. The status holds the
//! segments crossing the sweep line, bottom to top (a treap, see `tree`); a new segment is
//! placed by the side of the line through each segment that its left end lies on (on the
//! line: it touches that segment), and every two segments that become neighbours are
//! checked. Two segments that meet exactly are neighbours no later than the sweep reaches
//! the leftmost point where any two meet, so such a meeting is found if there is one.
//!
//! A vertex that touches a segment only to double precision (it lies in the segment's
//! bounding box, on its line within rounding) is found when nothing passes between the two
//! on the vertical line through the vertex: when the vertex's event comes, the segment is
//! in the status and one of the vertex's segments is its neighbour then or just before.
//! The segment is in the status unless the vertex lies straight above its right end or
//! straight below its left end (same x, past it in the order); those cases are the other
//! way round in the mirror image (y negated), so when one sweep finds nothing (or, for
//! [`Find::Cover`], always) the mirror image is swept too, if the sort of the vertices
//! found two with the same x close enough for such a touch (`COLUMN_GAP`; real shapes have
//! none, so they are swept once). That is every near-touch a mesh
//! could contain: a triangle with the vertex and (part of) the segment as its opposite
//! side has nothing between them. A near-touch behind a third segment that passes still
//! closer to the vertex, yet certainly apart from it, may go unreported: no triangle can
//! have that vertex and that segment as opposite corner and side.
//!
//! To find more than one ([`Find::Cover`]), both segments of a meeting pair leave the
//! sweep and it goes on: the segments left never meet, and every meeting pair shares a
//! segment with a reported pair. Containment comes from the same sweep: at a ring's
//! lexicographically smallest vertex, the segment just below is on the ring that contains
//! it if that ring's inside lies above the segment, and otherwise on a sibling.

use std::cmp::Ordering;

use crate::geometry::{normalising_exponent, orientation, scale_by_power_of_two, segments_intersect, Point};

mod tree;

use tree::{mix, Treap};

/// A segment of a ring: `(ring, index)`, from point `index` to the next.
pub(crate) type SegmentRef = (usize, usize);

/// What [`sweep`] looks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Find {
    /// Stops at the first pair of segments that meet.
    First,
    /// Pairs that meet, enough that every pair of meeting segments shares a segment with a
    /// reported pair (so that repairing the reported segments makes progress).
    Cover,
}

/// What a sweep found.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Sweep {
    /// Pairs of segments that meet, the smaller `(ring, index)` first.
    pub(crate) meetings: Vec<[SegmentRef; 2]>,
    /// When nothing meets: each ring's immediate container, `None` at the top level (and
    /// for rings of fewer than two points).
    pub(crate) parents: Vec<Option<usize>>,
    /// When nothing meets: every ring once, each after its container.
    pub(crate) order: Vec<usize>,
    /// Whether each ring runs counter-clockwise (decided at its lexicographically smallest
    /// vertex, exactly; meaningful for rings that do not meet themselves).
    pub(crate) counter_clockwise: Vec<bool>,
    /// Comparisons of segments made (at most the budget).
    pub(crate) comparisons: usize,
    /// Whether two vertices lie straight above one another closer than [`COLUMN_GAP`]: only
    /// then can a near-touch hide from this sweep's order (see the module's notes).
    close_in_a_column: bool,
}

/// How far apart (in the rings scaled into `[1, 2)`) two vertices with the same x must be
/// for neither to touch, to double precision, a segment ending at the other. A vertex `p`
/// straight above or below the end `q` of a segment `a b` touches it when the computed
/// `orient(a, b, p)` is within `4.5e-16 (|t1| + |t2|)` ([`crate::geometry::certain_orient`]),
/// so its exact value `(b.x - a.x)(p.y - q.y)` is within twice that, and `|t1| + |t2|` is
/// at most `8 |b.x - a.x|` for coordinates below 2: `|p.y - q.y| <= 7.2e-15`.
const COLUMN_GAP: f64 = 1e-14;

/// A segment with its ends in sweep order.
#[derive(Debug, Clone, Copy)]
struct Segment {
    left: Point,
    right: Point,
    ring: usize,
    index: usize,
    /// Whether the ring runs from `left` to `right`.
    forward: bool,
}

impl Segment {
    /// The ends in the ring's direction.
    fn ends(&self) -> (Point, Point) {
        if self.forward {
            (self.left, self.right)
        } else {
            (self.right, self.left)
        }
    }
}

/// The sweep order of points: by x, then by y.
fn lex(a: Point, b: Point) -> Ordering {
    a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
}

/// -0.0 becomes 0.0, so that equal points compare equal in [`lex`].
fn canonical(p: Point) -> Point {
    [p[0] + 0.0, p[1] + 0.0]
}

/// Sweeps the rings (closed implicitly; each segment runs from a point to the next).
/// `None` when more than `budget` comparisons of segments would be needed (the sweep makes
/// O(n log n)).
pub(crate) fn sweep(rings: &[Vec<Point>], find: Find, budget: usize) -> Option<Sweep> {
    // Scaled by the power of two that brings the largest coordinate into [1, 2) (exact), so
    // that rounding is all that is uncertain in `segments_intersect`: the same answers at
    // every scale. Rings already scaled (the outline checks') are swept as they are.
    let k = normalising_exponent(rings.iter().flatten().copied());
    let scaled: Vec<Vec<Point>>;
    let rings = if k == 0 {
        rings
    } else {
        scaled = rings.iter().map(|r| r.iter().map(|p| p.map(|x| scale_by_power_of_two(x, k))).collect()).collect();
        &scaled
    };
    let mut found = sweep_once(rings, find, budget)?;
    // Near-touches at a vertex straight above or below the end of a segment, which this
    // order passes when that segment is not in the status, are found by the sweep of the
    // mirror image (y negated, exact), where the vertex comes while it is.
    if found.close_in_a_column && (find == Find::Cover || found.meetings.is_empty()) {
        let mirrored: Vec<Vec<Point>> = rings.iter().map(|r| r.iter().map(|p| [p[0], -p[1]]).collect()).collect();
        let second = sweep_once(&mirrored, find, budget - found.comparisons)?;
        found.comparisons += second.comparisons;
        if !second.meetings.is_empty() {
            found.meetings.extend(second.meetings);
            found.meetings.sort_unstable();
            found.meetings.dedup();
            found.parents.clear();
            found.order.clear();
        }
    }
    Some(found)
}

/// One sweep in lexicographic order.
fn sweep_once(rings: &[Vec<Point>], find: Find, budget: usize) -> Option<Sweep> {
    let mut state = State::new(rings, find, budget);
    state.run()?;
    let State { meetings, parents, order, counter_clockwise, budget: left, close_in_a_column, .. } = state;
    Some(Sweep { meetings, parents, order, counter_clockwise, comparisons: budget - left, close_in_a_column })
}

struct State<'a> {
    rings: &'a [Vec<Point>],
    find: Find,
    budget: usize,
    segments: Vec<Segment>,
    /// The first segment of each ring.
    first: Vec<usize>,
    /// Each ring's lexicographically smallest vertex.
    lowest: Vec<usize>,
    alive: Vec<bool>,
    in_tree: Vec<bool>,
    tree: Treap,
    meetings: Vec<[SegmentRef; 2]>,
    parents: Vec<Option<usize>>,
    order: Vec<usize>,
    counter_clockwise: Vec<bool>,
    /// Neighbour pairs still to check.
    pending: Vec<(u32, u32)>,
    close_in_a_column: bool,
}

/// The sweep stops: the budget ran out, or the first meeting was found.
enum Stop {
    Budget,
    Found,
}

impl<'a> State<'a> {
    fn new(rings: &'a [Vec<Point>], find: Find, budget: usize) -> Self {
        let mut segments = Vec::new();
        let mut first = Vec::with_capacity(rings.len());
        let mut lowest = Vec::with_capacity(rings.len());
        let mut counter_clockwise = Vec::with_capacity(rings.len());
        let mut seed = 0u64;
        for (ring, points) in rings.iter().enumerate() {
            first.push(segments.len());
            let m = points.len();
            let low = (0..m).min_by(|&i, &j| lex(canonical(points[i]), canonical(points[j]))).unwrap_or(0);
            lowest.push(low);
            counter_clockwise
                .push(m >= 3 && orientation(points[(low + m - 1) % m], points[low], points[(low + 1) % m]).is_gt());
            if m < 2 {
                continue;
            }
            for index in 0..m {
                let (a, b) = (canonical(points[index]), canonical(points[(index + 1) % m]));
                seed = mix(seed ^ a[0].to_bits() ^ a[1].to_bits().rotate_left(32));
                let forward = lex(a, b).is_le();
                let (left, right) = if forward { (a, b) } else { (b, a) };
                segments.push(Segment { left, right, ring, index, forward });
            }
        }
        let n = segments.len();
        Self {
            rings,
            find,
            budget,
            segments,
            first,
            lowest,
            alive: vec![true; n],
            in_tree: vec![false; n],
            tree: Treap::new(n, seed),
            meetings: Vec::new(),
            parents: vec![None; rings.len()],
            order: Vec::with_capacity(rings.len()),
            counter_clockwise,
            pending: Vec::new(),
            close_in_a_column: false,
        }
    }

    fn run(&mut self) -> Option<()> {
        match self.shared_points().and_then(|()| self.events()) {
            Ok(()) | Err(Stop::Found) => {}
            Err(Stop::Budget) => return None,
        }
        if self.meetings.is_empty() {
            // Rings without segments belong nowhere.
            self.order.extend((0..self.rings.len()).filter(|&r| self.rings[r].len() < 2));
        } else {
            self.parents.clear();
            self.order.clear();
        }
        Some(())
    }

    /// The segment from vertex `index` of `ring`, and the one into it.
    fn at_vertex(&self, ring: usize, index: usize) -> [usize; 2] {
        let m = self.rings[ring].len();
        [self.first[ring] + index, self.first[ring] + (index + m - 1) % m]
    }

    /// Vertices at one point: the segments from them meet there.
    fn shared_points(&mut self) -> Result<(), Stop> {
        let mut vertices: Vec<(usize, usize)> = (0..self.rings.len())
            .filter(|&r| self.rings[r].len() >= 2)
            .flat_map(|r| (0..self.rings[r].len()).map(move |i| (r, i)))
            .collect();
        let point = |&(r, i): &(usize, usize)| canonical(self.rings[r][i]);
        vertices.sort_unstable_by(|a, b| lex(point(a), point(b)).then(a.cmp(b)));
        self.close_in_a_column = vertices.windows(2).any(|w| {
            let (p, q) = (point(&w[0]), point(&w[1]));
            p[0] == q[0] && p[1] != q[1] && q[1] - p[1] <= COLUMN_GAP
        });
        let mut found = Vec::new();
        for group in vertices.chunk_by(|a, b| lex(point(a), point(b)).is_eq()) {
            for &(ring, index) in &group[1..] {
                let (r0, i0) = group[0];
                found.push((self.at_vertex(r0, i0), self.at_vertex(ring, index)));
            }
        }
        // Every segment at the point is reported and leaves the sweep.
        for ([a, a_in], [b, b_in]) in found {
            self.report(a as u32, b as u32)?;
            self.report(a_in as u32, b_in as u32)?;
        }
        Ok(())
    }

    fn events(&mut self) -> Result<(), Stop> {
        let mut events: Vec<(u32, bool)> = (0..self.segments.len() as u32)
            .filter(|&s| self.alive[s as usize])
            .flat_map(|s| [(s, false), (s, true)])
            .collect();
        let segments = &self.segments;
        let at = |&(s, insert): &(u32, bool)| {
            let segment = &segments[s as usize];
            if insert {
                segment.left
            } else {
                segment.right
            }
        };
        // Removals before insertions at one point; the segments' order keeps it repeatable.
        events.sort_unstable_by(|a, b| lex(at(a), at(b)).then(a.1.cmp(&b.1)).then(a.0.cmp(&b.0)));
        for (s, insert) in events {
            if !self.alive[s as usize] {
                continue;
            }
            if insert {
                self.insert(s)?;
            } else {
                self.remove(s);
            }
            self.check_pending()?;
        }
        Ok(())
    }

    fn spend(&mut self) -> Result<(), Stop> {
        if self.budget == 0 {
            return Err(Stop::Budget);
        }
        self.budget -= 1;
        Ok(())
    }

    fn insert(&mut self, s: u32) -> Result<(), Stop> {
        let new = self.segments[s as usize];
        let segments = &self.segments;
        let mut budget = self.budget;
        let placed = self.tree.insert(s, |other| {
            if budget == 0 {
                return Err(None);
            }
            budget -= 1;
            let u = &segments[other as usize];
            match orientation(u.left, u.right, new.left) {
                Ordering::Less => Ok(true),
                Ordering::Greater => Ok(false),
                // The new segment starts on `u`: they meet, unless they are the two
                // segments of one vertex, whose other ends decide.
                Ordering::Equal if new.left == u.left => match orientation(u.left, u.right, new.right) {
                    Ordering::Less => Ok(true),
                    Ordering::Greater => Ok(false),
                    Ordering::Equal => Err(Some(other)),
                },
                Ordering::Equal => Err(Some(other)),
            }
        });
        self.budget = budget;
        match placed {
            Err(None) => return Err(Stop::Budget),
            Err(Some(other)) => {
                self.alive[s as usize] = false;
                return self.report(s, other);
            }
            Ok(()) => {}
        }
        self.in_tree[s as usize] = true;
        if let Some(below) = self.tree.below(s) {
            self.pending.push((below, s));
        }
        if let Some(above) = self.tree.above(s) {
            self.pending.push((s, above));
        }
        self.contain(s);
        Ok(())
    }

    /// At a ring's lowest vertex, once both its segments are in: its container.
    fn contain(&mut self, s: u32) {
        let Segment { ring, left, .. } = self.segments[s as usize];
        let low = self.lowest[ring];
        if left != canonical(self.rings[ring][low]) {
            return;
        }
        let [out, into] = self.at_vertex(ring, low);
        if !(self.in_tree[out] && self.in_tree[into]) {
            return;
        }
        // The lower of the two has the segment just below the vertex under it.
        let below = match self.tree.below(out as u32) {
            Some(b) if b as usize == into => self.tree.below(into as u32),
            other => other,
        };
        self.parents[ring] = below.and_then(|b| {
            let e = &self.segments[b as usize];
            if e.forward == self.counter_clockwise[e.ring] {
                Some(e.ring)
            } else {
                self.parents[e.ring]
            }
        });
        self.order.push(ring);
    }

    fn remove(&mut self, s: u32) {
        let (below, above) = (self.tree.below(s), self.tree.above(s));
        self.tree.remove(s);
        self.in_tree[s as usize] = false;
        if let (Some(b), Some(a)) = (below, above) {
            self.pending.push((b, a));
        }
    }

    fn check_pending(&mut self) -> Result<(), Stop> {
        while let Some((a, b)) = self.pending.pop() {
            if !(self.alive[a as usize] && self.alive[b as usize]) {
                continue;
            }
            self.spend()?;
            if meet(&self.segments[a as usize], &self.segments[b as usize], self.rings) {
                self.report(a, b)?;
            }
        }
        Ok(())
    }

    /// Records a meeting; stops the sweep when only the first is wanted, else takes both
    /// segments out of it.
    fn report(&mut self, a: u32, b: u32) -> Result<(), Stop> {
        let name = |s: u32| (self.segments[s as usize].ring, self.segments[s as usize].index);
        let (x, y) = (name(a), name(b));
        self.meetings.push(if x <= y { [x, y] } else { [y, x] });
        if self.find == Find::First {
            return Err(Stop::Found);
        }
        for s in [a, b] {
            self.alive[s as usize] = false;
            if self.in_tree[s as usize] {
                self.remove(s);
            }
        }
        Ok(())
    }
}

/// Whether two distinct segments meet anywhere they should not.
fn meet(s: &Segment, t: &Segment, rings: &[Vec<Point>]) -> bool {
    let ((sa, sb), (ta, tb)) = (s.ends(), t.ends());
    if s.ring == t.ring {
        let len = rings[s.ring].len();
        // Consecutive segments share one end; they meet elsewhere only if they fold back
        // onto each other, i.e. the far end of one lies on the other.
        if (s.index + 1) % len == t.index {
            return on_segment(tb, sa, sb) || on_segment(sa, ta, tb);
        }
        if (t.index + 1) % len == s.index {
            return on_segment(sb, ta, tb) || on_segment(ta, sa, sb);
        }
    }
    segments_intersect(sa, sb, ta, tb)
}

/// Whether `p` lies on the closed segment `a b`.
fn on_segment(p: Point, a: Point, b: Point) -> bool {
    segments_intersect(p, p, a, b)
}

#[cfg(test)]
mod tests;
