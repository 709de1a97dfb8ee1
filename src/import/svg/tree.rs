//! The drawing as usvg resolves it (CSS, `<use>`, units, transforms, `switch`, markers,
//! paint references), turned into the paths our downstream steps take ([`SvgPath`]: the
//! geometry, fill rule, [`FillColour`] and [`Part`] of each), in output coordinates (the
//! root's user units, y up).
//!
//! - Visible fills become filled paths with their rule and colour.
//! - Visible strokes become their outlines (dashes first, then tiny-skia's stroker: width,
//!   joins, caps, miter limit), filled with the non-zero rule, in the stroke's colour.
//! - Groups with zero opacity, hidden paths and paints with zero opacity draw nothing.
//! - Clip paths become regions that what they clip is intersected with (their shapes'
//!   union under each one's `clip-rule`, itself clipped by the clip path's own
//!   `clip-path`). Masks are approximated the same way: the union of the mask's visible
//!   shapes that let something through (luminance or alpha above zero), within the mask's
//!   rectangle. Partial transparency is not modelled: a shape is in or out.

use tiny_skia_path::{PathSegment, Transform};

use crate::import::error::ElementRef;
use crate::import::vector::{FillRule, VectorPath, Verb};

/// A colour with its alpha: every opacity on the way from the root folded in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FillColour {
    /// Red, 0-255.
    pub red: u8,
    /// Green, 0-255.
    pub green: u8,
    /// Blue, 0-255.
    pub blue: u8,
    /// Alpha, 0-1.
    pub alpha: f64,
}

/// One filled area's geometry (an element's fill, or its stroke's outline), in output
/// coordinates, for exporting the art deformed.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgPath {
    /// The element it comes from (its position is known when it has an `id`).
    pub element: ElementRef,
    /// Its path: cubics, quadratics and lines as usvg resolved them; where a clip path or a
    /// mask applies, the clipped area's flattened outline.
    pub path: VectorPath,
    /// Its fill rule (non-zero for stroke outlines).
    pub fill_rule: FillRule,
    /// Its colour (the fill's or the stroke's), with the paint's opacity and every group
    /// `opacity` on the way from the root folded into the alpha (exact where the group's
    /// shapes do not overlap); `None` when the paint is a gradient or a pattern (the area
    /// still counts).
    pub fill: Option<FillColour>,
    /// Whether it is the element's fill or its stroke.
    pub part: Part,
}

/// What a path contributes: its fill, or its stroke's outline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// The path's interior.
    Fill,
    /// The area its stroke covers.
    Stroke,
}

/// A region that paths are intersected with: the union of its members, each intersected
/// with its own clips, intersected with every region of `clips`.
#[derive(Debug, Clone, PartialEq)]
pub struct Clip {
    /// The shapes (fill rule and geometry, in output coordinates) and their own clips.
    pub members: Vec<(SvgPath, Vec<usize>)>,
    /// Further clips (indices into [`Drawing::clips`], always smaller than this one's).
    pub clips: Vec<usize>,
}

/// The visible paths of a drawing, and the clips they refer to.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Drawing {
    /// Filled and stroked areas in document order (a path's fill before its stroke).
    pub paths: Vec<(SvgPath, Vec<usize>)>,
    /// Regions referred to by [`Drawing::paths`] (each path is intersected with all of its).
    pub clips: Vec<Clip>,
    /// For each of [`Drawing::paths`], the layer it is drawn in: the one of its outermost
    /// group that `layer` (given to [`drawing`]) knows; `None` when there is none.
    pub layers: Vec<Option<usize>>,
}

/// Where an element came from, for messages: usvg keeps the `id`, and `locate` finds it.
pub type Locate<'a> = dyn Fn(&str) -> ElementRef + 'a;

/// The layer a group is, by its `id` (usvg keeps every `<g>` and `<use>` as a group with
/// its `id`), if it is one.
pub type Layer<'a> = dyn Fn(&str) -> Option<usize> + 'a;

/// A plane affine map `[a, b, c, d, e, f]`: `(x, y) -> (a x + c y + e, b x + d y + f)`.
type Map = [f64; 6];

fn of(t: Transform) -> Map {
    [t.sx, t.ky, t.kx, t.sy, t.tx, t.ty].map(f64::from)
}

/// `outer` after `inner`.
fn then(outer: Map, inner: Map) -> Map {
    let [a, b, c, d, e, f] = outer;
    let [p, q, r, s, t, u] = inner;
    [a * p + c * q, b * p + d * q, a * r + c * s, b * r + d * s, a * t + c * u + e, b * t + d * u + f]
}

/// Which parts of paths a walk takes.
#[derive(Clone, Copy)]
enum Take {
    /// The drawing: fills and, if asked, strokes, with their colours.
    Drawing { strokes: bool },
    /// A clip path: fills only, whatever their paint (`clip-rule` is usvg's fill rule).
    Clip,
    /// A mask: fills and strokes that let something through.
    Mask,
}

/// Walks `tree`: the root's user units mapped by `output`, each path in the layer of its
/// outermost group that `layer` names.
pub fn drawing(tree: &usvg::Tree, output: Map, strokes: bool, locate: &Locate, layer: &Layer) -> Drawing {
    let mut walker = Walker { drawing: Drawing::default(), locate, layer };
    let mut paths = Vec::new();
    let mut layers = Vec::new();
    walker.walk(tree.root(), output, Take::Drawing { strokes }, &[], &mut paths, &mut layers);
    walker.drawing.paths = paths;
    walker.drawing.layers = layers;
    walker.drawing
}

/// A node still to walk, with what it inherits: the map of its parent's user units to
/// output, the opacity, the clips and the layer of its groups.
struct Pending<'t> {
    node: &'t usvg::Node,
    map: Map,
    opacity: f32,
    clips: Vec<usize>,
    layer: Option<usize>,
}

struct Walker<'a> {
    drawing: Drawing,
    locate: &'a Locate<'a>,
    layer: &'a Layer<'a>,
}

impl Walker<'_> {
    /// Adds the paths under `group` (whose parent's user units `map` takes to output) to
    /// `out`, each with `clips` and those of the groups on the way, and its layer to
    /// `layers`. Without recursion.
    fn walk(
        &mut self,
        group: &usvg::Group,
        map: Map,
        take: Take,
        clips: &[usize],
        out: &mut Vec<(SvgPath, Vec<usize>)>,
        layers: &mut Vec<Option<usize>>,
    ) {
        let mut pending: Vec<Pending> = Vec::new();
        for node in group.children().iter().rev() {
            pending.push(Pending { node, map, opacity: 1.0, clips: clips.to_vec(), layer: None });
        }
        while let Some(Pending { node, map, opacity, clips, layer }) = pending.pop() {
            match node {
                usvg::Node::Group(g) => {
                    let layer = layer.or_else(|| (self.layer)(g.id()));
                    // A group with zero opacity draws nothing (in a clip path opacity does
                    // not apply).
                    let opacity = opacity * g.opacity().get();
                    if opacity <= 0.0 && !matches!(take, Take::Clip) {
                        continue;
                    }
                    let map = then(map, of(g.transform()));
                    let mut clips = clips;
                    if let Some(clip) = g.clip_path() {
                        clips.push(self.clip(clip, map));
                    }
                    if let Some(mask) = g.mask() {
                        clips.push(self.mask(mask, map));
                    }
                    for node in g.children().iter().rev() {
                        pending.push(Pending { node, map, opacity, clips: clips.clone(), layer });
                    }
                }
                usvg::Node::Path(p) if p.is_visible() => {
                    let parts = self.parts(p, map, opacity, take);
                    layers.extend(std::iter::repeat_n(layer, parts.len()));
                    out.extend(parts.into_iter().map(|path| (path, clips.clone())));
                }
                _ => {}
            }
        }
    }

    /// A clip path applied in the user units that `map` takes to output.
    fn clip(&mut self, clip: &usvg::ClipPath, map: Map) -> usize {
        let mut clips = Vec::new();
        if let Some(inner) = clip.clip_path() {
            clips.push(self.clip(inner, map));
        }
        let mut members = Vec::new();
        let root = clip.root();
        self.walk(root, then(map, of(clip.transform())), Take::Clip, &[], &mut members, &mut Vec::new());
        self.add(members, clips)
    }

    /// A mask, as the union of its shapes that let something through, in its rectangle.
    fn mask(&mut self, mask: &usvg::Mask, map: Map) -> usize {
        let mut clips = Vec::new();
        if let Some(inner) = mask.mask() {
            clips.push(self.mask(inner, map));
        }
        let r = mask.rect();
        let corners = [[r.left(), r.top()], [r.right(), r.top()], [r.right(), r.bottom()], [r.left(), r.bottom()]];
        let place = |p: [f32; 2]| apply(map, [f64::from(p[0]), f64::from(p[1])]);
        let verbs = vec![Verb::Move, Verb::Line, Verb::Line, Verb::Line, Verb::Close];
        let rect = VectorPath { verbs, points: corners.map(place).to_vec() };
        clips.push(self.add(vec![(rect_path(rect), Vec::new())], Vec::new()));
        let mut members = Vec::new();
        self.walk(mask.root(), map, Take::Mask, &[], &mut members, &mut Vec::new());
        self.add(members, clips)
    }

    fn add(&mut self, members: Vec<(SvgPath, Vec<usize>)>, clips: Vec<usize>) -> usize {
        self.drawing.clips.push(Clip { members, clips });
        self.drawing.clips.len() - 1
    }

    /// The fill and stroke areas of `p` that `take` wants.
    fn parts(&self, p: &usvg::Path, map: Map, opacity: f32, take: Take) -> Vec<SvgPath> {
        let mut out = Vec::new();
        let element = || if p.id().is_empty() { unnamed() } else { (self.locate)(p.id()) };
        // A fill of a path without area (a line, two points) draws nothing.
        let bounds = p.data().bounds();
        let has_area = p.data().len() >= 3 && bounds.width() > 0.0 && bounds.height() > 0.0;
        if let Some(fill) = p.fill().filter(|_| has_area) {
            let alpha = opacity * fill.opacity().get();
            let wanted = match take {
                Take::Clip => true,
                Take::Drawing { .. } => alpha > 0.0,
                Take::Mask => alpha > 0.0 && lets_through(fill.paint()),
            };
            if wanted {
                let fill_rule = match fill.rule() {
                    usvg::FillRule::NonZero => FillRule::NonZero,
                    usvg::FillRule::EvenOdd => FillRule::EvenOdd,
                };
                let path = convert(p.data(), map);
                let fill = colour(fill.paint(), alpha);
                out.push(SvgPath { element: element(), path, fill_rule, fill, part: Part::Fill });
            }
        }
        let strokes = match take {
            Take::Drawing { strokes } => strokes,
            Take::Clip => false,
            Take::Mask => true,
        };
        if let Some(stroke) = p.stroke().filter(|_| strokes) {
            let alpha = opacity * stroke.opacity().get();
            let lets = !matches!(take, Take::Mask) || lets_through(stroke.paint());
            if alpha > 0.0 && lets {
                if let Some(outline) = stroke_outline(p, stroke) {
                    let path = convert(&outline, map);
                    let fill = colour(stroke.paint(), alpha);
                    let fill_rule = FillRule::NonZero;
                    out.push(SvgPath { element: element(), path, fill_rule, fill, part: Part::Stroke });
                }
            }
        }
        out
    }
}

/// A path without an `id` (usvg keeps no position).
fn unnamed() -> ElementRef {
    ElementRef { name: "path".into(), id: None, line: 0, column: 0 }
}

fn rect_path(path: VectorPath) -> SvgPath {
    SvgPath { element: unnamed(), path, fill_rule: FillRule::NonZero, fill: None, part: Part::Fill }
}

/// Whether a paint in a mask lets anything through (a colour of luminance above zero; a
/// gradient or pattern is taken to).
fn lets_through(paint: &usvg::Paint) -> bool {
    match paint {
        usvg::Paint::Color(c) => c.red > 0 || c.green > 0 || c.blue > 0,
        _ => true,
    }
}

/// The area `stroke` covers along `p`, in the path's own coordinates (where width and
/// dashes are given). tiny-skia's stroker's nominal accuracy is 1/(4 scale); at a thousandth
/// of the size (the flattening's) a stroked circle's area was 0.4% off, at 1e-5 of it within
/// 2e-4 (see the tests), so the scale is set for 1e-5 of the path's size.
fn stroke_outline(p: &usvg::Path, stroke: &usvg::Stroke) -> Option<tiny_skia_path::Path> {
    let b = p.data().bounds();
    let size = (b.width().hypot(b.height()) + stroke.width().get()).max(1e-6);
    let scale = 0.25 / (1e-5 * size);
    let tiny = stroke.to_tiny_skia();
    let dashed = match &tiny.dash {
        Some(dash) => p.data().dash(dash, scale),
        None => Some(p.data().clone()),
    };
    dashed.and_then(|d| d.stroke(&tiny, scale))
}

fn colour(paint: &usvg::Paint, alpha: f32) -> Option<FillColour> {
    match paint {
        usvg::Paint::Color(c) => Some(FillColour { red: c.red, green: c.green, blue: c.blue, alpha: f64::from(alpha) }),
        _ => None,
    }
}

fn apply(m: Map, [x, y]: [f64; 2]) -> [f64; 2] {
    [m[0] * x + m[2] * y + m[4], m[1] * x + m[3] * y + m[5]]
}

/// A tiny-skia path (f32, as usvg keeps it) through `map`, in f64.
fn convert(path: &tiny_skia_path::Path, map: Map) -> VectorPath {
    let place = |p: tiny_skia_path::Point| apply(map, [f64::from(p.x), f64::from(p.y)]);
    let mut verbs = Vec::new();
    let mut points = Vec::new();
    for segment in path.segments() {
        match segment {
            PathSegment::MoveTo(p) => {
                verbs.push(Verb::Move);
                points.push(place(p));
            }
            PathSegment::LineTo(p) => {
                verbs.push(Verb::Line);
                points.push(place(p));
            }
            PathSegment::QuadTo(p1, p) => {
                verbs.push(Verb::Quad);
                points.extend([place(p1), place(p)]);
            }
            PathSegment::CubicTo(p1, p2, p) => {
                verbs.push(Verb::Cubic);
                points.extend([place(p1), place(p2), place(p)]);
            }
            PathSegment::Close => verbs.push(Verb::Close),
        }
    }
    VectorPath { verbs, points }
}
