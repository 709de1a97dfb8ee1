//! The Killing matrix against the energy computed straight from its definition.

use akap::deform::akap::killing::KillingMatrix;
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

/// `sum_f |A_f| ||J_f + J_f^T||_F^2`, with each J_f found by solving
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
        // The integral over the triangle: its unsigned area, also when it is flipped.
        let area = 0.5 * det.abs();
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
    let u = rigid_field(mesh.positions(), a, c, d);
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

/// A rigid field `a i (p - c) + d` at the given positions, interleaved.
fn rigid_field(positions: &[Point], a: f64, c: Point, d: [f64; 2]) -> Vec<f64> {
    positions.iter().flat_map(|p| [-a * (p[1] - c[1]) + d[0], a * (p[0] - c[0]) + d[1]]).collect()
}

#[test]
fn flipped_triangles_count_with_their_unsigned_area() {
    // Large random moves flip triangles; the energy is still the integral of a square, so
    // it must match the definition with |A| and never be negative.
    let mesh = mesh();
    let mut rng = Rng::new(406);
    let mut k = KillingMatrix::new(&mesh);
    let signed = |p: &[Point], t: &[u32; 3]| {
        let [a, b, c] = t.map(|v| p[v as usize]);
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let mut flipped_poses = 0;
    for _ in 0..10 {
        let positions: Vec<Point> = mesh
            .positions()
            .iter()
            .map(|p| [p[0] + 0.3 * (rng.unit() - 0.5), p[1] + 0.3 * (rng.unit() - 0.5)])
            .collect();
        if mesh.triangles().iter().any(|t| signed(&positions, t) < 0.0) {
            flipped_poses += 1;
        }
        k.assemble(&positions);
        for _ in 0..5 {
            let u: Vec<f64> = (0..2 * mesh.vertex_count()).map(|_| rng.unit() - 0.5).collect();
            let expected = energy_by_definition(&mesh, &positions, &u);
            let got = quadratic_form(&k, &u);
            assert!(got >= 0.0, "negative energy {got}");
            assert!((got - expected).abs() <= 1e-10 * expected, "{got} vs {expected}");
        }
    }
    assert!(flipped_poses >= 5, "only {flipped_poses} poses had flipped triangles");
}

#[test]
fn collapsed_triangles_keep_the_matrix_finite_and_rigid_fields_free() {
    // A vertex on the line through two others (a sliver of zero area), two vertices at one
    // place, and a whole triangle collapsed to a point: the energy of those triangles grows
    // without bound as they collapse, so assembly must bound it and stay finite, and a rigid
    // field, whose Jacobian is antisymmetric on any triangle, must still cost nothing.
    let mesh = mesh();
    let rest = mesh.positions();
    let interior = |t: &[u32; 3]| t.iter().all(|&v| !mesh.is_boundary_vertex(v as usize));
    let t = *mesh.triangles().iter().find(|t| interior(t)).unwrap();
    let [a, b, c] = t.map(|v| v as usize);
    let mut rng = Rng::new(3);
    for pose in 0..3 {
        let mut positions = rest.to_vec();
        match pose {
            0 => positions[a] = [0.5 * (rest[b][0] + rest[c][0]), 0.5 * (rest[b][1] + rest[c][1])],
            1 => positions[a] = rest[b],
            _ => (positions[a], positions[c]) = (rest[b], rest[b]),
        }
        let mut k = KillingMatrix::new(&mesh);
        k.assemble(&positions);
        assert!(k.matrix().data().iter().all(|v| v.is_finite()), "pose {pose}");
        let u = rigid_field(&positions, 0.7, [1.2, -0.4], [0.3, -2.0]);
        let scale: f64 = k.matrix().data().iter().map(|v| v.abs()).sum::<f64>() * u.iter().map(|x| x * x).sum::<f64>();
        assert!(quadratic_form(&k, &u).abs() <= 1e-14 * scale, "pose {pose}");
        for _ in 0..5 {
            let u: Vec<f64> = (0..2 * mesh.vertex_count()).map(|_| rng.unit() - 0.5).collect();
            assert!(quadratic_form(&k, &u) >= -1e-14 * scale, "pose {pose}");
        }
    }
}
