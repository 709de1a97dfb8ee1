//! Mesh tests on a shape of `shapes` (the unit tests in `src/mesh.rs` build their meshes
//! by hand: the mesh module imports nothing above it, not even in its tests).

use akap::shapes::grid_mesh;
use akap::Mesh;
// On wasm32 the same tests run under wasm-bindgen-test in Node.
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

#[test]
fn boundary_loops_follow_the_outline_and_each_hole() {
    // A 3 x 3 grid without its middle square: the outer loop of 12 vertices and the
    // hole's 4, each a cycle of boundary edges.
    let grid = grid_mesh(3, 3);
    let triangles: Vec<[u32; 3]> =
        grid.triangles().iter().enumerate().filter(|(t, _)| *t / 2 != 4).map(|(_, t)| *t).collect();
    let mesh = Mesh::new(grid.positions().to_vec(), triangles).unwrap();
    let mut loops = mesh.boundary_loops();
    loops.sort_by_key(Vec::len);
    assert_eq!(loops.iter().map(Vec::len).collect::<Vec<_>>(), vec![4, 12]);
    let mut hole = loops[0].clone();
    hole.sort();
    assert_eq!(hole, vec![5, 6, 9, 10]);
    for ring in &loops {
        for (k, &v) in ring.iter().enumerate() {
            let w = ring[(k + 1) % ring.len()];
            assert!(mesh.boundary_edges().contains(&[v, w]), "{v} -> {w}");
        }
    }
}
