//! The Killing matrix against the energy computed straight from its definition.

use akap::deform::killing::KillingMatrix;
use akap::geometry::Point;
use akap::shapes::ellipse;
use akap::{triangulate, Mesh, Outline, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::Rng;

fn mesh() -> Mesh {
    let outline =
        Outline::new(vec![[0.0, 0.0], [3.0, 0.0], [3.0, 1.0], [0.0, 1.0]]).with_hole(ellipse([1.5, 0.5], 0.2, 0.3, 9));
    triangulate(&outline, &TriangulationOptions::default().with_target_edge_length(0.3)).unwrap()
}

/// `sum_f A_f ||J_f + J_f^T||_F^2`, with each J_f found by solving
/// `J [p_b - p_a, p_c - p_a] = [U_b - U_a, U_c - U_a]` (no basis functions involved).
fn energy_by_definition(mesh: &Mesh, positions: &[Point], u: &[f64]) -> f64 {
    let mut total = 0.0;
    for t in mesh.triangles() {
        let [a, b, c] = t.map(|v| v as usize);
        let (e1, e2) = (
            [positions[b][0] - positions[a][0], positions[b][1] - positions[a][1]],
            [positions[c][0] - positions[a][0], positions[c][1] - positions[a][1]],
        );
        let det = e1[0] * e2[1] - e2[0] * e1[1];
        let du = |w: usize, k: usize| u[2 * w + k] - u[2 * a + k];
        // Row k of J solves J_k . e1 = du_b, J_k . e2 = du_c.
        let row = |k: usize| [(du(b, k) * e2[1] - du(c, k) * e1[1]) / det, (e1[0] * du(c, k) - e2[0] * du(b, k)) / det];
        let (r1, r2) = (row(0), row(1));
        let (ja, jb, jc, jd) = (r1[0], r1[1], r2[0], r2[1]);
        let area = 0.5 * det;
        total += area * (4.0 * ja * ja + 2.0 * (jb + jc) * (jb + jc) + 4.0 * jd * jd);
    }
    total
}

fn quadratic_form(k: &KillingMatrix, u: &[f64]) -> f64 {
    k.matrix().iter().map(|(v, (i, j))| u[i] * v * u[j]).sum()
}

#[test]
fn energy_matches_the_definition_for_random_fields_and_positions() {
    let mesh = mesh();
    let mut rng = Rng::new(17);
    let mut k = KillingMatrix::new(&mesh);
    for _ in 0..5 {
        // Move the vertices a little (keeping triangles positive) and use those positions.
        let positions: Vec<Point> = mesh
            .positions()
            .iter()
            .map(|p| [p[0] + 0.01 * (rng.unit() - 0.5), p[1] + 0.01 * (rng.unit() - 0.5)])
            .collect();
        k.assemble(&positions);
        let u: Vec<f64> = (0..2 * mesh.vertex_count()).map(|_| rng.unit() - 0.5).collect();
        let expected = energy_by_definition(&mesh, &positions, &u);
        let got = quadratic_form(&k, &u);
        assert!((got - expected).abs() <= 1e-12 * expected, "{got} vs {expected}");
    }
}

#[test]
fn rigid_fields_have_zero_energy_and_the_matrix_is_symmetric() {
    let mesh = mesh();
    let mut k = KillingMatrix::new(&mesh);
    k.assemble(mesh.positions());
    // u = a i (p - c) + d in complex notation: U1 = -a (y - cy) + d1, U2 = a (x - cx) + d2.
    let (a, c, d) = (0.7, [1.2, -0.4], [0.3, -2.0]);
    let u: Vec<f64> =
        mesh.positions().iter().flat_map(|p| [-a * (p[1] - c[1]) + d[0], a * (p[0] - c[0]) + d[1]]).collect();
    let scale: f64 = k.matrix().data().iter().map(|v| v.abs()).sum::<f64>() * u.iter().map(|x| x * x).sum::<f64>();
    assert!(quadratic_form(&k, &u).abs() <= 1e-14 * scale);
    // A uniform scaling is not Killing: its energy is 8 times the area (J = I, ||2I||^2 = 8).
    let s: Vec<f64> = mesh.positions().iter().flat_map(|p| [p[0], p[1]]).collect();
    let expected = 8.0 * mesh.area();
    assert!((quadratic_form(&k, &s) - expected).abs() <= 1e-12 * expected);

    let m = k.matrix();
    let t = m.transpose_view().to_csc();
    assert_eq!(m.indptr(), t.indptr());
    assert_eq!(m.indices(), t.indices());
    for (x, y) in m.data().iter().zip(t.data()) {
        assert!((x - y).abs() <= 1e-14 * x.abs().max(1.0));
    }
}

#[test]
fn block_slots_address_the_right_entries() {
    let mesh = mesh();
    let mut k = KillingMatrix::new(&mesh);
    k.assemble(mesh.positions());
    let [a, b] = mesh.edges().next().unwrap().map(|v| v as usize);
    let slots = k.block_slots(a, b).unwrap();
    let m = k.matrix();
    for (kc, col) in slots.iter().enumerate() {
        for (kr, &slot) in col.iter().enumerate() {
            assert_eq!(m.get(2 * a + kr, 2 * b + kc).copied(), Some(m.data()[slot]));
        }
    }
    let far = (0..mesh.vertex_count()).find(|&w| w != a && !mesh.neighbors(a).contains(&(w as u32))).unwrap();
    assert_eq!(k.block_slots(far, a), None);
}
