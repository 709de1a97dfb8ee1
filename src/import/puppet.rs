//! Layered drawings as puppets: one mesh made of sheets, one per part, with joints where a
//! part overlaps a part behind it (the [`Puppet`] that [`crate::deform::puppet`] poses).
//!
//! - **Parts.** An SVG's parts are its layers ([`import_svg_layers`]: top-level groups and
//!   shapes, back to front; depth 0 is the back-most), each named from its
//!   `inkscape:label`, else its `id`, else "Part N" (N its place among the parts, from 1).
//!   An image's parts are its separate opaque regions ([`import_image_puppet`]).
//! - **Sheets.** Each part's outlines are meshed on their own with
//!   [`triangulate_to_about`], the vertices asked for shared by area (at least
//!   [`MIN_PART_VERTICES`] a part, [`MIN_PIECE_VERTICES`] a separate piece), and the meshes
//!   are put one after another: no vertex is shared between parts.
//! - **Joints.** For each pair of parts whose regions overlap by at least [`MIN_OVERLAP`]
//!   of the smaller one's area, one joint, `[front, back]`, in the largest piece of the
//!   overlap (computed exactly by `union`): at its area centroid when that lies inside it,
//!   clear of its boundary by at least half the clearance of the best other candidate (the
//!   centroids of up to [`JOINT_CANDIDATES`] of the two sheets' triangles lying in it),
//!   else at that best candidate. The point is checked to lie on a triangle of each sheet;
//!   a pair with no such point gets no joint. Parts that overlap nothing get none.
//!
//! Cost: the meshing is the triangulator's; the joints take the pairs of parts whose boxes
//! meet (at most [`MAX_LAYERS`] parts, so at most 32,640 pairs), each an overlay of the two
//! regions (O(n log n) in their points) and a pass over the two sheets' triangles.

use crate::deform::{Joint, Part, Puppet};
use crate::geometry::{bounding_box, point_in_polygon, polygon_area, Point};
use crate::import::error::ImportError;
use crate::import::raster::{trace_image, TraceOptions};
use crate::import::svg::{import_svg_layers, SvgOptions, SvgPath, MAX_LAYERS};
use crate::import::union::{self, Region};
use crate::import::vector::FillRule;
use crate::import::Limits;
use crate::mesh::Mesh;
use crate::outline::Outline;
use crate::triangulate::{triangulate_to_about, TriangulationOptions};

/// The vertices a puppet is meshed to by default, in all.
pub const DEFAULT_PUPPET_VERTICES: usize = 3000;

/// The fewest vertices asked for a part, however small its share of the area.
pub const MIN_PART_VERTICES: usize = 30;

/// The fewest vertices asked for one separate piece of a part (an eye of a face).
pub const MIN_PIECE_VERTICES: usize = 10;

/// Two parts whose overlap is smaller than this fraction of the smaller part's area are
/// not joined (shapes that only touch, or meet by rounding).
pub const MIN_OVERLAP: f64 = 1e-4;

/// Most triangles of each sheet whose centroids are tried as a joint's point.
pub const JOINT_CANDIDATES: usize = 128;

/// Options of [`import_puppet`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PuppetOptions {
    /// How the SVG is read, as [`crate::import::svg::import_svg`] reads it.
    pub svg: SvgOptions,
    /// About how many vertices the puppet's mesh has in all (default
    /// [`DEFAULT_PUPPET_VERTICES`]), shared between the parts by area.
    pub vertices: usize,
}

impl Default for PuppetOptions {
    fn default() -> Self {
        Self { svg: SvgOptions::default(), vertices: DEFAULT_PUPPET_VERTICES }
    }
}

impl PuppetOptions {
    /// Sets the number of vertices, about, in all.
    pub fn with_vertices(mut self, vertices: usize) -> Self {
        self.vertices = vertices;
        self
    }
}

/// A puppet made from a layered drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportedPuppet {
    /// Every part's sheet, one after another (no vertex shared between parts).
    pub mesh: Mesh,
    /// The parts (their triangles index [`ImportedPuppet::mesh`]'s) and joints.
    pub puppet: Puppet,
    /// Each part's art, in drawing order: its own fills and strokes, as
    /// [`crate::import::svg::SvgShape::paths`] (empty for an image's parts).
    pub art: Vec<Vec<SvgPath>>,
    /// Elements of the SVG that were skipped (`text`, `image`, `foreignObject`), once each.
    pub skipped: Vec<String>,
}

/// Reads a layered SVG as a puppet: a part per layer, meshed on its own, joints where parts
/// overlap (see the module's documentation). Refused as
/// [`crate::import::svg::import_svg`] refuses a document, and when it has more than
/// [`MAX_LAYERS`] layers, or the parts' meshes together more than
/// [`Limits::max_vertices`] vertices.
///
/// ```
/// use akap::import::puppet::{import_puppet, PuppetOptions};
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">
///   <g id="body"><rect width="4" height="4"/></g> <rect id="arm" x="3" y="1" width="5" height="2"/></svg>"#;
/// let imported = import_puppet(svg, &PuppetOptions::default().with_vertices(500))?;
/// let parts = &imported.puppet.parts;
/// assert_eq!((parts[0].name.as_str(), parts[1].name.as_str()), ("body", "arm"));
/// let joint = imported.puppet.joints[0];
/// assert_eq!(joint.parts, [1, 0]); // the arm, in front, on the body
/// let [x, y] = joint.point; // in the overlap, 3 < x < 4 and 7 < y < 9 (y up)
/// assert!(3.0 < x && x < 4.0 && 7.0 < y && y < 9.0);
/// # Ok::<(), akap::import::ImportError>(())
/// ```
pub fn import_puppet(svg: &str, options: &PuppetOptions) -> Result<ImportedPuppet, ImportError> {
    check_vertices(options.vertices, &options.svg.limits)?;
    let read = import_svg_layers(svg, &options.svg)?;
    let mut names = Vec::with_capacity(read.layers.len());
    let mut parts = Vec::with_capacity(read.layers.len());
    let mut art = Vec::with_capacity(read.layers.len());
    for (k, layer) in read.layers.into_iter().enumerate() {
        names.push(layer.name.unwrap_or_else(|| format!("Part {}", k + 1)));
        parts.push(layer.outlines);
        art.push(layer.paths);
    }
    let (mesh, puppet) = build(names, &parts, options.vertices, &options.svg.limits, true)?;
    Ok(ImportedPuppet { mesh, puppet, art, skipped: read.skipped })
}

/// Traces an image (RGBA pixels, rows from the top, as [`trace_image`] takes them) into a
/// puppet with a part per separate region ("Part 1" the largest, and so on), meshed to about
/// `vertices` in all; regions do not overlap, so there are no joints. Refused as
/// [`trace_image`] refuses an image, and when it has more than [`MAX_LAYERS`] regions.
pub fn import_image_puppet(
    rgba: &[u8],
    width: usize,
    height: usize,
    trace: &TraceOptions,
    vertices: usize,
) -> Result<ImportedPuppet, ImportError> {
    check_vertices(vertices, &trace.limits)?;
    let outlines = trace_image(rgba, width, height, trace)?;
    if outlines.len() > MAX_LAYERS {
        return Err(ImportError::TooLarge {
            what: "the image",
            size: outlines.len(),
            limit: MAX_LAYERS,
            unit: "separate regions",
        });
    }
    let names = (1..=outlines.len()).map(|k| format!("Part {k}")).collect();
    let parts: Vec<Vec<Outline>> = outlines.into_iter().map(|o| vec![o]).collect();
    let (mesh, puppet) = build(names, &parts, vertices, &trace.limits, false)?;
    let art = vec![Vec::new(); parts.len()];
    Ok(ImportedPuppet { mesh, puppet, art, skipped: Vec::new() })
}

fn check_vertices(vertices: usize, limits: &Limits) -> Result<(), ImportError> {
    if vertices < 3 || vertices > limits.max_vertices {
        return Err(ImportError::InvalidOption {
            name: "vertices",
            value: vertices as f64,
            expected: "a whole number from 3 to the vertex limit",
        });
    }
    Ok(())
}

/// The sheets of `parts` (each part's outlines) in one mesh, and the puppet naming them,
/// depth by their order, with joints where they overlap if `join`.
fn build(
    names: Vec<String>,
    parts: &[Vec<Outline>],
    vertices: usize,
    limits: &Limits,
    join: bool,
) -> Result<(Mesh, Puppet), ImportError> {
    let areas: Vec<Vec<f64>> = parts.iter().map(|p| p.iter().map(Outline::area).collect()).collect();
    let part_areas: Vec<f64> = areas.iter().map(|a| a.iter().sum()).collect();
    let total: f64 = part_areas.iter().sum();
    let options = TriangulationOptions::default().with_max_vertices(limits.max_vertices);
    let share = |count: usize, area: f64, of: f64, least: usize| {
        let n = (count as f64 * area / of).round();
        // NaN (an area of 0 of 0) and anything below the least become the least.
        if n >= least as f64 {
            (n as usize).min(limits.max_vertices)
        } else {
            least
        }
    };
    let mut positions: Vec<Point> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut puppet = Puppet::default();
    for (k, ((outlines, areas), name)) in parts.iter().zip(&areas).zip(names).enumerate() {
        let part_vertices = share(vertices, part_areas[k], total, MIN_PART_VERTICES);
        let mut own = Vec::new();
        for (outline, &area) in outlines.iter().zip(areas) {
            let n = share(part_vertices, area, part_areas[k], MIN_PIECE_VERTICES);
            let (sheet, _) = triangulate_to_about(outline, n, &options)?;
            let (offset, first) = (positions.len(), triangles.len());
            if offset + sheet.vertex_count() > limits.max_vertices {
                return Err(ImportError::TooLarge {
                    what: "the puppet's mesh",
                    size: offset + sheet.vertex_count(),
                    limit: limits.max_vertices,
                    unit: "vertices",
                });
            }
            // Within the vertex limit, so within u32 (and so are the triangles, fewer than
            // two per vertex).
            let offset = offset as u32;
            positions.extend_from_slice(sheet.positions());
            triangles.extend(sheet.triangles().iter().map(|t| t.map(|v| v + offset)));
            own.extend(first as u32..triangles.len() as u32);
        }
        puppet.parts.push(Part { name, triangles: own, depth: k as i32 });
    }
    let mesh = Mesh::new(positions, triangles)?;
    if join {
        puppet.joints = joints(parts, &part_areas, &mesh, &puppet.parts);
    }
    Ok((mesh, puppet))
}

/// One joint per pair of overlapping parts, `[front, back]` (see the module's
/// documentation).
fn joints(parts: &[Vec<Outline>], areas: &[f64], mesh: &Mesh, sheets: &[Part]) -> Vec<Joint> {
    let regions: Vec<Region> = parts
        .iter()
        .map(|outlines| {
            let rings: Vec<Vec<Point>> = outlines.iter().flat_map(|o| o.rings().map(<[Point]>::to_vec)).collect();
            union::resolve(&rings, FillRule::EvenOdd)
        })
        .collect();
    let boxes: Vec<Option<(Point, Point)>> =
        parts.iter().map(|outlines| bounding_box(outlines.iter().flat_map(|o| o.outer.iter().copied()))).collect();
    let meet = |a: usize, b: usize| match (boxes[a], boxes[b]) {
        (Some((lo, hi)), Some((lo2, hi2))) => lo[0] <= hi2[0] && lo2[0] <= hi[0] && lo[1] <= hi2[1] && lo2[1] <= hi[1],
        _ => false,
    };
    let size = bounding_box(mesh.positions().iter().copied())
        .map_or(0.0, |(lo, hi)| libm::hypot(hi[0] - lo[0], hi[1] - lo[1]));
    let mut joints = Vec::new();
    for front in 0..parts.len() {
        for back in 0..front {
            if !meet(front, back) {
                continue;
            }
            let overlap = union::intersect(&regions[front], &regions[back]);
            let pieces: Vec<(f64, &Vec<Vec<Point>>)> =
                overlap.iter().filter(|rings| !rings.is_empty()).map(|rings| (piece_area(rings), rings)).collect();
            let area: f64 = pieces.iter().map(|(a, _)| a).sum();
            if !(area >= MIN_OVERLAP * areas[front].min(areas[back]) && area > 0.0) {
                continue;
            }
            let Some((_, piece)) = pieces.into_iter().max_by(|a, b| a.0.total_cmp(&b.0)) else { continue };
            let on = [&sheets[front].triangles, &sheets[back].triangles];
            if let Some(point) = joint_point(piece, mesh, on, size) {
                joints.push(Joint { point, parts: [front, back] });
            }
        }
    }
    joints
}

/// The area of a piece of a region: its outer ring less its holes.
fn piece_area(rings: &[Vec<Point>]) -> f64 {
    let outer = polygon_area(&rings[0]).abs();
    outer - rings[1..].iter().map(|h| polygon_area(h).abs()).sum::<f64>()
}

/// The area centroid of a piece (outer ring less holes), computed about its first point.
fn centroid(rings: &[Vec<Point>]) -> Option<Point> {
    let origin = *rings.first()?.first()?;
    let (mut area, mut x, mut y) = (0.0, 0.0, 0.0);
    for (k, ring) in rings.iter().enumerate() {
        // Twice the signed area and its first moments, times 3.
        let (mut a, mut mx, mut my) = (0.0, 0.0, 0.0);
        for (i, p) in ring.iter().enumerate() {
            let q = ring[(i + 1) % ring.len()];
            let (px, py, qx, qy) = (p[0] - origin[0], p[1] - origin[1], q[0] - origin[0], q[1] - origin[1]);
            let cross = px * qy - qx * py;
            a += cross;
            mx += (px + qx) * cross;
            my += (py + qy) * cross;
        }
        // The outer ring counts positive, holes negative, whatever their orientation.
        let sign = if (k == 0) == (a >= 0.0) { 1.0 } else { -1.0 };
        area += sign * a;
        x += sign * mx;
        y += sign * my;
    }
    let c = [origin[0] + x / (3.0 * area), origin[1] + y / (3.0 * area)];
    (area > 0.0 && c[0].is_finite() && c[1].is_finite()).then_some(c)
}

/// The distance from `p` to the nearest ring of the piece, if `p` lies inside it.
fn clearance(rings: &[Vec<Point>], p: Point) -> Option<f64> {
    let inside = point_in_polygon(p, &rings[0]) && !rings[1..].iter().any(|h| point_in_polygon(p, h));
    if !inside {
        return None;
    }
    let mut nearest = f64::INFINITY;
    for ring in rings {
        for (i, &a) in ring.iter().enumerate() {
            let b = ring[(i + 1) % ring.len()];
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let length2 = dx * dx + dy * dy;
            let t =
                if length2 > 0.0 { (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2).clamp(0.0, 1.0) } else { 0.0 };
            nearest = nearest.min(libm::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy));
        }
    }
    Some(nearest)
}

/// A point well inside the piece that lies on a triangle of both sheets `on` (front, back).
fn joint_point(piece: &[Vec<Point>], mesh: &Mesh, on: [&Vec<u32>; 2], size: f64) -> Option<Point> {
    let (lo, hi) = bounding_box(piece[0].iter().copied())?;
    let x = mesh.positions();
    let centre = |t: u32| {
        let [a, b, c] = mesh.triangles()[t as usize].map(|v| x[v as usize]);
        [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0]
    };
    let in_box = |p: &Point| lo[0] <= p[0] && p[0] <= hi[0] && lo[1] <= p[1] && p[1] <= hi[1];
    let mut candidates: Vec<(f64, Point)> = Vec::new();
    for sheet in on {
        let inside: Vec<Point> = sheet.iter().map(|&t| centre(t)).filter(in_box).collect();
        let stride = inside.len().div_ceil(JOINT_CANDIDATES).max(1);
        candidates.extend(inside.into_iter().step_by(stride).filter_map(|p| Some((clearance(piece, p)?, p))));
    }
    candidates.sort_by(|a, b| b.0.total_cmp(&a.0));
    let best = candidates.first().map_or(0.0, |c| c.0);
    if let Some(c) = centroid(piece) {
        if let Some(d) = clearance(piece, c).filter(|&d| d >= 0.5 * best) {
            candidates.insert(0, (d, c));
        }
    }
    // Clear of the boundary by more than the overlay's rounding, and on both sheets; a few
    // tries at most.
    candidates
        .into_iter()
        .take(8)
        .filter(|&(d, _)| d > 1e-9 * size)
        .map(|(_, p)| p)
        .find(|&p| on.iter().all(|sheet| on_sheet(mesh, sheet, p)))
}

/// Whether `p` lies in one of the triangles `sheet` of `mesh` (to rounding).
fn on_sheet(mesh: &Mesh, sheet: &[u32], p: Point) -> bool {
    let x = mesh.positions();
    sheet.iter().any(|&t| {
        let [a, b, c] = mesh.triangles()[t as usize].map(|v| x[v as usize]);
        let signed = |u: Point, v: Point| (u[0] - p[0]) * (v[1] - p[1]) - (u[1] - p[1]) * (v[0] - p[0]);
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        let least = signed(b, c).min(signed(c, a)).min(signed(a, b));
        area > 0.0 && least >= -1e-12 * area
    })
}
