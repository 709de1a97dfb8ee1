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
//! | [`svg`] | SVG to outlines (and the filled paths, for exporting the art deformed) |
//! | [`raster`] | RGBA pixels to outlines: threshold, marching squares, simplification |
//! | [`mesh_file`] | JSON and OBJ meshes, read (validated) and written |
//! | [`warp`] | points through a deformed mesh (barycentric), texture coordinates |
//! | [`vector`] | vector paths: flattening, writing path data |

mod error;
mod merge;
pub mod mesh_file;
pub mod raster;
mod regions;
mod simplify;
pub mod svg;
pub mod vector;
pub mod warp;

pub use error::{ElementRef, ImportError};

/// Size limits for untrusted input. The defaults suit interactive use in a browser.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest text input (SVG, OBJ, JSON), in bytes.
    pub max_bytes: usize,
    /// Largest image, in pixels.
    pub max_pixels: usize,
    /// Most outline points an SVG or image may produce (after flattening or tracing).
    pub max_points: usize,
    /// Most vertices (and triangles) a mesh file may have.
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
    /// tests, squared distances, summed over every point) stay far from overflowing, the
    /// triangulator's exact predicates accept up to 2^201 (about 3.2e60), and positions
    /// still fit in single precision (3.4e38) for drawing.
    pub max_coordinate: f64,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_bytes: 32 << 20,
            max_pixels: 4096 * 4096,
            max_points: 100_000,
            max_vertices: 1_000_000,
            max_elements: 200_000,
            max_attribute_pairs: 10_000_000,
            max_segment_pairs: 50_000_000,
            max_coordinate: 1e30,
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
}
