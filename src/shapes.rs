//! Built-in shapes of our own making, by name ([`by_name`], [`NAMES`]).
//!
//! - `gingerbread`, the default shape: a waving gingerbread figure, a smooth outline
//!   through hand-placed control points (a centripetal Catmull-Rom spline, which neither
//!   overshoots nor forms cusps), with eyes and buttons as holes;
//! - `cat`: a standing cartoon cat seen from the side (four legs, raised tail, ears), built
//!   the same way, with an eye as a hole;
//! - `bar`: the paper's synthetic model for its comparison (Table 1, Figure 9), a long bar
//!   whose long sides carry small teeth, so that bending it shows how boundary detail is
//!   kept.
//!
//! Beside them, shapes for tests and benchmarks: [`comb`], the worst case of a sweep, and
//! [`grid_mesh`].

use crate::geometry::{distance, Point};
use crate::mesh::Mesh;
use crate::outline::Outline;

/// Control points of the figure's outline, counter-clockwise with y pointing up, from the
/// crotch round the right leg, right arm, head, raised left arm and left leg. About 1.4
/// units tall.
const FIGURE: [Point; 46] = [
    [0.0, 0.36],
    [0.06, 0.20],
    [0.09, 0.05],
    [0.13, -0.01],
    [0.29, -0.02],
    [0.34, 0.04],
    [0.28, 0.09],
    [0.22, 0.22],
    [0.21, 0.40],
    [0.23, 0.53],
    [0.32, 0.61],
    [0.46, 0.58],
    [0.56, 0.55],
    [0.63, 0.61],
    [0.59, 0.69],
    [0.46, 0.72],
    [0.31, 0.80],
    [0.17, 0.86],
    [0.08, 0.90],
    [0.17, 0.98],
    [0.21, 1.12],
    [0.15, 1.26],
    [0.0, 1.31],
    [-0.15, 1.26],
    [-0.21, 1.12],
    [-0.17, 0.98],
    [-0.08, 0.90],
    [-0.17, 0.86],
    [-0.28, 0.93],
    [-0.37, 1.05],
    [-0.41, 1.17],
    [-0.48, 1.23],
    [-0.54, 1.16],
    [-0.50, 1.06],
    [-0.43, 0.93],
    [-0.34, 0.79],
    [-0.24, 0.66],
    [-0.23, 0.53],
    [-0.21, 0.40],
    [-0.22, 0.22],
    [-0.28, 0.09],
    [-0.34, 0.04],
    [-0.29, -0.02],
    [-0.13, -0.01],
    [-0.09, 0.05],
    [-0.06, 0.20],
];

/// The default shape: a waving gingerbread figure with two eyes and two buttons as holes.
/// Boundary points are spaced about 0.025 apart along the outline.
pub fn gingerbread() -> Outline {
    let mut outline = Outline::new(closed_spline(&FIGURE, 0.025));
    for (cx, cy, rx, ry) in
        [(-0.07, 1.14, 0.028, 0.04), (0.07, 1.14, 0.028, 0.04), (0.0, 0.74, 0.03, 0.03), (0.0, 0.60, 0.03, 0.03)]
    {
        outline = outline.with_hole(ellipse([cx, cy], rx, ry, 16));
    }
    outline
}

/// Control points of the cat's outline, counter-clockwise with y pointing up, from the
/// rump down round the hind legs, the belly, the front legs, the head (facing right) and
/// back along the back to the raised tail. About 1.7 units long and 1.1 tall, paws at y = 0.
const CAT: [Point; 55] = [
    [-0.50, 0.50],
    [-0.50, 0.30],
    [-0.49, 0.12],
    [-0.52, 0.02],
    [-0.46, -0.01],
    [-0.37, 0.0],
    [-0.37, 0.10],
    [-0.36, 0.24],
    [-0.335, 0.29],
    [-0.31, 0.24],
    [-0.30, 0.10],
    [-0.31, 0.02],
    [-0.25, -0.01],
    [-0.16, 0.0],
    [-0.17, 0.12],
    [-0.15, 0.30],
    [0.0, 0.33],
    [0.12, 0.30],
    [0.14, 0.12],
    [0.13, 0.02],
    [0.19, -0.01],
    [0.27, 0.0],
    [0.26, 0.12],
    [0.27, 0.24],
    [0.295, 0.29],
    [0.32, 0.24],
    [0.33, 0.12],
    [0.32, 0.02],
    [0.38, -0.01],
    [0.47, 0.0],
    [0.46, 0.12],
    [0.47, 0.35],
    [0.52, 0.55],
    [0.62, 0.64],
    [0.76, 0.68],
    [0.84, 0.78],
    [0.80, 0.88],
    [0.74, 0.95],
    [0.76, 1.08],
    [0.66, 1.00],
    [0.58, 1.09],
    [0.54, 0.96],
    [0.46, 0.80],
    [0.30, 0.70],
    [0.0, 0.68],
    [-0.35, 0.70],
    [-0.52, 0.72],
    [-0.68, 0.80],
    [-0.78, 0.94],
    [-0.80, 1.08],
    [-0.86, 1.06],
    [-0.86, 0.92],
    [-0.76, 0.76],
    [-0.60, 0.64],
    [-0.52, 0.60],
];

/// A standing cartoon cat, side view, facing right, with one eye as a hole. Boundary
/// points are spaced about 0.02 apart.
pub fn cat() -> Outline {
    Outline::new(closed_spline(&CAT, 0.02)).with_hole(ellipse([0.71, 0.85], 0.022, 0.03, 12))
}

/// Length and height of [`toothed_bar`].
pub const BAR_SIZE: [f64; 2] = [2.0, 0.4];

/// The paper's synthetic model: a 2 x 0.4 bar (lower left corner at the origin) whose long
/// sides each carry 16 trapezoidal teeth 0.035 high, 0.07 wide at the base and 0.04 at the
/// top, one every 0.125. The short ends are straight, for handles.
pub fn toothed_bar() -> Outline {
    let [length, height] = BAR_SIZE;
    let (teeth, tooth_height, base, top) = (16, 0.035, 0.07, 0.04);
    let period = length / teeth as f64;
    // Along the bottom from left to right, teeth pointing down; then the top from right to
    // left, teeth pointing up: counter-clockwise.
    let mut ring = vec![[0.0, 0.0]];
    for k in 0..teeth {
        let centre = (k as f64 + 0.5) * period;
        ring.push([centre - base / 2.0, 0.0]);
        ring.push([centre - top / 2.0, -tooth_height]);
        ring.push([centre + top / 2.0, -tooth_height]);
        ring.push([centre + base / 2.0, 0.0]);
    }
    ring.push([length, 0.0]);
    ring.push([length, height]);
    for k in (0..teeth).rev() {
        let centre = (k as f64 + 0.5) * period;
        ring.push([centre + base / 2.0, height]);
        ring.push([centre + top / 2.0, height + tooth_height]);
        ring.push([centre - top / 2.0, height + tooth_height]);
        ring.push([centre - base / 2.0, height]);
    }
    ring.push([0.0, height]);
    Outline::new(ring)
}

/// The names of the built-in shapes, as [`by_name`] takes them.
pub const NAMES: [&str; 3] = ["gingerbread", "cat", "bar"];

/// A built-in shape by name (see [`NAMES`]).
pub fn by_name(name: &str) -> Option<Outline> {
    match name {
        "gingerbread" => Some(gingerbread()),
        "cat" => Some(cat()),
        "bar" => Some(toothed_bar()),
        _ => None,
    }
}

/// A comb: a spine one unit wide on the left and `teeth` teeth of `length` to the right,
/// each tooth and gap one unit high; `4 teeth` points, counter-clockwise, of area
/// `teeth length + 2 teeth - 1`. Its long edges all overlap in x, the worst case of a
/// sweep that compares segments overlapping in x (the adversarial benchmark, the hostile
/// tests).
pub fn comb(teeth: usize, length: f64) -> Vec<Point> {
    let mut ring = Vec::with_capacity(4 * teeth);
    for i in 0..teeth {
        let y = 2.0 * i as f64;
        ring.push([if i == 0 { -1.0 } else { 0.0 }, y]);
        ring.push([length, y]);
        ring.push([length, y + 1.0]);
        ring.push([if i + 1 == teeth { -1.0 } else { 0.0 }, y + 1.0]);
    }
    ring
}

/// A grid of `columns x rows` unit squares over `[0, columns] x [0, rows]`, two
/// counter-clockwise triangles each, vertices numbered row by row from the origin.
///
/// ```
/// let mesh = akap::shapes::grid_mesh(3, 2);
/// assert_eq!((mesh.vertex_count(), mesh.triangle_count()), (12, 12));
/// assert_eq!(mesh.positions()[4], [0.0, 1.0]);
/// ```
pub fn grid_mesh(columns: usize, rows: usize) -> Mesh {
    let index = |i: usize, j: usize| (j * (columns + 1) + i) as u32;
    let positions = (0..=rows).flat_map(|j| (0..=columns).map(move |i| [i as f64, j as f64])).collect();
    let mut triangles = Vec::with_capacity(2 * columns * rows);
    for j in 0..rows {
        for i in 0..columns {
            let (a, b, c, d) = (index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1));
            triangles.extend([[a, b, c], [a, c, d]]);
        }
    }
    Mesh::new(positions, triangles).expect("a grid of at least one square is a valid mesh")
}

/// An axis-aligned ellipse as a counter-clockwise polygon of `n` points.
pub fn ellipse(centre: Point, rx: f64, ry: f64, n: usize) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            [centre[0] + rx * libm::cos(t), centre[1] + ry * libm::sin(t)]
        })
        .collect()
}

/// Samples the closed centripetal Catmull-Rom spline through `control`, with about
/// `spacing` between consecutive samples; every control point is a sample.
pub fn closed_spline(control: &[Point], spacing: f64) -> Vec<Point> {
    let n = control.len();
    let mut out = Vec::new();
    for i in 0..n {
        let p = [control[(i + n - 1) % n], control[i], control[(i + 1) % n], control[(i + 2) % n]];
        let steps = (distance(p[1], p[2]) / spacing).ceil().max(1.0) as usize;
        for s in 0..steps {
            out.push(catmull_rom(p, s as f64 / steps as f64));
        }
    }
    out
}

/// Point at parameter `u` in [0, 1] on the centripetal Catmull-Rom segment from `p[1]` to
/// `p[2]` (Barry-Goldman pyramidal evaluation with knot spacing |chord|^0.5).
fn catmull_rom(p: [Point; 4], u: f64) -> Point {
    let knot = |a: Point, b: Point| distance(a, b).sqrt().max(1e-12);
    let t0 = 0.0;
    let t1 = t0 + knot(p[0], p[1]);
    let t2 = t1 + knot(p[1], p[2]);
    let t3 = t2 + knot(p[2], p[3]);
    let t = t1 + u * (t2 - t1);
    let lerp = |a: Point, b: Point, ta: f64, tb: f64| {
        let w = (t - ta) / (tb - ta);
        [a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])]
    };
    let a1 = lerp(p[0], p[1], t0, t1);
    let a2 = lerp(p[1], p[2], t1, t2);
    let a3 = lerp(p[2], p[3], t2, t3);
    let b1 = lerp(a1, a2, t0, t2);
    let b2 = lerp(a2, a3, t1, t3);
    lerp(b1, b2, t1, t2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polygon_area;

    #[test]
    fn spline_passes_through_its_control_points() {
        let control = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let samples = closed_spline(&control, 0.1);
        for c in control {
            assert!(samples.contains(&c));
        }
    }

    #[test]
    fn figure_is_a_valid_counter_clockwise_outline() {
        let figure = gingerbread();
        assert!(polygon_area(&figure.outer) > 0.0);
        let rings = figure.validated(10_000).expect("the default shape is valid");
        assert_eq!(rings.len(), 5);
    }

    #[test]
    fn every_named_shape_is_a_valid_counter_clockwise_outline() {
        for name in NAMES {
            let shape = by_name(name).expect("a listed name");
            assert!(polygon_area(&shape.outer) > 0.0, "{name}");
            shape.validated(10_000).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
        assert!(by_name("dragon").is_none());
    }
}
