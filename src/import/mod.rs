//! Shapes in: SVG documents and raster images become [`Outline`](crate::Outline)s, and mesh
//! files (our JSON, Wavefront OBJ) become validated [`Mesh`](crate::Mesh)es. Everything here
//! is plain Rust and knows nothing of the browser: the page decodes images into RGBA pixels
//! and hands over file contents as text.
//!
//! Input is untrusted: every parser has size limits ([`Limits`]), reports malformed input
//! as an [`ImportError`] that says what and where, and bounds its loops and nesting.
//!
//! | module | what |
//! |---|---|
//! | [`svg`] | SVG to outlines, through usvg (and the filled and stroked areas as paths, for exporting the art deformed); layer by layer |
//! | [`puppet`] | a layered SVG (or an image's separate regions) to a puppet: a sheet per part, one mesh, joints where parts overlap |
//! | [`raster`] | RGBA pixels to outlines: threshold, marching squares, simplification |
//! | [`mesh_file`] | JSON and OBJ meshes, read (validated) and written |
//! | [`warp`] | points through a deformed mesh (barycentric), texture coordinates |
//! | [`vector`] | vector paths: flattening, writing path data |

mod error;
pub mod mesh_file;
pub mod puppet;
pub mod raster;
mod regions;
pub(crate) mod simplify;
pub mod svg;
pub(crate) mod union;
pub mod vector;
pub mod warp;

pub use error::{ElementRef, ImportError};

/// Size limits for untrusted input, one set for the readers and the writers: a mesh file
/// the writers produce within these limits is one the readers accept. The defaults suit
/// interactive use in a browser, and docs/formats.md states them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest text input (SVG, OBJ, JSON), in bytes (default 32 MiB, 33,554,432 bytes).
    pub max_bytes: usize,
    /// Largest image, in pixels (default 4096 x 4096).
    pub max_pixels: usize,
    /// Most outline points an SVG or image may produce (after flattening or tracing;
    /// default 100,000).
    pub max_points: usize,
    /// Most vertices a mesh file may have, and texture coordinates; twice as many
    /// triangles (a planar mesh has fewer than 2 per vertex). Default
    /// [`crate::mesh::DEFAULT_MAX_VERTICES`], 100,000, the triangulator's default limit too.
    ///
    /// With the defaults every mesh within these counts fits in `max_bytes` as a file: the
    /// writers put at most 25 characters in a number (`-0.0000012345678901234567`, or
    /// `-1.2345678901234567e-300` in exponent form), so an OBJ vertex takes at most 56
    /// bytes (`v x y 0`) and its texture coordinate 55 (`vt u v`), a triangle 44 (`f a/a
    /// b/b c/c`, indices of up to 6 digits): at most 11.1 MB for 100,000 vertices and 8.8
    /// MB for 200,000 triangles, 19.9 MB in all (JSON needs less). The writers check
    /// anyway, against whatever limits they are given.
    pub max_vertices: usize,
    /// Most XML nodes (elements, attributes' text nodes and so on) of an SVG.
    pub max_elements: usize,
    /// Most comparisons the XML parser may make to find duplicate attributes in an SVG:
    /// it compares every pair of an element's attributes, n(n-1)/2 for n of them, summed
    /// over the elements (an element an entity defines counts once per node the document
    /// may hold). The default, 10 million (about 15 ms of the parser's time natively),
    /// allows one element of 4,000 attributes, or 100,000 elements of 14 each; real
    /// elements have a few dozen at most.
    pub max_attribute_pairs: usize,
    /// Most comparisons of segments when checking that outlines neither cross nor touch
    /// (a sweep making O(n log n) of them for n segments: about 20 per segment at the
    /// point limit; simplifying a traced image repeats it, on fewer points, until nothing
    /// crosses). The default, 50 million, is a backstop far above what the point limit
    /// needs.
    pub max_segment_pairs: usize,
    /// Largest magnitude of a coordinate of an SVG's shapes once placed in the drawing (in
    /// the root `viewBox`'s units, after every transform), which also bounds the drawing's
    /// extent. The default, 1e30, is far beyond any real drawing and keeps everything
    /// downstream working in double precision: products of coordinates (areas, orientation
    /// tests, squared distances, summed over every point) stay far from overflowing, and
    /// positions still fit in single precision (3.4e38) for drawing.
    pub max_coordinate: f64,
    /// Most bytes of RGBA an animation's frames may add up to, 4 per pixel per frame
    /// (default 1 GiB, 1,073,741,824 bytes: 1,024 frames of 512 x 512, 129 of 1920 x
    /// 1080). The encoders hold the frames compressed, so they need at most about this much
    /// memory, and far less for a rendered mesh on a plain background (see
    /// [`crate::animation::AnimationEncoder`]).
    pub max_animation_bytes: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_bytes: 32 << 20,
            max_pixels: 4096 * 4096,
            max_points: 100_000,
            max_vertices: crate::mesh::DEFAULT_MAX_VERTICES,
            max_elements: 200_000,
            max_attribute_pairs: 10_000_000,
            max_segment_pairs: 50_000_000,
            max_coordinate: 1e30,
            max_animation_bytes: 1 << 30,
        }
    }
}

impl Limits {
    fn check(value: usize, limit: usize, what: &'static str, unit: &'static str) -> Result<(), ImportError> {
        if value > limit {
            return Err(ImportError::TooLarge { what, size: value, limit, unit });
        }
        Ok(())
    }

    /// Refuses limits that no input could meet (a limit of 0, which is no more "unlimited"
    /// than any other number), or a coordinate limit that is not a finite number above 0,
    /// each by the name of its JavaScript option (`maxBytes`, `maxPixels`, `maxPoints`; the
    /// others are Rust's only).
    pub fn validate(&self) -> Result<(), ImportError> {
        let counts = [
            ("maxBytes", self.max_bytes),
            ("maxPixels", self.max_pixels),
            ("maxPoints", self.max_points),
            ("maxVertices", self.max_vertices),
            ("maxElements", self.max_elements),
            ("maxAttributePairs", self.max_attribute_pairs),
            ("maxSegmentPairs", self.max_segment_pairs),
            ("maxAnimationBytes", self.max_animation_bytes),
        ];
        for (name, value) in counts {
            if value == 0 {
                return Err(ImportError::InvalidOption { name, value: 0.0, expected: "a whole number, at least 1" });
            }
        }
        let c = self.max_coordinate;
        if !(c.is_finite() && c > 0.0) {
            return Err(ImportError::InvalidOption {
                name: "maxCoordinate",
                value: c,
                expected: "a finite number above 0",
            });
        }
        Ok(())
    }
}
