//! SVG documents to outlines. The document is read as data (roxmltree, with every limit of
//! [`Limits`] applied first), never rendered or run, and resolved by `usvg` (the resvg
//! project's SVG simplifier): CSS (`<style>` sheets, classes, `style` attributes), `<use>`
//! and `<symbol>`, units, transforms and `transform-origin`, nested `<svg>` viewports,
//! `<switch>`, markers and paint references become a plain tree of paths. From it (see
//! [`tree`]) every visible fill counts, and so does every visible stroke, as the area its
//! outline covers (width, joins, caps, miter limit, dashes), unless
//! [`SvgOptions::strokes`] is off. Clip paths intersect what they clip; masks are
//! approximated by the union of their shapes that let anything through. Hidden things
//! (`display="none"`, `visibility="hidden"`, zero opacity) and text are not imported;
//! images and text are named in [`SvgShape::skipped`].
//!
//! Malformed attributes are read as browsers read them: path data is drawn up to its first
//! error, and an attribute that cannot be parsed is ignored (its default applies). Malformed
//! XML is refused with its line and column.
//!
//! Curves are flattened to a tolerance and the rings become outlines with holes by nesting
//! (see `regions`), exactly; when boundaries cross or touch (overlapping shapes), strokes
//! count or clips apply, the exact union is computed instead (see `union`).
//! Elements reaching coordinates beyond [`Limits::max_coordinate`] are refused.
//!
//! Output coordinates are the root's user units (its `viewBox`) with y flipped to point
//! up: the bottom-left corner of the `viewBox` is the origin.

mod layers;
mod text;
pub mod tree;

use std::collections::HashMap;

use roxmltree::{Document, Node, ParsingOptions};

pub use tree::{FillColour, Part, SvgPath};

use crate::geometry::bounding_box;
use crate::import::error::{ElementRef, ImportError};
use crate::import::regions::{assemble, RegionError, SourceRing};
use crate::import::union::{self, Region};
use crate::import::vector::{FillRule, VectorPath, Verb};
use crate::import::Limits;
use crate::outline::Outline;
use layers::in_svg_namespace;
use text::{check_attributes, Cursor};
use tree::{Clip, Drawing};

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
    /// Whether strokes count as area (the default) or only fills do.
    pub strokes: bool,
    /// Size limits.
    pub limits: Limits,
}

impl Default for SvgOptions {
    fn default() -> Self {
        Self { tolerance: None, min_area: 0.0, strokes: true, limits: Limits::default() }
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

/// What an SVG document gave.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgShape {
    /// The filled region's separate parts, largest first.
    pub outlines: Vec<Outline>,
    /// Every filled area in drawing order: an element's fill, then its stroke.
    pub paths: Vec<SvgPath>,
    /// Elements that were skipped (`text`, `image`, `foreignObject`), once each.
    pub skipped: Vec<String>,
}

/// Reads an SVG document and builds the outlines of its filled and stroked shapes.
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
    let Read { drawing: Drawing { paths, clips, .. }, skipped, .. } = read(text, options, false)?;
    let Some(mut shaper) = Shaper::new(&paths, &clips, options) else {
        return Err(ImportError::NoShapes { skipped });
    };
    let (outlines, paths) = shaper.shape(paths)?;
    if outlines.is_empty() {
        return Err(ImportError::NoShapes { skipped });
    }
    Ok(SvgShape { outlines, paths, skipped })
}

/// Most layers [`import_svg_layers`] takes (their overlaps are found pair by pair).
pub const MAX_LAYERS: usize = 256;

/// One layer of an SVG document (see [`import_svg_layers`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SvgLayer {
    /// Its `inkscape:label`, else its `id`; `None` when it has neither.
    pub name: Option<String>,
    /// Its filled region's separate parts, largest first, built as [`import_svg`] builds a
    /// whole document's (overlapping shapes of the layer united).
    pub outlines: Vec<Outline>,
    /// Its filled areas in drawing order, as [`SvgShape::paths`].
    pub paths: Vec<SvgPath>,
}

/// What [`import_svg_layers`] gave.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgLayers {
    /// The layers with an area, back to front.
    pub layers: Vec<SvgLayer>,
    /// Elements that were skipped (`text`, `image`, `foreignObject`), once each.
    pub skipped: Vec<String>,
}

/// Reads an SVG document layer by layer: its top-level groups (an Inkscape layer, a `<g>`
/// with an `id` or `inkscape:label`) and top-level shapes outside groups, back to front in
/// document order (a `<g>` with neither `id` nor label is looked through; a document whose
/// only layer is a group of several takes those). Each layer's outlines are built on their
/// own, as [`import_svg`] builds a document's, and hold only its own paths. Layers without
/// area are left out; a document with none is refused as [`import_svg`] refuses it, one
/// with more than [`MAX_LAYERS`] too.
///
/// ```
/// use akap::import::svg::{import_svg_layers, SvgOptions};
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">
///   <g id="body"><rect width="4" height="4"/></g> <rect id="arm" x="3" y="3" width="4" height="1"/></svg>"#;
/// let read = import_svg_layers(svg, &SvgOptions::default())?;
/// let names: Vec<_> = read.layers.iter().map(|l| l.name.as_deref()).collect();
/// assert_eq!(names, [Some("body"), Some("arm")]);
/// assert_eq!(read.layers[1].outlines[0].area(), 4.0);
/// # Ok::<(), akap::import::ImportError>(())
/// ```
pub fn import_svg_layers(text: &str, options: &SvgOptions) -> Result<SvgLayers, ImportError> {
    let Read { drawing: Drawing { paths, clips, layers }, skipped, names } = read(text, options, true)?;
    let Some(mut shaper) = Shaper::new(&paths, &clips, options) else {
        return Err(ImportError::NoShapes { skipped });
    };
    let mut by_layer: Vec<Vec<(SvgPath, Vec<usize>)>> = vec![Vec::new(); names.len()];
    let mut outside = Vec::new();
    for (path, layer) in paths.into_iter().zip(layers) {
        match layer.and_then(|k| by_layer.get_mut(k)) {
            Some(paths) => paths.push(path),
            None => outside.push(path),
        }
    }
    // Every drawn element lies in a layer; should usvg ever draw one outside them, it is a
    // layer of its own, in front.
    let mut layers = Vec::new();
    let named = names.into_iter().map(Some);
    for (name, paths) in named.chain([None]).zip(by_layer.into_iter().chain([outside])) {
        if paths.is_empty() {
            continue;
        }
        let (outlines, paths) = shaper.shape(paths)?;
        if !outlines.is_empty() {
            layers.push(SvgLayer { name: name.flatten(), outlines, paths });
        }
    }
    if layers.is_empty() {
        return Err(ImportError::NoShapes { skipped });
    }
    Ok(SvgLayers { layers, skipped })
}

/// A document read into a drawing.
struct Read {
    drawing: Drawing,
    skipped: Vec<String>,
    /// The layers' names, when read by layer ([`Drawing::layers`] index them).
    names: Vec<Option<String>>,
}

/// Reads the document into a drawing, by layer if `by_layer`.
fn read(text: &str, options: &SvgOptions, by_layer: bool) -> Result<Read, ImportError> {
    options.validate()?;
    let limits = &options.limits;
    let document = parse_document(text, limits)?;
    let root = document.root_element();
    if root.tag_name().name() != "svg" || !in_svg_namespace(root) {
        return Err(ImportError::NotSvg { root: root.tag_name().name().to_string() });
    }
    check_depth(root, text)?;
    check_numbers(&document, text, limits.max_coordinate)?;
    let layer_nodes = if by_layer { layers::layers(root) } else { Vec::new() };
    if layer_nodes.len() > MAX_LAYERS {
        return Err(ImportError::TooLarge {
            what: "the SVG",
            size: layer_nodes.len(),
            limit: MAX_LAYERS,
            unit: "layers",
        });
    }
    let names = layer_nodes.iter().map(|&n| layers::name(n)).collect();
    let sized = sized_to_view_box(text, &document, &layer_nodes);
    let output = sized.output;
    let sized = parse_document(&sized.text, limits)?;
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
    // usvg keeps ids only: every shape has one (see `sized_to_view_box`) to find it by.
    let shapes: Vec<Node> = document.descendants().filter(is_shape).collect();
    let elements: HashMap<&str, Node> =
        document.descendants().filter_map(|n| n.attribute("id").map(|id| (id, n))).collect();
    let cursor = std::cell::RefCell::new(Cursor::new(text));
    let locate = |id: &str| {
        let node = match id.strip_prefix(SHAPE_ID) {
            Some(k) => k.parse::<usize>().ok().and_then(|k| shapes.get(k)).copied(),
            None => elements.get(id).copied(),
        };
        match node {
            Some(node) => element_ref(node, &mut cursor.borrow_mut()),
            None => ElementRef { name: "path".into(), id: Some(id.to_string()), line: 0, column: 0 },
        }
    };
    let layer = |id: &str| {
        let k = id.strip_prefix(LAYER_ID)?.parse::<usize>().ok()?;
        (k < layer_nodes.len()).then_some(k)
    };
    let drawing = tree::drawing(&tree, output, options.strokes, &locate, &layer);
    check_points(&drawing, limits)?;
    Ok(Read { drawing, skipped, names })
}

/// The document's text with its root sized to its `viewBox` (or 1 x 1 with a unit
/// `viewBox` when it has none), an id on every shape without one (`SHAPE_ID` and its
/// index among the shapes) and each layer wrapped in a group of id `LAYER_ID` and its
/// index (which changes what CSS child and sibling selectors match, `svg > g` say, if a
/// `<style>` has them; Inkscape and Illustrator write none), and the map from the root's
/// user units to output.
struct Sized {
    text: String,
    output: [f64; 6],
}

/// usvg maps the root's user units into its size through the viewBox; with the size set to
/// the viewBox's own, that map is the shift by the viewBox's corner, and none of usvg's
/// sizing rules (percentages, aspect ratios) apply.
fn sized_to_view_box(text: &str, document: &Document, layers: &[Node]) -> Sized {
    let root = document.root_element();
    let (view_box, output) = match root.attribute("viewBox").and_then(|v| v.parse::<svgtypes::ViewBox>().ok()) {
        Some(v) if v.w > 0.0 && v.h > 0.0 && v.w.is_finite() && v.h.is_finite() => {
            ([v.x, v.y, v.w, v.h], [1.0, 0.0, 0.0, -1.0, 0.0, v.h])
        }
        _ => {
            let height = root.attribute("height").and_then(parse_length).unwrap_or(0.0);
            ([0.0, 0.0, 1.0, 1.0], [1.0, 0.0, 0.0, -1.0, 0.0, height])
        }
    };
    // Insertions after tag names, made from the end so that earlier offsets stay valid.
    let name_end = |node: Node| {
        let tag = node.range().start + 1;
        tag + text[tag..].find(|c: char| c.is_whitespace() || c == '>' || c == '/').unwrap_or(0)
    };
    let mut edits: Vec<(std::ops::Range<usize>, String)> = document
        .descendants()
        .filter(is_shape)
        .enumerate()
        .filter(|(_, n)| n.attribute("id").is_none())
        .map(|(k, n)| (name_end(n)..name_end(n), format!(r#" id="{SHAPE_ID}{k}""#)))
        .collect();
    // svgtypes skips repeated closepaths by recursing once per repeat: a hostile run of
    // them would overflow the stack. One closepath does what a run does.
    for node in document.descendants().filter(is_shape) {
        if let Some(d) = node.attributes().find(|a| a.name() == "d") {
            let range = d.range_value();
            if let Some(collapsed) = collapse_closepaths(&text[range.clone()]) {
                edits.push((range, collapsed));
            }
        }
    }
    // Openings before closings: where one layer ends and the next begins, the closing,
    // made second, comes first.
    for (k, layer) in layers.iter().enumerate() {
        let at = layer.range().start;
        edits.push((at..at, format!(r#"<g id="{LAYER_ID}{k}">"#)));
    }
    for layer in layers {
        let at = layer.range().end;
        edits.push((at..at, "</g>".to_string()));
    }
    let mut sized = text.to_string();
    for a in root.attributes().filter(|a| matches!(a.name(), "width" | "height" | "viewBox" | "preserveAspectRatio")) {
        let range = a.range();
        sized.replace_range(range.clone(), &" ".repeat(range.len()));
    }
    let [vx, vy, vw, vh] = view_box;
    let at = name_end(root);
    edits.push((at..at, format!(r#" width="{vw}" height="{vh}" viewBox="{vx} {vy} {vw} {vh}""#)));
    edits.sort_by_key(|(range, _)| std::cmp::Reverse(range.start));
    for (range, replacement) in edits {
        sized.replace_range(range, &replacement);
    }
    Sized { text: sized, output }
}

/// Path data with each run of closepaths (`Z`, `z`, with spaces between) made one, or
/// `None` when it has no such run.
fn collapse_closepaths(data: &str) -> Option<String> {
    let mut out = String::with_capacity(data.len());
    let (mut closed, mut changed) = (false, false);
    for c in data.chars() {
        match c {
            'Z' | 'z' if closed => changed = true,
            'Z' | 'z' => {
                closed = true;
                out.push(c);
            }
            c if c.is_whitespace() => out.push(c),
            c => {
                closed = false;
                out.push(c);
            }
        }
    }
    changed.then_some(out)
}

/// A length in user units: a number with an optional absolute unit; `None` for anything
/// else (the root's height without a `viewBox` only places the y flip).
fn parse_length(text: &str) -> Option<f64> {
    let length: svgtypes::Length = text.parse().ok()?;
    let scale = match length.unit {
        svgtypes::LengthUnit::None | svgtypes::LengthUnit::Px => 1.0,
        svgtypes::LengthUnit::Mm => 96.0 / 25.4,
        svgtypes::LengthUnit::Cm => 96.0 / 2.54,
        svgtypes::LengthUnit::In => 96.0,
        svgtypes::LengthUnit::Pt => 96.0 / 72.0,
        svgtypes::LengthUnit::Pc => 16.0,
        _ => return None,
    };
    Some(length.number * scale)
}

/// The element `node` in messages: its name, `id` and position.
fn element_ref(node: Node, cursor: &mut Cursor) -> ElementRef {
    let (line, column) = cursor.at(node.range().start);
    let id = node.attribute("id").map(str::to_string);
    ElementRef { name: node.tag_name().name().to_string(), id, line, column }
}

/// Refuses drawings of more than [`Limits::max_points`] points before flattening, and
/// elements reaching beyond [`Limits::max_coordinate`].
fn check_points(drawing: &Drawing, limits: &Limits) -> Result<(), ImportError> {
    let members = drawing.clips.iter().flat_map(|c| &c.members);
    let mut count = 0usize;
    for (SvgPath { path, element, .. }, _) in drawing.paths.iter().chain(members) {
        count += path.points.len();
        if count > limits.max_points {
            return Err(ImportError::TooManyPoints {
                what: "the SVG's shapes",
                needed: None,
                limit: limits.max_points,
            });
        }
        let limit = limits.max_coordinate;
        if let Some(&value) = path.points.iter().flatten().find(|v| v.is_nan() || v.abs() > limit) {
            return Err(ImportError::CoordinateTooLarge { element: element.clone(), attribute: None, value, limit });
        }
    }
    Ok(())
}

/// Flattens `path` to rings within what is left of the point budget.
fn flatten(
    path: &VectorPath,
    tolerance: f64,
    count: &mut usize,
    limits: &Limits,
) -> Result<Vec<Vec<crate::geometry::Point>>, ImportError> {
    let flat = path.flatten(tolerance.max(f64::MIN_POSITIVE), *count, limits.max_points).map_err(|needed| {
        ImportError::TooManyPoints {
            what: "the outline flattened to the tolerance",
            needed: needed.is_finite().then_some(needed),
            limit: limits.max_points,
        }
    })?;
    *count += flat.iter().map(Vec::len).sum::<usize>();
    Ok(flat)
}

/// Builds outlines from a drawing's paths (all of them, or each layer's in turn): one
/// flattening tolerance for the whole drawing, one point budget, the clips' regions built
/// once.
struct Shaper<'a> {
    options: &'a SvgOptions,
    tolerance: f64,
    /// Points made so far, against [`Limits::max_points`].
    count: usize,
    clips: &'a [Clip],
    /// The clips' regions, once built.
    regions: Option<Vec<Region>>,
}

impl<'a> Shaper<'a> {
    /// For the drawing's `paths` and `clips`; `None` when the paths have no point.
    fn new(paths: &[(SvgPath, Vec<usize>)], clips: &'a [Clip], options: &'a SvgOptions) -> Option<Self> {
        let every_point = paths.iter().flat_map(|(p, _)| p.path.points.iter().copied());
        let (lo, hi) = bounding_box(every_point)?;
        let size = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
        let tolerance = options.tolerance.unwrap_or(DEFAULT_RELATIVE_TOLERANCE * size);
        Some(Self { options, tolerance, count: 0, clips, regions: None })
    }

    /// The clip regions in order (a clip only refers to earlier ones).
    fn regions(&mut self) -> Result<&[Region], ImportError> {
        if self.regions.is_none() {
            let mut regions: Vec<Region> = Vec::with_capacity(self.clips.len());
            for clip in self.clips {
                let mut members = Vec::with_capacity(clip.members.len());
                for (member, own) in &clip.members {
                    let rings = flatten(&member.path, self.tolerance, &mut self.count, &self.options.limits)?;
                    members.push(clipped_by(union::resolve(&rings, member.fill_rule), own, &regions));
                }
                regions.push(clipped_by(union::union(members), &clip.clips, &regions));
            }
            self.regions = Some(regions);
        }
        Ok(self.regions.as_deref().unwrap_or_default())
    }

    /// The outlines of `paths` (flattened, then nested, or united where shapes cross or
    /// clips apply), largest first, and the paths kept (what is left of clipped ones).
    fn shape(&mut self, paths: Vec<(SvgPath, Vec<usize>)>) -> Result<(Vec<Outline>, Vec<SvgPath>), ImportError> {
        let (options, tolerance) = (self.options, self.tolerance);
        let limits = &options.limits;
        let mut flat = Vec::with_capacity(paths.len());
        for (p, _) in &paths {
            flat.push(flatten(&p.path, tolerance, &mut self.count, limits)?);
        }
        // Nesting is exact and keeps every vertex, but only decides drawings whose
        // boundaries neither cross nor touch. A stroke's outline nearly always meets itself
        // (at the inner side of each corner), so with strokes the union is taken straight
        // away: skipping the sweep that would find the crossing took 20% off a 1 MB drawing
        // and 15% off resvg's test files (see the commit).
        let clipped = paths.iter().any(|(_, c)| !c.is_empty());
        let stroked = paths.iter().any(|(p, _)| p.part == Part::Stroke);
        if !clipped && !stroked {
            let rings: Vec<SourceRing> = flat
                .iter()
                .enumerate()
                .flat_map(|(shape, rings)| rings.iter().map(move |r| SourceRing { points: r.clone(), shape }))
                .collect();
            let rules: Vec<FillRule> = paths.iter().map(|(p, _)| p.fill_rule).collect();
            match assemble(&rings, &rules, options.min_area, limits.max_segment_pairs) {
                Ok(outlines) => return Ok((outlines, paths.into_iter().map(|(p, _)| p).collect())),
                Err(RegionError::Crossing(..)) => {}
                Err(RegionError::TooComplex) => {
                    return Err(ImportError::TooComplex { pairs: limits.max_segment_pairs })
                }
            }
        }
        let regions = if clipped { self.regions()? } else { &[] };
        let mut parts = Vec::with_capacity(paths.len());
        let mut kept = Vec::with_capacity(paths.len());
        for ((mut p, own), rings) in paths.into_iter().zip(&flat) {
            let region = union::resolve(rings, p.fill_rule);
            if own.is_empty() {
                parts.push(region);
                kept.push(p);
                continue;
            }
            // A clipped area is exported as what is left of it.
            let region = clipped_by(region, &own, regions);
            if region.is_empty() {
                continue;
            }
            p.path = polygon_path(&region);
            p.fill_rule = FillRule::NonZero;
            parts.push(region);
            kept.push(p);
        }
        let region = union::union(parts);
        let points = union::point_count(&region);
        if points > limits.max_points {
            return Err(ImportError::TooManyPoints {
                what: "the united outline",
                needed: Some(points as f64),
                limit: limits.max_points,
            });
        }
        Ok((union::outlines(region, options.min_area), kept))
    }
}

/// `region` intersected with each of `clips` (indices into `regions`).
fn clipped_by(mut region: Region, clips: &[usize], regions: &[Region]) -> Region {
    for &c in clips {
        region = union::intersect(&region, &regions[c]);
    }
    region
}

/// A region's rings as a path of lines.
fn polygon_path(region: &Region) -> VectorPath {
    let mut path = VectorPath { verbs: Vec::new(), points: Vec::new() };
    for ring in region.iter().flatten() {
        path.verbs.push(Verb::Move);
        path.verbs.extend(std::iter::repeat_n(Verb::Line, ring.len().saturating_sub(1)));
        path.verbs.push(Verb::Close);
        path.points.extend_from_slice(ring);
    }
    path
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
            let element = element_ref(node, &mut Cursor::new(text));
            return Err(ImportError::TooDeep { element, limit: MAX_DEPTH });
        }
        stack.extend(node.children().filter(Node::is_element).map(|c| (c, depth + 1)));
    }
    Ok(())
}

/// The prefix of the ids given to shapes without one.
const SHAPE_ID: &str = "akap-shape-";

/// The prefix of the ids of the groups wrapped around layers.
const LAYER_ID: &str = "akap-layer-";

/// Whether `node` is an SVG shape element.
fn is_shape(node: &Node) -> bool {
    node.is_element()
        && in_svg_namespace(*node)
        && matches!(node.tag_name().name(), "path" | "rect" | "circle" | "ellipse" | "line" | "polyline" | "polygon")
}

/// Attributes that place geometry.
const GEOMETRY: [&str; 18] = [
    "d",
    "points",
    "x",
    "y",
    "width",
    "height",
    "x1",
    "y1",
    "x2",
    "y2",
    "cx",
    "cy",
    "r",
    "rx",
    "ry",
    "transform",
    "viewBox",
    "stroke-width",
];

/// Refuses an element with a number beyond [`Limits::max_coordinate`] in an attribute that
/// places geometry, naming it, before usvg reads the numbers in single precision (where
/// those beyond about 3.4e38 become infinite and the element would silently vanish).
fn check_numbers(document: &Document, text: &str, limit: f64) -> Result<(), ImportError> {
    let mut cursor = Cursor::new(text);
    for node in document.descendants().filter(Node::is_element) {
        for attribute in node.attributes().filter(|a| GEOMETRY.contains(&a.name())) {
            let tokens =
                attribute.value().split(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '-' | '+')));
            if let Some(value) = tokens.filter_map(|t| t.parse::<f64>().ok()).find(|v| v.abs() > limit) {
                let element = element_ref(node, &mut cursor);
                let attribute = Some(attribute.name().to_string());
                return Err(ImportError::CoordinateTooLarge { element, attribute, value, limit });
            }
        }
    }
    Ok(())
}
