//! The cage of Cauchy-Green deformation: a simple polygon around the shape. Built
//! automatically from the mesh's outer outline (offset outward, simplified, and its edges
//! split to the vertex count asked for), or given by the caller and checked.
//!
//! The automatic cage offsets the outline by a margin `d` (`import::union::grown`: round
//! joins, with i_overlay), keeps the outer contour of the result (concavities narrower than
//! `2 d` close up), simplifies it with a tolerance of `d / 2` without breaking
//! its topology (`import::simplify`), which keeps its corners, and then splits the longest
//! edges until it has the vertices asked for: they are the map's degrees of freedom, so a
//! bar's cage needs more than its eight corners. The margin starts at half the spacing of
//! the cage's vertices along the outline (closer, and the shape would see the kinks of the
//! piecewise-linear boundary values at the corners; farther, and neighbouring limbs would
//! share cage edges) and grows by half until the simplified contour has no more vertices
//! than asked for and encloses the shape without touching it.

use super::super::error::DeformError;
use super::super::options::CAGE_VERTICES_RANGE;
use crate::geometry::{
    bounding_box, distance, point_in_polygon, polygon_area, segments_intersect, Point, MAX_COORDINATE,
};
use crate::import::simplify::simplify_rings;
use crate::import::union::grown;
use crate::mesh::Mesh;
use crate::sweep::{sweep, Find};

/// The first margin, in spacings of the cage's vertices along the outline, and its growth.
const FIRST_MARGIN: f64 = 0.5;
const GROWTH: f64 = 1.5;
/// Margins tried before giving up (1.5^30: from half a spacing to about 10^5 spacings, where
/// any cage is a rough polygon around a distant shape).
const ATTEMPTS: usize = 30;

/// A counter-clockwise cage of `vertices` vertices around the mesh's outer outline,
/// touching nothing. `positions` are the mesh's vertices (or those scaled alike).
pub(crate) fn automatic(mesh: &Mesh, positions: &[Point], vertices: usize) -> Result<Vec<Point>, DeformError> {
    let outline = outer_outline(mesh, positions);
    let perimeter: f64 = (0..outline.len()).map(|i| distance(outline[i], outline[(i + 1) % outline.len()])).sum();
    let mut margin = FIRST_MARGIN * perimeter / vertices as f64;
    for _ in 0..ATTEMPTS {
        if let Some(corners) = around(&outline, margin, vertices) {
            if encloses(&corners, &outline) {
                return Ok(subdivided(corners, vertices));
            }
        }
        margin *= GROWTH;
    }
    Err(DeformError::InvalidCage { reason: format!("no cage of {vertices} vertices could be fitted around the shape") })
}

/// The outline offset by `margin` and simplified, counter-clockwise, if it has at most
/// `max_vertices`.
fn around(outline: &[Point], margin: f64, max_vertices: usize) -> Option<Vec<Point>> {
    let offset = grown(outline, margin)?;
    let simplified = simplify_rings(&[offset], &[None], margin / 2.0, 1 << 26)?.pop()?;
    if simplified.len() < 3 || simplified.len() > max_vertices {
        return None;
    }
    Some(counter_clockwise(simplified))
}

/// `ring` with its longest edges split evenly (the edge whose pieces are longest gets one
/// more piece each time) until it has `vertices` points; the polygon is unchanged.
fn subdivided(ring: Vec<Point>, vertices: usize) -> Vec<Point> {
    let n = ring.len();
    let lengths: Vec<f64> = (0..n).map(|i| distance(ring[i], ring[(i + 1) % n])).collect();
    let mut pieces = vec![1usize; n];
    for _ in n..vertices {
        let longest = (0..n)
            .max_by(|&a, &b| (lengths[a] / pieces[a] as f64).total_cmp(&(lengths[b] / pieces[b] as f64)))
            .expect("a ring has edges");
        pieces[longest] += 1;
    }
    let mut cage = Vec::with_capacity(vertices);
    for (i, &k) in pieces.iter().enumerate() {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        cage.extend((0..k).map(|j| {
            let t = j as f64 / k as f64;
            [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
        }));
    }
    cage
}

/// A cage given by the caller, checked and turned counter-clockwise: 3 to 1000 points (the
/// largest automatic cage; the smoothness matrix is dense),
/// finite and within the coordinate limit, no repeated consecutive points, edges that do
/// not meet (but consecutive ones at their shared point), and the mesh's outer outline
/// strictly inside (no edge of the outline touching the cage). `positions` are the mesh's
/// vertices (or those scaled alike, with the cage).
pub(crate) fn checked(mesh: &Mesh, positions: &[Point], cage: &[Point]) -> Result<Vec<Point>, DeformError> {
    let invalid = |reason: String| Err(DeformError::InvalidCage { reason });
    if cage.len() < 3 || cage.len() > *CAGE_VERTICES_RANGE.end() {
        return invalid(format!("it has {} points, from 3 to {} are allowed", cage.len(), CAGE_VERTICES_RANGE.end()));
    }
    if let Some(i) = cage.iter().position(|p| !p.iter().all(|x| x.is_finite() && x.abs() <= MAX_COORDINATE)) {
        return invalid(format!("point {i} is not finite or beyond ±{MAX_COORDINATE:e}"));
    }
    if let Some(i) = (0..cage.len()).find(|&i| cage[i] == cage[(i + 1) % cage.len()]) {
        return invalid(format!("points {i} and {} are equal", (i + 1) % cage.len()));
    }
    match sweep(&[cage.to_vec()], Find::First, 1 << 26) {
        Some(found) if found.meetings.is_empty() => {}
        Some(found) => {
            let [(_, a), (_, b)] = found.meetings[0];
            return invalid(format!("its edges {a} and {b} meet"));
        }
        None => return invalid("it has too many edges to check".into()),
    }
    let cage = counter_clockwise(cage.to_vec());
    if !encloses(&cage, &outer_outline(mesh, positions)) {
        return invalid("the shape is not strictly inside it (the cage crosses or touches the shape)".into());
    }
    Ok(cage)
}

/// The mesh's outer boundary loop, counter-clockwise (its holes lie inside it); for a mesh
/// in several pieces (a puppet's sheets, posed as one shape) the convex hull of its
/// vertices, so that the cage goes round every piece.
fn outer_outline(mesh: &Mesh, positions: &[Point]) -> Vec<Point> {
    if mesh.connected_components() > 1 {
        return convex_hull(positions);
    }
    let rings: Vec<Vec<Point>> =
        mesh.boundary_loops().iter().map(|ring| ring.iter().map(|&v| positions[v as usize]).collect()).collect();
    // Boundary loops run with the shape on their left: the outer one counter-clockwise, with
    // the largest area.
    rings.into_iter().max_by(|a, b| polygon_area(a).total_cmp(&polygon_area(b))).expect("a mesh has a boundary")
}

/// The convex hull of `points` (at least three, not all on a line), counter-clockwise,
/// without collinear points: Andrew's monotone chain.
fn convex_hull(points: &[Point]) -> Vec<Point> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    sorted.dedup();
    let turn = |o: Point, a: Point, b: Point| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let mut hull: Vec<Point> = Vec::with_capacity(2 * sorted.len());
    for pass in 0..2 {
        let start = hull.len();
        let sweep: Box<dyn Iterator<Item = &Point>> =
            if pass == 0 { Box::new(sorted.iter()) } else { Box::new(sorted.iter().rev()) };
        for &p in sweep {
            while hull.len() >= start + 2 && turn(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

fn counter_clockwise(mut ring: Vec<Point>) -> Vec<Point> {
    if polygon_area(&ring) < 0.0 {
        ring.reverse();
    }
    ring
}

/// Whether the outline lies strictly inside the simple polygon `cage`: no edge of the one
/// meets an edge of the other, and a point of the outline is inside.
fn encloses(cage: &[Point], outline: &[Point]) -> bool {
    if !point_in_polygon(outline[0], cage) {
        return false;
    }
    // Pairs of edges whose bounding boxes overlap are tested (O(outline x cage), a few
    // million tests at most for the sizes allowed).
    let edges = |ring: &[Point]| {
        (0..ring.len())
            .map(|i| {
                let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                (a, b, bounding_box([a, b]).expect("two points"))
            })
            .collect::<Vec<_>>()
    };
    let cage_edges = edges(cage);
    edges(outline).iter().all(|&(a, b, (lo, hi))| {
        cage_edges.iter().all(|&(c, d, (clo, chi))| {
            let apart = clo[0] > hi[0] || chi[0] < lo[0] || clo[1] > hi[1] || chi[1] < lo[1];
            apart || !segments_intersect(a, b, c, d)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::grid_mesh;

    #[test]
    fn the_automatic_cage_encloses_the_shape_with_its_vertex_count() {
        let mesh = grid_mesh(20, 4);
        for vertices in [8, 16, 64] {
            let cage = automatic(&mesh, mesh.positions(), vertices).unwrap();
            assert_eq!(cage.len(), vertices);
            assert!(polygon_area(&cage) > mesh.area());
            assert!(checked(&mesh, mesh.positions(), &cage).is_ok());
        }
    }
}
