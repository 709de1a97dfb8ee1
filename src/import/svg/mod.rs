//! SVG documents to outlines: the document is read as data (roxmltree), never rendered or
//! run. Filled `path`, `rect` (with rounded corners), `circle`, `ellipse`, `polygon` and
//! `polyline` elements count, through `g`, `a`, `switch` and nested `svg` elements, with
//! their `transform`s and `viewBox`es; `fill`, `fill-rule`, `fill-opacity`, `color`,
//! `opacity` and `display` are read from attributes and `style` (see `style`), and each
//! filled element keeps its fill colour. Curves are flattened to a tolerance and the rings
//! become outlines with holes by nesting (see `regions`), exactly; when boundaries cross or
//! touch (overlapping shapes), the union is traced on a fine grid instead (see `merge`).
//! Elements reaching coordinates beyond [`Limits::max_coordinate`] are refused.
//!
//! Output coordinates are the root's user units (its `viewBox`) with y flipped to point
//! up: the bottom-left corner of the `viewBox` is the origin.

mod path_data;
mod style;
mod text;
mod transform;
pub mod tree;

use std::cell::RefCell;

use roxmltree::{Document, Node, ParsingOptions};

pub use path_data::{parse_path_data, SyntaxError};
pub use style::FillColour;
pub use transform::{parse_transform, Affine};

use crate::geometry::{bounding_box, Point};
use crate::import::error::{ElementRef, ImportError};
use crate::import::merge::merge;
use crate::import::regions::{assemble, RegionError, SourceRing};
use crate::import::vector::{FillRule, VectorPath, Verb};
use crate::import::Limits;
use crate::outline::Outline;
use style::Style;
use text::{check_attributes, Cursor};

const SVG_NAMESPACE: &str = "http://www.w3.org/2000/svg";

/// Elements deeper than this are refused (they would only come from hostile files).
pub const MAX_DEPTH: usize = 256;

/// Default flattening tolerance, as a fraction of the drawing's size (the diagonal of the
/// box around every point and control point).
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-3;

/// Options of [`import_svg`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SvgOptions {
    /// Largest distance between a curve and its flattened chords, in output units; `None`
    /// for [`DEFAULT_RELATIVE_TOLERANCE`] of the drawing's size.
    pub tolerance: Option<f64>,
    /// Parts and holes with a smaller area are dropped (holes are filled).
    pub min_area: f64,
    /// Size limits.
    pub limits: Limits,
}

impl Default for SvgOptions {
    fn default() -> Self {
        Self { tolerance: None, min_area: 0.0, limits: Limits::default() }
    }
}

impl SvgOptions {
    /// Sets the flattening tolerance.
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = Some(tolerance);
        self
    }

    fn validate(&self) -> Result<(), ImportError> {
        if let Some(t) = self.tolerance {
            if !(t.is_finite() && t > 0.0) {
                return Err(ImportError::InvalidOption {
                    name: "tolerance",
                    value: t,
                    expected: "a finite number above 0",
                });
            }
        }
        if !(self.min_area.is_finite() && self.min_area >= 0.0) {
            return Err(ImportError::InvalidOption {
                name: "minArea",
                value: self.min_area,
                expected: "a finite number, 0 or more",
            });
        }
        self.limits.validate()
    }
}

/// One filled element's geometry, in output coordinates, for exporting the art deformed.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgPath {
    /// The element it comes from.
    pub element: ElementRef,
    /// Its path (arcs converted to cubics).
    pub path: VectorPath,
    /// Its fill rule.
    pub fill_rule: FillRule,
    /// Its fill colour, with `fill-opacity` and every `opacity` on the way from the root
    /// folded into the alpha; `None` when the fill is a paint server (`url(#gradient)`) or
    /// a value the importer does not understand (still filled: the shape counts).
    pub fill: Option<FillColour>,
}

/// What an SVG document gave.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgShape {
    /// The filled region's separate parts, largest first.
    pub outlines: Vec<Outline>,
    /// Every filled element's path, in document order.
    pub paths: Vec<SvgPath>,
    /// Unsupported elements that were skipped (`text`, `use`, `image`, ...), once each.
    pub skipped: Vec<String>,
}

/// Reads an SVG document and builds the outlines of its filled shapes.
///
/// ```
/// use akap::import::svg::{import_svg, SvgOptions};
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">
///   <path fill-rule="evenodd" d="M1 1H9V9H1Z M3 3H5V5H3Z"/></svg>"#;
/// let shape = import_svg(svg, &SvgOptions::default())?;
/// assert_eq!(shape.outlines.len(), 1);
/// assert_eq!(shape.outlines[0].area(), 60.0);
/// # Ok::<(), akap::import::ImportError>(())
/// ```
pub fn import_svg(text: &str, options: &SvgOptions) -> Result<SvgShape, ImportError> {
    options.validate()?;
    let limits = &options.limits;
    let document = parse_document(text, limits)?;
    let root = document.root_element();
    if root.tag_name().name() != "svg" || !in_svg_namespace(root) {
        return Err(ImportError::NotSvg { root: root.tag_name().name().to_string() });
    }

    let mut walk =
        Walk { cursor: RefCell::new(Cursor::new(text)), limits, paths: Vec::new(), skipped: Vec::new(), points: 0 };
    walk.run(root)?;
    let Walk { paths, skipped, .. } = walk;
    shape_of(paths, skipped, options)
}

/// Issue 21's spike: the same, with the drawing resolved by usvg (fills and strokes; see
/// [`tree`]). Not the importer yet: for comparing the two. The document is read with every
/// limit first (as [`import_svg`] reads it) and handed to usvg as it is.
pub fn import_svg_usvg(text: &str, options: &SvgOptions) -> Result<SvgShape, ImportError> {
    options.validate()?;
    let limits = &options.limits;
    let document = parse_document(text, limits)?;
    let root = document.root_element();
    if root.tag_name().name() != "svg" || !in_svg_namespace(root) {
        return Err(ImportError::NotSvg { root: root.tag_name().name().to_string() });
    }
    check_depth(root, text)?;
    // usvg maps the root's user units into its size through the viewBox; with the size set
    // to the viewBox's own (or 1 x 1 with a unit viewBox when there is none), that map is
    // the shift by the viewBox's corner, and nothing of usvg's sizing rules is needed.
    let (view_box, output) = match root.attribute("viewBox").and_then(|v| v.parse::<svgtypes::ViewBox>().ok()) {
        Some(v) if v.w > 0.0 && v.h > 0.0 && v.w.is_finite() && v.h.is_finite() => {
            ([v.x, v.y, v.w, v.h], [1.0, 0.0, 0.0, -1.0, 0.0, v.h])
        }
        _ => {
            let height = root.attribute("height").and_then(|h| parse_length(h).ok()).unwrap_or(0.0);
            ([0.0, 0.0, 1.0, 1.0], [1.0, 0.0, 0.0, -1.0, 0.0, height])
        }
    };
    let mut plain = text.to_string();
    for a in root.attributes().filter(|a| matches!(a.name(), "width" | "height" | "viewBox" | "preserveAspectRatio")) {
        let range = a.range();
        plain.replace_range(range.clone(), &" ".repeat(range.len()));
    }
    let [vx, vy, vw, vh] = view_box;
    // Right after the root's (possibly prefixed) tag name.
    let tag = root.range().start + 1;
    let name_end = tag + text[tag..].find(|c: char| c.is_whitespace() || c == '>' || c == '/').unwrap_or(0);
    plain.insert_str(name_end, &format!(r#" width="{vw}" height="{vh}" viewBox="{vx} {vy} {vw} {vh}""#));
    let sized = parse_document(&plain, limits)?;
    let tree = usvg::Tree::from_xmltree(&sized, &usvg::Options::default())
        .map_err(|e| ImportError::Svg { message: e.to_string() })?;
    // Drawn by browsers, not imported: said once each.
    let mut skipped: Vec<String> = Vec::new();
    for node in document.descendants().filter(|n| n.is_element() && in_svg_namespace(*n)) {
        let name = node.tag_name().name();
        if matches!(name, "text" | "image" | "foreignObject") && !skipped.iter().any(|s| s == name) {
            skipped.push(name.to_string());
        }
    }
    let paths = tree::visible_paths(&tree, output, limits)?;
    shape_of(paths.into_iter().map(|(p, _)| p).collect(), skipped, options)
}

/// The outlines of `paths` (flattened, nested or merged), and the paths themselves.
fn shape_of(paths: Vec<SvgPath>, skipped: Vec<String>, options: &SvgOptions) -> Result<SvgShape, ImportError> {
    let limits = &options.limits;
    let every_point = paths.iter().flat_map(|p| p.path.points.iter().copied());
    let Some((lo, hi)) = bounding_box(every_point) else {
        return Err(ImportError::NoShapes { skipped });
    };
    let size = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let tolerance = options.tolerance.unwrap_or(DEFAULT_RELATIVE_TOLERANCE * size);
    let mut rings = Vec::new();
    let mut count = 0;
    for (shape, p) in paths.iter().enumerate() {
        let flat = p.path.flatten(tolerance.max(f64::MIN_POSITIVE), count, limits.max_points).map_err(|needed| {
            ImportError::TooManyPoints {
                what: "the outline flattened to the tolerance",
                needed: needed.is_finite().then_some(needed),
                limit: limits.max_points,
            }
        })?;
        count += flat.iter().map(Vec::len).sum::<usize>();
        rings.extend(flat.into_iter().map(|points| SourceRing { points, shape }));
    }
    let rules: Vec<FillRule> = paths.iter().map(|p| p.fill_rule).collect();
    // Boundaries that cross or touch leave nesting undecided: merge those shapes on a grid.
    let outlines = match assemble(&rings, &rules, options.min_area, limits.max_segment_pairs) {
        Ok(outlines) => outlines,
        Err(RegionError::Crossing(..)) => merge(&rings, &rules, tolerance, options.min_area, limits)?,
        Err(RegionError::TooComplex) => return Err(ImportError::TooComplex { pairs: limits.max_segment_pairs }),
    };
    if outlines.is_empty() {
        return Err(ImportError::NoShapes { skipped });
    }
    Ok(SvgShape { outlines, paths, skipped })
}

/// The document read as data with every limit applied: its size in bytes, its start tags'
/// attribute pairs (before roxmltree's quadratic duplicate check), its node count.
fn parse_document<'i>(text: &'i str, limits: &Limits) -> Result<Document<'i>, ImportError> {
    if text.len() > limits.max_bytes {
        return Err(ImportError::TooLarge {
            what: "the SVG text",
            size: text.len(),
            limit: limits.max_bytes,
            unit: "bytes",
        });
    }
    check_attributes(text, limits.max_elements, limits.max_attribute_pairs).map_err(|e| {
        let (line, column) = Cursor::new(text).at(e.tag);
        ImportError::TooManyAttributes { line, column, attributes: e.attributes, limit: limits.max_attribute_pairs }
    })?;
    let parsing = ParsingOptions {
        allow_dtd: true,
        nodes_limit: u32::try_from(limits.max_elements).unwrap_or(u32::MAX),
        ..ParsingOptions::default()
    };
    let document = Document::parse_with_options(text, parsing).map_err(|e| {
        let pos = e.pos();
        let message = e.to_string();
        let suffix = format!(" at {}:{}", pos.row, pos.col);
        let message = message.strip_suffix(&suffix).unwrap_or(&message).to_string();
        ImportError::Xml { message, line: pos.row, column: pos.col }
    })?;
    Ok(document)
}

/// Refuses elements nested deeper than [`MAX_DEPTH`], found without recursion.
fn check_depth(root: Node, text: &str) -> Result<(), ImportError> {
    let mut stack = vec![(root, 0usize)];
    while let Some((node, depth)) = stack.pop() {
        if depth > MAX_DEPTH {
            let (line, column) = Cursor::new(text).at(node.range().start);
            let element = ElementRef {
                name: node.tag_name().name().to_string(),
                id: node.attribute("id").map(str::to_string),
                line,
                column,
            };
            return Err(ImportError::TooDeep { element, limit: MAX_DEPTH });
        }
        stack.extend(node.children().filter(Node::is_element).map(|c| (c, depth + 1)));
    }
    Ok(())
}

fn in_svg_namespace(node: Node) -> bool {
    matches!(node.tag_name().namespace(), None | Some(SVG_NAMESPACE))
}

struct Walk<'a, 'input> {
    /// Lines and columns of elements, met in document order.
    cursor: RefCell<Cursor<'input>>,
    limits: &'a Limits,
    paths: Vec<SvgPath>,
    skipped: Vec<String>,
    points: usize,
}

impl<'a, 'input> Walk<'a, 'input> {
    fn element_ref(&self, node: Node) -> ElementRef {
        let (line, column) = self.cursor.borrow_mut().at(node.range().start);
        ElementRef {
            name: node.tag_name().name().to_string(),
            id: node.attribute("id").map(str::to_string),
            line,
            column,
        }
    }

    fn attribute_error(&self, node: Node, attribute: &str, message: impl Into<String>) -> ImportError {
        ImportError::Attribute {
            element: self.element_ref(node),
            attribute: attribute.to_string(),
            message: message.into(),
        }
    }

    /// Walks the tree without recursion: (node, transform to output, style, depth).
    fn run(&mut self, root: Node<'a, 'input>) -> Result<(), ImportError> {
        let viewport = self.root_viewport(root)?;
        let mut stack = vec![(root, viewport, Style::initial(), 0usize)];
        while let Some((node, parent_transform, parent_style, depth)) = stack.pop() {
            if depth > MAX_DEPTH {
                return Err(ImportError::TooDeep { element: self.element_ref(node), limit: MAX_DEPTH });
            }
            let style =
                Style::of(node, &parent_style).map_err(|e| self.attribute_error(node, e.property, e.message))?;
            let Some(style) = style else { continue };
            let mut transform = parent_transform;
            if let Some(text) = node.attribute("transform") {
                let local = parse_transform(text).map_err(|e| self.syntax_error(node, "transform", e))?;
                transform = transform.then_apply_to(local);
            }
            let name = node.tag_name().name();
            match name {
                "svg" | "g" | "a" | "switch" => {
                    if name == "svg" && depth > 0 {
                        transform = transform.then_apply_to(self.nested_viewport(node)?);
                    }
                    let children: Vec<_> = node.children().filter(|c| c.is_element() && in_svg_namespace(*c)).collect();
                    // Reversed, so that the stack pops them in document order.
                    stack.extend(children.into_iter().rev().map(|c| (c, transform, style, depth + 1)));
                }
                "path" | "rect" | "circle" | "ellipse" | "polygon" | "polyline" => {
                    if !style.filled() {
                        continue;
                    }
                    if let Some(mut path) = self.shape(node)? {
                        path.map_points(|p| transform.apply(p));
                        self.check_coordinates(node, &path)?;
                        self.paths.push(SvgPath {
                            element: self.element_ref(node),
                            path,
                            fill_rule: style.fill_rule,
                            fill: style.fill_colour(),
                        });
                    }
                }
                "text" | "use" | "image" | "foreignObject" | "textPath" | "tspan"
                    if !self.skipped.iter().any(|s| s == name) =>
                {
                    self.skipped.push(name.to_string());
                }
                // Definitions, metadata, lines and anything unknown draw no filled area.
                _ => {}
            }
        }
        Ok(())
    }

    /// Refuses an element whose points, placed in the drawing, lie beyond
    /// [`Limits::max_coordinate`] (or overflowed on the way there).
    fn check_coordinates(&self, node: Node, path: &VectorPath) -> Result<(), ImportError> {
        let limit = self.limits.max_coordinate;
        match path.points.iter().flatten().find(|v| v.is_nan() || v.abs() > limit) {
            Some(&value) => Err(ImportError::CoordinateTooLarge { element: self.element_ref(node), value, limit }),
            None => Ok(()),
        }
    }

    fn syntax_error(&self, node: Node, attribute: &str, e: SyntaxError) -> ImportError {
        if e.too_many {
            // Parsed with what is left of the document's budget: the caller's limit is the
            // news, not the remainder (which may be 0).
            return ImportError::TooManyPoints {
                what: "the SVG's shapes",
                needed: None,
                limit: self.limits.max_points,
            };
        }
        self.attribute_error(node, attribute, format!("{} (at character {})", e.message, e.offset))
    }

    /// The map from the root's user units to output coordinates (y up).
    fn root_viewport(&self, root: Node) -> Result<Affine, ImportError> {
        if let Some([x, y, _, h]) = self.view_box(root)? {
            return Ok(Affine([1.0, 0.0, 0.0, -1.0, -x, y + h]));
        }
        let height = root.attribute("height").and_then(|h| parse_length(h).ok()).unwrap_or(0.0);
        Ok(Affine([1.0, 0.0, 0.0, -1.0, 0.0, height]))
    }

    fn view_box(&self, node: Node) -> Result<Option<[f64; 4]>, ImportError> {
        let Some(text) = node.attribute("viewBox") else { return Ok(None) };
        let numbers = path_data::parse_number_list(text, 4).map_err(|e| self.syntax_error(node, "viewBox", e))?;
        match numbers[..] {
            [x, y, w, h] if w > 0.0 && h > 0.0 => Ok(Some([x, y, w, h])),
            _ => Err(self.attribute_error(
                node,
                "viewBox",
                "expected four numbers: x, y, and a width and height above 0",
            )),
        }
    }

    /// A nested `svg`: its position, and its `viewBox` fitted into its width and height as
    /// `preserveAspectRatio` says.
    fn nested_viewport(&self, node: Node) -> Result<Affine, ImportError> {
        let x = self.length(node, "x")?.unwrap_or(0.0);
        let y = self.length(node, "y")?.unwrap_or(0.0);
        let mut map = Affine::translate(x, y);
        let (Some([vx, vy, vw, vh]), Some(w), Some(h)) =
            (self.view_box(node)?, self.length(node, "width")?, self.length(node, "height")?)
        else {
            return Ok(map);
        };
        let aspect = node.attribute("preserveAspectRatio").unwrap_or("xMidYMid meet").trim();
        let (mut sx, mut sy) = (w / vw, h / vh);
        let (mut tx, mut ty) = (0.0, 0.0);
        if aspect != "none" {
            let s = if aspect.ends_with("slice") { sx.max(sy) } else { sx.min(sy) };
            (sx, sy) = (s, s);
            let align = |axis: &str, free: f64| {
                if aspect.contains(&format!("{axis}Mid")) {
                    free / 2.0
                } else if aspect.contains(&format!("{axis}Max")) {
                    free
                } else {
                    0.0
                }
            };
            tx = align("x", w - vw * s);
            ty = align("Y", h - vh * s);
        }
        map = map.then_apply_to(Affine([sx, 0.0, 0.0, sy, tx - vx * sx, ty - vy * sy]));
        Ok(map)
    }

    /// An optional length attribute in user units.
    fn length(&self, node: Node, attribute: &str) -> Result<Option<f64>, ImportError> {
        node.attribute(attribute)
            .map(|text| parse_length(text).map_err(|message| self.attribute_error(node, attribute, message)))
            .transpose()
    }

    /// The element's geometry in its own user units, or `None` if it draws nothing.
    fn shape(&mut self, node: Node) -> Result<Option<VectorPath>, ImportError> {
        let remaining = self.limits.max_points.saturating_sub(self.points);
        let path = match node.tag_name().name() {
            "path" => {
                let Some(d) = node.attribute("d") else { return Ok(None) };
                parse_path_data(d, remaining).map_err(|e| self.syntax_error(node, "d", e))?
            }
            "rect" => {
                let get = |a| self.length(node, a);
                let (x, y) = (get("x")?.unwrap_or(0.0), get("y")?.unwrap_or(0.0));
                let (Some(w), Some(h)) = (get("width")?, get("height")?) else { return Ok(None) };
                if !(w > 0.0 && h > 0.0) {
                    return Ok(None);
                }
                let (rx, ry) = match (get("rx")?.filter(|r| *r >= 0.0), get("ry")?.filter(|r| *r >= 0.0)) {
                    (Some(rx), Some(ry)) => (rx, ry),
                    (Some(r), None) | (None, Some(r)) => (r, r),
                    (None, None) => (0.0, 0.0),
                };
                let (rx, ry) = (rx.min(w / 2.0), ry.min(h / 2.0));
                let d = if rx > 0.0 && ry > 0.0 {
                    let arc = |x: f64, y: f64| format!("A{rx} {ry} 0 0 1 {x} {y}");
                    format!(
                        "M{} {y}H{}{}V{}{}H{}{}V{}{}Z",
                        x + rx,
                        x + w - rx,
                        arc(x + w, y + ry),
                        y + h - ry,
                        arc(x + w - rx, y + h),
                        x + rx,
                        arc(x, y + h - ry),
                        y + ry,
                        arc(x + rx, y),
                    )
                } else {
                    format!("M{x} {y}H{}V{}H{x}Z", x + w, y + h)
                };
                parse_path_data(&d, remaining).map_err(|e| self.syntax_error(node, "(rect)", e))?
            }
            "circle" | "ellipse" => {
                let get = |a| self.length(node, a);
                let (cx, cy) = (get("cx")?.unwrap_or(0.0), get("cy")?.unwrap_or(0.0));
                let (rx, ry) = if node.tag_name().name() == "circle" {
                    let r = get("r")?.unwrap_or(0.0);
                    (r, r)
                } else {
                    match (get("rx")?, get("ry")?) {
                        (Some(rx), Some(ry)) => (rx, ry),
                        (Some(r), None) | (None, Some(r)) => (r, r),
                        (None, None) => (0.0, 0.0),
                    }
                };
                if !(rx > 0.0 && ry > 0.0) {
                    return Ok(None);
                }
                let d = format!("M{} {cy}A{rx} {ry} 0 0 1 {} {cy}A{rx} {ry} 0 0 1 {} {cy}Z", cx + rx, cx - rx, cx + rx);
                parse_path_data(&d, remaining).map_err(|e| self.syntax_error(node, "(ellipse)", e))?
            }
            _ => {
                // polygon and polyline: a polyline is closed when filled.
                let Some(text) = node.attribute("points") else { return Ok(None) };
                let numbers = path_data::parse_number_list(text, remaining.saturating_mul(2))
                    .map_err(|e| self.syntax_error(node, "points", e))?;
                if numbers.len() % 2 == 1 {
                    return Err(self.attribute_error(node, "points", "an odd count of numbers (x y pairs expected)"));
                }
                let points: Vec<Point> = numbers.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
                if points.is_empty() {
                    return Ok(None);
                }
                let mut verbs = vec![Verb::Line; points.len()];
                verbs[0] = Verb::Move;
                verbs.push(Verb::Close);
                VectorPath { verbs, points }
            }
        };
        self.points += path.points.len();
        Ok(Some(path))
    }
}

/// A length in user units: a number with an optional absolute unit (px, mm, cm, in, pt, pc).
fn parse_length(text: &str) -> Result<f64, String> {
    let text = text.trim();
    let mut s = path_data::Scanner::new(text);
    let value = s.number().map_err(|e| format!("{} in `{text}`", e.message))?;
    let unit = &text[s.offset()..];
    let scale = match unit.trim() {
        "" | "px" => 1.0,
        "mm" => 96.0 / 25.4,
        "cm" => 96.0 / 2.54,
        "in" => 96.0,
        "pt" => 96.0 / 72.0,
        "pc" => 16.0,
        other => {
            return Err(format!("unsupported unit `{other}` in `{text}` (use user units, px, mm, cm, in, pt or pc)"))
        }
    };
    Ok(value * scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_take_absolute_units() {
        assert_eq!(parse_length(" 12 "), Ok(12.0));
        assert_eq!(parse_length("1in"), Ok(96.0));
        assert_eq!(parse_length("3pt"), Ok(4.0));
        assert!(parse_length("50%").unwrap_err().contains("unsupported unit `%`"));
        assert!(parse_length("wide").is_err());
    }
}
