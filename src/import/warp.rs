//! Carrying imported art along with a deformed mesh: points (an SVG's path points and
//! control points) by barycentric coordinates in the rest mesh, and image texture
//! coordinates for the vertices of a traced image's mesh.
//!
//! Nothing here returns NaN or infinity: input that is not finite is refused, and so is a
//! result that overflows double precision (a point far outside the mesh extrapolated through
//! a huge deformed triangle, a position divided by a tiny image size), each by index.

use crate::geometry::{distance, normalising_exponent, orient, scale_by_power_of_two, Point};
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
    /// follows that triangle's affine motion. Refuses a point with a coordinate that is not
    /// finite ([`ImportError::NonFinite`]).
    pub fn new(rest: &Mesh, points: &[Point]) -> Result<Self, ImportError> {
        if let Some(index) = points.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
            return Err(ImportError::NonFinite { what: "point", index });
        }
        // Located on the mesh and points scaled by the power of two that brings the mesh's
        // largest coordinate into [1, 2) (exact; barycentric weights do not change), so
        // products of its coordinates neither overflow nor underflow.
        let k = normalising_exponent(rest.positions().iter().copied());
        let scale = |p: &Point| p.map(|x| scale_by_power_of_two(x, k));
        let positions: Vec<Point> = rest.positions().iter().map(scale).collect();
        let grid = Grid::new(&positions, rest.triangles());
        let locations = points.iter().map(|p| grid.locate(&positions, rest.triangles(), scale(p))).collect();
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

/// Maps `points` from `rest` to `deformed` in one go (see [`PointMapper`]).
pub fn map_points(rest: &Mesh, deformed: &[Point], points: &[Point]) -> Result<Vec<Point>, ImportError> {
    PointMapper::new(rest, points)?.map(deformed)
}

/// Texture coordinates of points given in the pixel frame of a traced image (y up, origin
/// at the bottom-left corner, see [`crate::import::raster`]): `u = x / width` and, as
/// images store their top row first, `v = 1 - y / height` (so `v = 0` at the top row).
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
            let uv = [p[0] / width, 1.0 - p[1] / height];
            if uv[0].is_finite() && uv[1].is_finite() {
                Ok(uv)
            } else {
                Err(ImportError::NonFiniteResult { what: "the texture coordinate of position", index })
            }
        })
        .collect()
}

/// Triangles bucketed by a uniform grid over the mesh's bounding box.
struct Grid {
    origin: Point,
    cell: f64,
    columns: usize,
    rows: usize,
    /// Triangles of cell `k` are `triangles[start[k]..start[k + 1]]`.
    start: Vec<usize>,
    triangles: Vec<u32>,
}

impl Grid {
    fn new(p: &[Point], triangles: &[[u32; 3]]) -> Self {
        let (lo, hi) = crate::geometry::bounding_box(p.iter().copied()).unwrap_or(([0.0; 2], [1.0; 2]));
        let (w, h) = ((hi[0] - lo[0]).max(f64::MIN_POSITIVE), (hi[1] - lo[1]).max(f64::MIN_POSITIVE));
        // About one triangle per cell.
        let cell = (w * h / triangles.len() as f64).sqrt().max(w.max(h) / 4096.0);
        let columns = ((w / cell).ceil() as usize).clamp(1, 4096);
        let rows = ((h / cell).ceil() as usize).clamp(1, 4096);
        let mut grid =
            Self { origin: lo, cell, columns, rows, start: vec![0; columns * rows + 1], triangles: Vec::new() };
        let ranges: Vec<(usize, usize, usize, usize)> = triangles
            .iter()
            .map(|t| {
                let corners = t.map(|i| p[i as usize]);
                let (a, b) = grid.cell_of(corners[0]);
                let (mut c0, mut c1, mut r0, mut r1) = (a, a, b, b);
                for &q in &corners[1..] {
                    let (c, r) = grid.cell_of(q);
                    (c0, c1, r0, r1) = (c0.min(c), c1.max(c), r0.min(r), r1.max(r));
                }
                (c0, c1, r0, r1)
            })
            .collect();
        for &(c0, c1, r0, r1) in &ranges {
            for r in r0..=r1 {
                for c in c0..=c1 {
                    grid.start[r * columns + c + 1] += 1;
                }
            }
        }
        for k in 0..columns * rows {
            grid.start[k + 1] += grid.start[k];
        }
        let mut fill = grid.start.clone();
        grid.triangles = vec![0; grid.start[columns * rows]];
        for (t, &(c0, c1, r0, r1)) in ranges.iter().enumerate() {
            for r in r0..=r1 {
                for c in c0..=c1 {
                    grid.triangles[fill[r * columns + c]] = t as u32;
                    fill[r * columns + c] += 1;
                }
            }
        }
        grid
    }

    /// The cell of a point, clamped to the grid.
    fn cell_of(&self, p: Point) -> (usize, usize) {
        let c = ((p[0] - self.origin[0]) / self.cell).floor().clamp(0.0, (self.columns - 1) as f64) as usize;
        let r = ((p[1] - self.origin[1]) / self.cell).floor().clamp(0.0, (self.rows - 1) as f64) as usize;
        (c, r)
    }

    fn locate(&self, positions: &[Point], triangles: &[[u32; 3]], p: Point) -> ([u32; 3], [f64; 3]) {
        let (c, r) = self.cell_of(p);
        let k = r * self.columns + c;
        let in_cell = &self.triangles[self.start[k]..self.start[k + 1]];
        let best = in_cell
            .iter()
            .map(|&t| t as usize)
            .find(|&t| triangle_distance(triangles[t].map(|i| positions[i as usize]), p) == 0.0)
            .unwrap_or_else(|| {
                // Outside the mesh (or on a crack between cells): the nearest triangle.
                (0..triangles.len())
                    .min_by(|&s, &t| {
                        let d = |t: usize| triangle_distance(triangles[t].map(|i| positions[i as usize]), p);
                        d(s).total_cmp(&d(t))
                    })
                    .expect("a mesh has triangles")
            });
        let tri = triangles[best];
        let [a, b, c] = tri.map(|i| positions[i as usize]);
        let whole = orient(a, b, c);
        (tri, [orient(b, c, p) / whole, orient(c, a, p) / whole, orient(a, b, p) / whole])
    }
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

    #[test]
    fn texture_coordinates_put_the_top_row_at_v_0() {
        assert_eq!(texture_coordinates(&[[0.0, 10.0], [20.0, 0.0]], 20.0, 10.0), Ok(vec![[0.0, 0.0], [1.0, 1.0]]));
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
