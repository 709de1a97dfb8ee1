//! Deformation-operator evaluation (src/defop/operator.rs on the blocked kernels of
//! src/defop/kernels.rs): for every handle basis, with hat functions and with a reduced
//! spatial basis, and at sizes that leave remainders in every block, the positions equal the
//! triple sum `Σ_i D_iv Σ_j X^ν_ij ψ_j(Q)` over the operator's own coefficients, summed
//! here in plain order, to rounding; the single-precision output is the double one rounded;
//! the single-precision copy (`Operator::single_precision`) is within its rounding bound
//! and within 1e-5 of the bounding-box diagonal (test plan 13).
//! Runs natively and as wasm (where the kernels are simd128).

use akap::defop::{fit, BasisKind, FitOptions, MeshPoint, Operator, Sample, SpatialBasis};
use akap::{shapes, Mesh};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::Rng;

/// The positions of the triple sum over the operator's coefficients, and for each the sum
/// of the magnitudes of its terms (the scale of its rounding error).
fn triple_sum(operator: &Operator, spatial: &SpatialBasis, targets: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let basis = operator.handle_basis();
    let mut psi = vec![0.0; basis.len()];
    basis.evaluate_into(targets, &mut psi).unwrap();
    let n = operator.vertex_count();
    let (mut out, mut scale) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
    for nu in 0..2 {
        let mut nodal = Vec::new();
        for i in 0..operator.spatial_len() {
            let (mut sum, mut size) = (0.0, 0.0);
            for (j, p) in psi.iter().enumerate() {
                let term = operator.coefficient(nu, i, j).unwrap() * p;
                sum += term;
                size += term.abs();
            }
            nodal.push((sum, size));
        }
        for v in 0..n {
            (out[2 * v + nu], scale[2 * v + nu]) = match spatial.reduction() {
                None => nodal[v],
                Some(d) => nodal
                    .iter()
                    .enumerate()
                    .fold((0.0, 0.0), |(s, m), (i, (x, size))| (s + d[(i, v)] * x, m + d[(i, v)].abs() * size)),
            };
        }
    }
    (out, scale)
}

#[test]
fn evaluation_equals_the_triple_sum_of_its_coefficients() {
    // 7 × 5 = 35 vertices and 3 handles: |Ψ| = 7 (linear), 28 (quadratic), 84 (cubic) and
    // 7 + 23 (TPS on 22 samples and the rest pose); |Φ| = 35 or 3 + 6 = 9.
    let mesh: Mesh = shapes::grid_mesh(6, 4);
    let extent = |c: usize| {
        let values = mesh.positions().iter().map(|p| p[c]);
        values.clone().fold(f64::NEG_INFINITY, f64::max) - values.fold(f64::INFINITY, f64::min)
    };
    let size = extent(0).hypot(extent(1)); // the bounding-box diagonal
    let handles = [8usize, 12, 31];
    let rest: Vec<f64> = handles.iter().flat_map(|&v| mesh.positions()[v]).collect();
    let mut rng = Rng::new(11);
    let targets: Vec<Vec<f64>> = (0..90).map(|_| rest.iter().map(|p| p + 0.8 * (rng.unit() - 0.5)).collect()).collect();
    let positions: Vec<Vec<f64>> = targets
        .iter()
        .map(|q| {
            let s: f64 = q.iter().zip(&rest).enumerate().map(|(a, (q, p))| (0.4 + 0.1 * a as f64) * (q - p)).sum();
            mesh.positions().iter().flat_map(|x| [x[0] + 0.3 * (s + x[1]).sin(), x[1] + 0.2 * s * s * x[0]]).collect()
        })
        .collect();
    let points: Vec<MeshPoint> = handles.iter().map(|&v| MeshPoint::Vertex(v as u32)).collect();
    let extra: Vec<Vec<f64>> =
        (1..7).map(|k| mesh.positions().iter().map(|p| (0.9 * k as f64 * p[0] - 0.4 * p[1]).cos()).collect()).collect();
    let queries: Vec<Vec<f64>> = (0..5).map(|_| rest.iter().map(|p| p + 2.0 * (rng.unit() - 0.5)).collect()).collect();
    for spatial in [SpatialBasis::hat(&mesh), SpatialBasis::orthonormalised(&mesh, &extra).unwrap()] {
        for (kind, count) in
            [(BasisKind::Linear, 90), (BasisKind::Quadratic, 90), (BasisKind::Cubic, 90), (BasisKind::Tps, 22)]
        {
            let samples: Vec<Sample<'_>> =
                targets[..count].iter().zip(&positions).map(|(t, p)| Sample { targets: t, positions: p }).collect();
            let options = FitOptions::default().with_kind(kind);
            let mut operator = fit(&mesh, &spatial, &points, &samples, &options).unwrap();
            let mut single = vec![0.0f32; 2 * mesh.vertex_count()];
            let mut copy = operator.single_precision();
            let mut copied = vec![0.0f32; 2 * mesh.vertex_count()];
            for q in &queries {
                let found = operator.evaluate(q).unwrap();
                let (expected, scale) = triple_sum(&operator, &spatial, q);
                // Each sum of k terms is within about k ε of the sum of their magnitudes
                // (Higham, Accuracy and Stability of Numerical Algorithms, §3.1); the two
                // stages add their bounds.
                let terms = (operator.handle_basis().len() + operator.spatial_len()) as f64;
                for (v, ((f, e), s)) in found.iter().zip(&expected).zip(&scale).enumerate() {
                    let bound = 2.0 * (terms + 2.0) * f64::EPSILON * s;
                    assert!(
                        (f - e).abs() <= bound,
                        "{kind:?}, |Φ| = {}: position {v} is {f}, the triple sum {e} (bound {bound})",
                        spatial.len()
                    );
                }
                operator.evaluate_into_f32(q, &mut single).unwrap();
                let rounded: Vec<f32> = found.iter().map(|&x| x as f32).collect();
                assert_eq!(single, rounded, "{kind:?}, |Φ| = {}", spatial.len());
                // In single precision each term also carries the rounding of its coefficient,
                // of ψ_j and of D_iv: a few ε_32 more per term.
                copy.evaluate_into(q, &mut copied).unwrap();
                for (v, ((f, e), s)) in copied.iter().zip(&expected).zip(&scale).enumerate() {
                    let error = (f64::from(*f) - e).abs();
                    let bound = 2.0 * (terms + 6.0) * f64::from(f32::EPSILON) * s;
                    assert!(
                        error <= bound && error <= 1e-5 * size,
                        "{kind:?}, |Φ| = {}: single-precision position {v} is {f}, the triple sum {e} \
                         (bound {bound}, diagonal {size})",
                        spatial.len()
                    );
                }
            }
        }
    }
}
