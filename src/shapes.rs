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
//! The DefOp paper's other models, our own designs (not traced from the paper), are
//! functions only, outside [`NAMES`] (so the app's shape menu is unchanged), each with the
//! spots where its handles go: [`aleph`] (a letter-like glyph, 5 handles), [`octopus`]
//! (a head and 8 wavy tentacles, 9 handles) and [`crab`] (a body, two claws and 8 legs,
//! 11 handles).
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

/// Corners of [`aleph`], counter-clockwise: a diagonal stroke 0.18 wide from the upper
/// left to the lower right, an arm rising from the upper half of its upper side to the
/// upper right and a leg with a foot falling from the lower half of its lower side to the
/// lower left. In the unit square.
const ALEPH: [Point; 15] = [
    [0.836, 0.036],
    [0.964, 0.164],
    [0.524, 0.604],
    [0.778, 0.822],
    [0.80, 0.93],
    [0.67, 0.966],
    [0.364, 0.764],
    [0.164, 0.964],
    [0.036, 0.836],
    [0.476, 0.396],
    [0.22, 0.17],
    [0.10, 0.12],
    [0.08, 0.03],
    [0.30, 0.03],
    [0.636, 0.236],
];

/// Where [`aleph`]'s 5 handles go: the stroke's two ends, its middle, the arm's tip and the
/// foot.
pub fn aleph_handles() -> Vec<Point> {
    vec![[0.12, 0.88], [0.88, 0.12], [0.5, 0.5], [0.74, 0.9], [0.16, 0.09]]
}

/// A letter-like glyph in the unit square (after the Hebrew aleph, our own design): a
/// thick diagonal stroke with an arm to the upper right and a leg to the lower left,
/// straight-sided. Handles: [`aleph_handles`].
pub fn aleph() -> Outline {
    Outline::new(ALEPH.to_vec())
}

/// How a limb of [`body_with_limbs`] ends.
#[derive(Clone, Copy)]
enum Cap {
    /// One point beyond the centreline's end.
    Round,
    /// Two fingers with a notch between them (a pincer).
    Pincer,
}

/// A limb: its centreline (a function of `s` in [0, 1], starting on the body's ellipse),
/// its half width along it and its end.
struct Limb {
    centre: Box<dyn Fn(f64) -> Point>,
    half_width: Box<dyn Fn(f64) -> f64>,
    cap: Cap,
}

/// Samples along a limb's centreline.
const LIMB_SAMPLES: usize = 40;

/// An elliptic body (centre, semi-axes) with limbs, as one counter-clockwise ring: the
/// ellipse's arcs between the limbs, and round each limb its right side out, its cap and
/// its left side back. Limbs must be given counter-clockwise round the body.
fn body_with_limbs(centre: Point, radii: [f64; 2], limbs: &[Limb], spacing: f64) -> Vec<Point> {
    use std::f64::consts::TAU;
    let on_ellipse = |t: f64| [centre[0] + radii[0] * libm::cos(t), centre[1] + radii[1] * libm::sin(t)];
    // The ellipse parameter of a point near the ellipse.
    let parameter = |p: Point| libm::atan2((p[1] - centre[1]) / radii[1], (p[0] - centre[0]) / radii[0]);
    let mut ring = Vec::new();
    let mut sides = Vec::new();
    for limb in limbs {
        let c: Vec<Point> = (0..=LIMB_SAMPLES).map(|k| (limb.centre)(k as f64 / LIMB_SAMPLES as f64)).collect();
        let (mut right, mut left) = (Vec::new(), Vec::new());
        for (k, p) in c.iter().enumerate() {
            let (a, b) = (c[k.saturating_sub(1)], c[(k + 1).min(LIMB_SAMPLES)]);
            let length = distance(a, b);
            let normal = [-(b[1] - a[1]) / length, (b[0] - a[0]) / length];
            let w = (limb.half_width)(k as f64 / LIMB_SAMPLES as f64);
            right.push([p[0] - w * normal[0], p[1] - w * normal[1]]);
            left.push([p[0] + w * normal[0], p[1] + w * normal[1]]);
        }
        let (end, before) = (c[LIMB_SAMPLES], c[LIMB_SAMPLES - 1]);
        let length = distance(before, end);
        let tangent = [(end[0] - before[0]) / length, (end[1] - before[1]) / length];
        let w = (limb.half_width)(1.0);
        let cap = match limb.cap {
            Cap::Round => vec![[end[0] + w * tangent[0], end[1] + w * tangent[1]]],
            Cap::Pincer => {
                let notch = c[LIMB_SAMPLES * 17 / 20];
                let (r, l) = (right[LIMB_SAMPLES], left[LIMB_SAMPLES]);
                let reach = 1.5 * w;
                vec![
                    [r[0] + reach * tangent[0], r[1] + reach * tangent[1]],
                    notch,
                    [l[0] + reach * tangent[0], l[1] + reach * tangent[1]],
                ]
            }
        };
        sides.push((right, cap, left));
    }
    // From the last limb's left root round to the first limb's right root, then limb by
    // limb.
    let mut from = sides.last().map_or(0.0, |s| parameter(s.2[0]));
    for (right, cap, left) in sides {
        let mut to = parameter(right[0]);
        while to <= from {
            to += TAU;
        }
        let steps = ((to - from) * radii[0].max(radii[1]) / spacing).ceil() as usize;
        ring.extend((1..steps).map(|k| on_ellipse(from + (to - from) * k as f64 / steps as f64)));
        ring.extend(right);
        ring.extend(cap);
        ring.extend(left.into_iter().rev());
        from = parameter(*ring.last().expect("a limb has points"));
    }
    ring
}

/// A limb's centreline leaving the ellipse at `angle` along its outward normal, then
/// following `path`: pieces (length, turn in radians over the piece's first [`BEND`]),
/// with a sideways wave `wave` = (amplitude, half-periods) growing from the root.
fn limb_path(
    centre: Point,
    radii: [f64; 2],
    angle: f64,
    path: Vec<(f64, f64)>,
    wave: (f64, f64),
) -> impl Fn(f64) -> Point {
    let root = [centre[0] + radii[0] * libm::cos(angle), centre[1] + radii[1] * libm::sin(angle)];
    let heading = libm::atan2(libm::sin(angle) / radii[1], libm::cos(angle) / radii[0]);
    let total: f64 = path.iter().map(|p| p.0).sum();
    move |s: f64| {
        // Integrated in small steps (the bends are arcs), at the midpoint of each.
        let (mut p, mut base, mut direction) = (root, heading, heading);
        let mut left = s * total;
        for &(length, turn) in &path {
            let steps = (length / 0.002).ceil() as usize;
            let h = length / steps as f64;
            for k in 0..steps {
                if left <= 0.0 {
                    break;
                }
                let step = left.min(h);
                let mid = (k as f64 + 0.5) * h;
                direction = base + turn * (mid / BEND).min(1.0);
                p = [p[0] + step * libm::cos(direction), p[1] + step * libm::sin(direction)];
                left -= step;
            }
            base += turn;
        }
        let lateral = wave.0 * s * libm::sin(std::f64::consts::PI * wave.1 * s);
        [p[0] - lateral * libm::sin(direction), p[1] + lateral * libm::cos(direction)]
    }
}

/// The length over which a limb turns into its next piece.
const BEND: f64 = 0.08;

/// The octopus's head: centre and semi-axes.
const OCTOPUS_HEAD: (Point, [f64; 2]) = ([0.0, 0.55], [0.48, 0.45]);

/// The octopus's 8 tentacles, left to right (counter-clockwise round the head's bottom).
fn octopus_limbs() -> Vec<Limb> {
    let (centre, radii) = OCTOPUS_HEAD;
    (0..8)
        .map(|k| {
            let angle = -std::f64::consts::FRAC_PI_2 + 0.2 * (k as f64 - 3.5);
            Limb {
                centre: Box::new(limb_path(centre, radii, angle, vec![(0.8, 0.0)], (0.12, 3.0))),
                half_width: Box::new(|s| 0.035 * (1.0 - 0.7 * s) + 0.008),
                cap: Cap::Round,
            }
        })
        .collect()
}

/// A cartoon octopus (our own design): an elliptic head, 0.96 wide, with 8 wavy tapering
/// tentacles 0.8 long fanning out below it; about 1.7 units wide and 1.5 tall. Handles:
/// [`octopus_handles`].
pub fn octopus() -> Outline {
    let (centre, radii) = OCTOPUS_HEAD;
    Outline::new(body_with_limbs(centre, radii, &octopus_limbs(), 0.02))
}

/// Where [`octopus`]'s 9 handles go: the head's centre, then near each tentacle's tip.
pub fn octopus_handles() -> Vec<Point> {
    let head = [OCTOPUS_HEAD.0[0], OCTOPUS_HEAD.0[1] + 0.05];
    std::iter::once(head).chain(octopus_limbs().iter().map(|l| (l.centre)(0.93))).collect()
}

/// The crab's body: centre and semi-axes.
const CRAB_BODY: (Point, [f64; 2]) = ([0.0, 0.0], [0.5, 0.34]);

/// The crab's limbs counter-clockwise from its rear right leg: 4 legs and a claw on the
/// right, their mirror images on the left.
fn crab_limbs() -> Vec<Limb> {
    use std::f64::consts::PI;
    let (centre, radii) = CRAB_BODY;
    let leg = |angle: f64, side: f64| Limb {
        centre: Box::new(limb_path(centre, radii, angle, vec![(0.26, 0.35 * side), (0.3, -1.1 * side)], (0.0, 0.0))),
        half_width: Box::new(|s| 0.04 * (1.0 - 0.6 * s) + 0.006),
        cap: Cap::Round,
    };
    let claw = |angle: f64, side: f64| Limb {
        centre: Box::new(limb_path(centre, radii, angle, vec![(0.22, 0.3 * side), (0.3, 0.5 * side)], (0.0, 0.0))),
        half_width: Box::new(|s| if s < 0.4 { 0.045 } else { 0.045 + 0.06 * libm::sin(PI * (s - 0.4) / 0.6) }),
        cap: Cap::Pincer,
    };
    let legs = [-0.75, -0.42, -0.09, 0.24];
    let mut limbs: Vec<Limb> = legs.iter().map(|&a| leg(a, 1.0)).collect();
    limbs.push(claw(0.95, 1.0));
    limbs.push(claw(PI - 0.95, -1.0));
    limbs.extend(legs.iter().rev().map(|&a| leg(PI - a, -1.0)));
    limbs
}

/// A cartoon crab seen from above (our own design): an elliptic body 1 wide, two claws
/// with pincers reaching forward (up) and 8 bent legs, 4 a side; about 2 units wide.
/// Handles: [`crab_handles`].
pub fn crab() -> Outline {
    let (centre, radii) = CRAB_BODY;
    Outline::new(body_with_limbs(centre, radii, &crab_limbs(), 0.02))
}

/// Where [`crab`]'s 11 handles go: the body's centre, then, counter-clockwise from the
/// rear right leg, near each leg's tip and in each claw's hand.
pub fn crab_handles() -> Vec<Point> {
    let limbs = crab_limbs();
    std::iter::once(CRAB_BODY.0)
        .chain(limbs.iter().map(|l| (l.centre)(if matches!(l.cap, Cap::Pincer) { 0.75 } else { 0.92 })))
        .collect()
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

    #[test]
    fn the_defop_models_are_simple_outlines_that_triangulate_round_their_handles() {
        use crate::geometry::point_in_polygon;
        let models = [("aleph", aleph(), aleph_handles(), 5), ("octopus", octopus(), octopus_handles(), 9)];
        for (name, shape, handles, n) in models.into_iter().chain([("crab", crab(), crab_handles(), 11)]) {
            assert!(polygon_area(&shape.outer) > 0.0, "{name} runs counter-clockwise");
            // Simple (validation finds crossings) and counter-clockwise.
            shape.validated(10_000).unwrap_or_else(|e| panic!("{name}: {e}"));
            let ring = &shape.outer;
            let m = ring.len();
            assert_eq!(handles.len(), n, "{name}");
            for (k, h) in handles.iter().enumerate() {
                assert!(point_in_polygon(*h, ring), "{name}: handle {k} at {h:?} is outside");
                let clearance =
                    (0..m).map(|i| segment_distance(*h, ring[i], ring[(i + 1) % m])).fold(f64::MAX, f64::min);
                assert!(clearance > 0.005, "{name}: handle {k} is {clearance} from the boundary");
            }
            let options = crate::TriangulationOptions::default().with_target_edge_length(0.03);
            let mesh = crate::triangulate(&shape, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(mesh.connected_components(), 1, "{name}");
            assert!((mesh.area() - polygon_area(ring)).abs() < 1e-9 * polygon_area(ring), "{name}");
        }
    }

    /// The distance from `p` to the segment `a b`.
    fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
        distance(p, [a[0] + t * dx, a[1] + t * dy])
    }
}
