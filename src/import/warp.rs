//! Carrying imported art along with a deformed mesh: points (an SVG's path points and
//! control points) by barycentric coordinates in the rest mesh, and image texture
//! coordinates for the vertices of a traced image's mesh. Points are located by a
//! bounding-volume hierarchy of the triangles: the nearest triangle in about O(log m)
//! whether the point lies inside the mesh or outside it.
//!
//! Nothing here returns NaN or infinity: input that is not finite is refused, and so is a
//! result that overflows double precision (a point far outside the mesh extrapolated through
//! a huge deformed triangle, a position divided by a tiny image size), each by index.

use crate::geometry::{
    binary_exponent, bounding_box, distance, normalising_exponent, orient, scale_by_power_of_two, Point,
};
use crate::import::ImportError;
use crate::mesh::Mesh;

/// Where each of a set of points sits in a rest mesh: three vertices and barycentric
/// weights. Locating happens once; [`PointMapper::map`] then costs a few multiplications
/// per point, so deformed vector art can be redrawn every frame.
#[derive(Debug, Clone, PartialEq)]
pub struct PointMapper {
    vertex_count: usize,
    locations: Vec<([u32; 3], [f64; 3])>,
}

impl PointMapper {
    /// Locates `points` in `rest`. A point inside the mesh gets the triangle that contains
    /// it; a point outside (a curve's control point, say) gets the nearest triangle, and
    /// follows that triangle's affine motion. Of equally near triangles (a point on an
    /// edge, or nearest to a vertex) the one with the smallest index. O((m + n) log m) for
    /// m triangles and n points. Refuses a point with a coordinate that is not finite
    /// ([`ImportError::NonFinite`]).
    pub fn new(rest: &Mesh, points: &[Point]) -> Result<Self, ImportError> {
        let triangles = rest.triangles();
        let locations = locate(rest, points)?.into_iter().map(|(t, w)| (triangles[t as usize], w)).collect();
        Ok(Self { vertex_count: rest.vertex_count(), locations })
    }

    /// Number of vertices of the rest mesh: [`Self::map`] takes one position per vertex.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.locations.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.locations.is_empty()
    }

    /// The points carried along to `deformed` (one position per rest-mesh vertex). Refuses
    /// a wrong number of positions ([`ImportError::Length`], counted in numbers), a position
    /// that is not finite ([`ImportError::NonFinite`]), and a mapped point that would not
    /// be finite ([`ImportError::NonFiniteResult`]).
    pub fn map(&self, deformed: &[Point]) -> Result<Vec<Point>, ImportError> {
        if deformed.len() != self.vertex_count {
            return Err(ImportError::Length {
                what: "deformed positions",
                expected: 2 * self.vertex_count,
                found: 2 * deformed.len(),
                per: 2,
                items: "rest vertices",
            });
        }
        if let Some(index) = deformed.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
            return Err(ImportError::NonFinite { what: "deformed position", index });
        }
        self.locations
            .iter()
            .enumerate()
            .map(|(index, &(v, w))| {
                let [a, b, c] = v.map(|i| deformed[i as usize]);
                let p = [w[0] * a[0] + w[1] * b[0] + w[2] * c[0], w[0] * a[1] + w[1] * b[1] + w[2] * c[1]];
                if p[0].is_finite() && p[1].is_finite() {
                    Ok(p)
                } else {
                    Err(ImportError::NonFiniteResult { what: "mapped point", index })
                }
            })
            .collect()
    }
}

/// Where each of `points` sits in `rest`: its triangle (the one containing it, or the
/// nearest for a point outside; of equally near ones the smallest index) and its
/// barycentric coordinates there, extrapolated outside (negative ones then), the location
/// [`PointMapper`] and DefOp's carried rigs (`defop::carry`) share. O((m + n) log m).
/// Refuses a point with a coordinate that is not finite ([`ImportError::NonFinite`]).
pub(crate) fn locate(rest: &Mesh, points: &[Point]) -> Result<Vec<(u32, [f64; 3])>, ImportError> {
    if let Some(index) = points.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
        return Err(ImportError::NonFinite { what: "point", index });
    }
    // Located on the mesh and points scaled by the power of two that brings the mesh's
    // largest coordinate into [1, 2) (exact; barycentric weights do not change), so
    // products of its coordinates neither overflow nor underflow.
    let k = normalising_exponent(rest.positions().iter().copied());
    let scale = |p: &Point| p.map(|x| scale_by_power_of_two(x, k));
    let positions: Vec<Point> = rest.positions().iter().map(scale).collect();
    let tree = Tree::new(&positions, rest.triangles());
    Ok(points.iter().map(|p| tree.locate(&positions, rest.triangles(), *p, k)).collect())
}

/// Maps `points` from `rest` to `deformed` in one go (see [`PointMapper`]).
pub fn map_points(rest: &Mesh, deformed: &[Point], points: &[Point]) -> Result<Vec<Point>, ImportError> {
    PointMapper::new(rest, points)?.map(deformed)
}

/// Texture coordinates of points given in the pixel frame of a traced image (y up, origin
/// at the image's bottom-left corner, see [`crate::import::raster`]), in the one
/// convention of this crate, Wavefront OBJ's: `u = x / width` from the left edge and
/// `v = y / height` up from the bottom edge, so `(0, 0)` is the image's bottom-left corner,
/// `v = 1` its top edge, and the centre of the top-left pixel is
/// `(0.5 / width, 1 - 0.5 / height)`. Images store their top row first: a renderer samples
/// row `(1 - v) * height` from the top (WebGL flips the image on upload for this).
/// Refuses a size that is not a finite number above 0 ([`ImportError::InvalidOption`]), a
/// point that is not finite, and a coordinate that overflows (a huge position over a tiny
/// size).
pub fn texture_coordinates(points: &[Point], width: f64, height: f64) -> Result<Vec<Point>, ImportError> {
    for (name, value) in [("width", width), ("height", height)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(ImportError::InvalidOption { name, value, expected: "a finite number above 0" });
        }
    }
    points
        .iter()
        .enumerate()
        .map(|(index, p)| {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(ImportError::NonFinite { what: "position", index });
            }
            let uv = [p[0] / width, p[1] / height];
            if uv[0].is_finite() && uv[1].is_finite() {
                Ok(uv)
            } else {
                Err(ImportError::NonFiniteResult { what: "the texture coordinate of position", index })
            }
        })
        .collect()
}

/// Triangles in a bounding-volume hierarchy: each node's box holds a range of triangles,
/// split at the median of their centroids along the box's longer side, down to leaves of
/// a few. Built in O(m log m); a query visits the nodes nearest the point first and skips
/// any whose box lies farther than the best triangle so far, about O(log m) nodes for a
/// point inside or outside the mesh.
struct Tree {
    nodes: Vec<Node>,
    /// Triangle indices; each node holds a contiguous range of them.
    triangles: Vec<u32>,
    /// Slack for rounding when comparing box and triangle distances: a small fraction of
    /// the mesh's size.
    slack: f64,
}

#[derive(Debug, Clone, Copy)]
struct Node {
    lo: Point,
    hi: Point,
    start: usize,
    end: usize,
    /// The children, or `None` for a leaf.
    children: Option<[usize; 2]>,
}

/// Triangles per leaf, at most.
const LEAF: usize = 8;

impl Tree {
    /// The hierarchy of `triangles` on `p` (the mesh's positions, scaled).
    fn new(p: &[Point], mesh_triangles: &[[u32; 3]]) -> Self {
        let corners = |t: u32| mesh_triangles[t as usize].map(|i| p[i as usize]);
        let centroids: Vec<Point> = (0..mesh_triangles.len() as u32)
            .map(|t| {
                let [a, b, c] = corners(t);
                [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0]
            })
            .collect();
        let mut triangles: Vec<u32> = (0..mesh_triangles.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * triangles.len() / LEAF + 1);
        // (node, start, end): nodes are made parent first, children filled in later.
        let mut stack = vec![(0, 0, triangles.len())];
        nodes.push(Node { lo: [0.0; 2], hi: [0.0; 2], start: 0, end: 0, children: None });
        while let Some((k, start, end)) = stack.pop() {
            let range = &mut triangles[start..end];
            let (lo, hi) = bounding_box(range.iter().flat_map(|&t| corners(t))).unwrap_or(([0.0; 2], [0.0; 2]));
            nodes[k] = Node { lo, hi, start, end, children: None };
            if range.len() <= LEAF {
                continue;
            }
            let axis = usize::from(hi[1] - lo[1] > hi[0] - lo[0]);
            let mid = range.len() / 2;
            range.select_nth_unstable_by(mid, |&s, &t| {
                centroids[s as usize][axis].total_cmp(&centroids[t as usize][axis])
            });
            let (left, right) = (nodes.len(), nodes.len() + 1);
            nodes.push(nodes[k]);
            nodes.push(nodes[k]);
            nodes[k].children = Some([left, right]);
            stack.push((left, start, start + mid));
            stack.push((right, start + mid, end));
        }
        let size = (nodes[0].hi[0] - nodes[0].lo[0]).hypot(nodes[0].hi[1] - nodes[0].lo[1]);
        Self { nodes, triangles, slack: 1e-9 * size }
    }

    /// The triangle nearest `p` (distance 0 inside or on it), the smallest index among
    /// equally near ones: the same as comparing every triangle.
    fn nearest(&self, positions: &[Point], triangles: &[[u32; 3]], p: Point) -> usize {
        let distance_to = |t: u32| triangle_distance(triangles[t as usize].map(|i| positions[i as usize]), p);
        // Rounding grows with the coordinates: the slack covers points far away too.
        let slack = self.slack + 1e-12 * p[0].abs().max(p[1].abs());
        let (mut best, mut best_distance) = (usize::MAX, f64::INFINITY);
        let mut stack = vec![0];
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k];
            if box_distance(node, p) > best_distance + slack {
                continue;
            }
            match node.children {
                None => {
                    for &t in &self.triangles[node.start..node.end] {
                        let d = distance_to(t);
                        if d < best_distance || (d == best_distance && (t as usize) < best) {
                            (best, best_distance) = (t as usize, d);
                        }
                    }
                }
                Some([a, b]) => {
                    // The nearer child last, so that it is searched first.
                    if box_distance(&self.nodes[a], p) < box_distance(&self.nodes[b], p) {
                        stack.extend([b, a]);
                    } else {
                        stack.extend([a, b]);
                    }
                }
            }
        }
        best
    }

    /// The triangle of `point` (as given; `k` scales it like `positions`) and its
    /// barycentric coordinates there.
    fn locate(&self, positions: &[Point], triangles: &[[u32; 3]], point: Point, k: i32) -> (u32, [f64; 3]) {
        let p = point.map(|x| scale_by_power_of_two(x, k));
        // A point more than 2^900 times the mesh's size away is looked for along its
        // direction at 2^900 (there the mesh is a dot: every triangle is as near as rounding
        // tells), so that distances stay finite; its weights, from where it is, may not be,
        // and `map` refuses it then.
        let largest = point[0].abs().max(point[1].abs());
        let probe = if largest > 0.0 && binary_exponent(largest) + k > 900 {
            point.map(|x| scale_by_power_of_two(x, 900 - binary_exponent(largest)))
        } else {
            p
        };
        let t = self.nearest(positions, triangles, probe);
        let [a, b, c] = triangles[t].map(|i| positions[i as usize]);
        let whole = orient(a, b, c);
        (t as u32, [orient(b, c, p) / whole, orient(c, a, p) / whole, orient(a, b, p) / whole])
    }
}

/// Distance from `p` to a node's box: 0 inside it.
fn box_distance(node: &Node, p: Point) -> f64 {
    let dx = (node.lo[0] - p[0]).max(p[0] - node.hi[0]).max(0.0);
    let dy = (node.lo[1] - p[1]).max(p[1] - node.hi[1]).max(0.0);
    dx.hypot(dy)
}

/// Distance from `p` to a counter-clockwise triangle: 0 inside or on it.
fn triangle_distance(t: [Point; 3], p: Point) -> f64 {
    if (0..3).all(|i| orient(t[i], t[(i + 1) % 3], p) >= 0.0) {
        return 0.0;
    }
    (0..3).map(|i| segment_distance(p, t[i], t[(i + 1) % 3])).fold(f64::INFINITY, f64::min)
}

fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let t = if len2 > 0.0 { (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0) } else { 0.0 };
    distance(p, [a[0] + t * d[0], a[1] + t * d[1]])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_follow_an_affine_motion_exactly() {
        let rest = Mesh::new(vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]], vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        let motion = |p: Point| [2.0 * p[0] - p[1] + 3.0, 0.5 * p[0] + p[1] - 1.0];
        let deformed: Vec<Point> = rest.positions().iter().map(|&p| motion(p)).collect();
        // Inside, on an edge, and outside (nearest triangle, extrapolated).
        let points = [[0.5, 0.25], [1.0, 1.0], [3.0, 0.5], [-1.0, -1.0]];
        let mapped = map_points(&rest, &deformed, &points).unwrap();
        for (q, p) in mapped.iter().zip(points) {
            let expected = motion(p);
            assert!(distance(*q, expected) < 1e-12, "{p:?} -> {q:?}, expected {expected:?}");
        }
        let mapper = PointMapper::new(&rest, &points).unwrap();
        assert_eq!(mapper.vertex_count(), 4);
        let error = mapper.map(&deformed[..3]).unwrap_err();
        assert_eq!(
            error.to_string(),
            "deformed positions have 6 numbers, expected 8 (2 for each of the 4 rest vertices)"
        );
    }

    #[test]
    fn points_are_located_the_same_at_any_scale() {
        let rest = |s: f64| {
            Mesh::new(vec![[0.0, 0.0], [2.0 * s, 0.0], [2.0 * s, s], [0.0, s]], vec![[0, 1, 2], [0, 2, 3]]).unwrap()
        };
        let points = [[0.5, 0.25], [1.0, 1.0], [3.0, 0.5], [-1.0, -1.0]];
        let unit = PointMapper::new(&rest(1.0), &points).unwrap();
        for s in [1e-300, 1e200, 4e299] {
            let scaled: Vec<Point> = points.iter().map(|p| [p[0] * s, p[1] * s]).collect();
            let mapper = PointMapper::new(&rest(s), &scaled).unwrap();
            for (a, b) in mapper.locations.iter().zip(&unit.locations) {
                assert_eq!(a.0, b.0, "at {s}");
                assert!(a.1.iter().zip(b.1).all(|(x, y)| (x - y).abs() < 1e-12), "at {s}: {a:?} vs {b:?}");
            }
        }
    }

    #[test]
    fn nothing_goes_in_or_comes_out_that_is_not_finite() {
        let rest = Mesh::new(vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]], vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        assert_eq!(
            PointMapper::new(&rest, &[[0.5, 0.5], [f64::NAN, 0.0]]),
            Err(ImportError::NonFinite { what: "point", index: 1 })
        );
        let mapper = PointMapper::new(&rest, &[[0.5, 0.25], [-1e300, 0.5]]).unwrap();
        let mut deformed = rest.positions().to_vec();
        deformed[2] = [f64::INFINITY, 1.0];
        assert_eq!(mapper.map(&deformed), Err(ImportError::NonFinite { what: "deformed position", index: 2 }));
        // The second point, 1e300 to the left, follows its triangle's affine motion: the mesh
        // stretched 1e10 times along x sends it to x = -1e310, beyond the largest double.
        let wide: Vec<Point> = rest.positions().iter().map(|p| [1e10 * p[0], p[1]]).collect();
        assert_eq!(mapper.map(&wide), Err(ImportError::NonFiniteResult { what: "mapped point", index: 1 }));
    }

    /// A grid of `n x n` unit squares, two triangles each, without the squares of `hole`
    /// (columns and rows from `hole.0` to `hole.1`, exclusive), vertices numbered as used.
    fn grid(n: usize, hole: (usize, usize)) -> Mesh {
        let mut index = vec![u32::MAX; (n + 1) * (n + 1)];
        let (mut positions, mut triangles) = (Vec::new(), Vec::new());
        let mut vertex = |i: usize, j: usize, positions: &mut Vec<Point>| {
            let k = j * (n + 1) + i;
            if index[k] == u32::MAX {
                index[k] = positions.len() as u32;
                positions.push([i as f64, j as f64]);
            }
            index[k]
        };
        for j in 0..n {
            for i in 0..n {
                if (hole.0..hole.1).contains(&i) && (hole.0..hole.1).contains(&j) {
                    continue;
                }
                let [a, b, c, d] =
                    [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(x, y)| vertex(x, y, &mut positions));
                triangles.extend([[a, b, c], [a, c, d]]);
            }
        }
        Mesh::new(positions, triangles).unwrap()
    }

    #[test]
    fn nearest_triangle_matches_comparing_every_triangle() {
        let meshes = [grid(8, (0, 0)), grid(9, (3, 6))];
        let mut state = 11u64;
        let mut next = |n: u64| {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 33) % n
        };
        for mesh in &meshes {
            let positions = mesh.positions();
            let tree = Tree::new(positions, mesh.triangles());
            let brute_force = |p: Point| {
                let d = |t: usize| triangle_distance(mesh.triangles()[t].map(|i| positions[i as usize]), p);
                // The first of the nearest, as `min_by` keeps the first of equals.
                (0..mesh.triangle_count()).map(|t| (d(t), t)).min_by(|a, b| a.0.total_cmp(&b.0)).unwrap().1
            };
            // Half-unit points inside, on edges and vertices, in the hole and outside (ties
            // everywhere), and arbitrary points.
            let mut points: Vec<Point> =
                (0..400).map(|_| [next(60) as f64 / 2.0 - 10.0, next(60) as f64 / 2.0 - 10.0]).collect();
            points.extend(
                (0..4000).map(|_| [next(1 << 20) as f64 / 26214.4 - 10.0, next(1 << 20) as f64 / 26214.4 - 10.0]),
            );
            points.extend(positions.iter().copied());
            points.extend([[4.5, 4.5], [1e9, -1e9], [-0.5, -0.5]]);
            for p in points {
                assert_eq!(tree.nearest(positions, mesh.triangles(), p), brute_force(p), "at {p:?}");
            }
        }
    }

    #[test]
    fn texture_coordinates_have_v_up_from_the_bottom_row() {
        // A 4 x 2 image in its traced frame (y up, origin at the bottom-left corner). Its
        // top-left pixel, row 0 from the top, has its centre at (0.5, 2 - 0.5); OBJ's
        // convention puts that at u = 0.5 / 4 and v = 1 - 0.5 / 2.
        let (w, h) = (4.0, 2.0);
        let points = [[0.5, 1.5], [3.5, 0.5], [0.0, 0.0], [4.0, 2.0], [0.0, 2.0], [2.0, 1.0]];
        let expected = [[0.125, 0.75], [0.875, 0.25], [0.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]];
        assert_eq!(texture_coordinates(&points, w, h), Ok(expected.to_vec()));
    }

    #[test]
    fn texture_coordinates_refuse_what_is_not_finite() {
        let error = texture_coordinates(&[[0.0, 0.0]], 0.0, 10.0).unwrap_err();
        assert_eq!(error.to_string(), "option width is 0, expected a finite number above 0");
        assert!(texture_coordinates(&[[0.0, 0.0]], 10.0, f64::INFINITY).is_err());
        assert_eq!(
            texture_coordinates(&[[1.0, 2.0], [0.0, f64::NAN]], 1.0, 1.0),
            Err(ImportError::NonFinite { what: "position", index: 1 })
        );
        // 1e300 / 1e-10 overflows.
        assert_eq!(
            texture_coordinates(&[[1.0, 2.0], [1e300, 0.0]], 1e-10, 1.0),
            Err(ImportError::NonFiniteResult { what: "the texture coordinate of position", index: 1 })
        );
    }
}
