//! Exact boolean operations on filled regions, for drawings whose shapes cross or touch (an
//! arm drawn over a body, a stroke over its fill) and for clip paths: each shape resolved
//! under its own fill rule, the union of all, the intersection with a clip.
//!
//! The work is done by `i_overlay` (the polygon overlay engine `geo` uses): it snaps the
//! points to an integer grid spanning the inputs' box (2^30 steps across, so a relative
//! error near 1e-9) and computes the arrangement exactly on it. A region is a list of
//! simple rings oriented by the engine (outer boundaries one way, holes the other), so
//! regions can be summed under the non-zero rule: their union is where the sum is not zero.
//! It also offsets outlines, for the cages of Cauchy-Green deformation.

use i_overlay::core::fill_rule::FillRule as Rule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::simplify::SimplifyShape;
use i_overlay::float::single::SingleFloatOverlay;
use i_overlay::mesh::float::outline::offset::OutlineOffset;
use i_overlay::mesh::float::style::{LineJoin, OutlineStyle};

use crate::geometry::{polygon_area, Point};
use crate::import::vector::FillRule;
use crate::outline::Outline;

/// The outer contour of the simple ring `ring` grown by `margin` (round joins, arcs in
/// steps of at most half a radian; concavities narrower than `2 margin` close up), the
/// largest if the result has several pieces. `None` if nothing is left.
pub(crate) fn grown(ring: &[Point], margin: f64) -> Option<Vec<Point>> {
    let style = OutlineStyle::new(margin).line_join(LineJoin::Round(0.5));
    ring.outline(&style)
        .into_iter()
        .filter_map(|shape| shape.into_iter().next())
        .max_by(|a, b| polygon_area(a).abs().total_cmp(&polygon_area(b).abs()))
}

/// A filled region: parts, each an outer ring followed by its holes.
pub(crate) type Region = Vec<Vec<Vec<Point>>>;

fn rule(rule: FillRule) -> Rule {
    match rule {
        FillRule::NonZero => Rule::NonZero,
        FillRule::EvenOdd => Rule::EvenOdd,
    }
}

/// The region that `rings` fill under `fill_rule`.
pub(crate) fn resolve(rings: &[Vec<Point>], fill_rule: FillRule) -> Region {
    let rings: Vec<Vec<Point>> = rings.iter().filter(|r| r.len() >= 3).cloned().collect();
    if rings.is_empty() {
        return Vec::new();
    }
    rings.simplify_shape(rule(fill_rule))
}

/// The union of `regions`.
pub(crate) fn union(regions: impl IntoIterator<Item = Region>) -> Region {
    let rings: Vec<Vec<Point>> = regions.into_iter().flatten().flatten().collect();
    if rings.is_empty() {
        return Vec::new();
    }
    rings.simplify_shape(Rule::NonZero)
}

/// The intersection of two regions.
pub(crate) fn intersect(a: &Region, b: &Region) -> Region {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    a.overlay(b, OverlayRule::Intersect, Rule::NonZero)
}

/// Points in a region.
pub(crate) fn point_count(region: &Region) -> usize {
    region.iter().flatten().map(Vec::len).sum()
}

/// A region as outlines, largest first; parts and holes with an area below `min_area` are
/// dropped (holes that small are filled).
pub(crate) fn outlines(region: Region, min_area: f64) -> Vec<Outline> {
    let mut parts: Vec<(Outline, f64)> = Vec::new();
    for mut rings in region {
        if rings.is_empty() {
            continue;
        }
        let outer = rings.remove(0);
        let mut area = polygon_area(&outer).abs();
        rings.retain(|hole| polygon_area(hole).abs() >= min_area);
        area -= rings.iter().map(|hole| polygon_area(hole).abs()).sum::<f64>();
        if area >= min_area && area > 0.0 {
            parts.push((Outline { outer, holes: rings }, area));
        }
    }
    parts.sort_by(|a, b| b.1.total_cmp(&a.1));
    parts.into_iter().map(|(outline, _)| outline).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, s: f64) -> Vec<Point> {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    fn area(region: &Region) -> f64 {
        outlines(region.clone(), 0.0).iter().map(Outline::area).sum()
    }

    #[test]
    fn overlapping_squares_unite_exactly() {
        let a = resolve(&[square(0.0, 0.0, 2.0)], FillRule::NonZero);
        let b = resolve(&[square(1.0, 1.0, 2.0)], FillRule::NonZero);
        let u = union([a.clone(), b.clone()]);
        assert_eq!(u.len(), 1);
        assert!((area(&u) - 7.0).abs() < 1e-8, "{}", area(&u));
        assert!((area(&intersect(&a, &b)) - 1.0).abs() < 1e-8);
        let outline = &outlines(u, 0.0)[0];
        assert_eq!(outline.outer.len(), 8);
        outline.validated(usize::MAX).unwrap();
    }

    #[test]
    fn fill_rules_apply_per_shape_before_the_union() {
        // A bow tie fills both lobes under non-zero (winding +1 and -1).
        let bow = vec![vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]]];
        assert!((area(&resolve(&bow, FillRule::NonZero)) - 2.0).abs() < 1e-8);
        // Even-odd within one shape empties the overlap; a second shape covering it fills it.
        let one = vec![square(0.0, 0.0, 2.0), square(1.0, 1.0, 2.0)];
        let even_odd = resolve(&one, FillRule::EvenOdd);
        assert!((area(&even_odd) - 6.0).abs() < 1e-8);
        let patch = resolve(&[square(1.0, 1.0, 1.0)], FillRule::NonZero);
        assert!((area(&union([even_odd, patch])) - 7.0).abs() < 1e-8);
        // A clockwise square under non-zero is as filled as a counter-clockwise one, so a
        // union with it is no cancellation.
        let mut clockwise = square(5.0, 0.0, 1.0);
        clockwise.reverse();
        let both =
            union([resolve(&[clockwise], FillRule::NonZero), resolve(&[square(5.5, 0.0, 1.0)], FillRule::NonZero)]);
        assert!((area(&both) - 1.5).abs() < 1e-8);
    }

    #[test]
    fn small_parts_and_holes_are_dropped() {
        let frame = resolve(&[square(0.0, 0.0, 10.0), square(4.0, 4.0, 0.5)], FillRule::EvenOdd);
        let speck = resolve(&[square(20.0, 0.0, 0.1)], FillRule::NonZero);
        let kept = outlines(union([frame, speck]), 1.0);
        assert_eq!(kept.len(), 1);
        assert!(kept[0].holes.is_empty());
    }
}
