//! `ImportError`: why a file or image could not be read, and where.

use std::fmt;

use crate::error_code::ErrorCode;
use crate::mesh::MeshError;
use crate::message::Number;
use crate::triangulate::TriangulationError;

/// An element of an SVG document, for error messages: its name, its `id` if it has one, and
/// where its start tag begins (1-based line and column).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ElementRef {
    /// The element's local name, e.g. `path`.
    pub name: String,
    /// Its `id` attribute, if any.
    pub id: Option<String>,
    /// Line of the start tag, from 1.
    pub line: u32,
    /// Column of the start tag, from 1.
    pub column: u32,
}

impl fmt::Display for ElementRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.id {
            Some(id) => write!(f, "<{} id=\"{id}\"> (line {}, column {})", self.name, self.line, self.column),
            None => write!(f, "<{}> (line {}, column {})", self.name, self.line, self.column),
        }
    }
}

/// Why an SVG document, an image or a mesh file could not be imported.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ImportError {
    /// The input exceeds a size limit (see [`crate::import::Limits`]).
    TooLarge {
        /// What is too large, e.g. "the SVG text" or "the image".
        what: &'static str,
        /// Its size.
        size: usize,
        /// The limit.
        limit: usize,
        /// The unit of both, e.g. "bytes", "pixels", "points".
        unit: &'static str,
    },
    /// The XML is not well formed (or uses a feature the parser refuses).
    Xml {
        /// The parser's description.
        message: String,
        /// Line, from 1.
        line: u32,
        /// Column, from 1.
        column: u32,
    },
    /// usvg could not make a drawing of the document (no valid size, too many elements
    /// once `<use>` is expanded).
    Svg {
        /// What usvg said.
        message: String,
    },
    /// The document's root element is not `svg`.
    NotSvg {
        /// The root element's name.
        root: String,
    },
    /// SVG elements nest deeper than the limit.
    TooDeep {
        /// The first element past the limit.
        element: ElementRef,
        /// The nesting limit.
        limit: usize,
    },
    /// An SVG element reaches coordinates too large for the geometry (see
    /// [`crate::import::Limits::max_coordinate`]).
    CoordinateTooLarge {
        /// The element.
        element: ElementRef,
        /// The attribute that holds the number, when the number itself is beyond the limit
        /// (found before the drawing is placed); `None` when the element's points reach
        /// beyond it once placed.
        attribute: Option<String>,
        /// The first coordinate beyond the limit, in the drawing's units, or the number in
        /// the attribute (infinite or NaN when it overflowed).
        value: f64,
        /// The limit on the magnitude of coordinates.
        limit: f64,
    },
    /// An SVG's elements have too many attributes for the XML parser's duplicate check
    /// (see [`crate::import::Limits::max_attribute_pairs`]); refused before parsing.
    TooManyAttributes {
        /// Line of the start tag that goes beyond the limit, from 1.
        line: u32,
        /// Its column, from 1.
        column: u32,
        /// Its number of attributes.
        attributes: usize,
        /// The limit on pairs of attributes compared.
        limit: usize,
    },
    /// The SVG has no filled shape that could become an outline.
    NoShapes {
        /// Elements that were skipped because they are not supported (e.g. `text`, `use`).
        skipped: Vec<String>,
    },
    /// Checking the outline for crossings would take more comparisons of segments than
    /// [`crate::import::Limits::max_segment_pairs`] allows (only far more points than the
    /// point limit, or a small budget, come near it).
    TooComplex {
        /// The number of comparisons after which the check gave up.
        pairs: usize,
    },
    /// The pixel buffer does not match the image size.
    ImageSize {
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
        /// The buffer's length in bytes (4 per pixel are needed).
        len: usize,
    },
    /// No pixel of the image counts as part of the shape.
    EmptyImage,
    /// A syntax error in a mesh file.
    Syntax {
        /// The file format, "OBJ" or "JSON".
        format: &'static str,
        /// What is wrong.
        message: String,
        /// Line, from 1.
        line: usize,
        /// Column, from 1.
        column: usize,
    },
    /// Texture coordinates that do not fit the mesh.
    TextureCoordinates {
        /// What is wrong.
        message: String,
    },
    /// A mesh file's per-triangle stiffness is the wrong length or out of range.
    Stiffness {
        /// What is wrong.
        message: String,
    },
    /// The mesh in the file is invalid (the same rules and errors as [`crate::Mesh::new`]).
    Mesh(MeshError),
    /// More points than the limit ([`crate::import::Limits::max_points`]).
    TooManyPoints {
        /// What has them, e.g. "the SVG's shapes".
        what: &'static str,
        /// How many would be needed, when known (an estimate for flattened curves).
        needed: Option<f64>,
        /// The limit.
        limit: usize,
    },
    /// Tracing an image gives contours of more points, before simplification, than 20 times
    /// the limit on outline points.
    TooManyContourPoints {
        /// The limit on outline points ([`crate::import::Limits::max_points`]).
        limit: usize,
    },
    /// The number of values does not match, counted in numbers.
    Length {
        /// What was given, e.g. "deformed positions".
        what: &'static str,
        /// How many numbers are expected.
        expected: usize,
        /// How many numbers were given.
        found: usize,
        /// Numbers per item (2 for points).
        per: usize,
        /// The items, plural, e.g. "rest vertices".
        items: &'static str,
    },
    /// A value given is NaN or infinite.
    NonFinite {
        /// What it is, e.g. "point".
        what: &'static str,
        /// Its index.
        index: usize,
    },
    /// A value computed from finite input overflows double precision (or is NaN).
    NonFiniteResult {
        /// What it is, e.g. "mapped point".
        what: &'static str,
        /// Its index.
        index: usize,
    },
    /// An imported shape could not be meshed (a puppet's part).
    Triangulation(TriangulationError),
    /// An option is out of range.
    InvalidOption {
        /// The option's name as the JavaScript API spells it.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What would be accepted.
        expected: &'static str,
    },
}

impl fmt::Display for ImportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooLarge { what, size, limit, unit } => {
                write!(f, "{what} has {size} {unit}, more than the limit of {limit} {unit}")
            }
            Self::Xml { message, line, column } => {
                write!(f, "the SVG is not well-formed XML at line {line}, column {column}: {message}")
            }
            Self::NotSvg { root } => write!(f, "the document's root element is <{root}>, not <svg>"),
            Self::Svg { message } => write!(f, "the SVG cannot be drawn: {message}"),
            Self::TooDeep { element, limit } => write!(f, "{element} nests deeper than {limit} elements"),
            Self::CoordinateTooLarge { element, attribute, value, limit } => {
                write!(f, "{element} is too large: ")?;
                match (attribute, value.is_finite()) {
                    (Some(attribute), true) => write!(f, "its {attribute} holds {:e},", value.abs())?,
                    (Some(attribute), false) => write!(f, "its {attribute} holds a number out of range,")?,
                    (None, true) => write!(
                        f,
                        "it reaches {:e} in the drawing's units (after its transforms and viewBoxes),",
                        value.abs()
                    )?,
                    (None, false) => write!(f, "its coordinates overflow in the drawing's units,")?,
                }
                write!(
                    f,
                    " beyond ±{limit:e}, the limit for the geometry to work in double precision; scale the drawing \
                     down"
                )
            }
            Self::TooManyAttributes { line, column, attributes, limit } => write!(
                f,
                "too many attributes: the element at line {line}, column {column} has {attributes}, which takes \
                 the pairs of attributes the XML parser compares for duplicates (n(n-1)/2 per element of n) \
                 beyond the limit of {limit}; an SVG element needs a few dozen attributes at most"
            ),
            Self::NoShapes { skipped } if skipped.is_empty() => write!(f, "the SVG has no filled shape"),
            Self::NoShapes { skipped } => {
                write!(f, "the SVG has no filled shape (unsupported elements skipped: {})", skipped.join(", "))
            }
            Self::TooComplex { pairs } => write!(
                f,
                "checking the outline for crossings needs more than {pairs} comparisons of segments; \
                 simplify the shape"
            ),
            Self::ImageSize { width, height, len } if *width == 0 || *height == 0 => {
                write!(f, "the image is {width} x {height} pixels: it has no pixels ({len} bytes were given)")
            }
            Self::ImageSize { width, height, len } => write!(
                f,
                "a {width} x {height} image needs {} bytes of RGBA pixels (4 per pixel), but {len} were given",
                // In u128: 4 w h cannot overflow it, as it can a 32-bit usize.
                4 * *width as u128 * *height as u128
            ),
            Self::EmptyImage => write!(f, "no pixel of the image belongs to the shape (check the threshold)"),
            Self::Syntax { format, message, line, column } => {
                write!(f, "{format} error at line {line}, column {column}: {message}")
            }
            Self::TextureCoordinates { message } => write!(f, "texture coordinates: {message}"),
            Self::Stiffness { message } => write!(f, "stiffness: {message}"),
            Self::Mesh(e) => e.fmt(f),
            Self::Triangulation(e) => e.fmt(f),
            Self::TooManyPoints { what, needed: Some(needed), limit } => write!(
                f,
                "{what} would need {} points, more than the limit of {limit} (maxPoints)",
                Number(needed.ceil())
            ),
            Self::TooManyPoints { what, needed: None, limit } => {
                write!(f, "{what} have more than {limit} points (the maxPoints limit)")
            }
            Self::TooManyContourPoints { limit } => write!(
                f,
                "the image traces to contours of more than {} points before simplification, 20 times the \
                 limit of {limit} outline points (maxPoints); raise maxPoints, or trace a smaller or simpler image",
                limit.saturating_mul(20)
            ),
            Self::Length { what, expected, found, per, items } => write!(
                f,
                "{what} have {found} numbers, expected {expected} ({per} for each of the {} {items})",
                expected / per.max(&1)
            ),
            Self::NonFinite { what, index } => write!(f, "{what} {index} has a value that is not a finite number"),
            Self::NonFiniteResult { what, index } => {
                write!(f, "{what} {index} comes out beyond the range of double precision (not a finite number)")
            }
            Self::InvalidOption { name, value, expected } => {
                write!(f, "option {name} is {}, expected {expected}", Number(*value))
            }
        }
    }
}

impl std::error::Error for ImportError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Mesh(e) => Some(e),
            Self::Triangulation(e) => Some(e),
            _ => None,
        }
    }
}

impl ImportError {
    /// The kind of error: the mesh's own for an invalid mesh in a file, otherwise by what
    /// went wrong ([`ErrorCode::Import`] for what is wrong with the file itself).
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::Mesh(e) => e.code(),
            Self::Triangulation(e) => e.code(),
            Self::TooLarge { .. }
            | Self::TooDeep { .. }
            | Self::CoordinateTooLarge { .. }
            | Self::TooManyAttributes { .. }
            | Self::TooComplex { .. }
            | Self::TooManyPoints { .. }
            | Self::TooManyContourPoints { .. } => ErrorCode::Limit,
            Self::Xml { .. }
            | Self::Svg { .. }
            | Self::NotSvg { .. }
            | Self::NoShapes { .. }
            | Self::EmptyImage
            | Self::Syntax { .. }
            | Self::TextureCoordinates { .. }
            | Self::Stiffness { .. } => ErrorCode::Import,
            Self::ImageSize { .. } | Self::Length { .. } | Self::NonFinite { .. } => ErrorCode::InvalidArgument,
            Self::NonFiniteResult { .. } => ErrorCode::Overflow,
            Self::InvalidOption { .. } => ErrorCode::InvalidOption,
        }
    }
}

impl From<TriangulationError> for ImportError {
    fn from(e: TriangulationError) -> Self {
        Self::Triangulation(e)
    }
}

impl From<MeshError> for ImportError {
    fn from(e: MeshError) -> Self {
        Self::Mesh(e)
    }
}
