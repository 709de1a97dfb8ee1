//! The gallery (`www/gallery/`): every entry of `index.json` imports, triangulates and
//! gives a valid, connected mesh covering its outline.

use akap::import::svg::{import_svg, SvgOptions};
use akap::{triangulate, Outline, TriangulationOptions};
use serde::Deserialize;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::{assert_area_matches, assert_positive_triangles};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Entry {
    name: String,
    file: String,
    kind: String,
}

const INDEX: &str = include_str!("../www/gallery/index.json");
const SVGS: [(&str, &str); 3] = [
    ("ghost.svg", include_str!("../www/gallery/ghost.svg")),
    ("cat.svg", include_str!("../www/gallery/cat.svg")),
    ("donut.svg", include_str!("../www/gallery/donut.svg")),
];
const PNG: (&str, &[u8]) = ("pip.png", include_bytes!("../www/gallery/pip.png"));
/// A layered character: its file name and text, its layers back to front, and the pairs of
/// layers that overlap (front, back), where its joints go.
type Layered = (&'static str, &'static str, &'static [&'static str], &'static [(&'static str, &'static str)]);

/// The layered characters, posed as puppets.
const PUPPETS: [Layered; 2] = [
    (
        "magician.svg",
        include_str!("../www/gallery/magician.svg"),
        &["Left arm", "Right leg", "Left leg", "Torso", "Head", "Right arm", "Hat"],
        &[
            ("Torso", "Left arm"),
            ("Torso", "Right leg"),
            ("Torso", "Left leg"),
            ("Head", "Torso"),
            ("Right arm", "Torso"),
        ],
    ),
    (
        "dragon.svg",
        include_str!("../www/gallery/dragon.svg"),
        &["Tail", "Hind leg", "Body", "Front leg", "Wing", "Head"],
        &[("Body", "Tail"), ("Body", "Hind leg"), ("Front leg", "Body"), ("Wing", "Body"), ("Head", "Body")],
    ),
];

/// Triangulates the largest part with edges of about `edge` and checks the mesh.
fn check(name: &str, outlines: &[Outline], edge: f64) {
    assert!(!outlines.is_empty(), "{name}");
    let main = &outlines[0];
    assert!(!main.holes.is_empty(), "{name} should have a hole");
    let options = TriangulationOptions::default().with_target_edge_length(edge);
    let mesh = triangulate(main, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_positive_triangles(&mesh);
    assert_area_matches(&mesh, main);
    assert_eq!(mesh.connected_components(), 1, "{name}");
    assert!(mesh.triangle_count() > 200, "{name}: {} triangles", mesh.triangle_count());
}

#[test]
fn index_lists_every_file() {
    let entries: Vec<Entry> = serde_json::from_str(INDEX).unwrap();
    let mut listed: Vec<(&str, &str)> = entries.iter().map(|e| (e.file.as_str(), e.kind.as_str())).collect();
    listed.sort();
    let mut known: Vec<(&str, &str)> = SVGS
        .iter()
        .map(|s| (s.0, "svg"))
        .chain(PUPPETS.iter().map(|p| (p.0, "svg")))
        .chain([(PNG.0, "image")])
        .collect();
    known.sort();
    assert_eq!(listed, known);
    assert!(entries.iter().all(|e| !e.name.is_empty()));
}

#[test]
fn cartoon_svgs_import_and_triangulate() {
    for (name, text) in SVGS {
        let shape = import_svg(text, &SvgOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(shape.outlines.len(), 1, "{name} is one piece");
        assert!(shape.paths.iter().any(|p| p.path.verbs.contains(&akap::import::vector::Verb::Cubic)));
        check(name, &shape.outlines, 6.0);
    }
}

#[cfg(not(target_arch = "wasm32"))]
#[test]
fn textured_png_traces_and_triangulates() {
    use akap::import::raster::{trace_image, TraceOptions};
    use akap::import::warp::texture_coordinates;

    let decoder = png::Decoder::new(std::io::Cursor::new(PNG.1));
    let mut reader = decoder.read_info().unwrap();
    let mut rgba = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut rgba).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba);
    let (w, h) = (info.width as usize, info.height as usize);
    let outlines = trace_image(&rgba[..w * h * 4], w, h, &TraceOptions::default()).unwrap();
    assert_eq!(outlines.len(), 1);
    assert_eq!(outlines[0].holes.len(), 2, "two eyes");
    check(PNG.0, &outlines, 8.0);
    let uvs = texture_coordinates(&outlines[0].outer, w as f64, h as f64).unwrap();
    assert!(uvs.iter().all(|t| (0.0..=1.0).contains(&t[0]) && (0.0..=1.0).contains(&t[1])));
}

#[test]
fn layered_characters_import_as_puppets_joined_where_their_layers_overlap() {
    use akap::deform::{AkapOptions, Deformer};
    use akap::import::puppet::{import_puppet, PuppetOptions};
    for (name, text, layers, overlaps) in PUPPETS {
        let p = import_puppet(text, &PuppetOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        let names: Vec<&str> = p.puppet.parts.iter().map(|part| part.name.as_str()).collect();
        assert_eq!(names, layers, "{name}");
        let index = |layer: &str| layers.iter().position(|l| *l == layer).unwrap();
        let mut joined: Vec<[usize; 2]> = p.puppet.joints.iter().map(|j| j.parts).collect();
        joined.sort();
        let mut expected: Vec<[usize; 2]> = overlaps.iter().map(|(f, b)| [index(f), index(b)]).collect();
        expected.sort();
        assert_eq!(joined, expected, "{name}");
        Deformer::with_puppet(p.mesh, AkapOptions::default(), p.puppet, None).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}
