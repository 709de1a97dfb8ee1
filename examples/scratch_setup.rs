//! scratch
use akap::deform::{Deformer, DeformerOptions};
use akap::{shapes, triangulate, TriangulationOptions};
use std::time::Instant;
fn main() {
    let t = Instant::now();
    let mesh = triangulate(&shapes::gingerbread(), &TriangulationOptions::default().with_target_edge_length(0.0054).with_max_vertices(100000)).unwrap();
    println!("{} vertices, triangulate {:?}", mesh.vertex_count(), t.elapsed());
    let t = Instant::now();
    let n = mesh.vertex_count();
    let mut ptr = vec![0]; let mut adj = Vec::new();
    for v in 0..n { adj.extend(mesh.neighbors(v).iter().map(|&w| w as usize)); ptr.push(adj.len()); }
    let _o = akap::sparse::amf_order(n, &ptr, &adj);
    println!("amf {:?}", t.elapsed());
    let t = Instant::now();
    let _d = akap::sparse::nested_dissection_order(&ptr, &adj, mesh.positions());
    println!("nd {:?}", t.elapsed());
    let t = Instant::now();
    let _d = Deformer::new(mesh, DeformerOptions::default()).unwrap();
    println!("deformer new {:?}", t.elapsed());
}
