//! Outline to mesh: constrained Delaunay triangulation with Ruppert-style refinement.
//!
//! This is the only module that touches spade. The outline's segments become constraint
//! edges; refinement inserts Steiner points until every triangle inside the shape is below
//! the area limit and above the minimum angle (near sharp input corners no triangulation can
//! promise the angle, and refinement leaves those corners alone; spade does so at every
//! convex corner, so a triangle whose shortest edge joins the two sides of a corner can stay
//! below the angle even when the corner is wider than 60 degrees). Constraint edges may be
//! split, never moved, so the boundary of the mesh traces the outline exactly.
//!
//! Scale: spade's exact predicates take coordinates of magnitude 2^-142 to 2^201 (or 0), so
//! the outline is triangulated scaled by the power of two that puts its largest coordinate
//! between 2^100 and 2^101 (exact), and the mesh scaled back (the outline's own points are
//! copied, not computed). Any outline the outline checks accept (coordinates up to
//! [`crate::geometry::MAX_COORDINATE`], at least [`crate::geometry::MIN_EXTENT`] across)
//! then meshes the same at every scale: scaling it by a power of two scales the mesh by the
//! same power, triangle for triangle. A coordinate below 2^-242 (1.4e-73) times the largest
//! one is taken as 0 inside spade, a move far below the rounding of the largest one.

use std::fmt;

use spade::{
    mitigate_underflow, AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation,
};

use crate::error_code::ErrorCode;
use crate::geometry::{normalising_exponent, scale_by_power_of_two, Point};
use crate::mesh::{Mesh, MeshError, DEFAULT_MAX_VERTICES, MAX_MESH_ELEMENTS};
use crate::message::Number;
use crate::outline::{Outline, OutlineError, Ring};

/// The largest minimum angle accepted, in degrees. Delaunay refinement is only guaranteed
/// to terminate below about 20.7 degrees and works well in practice up to about 33.
pub const MAX_MIN_ANGLE_DEGREES: f64 = 34.0;

/// Triangulation settings, with builders: `TriangulationOptions::default().with_target_edge_length(0.1)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangulationOptions {
    /// Upper bound on triangle area; `None` for no bound.
    pub max_area: Option<f64>,
    /// Desired edge length; becomes an area bound of an equilateral triangle with this
    /// edge (`sqrt(3)/4 h^2`). When both are set, the smaller area bound applies.
    pub target_edge_length: Option<f64>,
    /// Smallest angle in degrees that refinement enforces (0 disables angle refinement).
    pub min_angle_degrees: f64,
    /// Largest number of vertices of the result, outline points included (default
    /// [`DEFAULT_MAX_VERTICES`], 100,000).
    pub max_vertices: usize,
}

impl Default for TriangulationOptions {
    fn default() -> Self {
        Self { max_area: None, target_edge_length: None, min_angle_degrees: 25.0, max_vertices: DEFAULT_MAX_VERTICES }
    }
}

impl TriangulationOptions {
    /// Sets the area bound.
    pub fn with_max_area(mut self, area: f64) -> Self {
        self.max_area = Some(area);
        self
    }

    /// Sets the target edge length.
    pub fn with_target_edge_length(mut self, length: f64) -> Self {
        self.target_edge_length = Some(length);
        self
    }

    /// Sets the minimum angle in degrees.
    pub fn with_min_angle_degrees(mut self, degrees: f64) -> Self {
        self.min_angle_degrees = degrees;
        self
    }

    /// Sets the vertex limit.
    pub fn with_max_vertices(mut self, count: usize) -> Self {
        self.max_vertices = count;
        self
    }

    /// The area bound that refinement enforces, combining `max_area` and
    /// `target_edge_length`.
    pub fn effective_max_area(&self) -> Option<f64> {
        self.max_area_scaled(0)
    }

    /// [`Self::effective_max_area`] for the outline scaled by `2^k` (lengths times `2^k`,
    /// areas times `4^k`), computed without overflow or underflow on the way; `None` for no
    /// bound, or a bound too large to be a double.
    fn max_area_scaled(&self, k: i32) -> Option<f64> {
        let from_edge = self.target_edge_length.map(|h| {
            let h = scale_by_power_of_two(h, k);
            3f64.sqrt() / 4.0 * h * h
        });
        let from_area = self.max_area.map(|a| scale_by_power_of_two(a, 2 * k));
        let bound = match (from_area, from_edge) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        bound.filter(|a| a.is_finite())
    }

    fn validate(&self) -> Result<(), TriangulationError> {
        let positive = |name, value: Option<f64>| match value {
            Some(v) if !(v.is_finite() && v > 0.0) => {
                Err(TriangulationError::InvalidOption { name, value: v, expected: "a finite number above 0" })
            }
            _ => Ok(()),
        };
        positive("maxArea", self.max_area)?;
        positive("targetEdgeLength", self.target_edge_length)?;
        let angle = self.min_angle_degrees;
        if !(0.0..=MAX_MIN_ANGLE_DEGREES).contains(&angle) {
            return Err(TriangulationError::InvalidOption {
                name: "minAngle",
                value: angle,
                expected: "an angle in degrees from 0 to 34",
            });
        }
        if self.max_vertices < 3 || self.max_vertices > MAX_MESH_ELEMENTS {
            return Err(TriangulationError::InvalidOption {
                name: "maxVertices",
                value: self.max_vertices as f64,
                expected: "a count from 3 to 16777216",
            });
        }
        Ok(())
    }
}

/// Why triangulation failed.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum TriangulationError {
    /// The outline is invalid.
    Outline(OutlineError),
    /// An option is out of range.
    InvalidOption {
        /// The option's name as the JavaScript API spells it.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What would be accepted.
        expected: &'static str,
    },
    /// Exact arithmetic found a segment crossing another one that the outline check, in
    /// floating point, let through (nearly touching segments).
    ConstraintConflict {
        /// The ring of the segment.
        ring: Ring,
        /// The segment's index in the ring (after repeated points are dropped).
        segment: usize,
    },
    /// Meeting the area and angle bounds needs more vertices than the limit: the mesh
    /// keeps every outline point and refinement adds more.
    TooManyVertices {
        /// The vertex limit.
        limit: usize,
        /// The outline's points (after repeated points are dropped), all of them vertices.
        outline_points: usize,
    },
    /// The triangulation produced an invalid mesh (a bug: please report it).
    Mesh(MeshError),
    /// spade refused a point of the validated, scaled outline (a bug: please report it).
    Internal {
        /// spade's error.
        message: String,
    },
}

impl fmt::Display for TriangulationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Outline(e) => e.fmt(f),
            Self::InvalidOption { name, value, expected } => {
                write!(f, "option {name} is {}, expected {expected}", Number(*value))
            }
            Self::ConstraintConflict { ring, segment } => {
                write!(f, "segment {segment} of {ring} touches or crosses another segment of the outline")
            }
            // An outline that takes half the limit or more is the reason, whatever the options.
            Self::TooManyVertices { limit, outline_points } if 2 * outline_points >= *limit => write!(
                f,
                "the outline has {outline_points} points, too many to mesh within the vertex limit of {limit}: \
                 the mesh keeps every outline point and refinement adds more inside and along it (a smooth \
                 curve needs 2 to 3 vertices per outline point at the default minimum angle); raise \
                 maxVertices or simplify the outline"
            ),
            Self::TooManyVertices { limit, outline_points } => write!(
                f,
                "the requested triangle size and angle need more than {limit} vertices (the outline has \
                 {outline_points} points); raise maxVertices, or ask for larger triangles or a smaller minimum angle"
            ),
            Self::Mesh(e) => write!(f, "triangulation produced an invalid mesh (a bug, please report it): {e}"),
            Self::Internal { message } => {
                write!(f, "triangulation failed unexpectedly (a bug, please report it): {message}")
            }
        }
    }
}

impl std::error::Error for TriangulationError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Outline(e) => Some(e),
            Self::Mesh(e) => Some(e),
            _ => None,
        }
    }
}

impl TriangulationError {
    /// The kind of error.
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::Outline(e) => e.code(),
            Self::InvalidOption { .. } => ErrorCode::InvalidOption,
            Self::ConstraintConflict { .. } => ErrorCode::InvalidOutline,
            Self::TooManyVertices { .. } => ErrorCode::Limit,
            Self::Mesh(_) | Self::Internal { .. } => ErrorCode::Internal,
        }
    }
}

impl From<OutlineError> for TriangulationError {
    fn from(e: OutlineError) -> Self {
        Self::Outline(e)
    }
}

/// Triangulates an outline (with its holes) into a validated mesh.
///
/// ```
/// use akap::{triangulate, Outline, TriangulationOptions};
/// let square = Outline::new(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
/// let mesh = triangulate(&square, &TriangulationOptions::default().with_target_edge_length(0.2)).unwrap();
/// assert!((mesh.area() - 1.0).abs() < 1e-12);
/// ```
pub fn triangulate(outline: &Outline, options: &TriangulationOptions) -> Result<Mesh, TriangulationError> {
    options.validate()?;
    let rings = outline.validated(options.max_vertices)?;
    // Into spade's range, exactly: the largest coordinate between 2^100 and 2^101.
    let k = normalising_exponent(rings.iter().flatten().copied()) + 100;
    let into =
        |p: Point| mitigate_underflow(Point2::new(scale_by_power_of_two(p[0], k), scale_by_power_of_two(p[1], k)));

    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
    // The outline's own points, by spade's vertex index: copied into the mesh as given.
    let mut given: Vec<Point> = Vec::new();
    for (r, ring) in rings.iter().enumerate() {
        let mut handles = Vec::with_capacity(ring.len());
        for &p in ring {
            let handle = cdt.insert(into(p)).map_err(|e| TriangulationError::Internal { message: e.to_string() })?;
            if handle.index() == given.len() {
                given.push(p);
            }
            handles.push(handle);
        }
        for i in 0..handles.len() {
            let (a, b) = (handles[i], handles[(i + 1) % handles.len()]);
            // Outline validation rules out crossings; spade's exact predicates are the last word.
            if a == b || !cdt.can_add_constraint(a, b) {
                return Err(TriangulationError::ConstraintConflict { ring: Ring(r), segment: i });
            }
            cdt.add_constraint(a, b);
        }
    }

    let mut params = RefinementParameters::<f64>::new()
        .exclude_outer_faces(true)
        .with_angle_limit(AngleLimit::from_deg(options.min_angle_degrees))
        .with_max_additional_vertices(options.max_vertices.saturating_sub(cdt.num_vertices()));
    if let Some(area) = options.max_area_scaled(k) {
        params = params.with_max_allowed_area(area);
    }
    let result = cdt.refine(params);
    if !result.refinement_complete {
        let outline_points = rings.iter().map(Vec::len).sum();
        return Err(TriangulationError::TooManyVertices { limit: options.max_vertices, outline_points });
    }

    let mut outside = vec![false; cdt.num_all_faces()];
    for face in &result.excluded_faces {
        outside[face.index()] = true;
    }
    // Keep the vertices of inside faces only, numbered in order of first use; the outline's
    // points as given, the others scaled back.
    let mut new_index = vec![u32::MAX; cdt.num_vertices()];
    let mut positions = Vec::with_capacity(cdt.num_vertices());
    let mut triangles = Vec::with_capacity(cdt.num_inner_faces());
    for face in cdt.inner_faces().filter(|f| !outside[f.fix().index()]) {
        let corners = face.vertices().map(|v| {
            let slot = &mut new_index[v.fix().index()];
            if *slot == u32::MAX {
                *slot = positions.len() as u32;
                let p = v.position();
                let back = [scale_by_power_of_two(p.x, -k), scale_by_power_of_two(p.y, -k)];
                positions.push(given.get(v.fix().index()).copied().unwrap_or(back));
            }
            *slot
        });
        triangles.push(corners);
    }
    Mesh::new(positions, triangles).map_err(TriangulationError::Mesh)
}

/// How close [`triangulate_to_about`] brings the vertex count to the one asked for.
pub const ABOUT_TOLERANCE: f64 = 0.03;

/// Triangulates `outline` to about `vertices` vertices, the one rule the widget, the
/// examples and the benchmarks share. An equilateral mesh of edge `h` has about
/// `2 / (sqrt(3) h^2)` vertices per unit area, which gives a first edge length from the
/// outline's area; then, while the count is more than [`ABOUT_TOLERANCE`] off, at most
/// three corrections scale the edge by `sqrt(count / vertices)`. The other `options` apply
/// (`min_angle_degrees`, a `max_area` bound), and at most `4 vertices + 1000` vertices (or
/// `options.max_vertices` if lower) are made. Returns the mesh and the target edge length
/// that made it: `triangulate` with it gives the same mesh again. An outline with more
/// points than `vertices`, or corners too sharp to mesh coarsely, ends further off.
///
/// ```
/// use akap::{shapes, triangulate::triangulate_to_about, TriangulationOptions};
/// let (mesh, edge) = triangulate_to_about(&shapes::gingerbread(), 2000, &TriangulationOptions::default())?;
/// assert!(mesh.vertex_count().abs_diff(2000) <= 60);
/// let again = akap::triangulate(&shapes::gingerbread(), &TriangulationOptions::default().with_target_edge_length(edge))?;
/// assert_eq!(again, mesh);
/// # Ok::<(), akap::TriangulationError>(())
/// ```
pub fn triangulate_to_about(
    outline: &Outline,
    vertices: usize,
    options: &TriangulationOptions,
) -> Result<(Mesh, f64), TriangulationError> {
    if vertices < 3 || vertices > options.max_vertices {
        return Err(TriangulationError::InvalidOption {
            name: "vertices",
            value: vertices as f64,
            expected: "a count from 3 to the vertex limit",
        });
    }
    let limit = options.max_vertices.min(vertices.saturating_mul(4).saturating_add(1000));
    let target = vertices as f64;
    let mesh_with = |edge: f64| triangulate(outline, &options.with_target_edge_length(edge).with_max_vertices(limit));
    // The area of the outline scaled by 2^k (exact), so that no scale overflows or underflows.
    let k = normalising_exponent(outline.rings().flatten().copied());
    let scale = |ring: &Vec<Point>| ring.iter().map(|p| p.map(|x| scale_by_power_of_two(x, k))).collect();
    let scaled = Outline { outer: scale(&outline.outer), holes: outline.holes.iter().map(scale).collect() };
    let area = scaled.area();
    let mut edge = scale_by_power_of_two((2.0 * area / (3f64.sqrt() * target)).sqrt(), -k);
    let mut mesh = mesh_with(edge)?;
    for _ in 0..3 {
        let ratio = mesh.vertex_count() as f64 / target;
        if (ratio - 1.0).abs() <= ABOUT_TOLERANCE {
            break;
        }
        edge *= ratio.sqrt();
        mesh = mesh_with(edge)?;
    }
    Ok((mesh, edge))
}
