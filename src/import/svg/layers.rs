//! An SVG's layers, as the document has them: its top-level groups (an Inkscape layer,
//! `<g inkscape:groupmode="layer">`, or any `<g>` with an `id` or an `inkscape:label`) and
//! its top-level elements that draw outside groups (shapes, `<use>`, links, `<switch>`,
//! nested `<svg>`). A `<g>` with none of these marks is no layer: its children are
//! taken in its place, as if it were not there. A document whose only layer is a group of
//! several layers (everything drawn in Inkscape's "Layer 1") has those as its layers.
//! A document without any group among its layers (loose shapes only, perhaps in unmarked
//! wrappers: a logo, a donut with sprinkles) has no layers: it is one drawing, as
//! `import_svg` reads it, and its shapes are not taken apart.
//! Document order is the drawing order, back to front.

use roxmltree::Node;

const SVG_NAMESPACE: &str = "http://www.w3.org/2000/svg";

/// Inkscape's namespace, of `inkscape:label` and `inkscape:groupmode`.
const INKSCAPE: &str = "http://www.inkscape.org/namespaces/inkscape";

/// The elements of `group` that are layers, in document order (without recursion).
fn layers_in<'a, 'i>(group: Node<'a, 'i>) -> Vec<Node<'a, 'i>> {
    let mut layers = Vec::new();
    let mut pending: Vec<Node> = group.children().filter(Node::is_element).collect();
    pending.reverse();
    while let Some(node) = pending.pop() {
        if !in_svg_namespace(node) {
            continue;
        }
        match node.tag_name().name() {
            "g" if node.attribute("id").is_none() && label(node).is_none() && !is_layer(node) => {
                pending.extend(node.children().filter(Node::is_element).collect::<Vec<_>>().into_iter().rev());
            }
            "g" | "use" | "a" | "switch" | "svg" | "path" | "rect" | "circle" | "ellipse" | "line" | "polyline"
            | "polygon" => layers.push(node),
            _ => {}
        }
    }
    layers
}

/// The layers of the document whose root element is `root`, back to front.
pub(super) fn layers<'a, 'i>(root: Node<'a, 'i>) -> Vec<Node<'a, 'i>> {
    let mut layers = layers_in(root);
    while let [only] = layers[..] {
        let inner = layers_in(only);
        if only.tag_name().name() != "g" || inner.len() < 2 {
            break;
        }
        layers = inner;
    }
    if !layers.iter().any(|node| node.tag_name().name() == "g") {
        return Vec::new();
    }
    layers
}

/// Whether `node` is marked as an Inkscape layer.
fn is_layer(node: Node) -> bool {
    node.attribute((INKSCAPE, "groupmode")) == Some("layer")
}

fn label<'a>(node: Node<'a, '_>) -> Option<&'a str> {
    node.attribute((INKSCAPE, "label")).filter(|l| !l.trim().is_empty())
}

/// A layer's name: its `inkscape:label`, else its `id`; `None` when it has neither.
pub(super) fn name(node: Node) -> Option<String> {
    label(node).or_else(|| node.attribute("id").filter(|id| !id.trim().is_empty())).map(|n| n.trim().to_string())
}

/// Whether `node` is in SVG's namespace (or none, as SVG without `xmlns` is read).
pub(super) fn in_svg_namespace(node: Node) -> bool {
    matches!(node.tag_name().namespace(), None | Some(SVG_NAMESPACE))
}
