//! Unit tests of the fit: the structured solver equals a dense minimum-norm solve of the
//! paper's KKT system (test plan 9), and bad input is refused with typed errors.

use nalgebra::{DMatrix, DVector};

use super::*;
use crate::defop::spatial::resolve_points;
use crate::deform::DeformError;
use crate::shapes;

/// A small deterministic generator (SplitMix64) of numbers in [-1, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        2.0 * (z >> 11) as f64 / (1u64 << 53) as f64 - 1.0
    }
}

/// The paper's system (App. A) for coordinate ν, built densely and solved by the SVD
/// pseudo-inverse (minimum norm): unknowns vec X (column-major, |Φ||Ψ|), the rest
/// constraint X Ψ(P) = c_0 (20), the weak handle constraints Φ_Pᵀ X Ψ_k = q_k (21) and, for
/// a TPS, the side conditions on every row's radial weights.
fn kkt_min_norm(
    mesh: &Mesh,
    spatial: &SpatialBasis,
    handles: &[MeshPoint],
    samples: &[Sample<'_>],
    basis: &HandleBasis,
) -> [DMatrix<f64>; 2] {
    let nv = mesh.vertex_count();
    let mut a = DMatrix::zeros(nv, nv);
    for (j, column) in consistent_mass(mesh).outer_iterator().enumerate() {
        for (i, &value) in column.iter() {
            a[(i, j)] += value;
        }
    }
    let d = spatial.reduction().cloned().unwrap_or_else(|| DMatrix::identity(nv, nv));
    let (phi, len, m, n) = (d.nrows(), basis.len(), samples.len(), handles.len());
    let mm = &d * &a * d.transpose();
    let mut psi_s = DMatrix::zeros(len, m);
    for (k, s) in samples.iter().enumerate() {
        basis.evaluate_into(s.targets, psi_s.column_mut(k).as_mut_slice()).unwrap();
    }
    let b = &psi_s * psi_s.transpose();
    let hats = resolve_points(mesh, handles).unwrap();
    let phi_p = spatial.at_points(&hats);
    let rest: Vec<f64> = hats.iter().flat_map(|h| h.position(mesh)).collect();
    let mut a0 = DVector::zeros(len);
    basis.evaluate_into(&rest, a0.as_mut_slice()).unwrap();

    let unknowns = phi * len;
    let lin = basis.linear_len();
    let tps = basis.kind() == BasisKind::Tps;
    let rows = phi + n * m + if tps { phi * lin } else { 0 };
    let mut h = DMatrix::zeros(rows, unknowns);
    let at = |i: usize, j: usize| i + phi * j;
    for i in 0..phi {
        for j in 0..len {
            h[(i, at(i, j))] = a0[j];
        }
    }
    for k in 0..m {
        for l in 0..n {
            let row = phi + k * n + l;
            for i in 0..phi {
                for j in 0..len {
                    h[(row, at(i, j))] = phi_p[(i, l)] * psi_s[(j, k)];
                }
            }
        }
    }
    if tps {
        let d2 = basis.coordinate_count();
        for i in 0..phi {
            for t in 0..lin {
                let row = phi + n * m + i * lin + t;
                for (k, u) in basis.scaled_centres().chunks_exact(d2).enumerate() {
                    h[(row, at(i, lin + k))] = if t == 0 { 1.0 } else { u[t - 1] };
                }
            }
        }
    }
    let size = unknowns + rows;
    let mut kkt = DMatrix::zeros(size, size);
    for j in 0..len {
        for jj in 0..len {
            for i in 0..phi {
                for ii in 0..phi {
                    kkt[(at(i, j), at(ii, jj))] = 2.0 * b[(j, jj)] * mm[(i, ii)];
                }
            }
        }
    }
    kkt.view_mut((0, unknowns), (unknowns, rows)).copy_from(&h.transpose());
    kkt.view_mut((unknowns, 0), (rows, unknowns)).copy_from(&h);
    let svd = kkt.svd(true, true);
    let eps = 1e-11 * svd.singular_values.max();
    [0, 1].map(|nu| {
        // c_0: Dᵀ c_0 = the nodal coordinate ν.
        let coordinate = DVector::from_iterator(nv, mesh.positions().iter().map(|p| p[nu]));
        let c0 = d.transpose().svd(true, true).solve(&coordinate, 1e-12).unwrap();
        let g = DMatrix::from_fn(nv, m, |v, k| samples[k].positions[2 * v + nu]);
        let dag = &d * &a * &g * psi_s.transpose();
        let mut rhs = DVector::zeros(size);
        for j in 0..len {
            for i in 0..phi {
                rhs[at(i, j)] = 2.0 * dag[(i, j)];
            }
        }
        rhs.rows_mut(unknowns, phi).copy_from(&c0);
        for k in 0..m {
            for l in 0..n {
                rhs[unknowns + phi + k * n + l] = samples[k].targets[2 * l + nu];
            }
        }
        let solution = svd.solve(&rhs, eps).unwrap();
        DMatrix::from_fn(phi, len, |i, j| solution[at(i, j)])
    })
}

/// Test plan 9: the structured solver (strong constraint, QR with constraint elimination)
/// equals the dense KKT minimum-norm solution on small random problems, polynomial and TPS,
/// hat and reduced spatial bases, a handle at a vertex and one inside a triangle.
#[test]
fn structured_solver_equals_the_dense_kkt_minimum_norm_solution() {
    let mesh = shapes::grid_mesh(2, 2);
    let handles = [MeshPoint::Vertex(4), MeshPoint::Inside { triangle: 1, barycentric: [0.2, 0.5, 0.3] }];
    let mut rng = Rng(7);
    let extra: Vec<Vec<f64>> = (0..3).map(|_| (0..9).map(|_| rng.next()).collect()).collect();
    let spatials = [SpatialBasis::hat(&mesh), SpatialBasis::orthonormalised(&mesh, &extra).unwrap()];
    let hats = resolve_points(&mesh, &handles).unwrap();
    let rest: Vec<f64> = hats.iter().flat_map(|h| h.position(&mesh)).collect();
    for (kind, m) in [(BasisKind::Linear, 8), (BasisKind::Quadratic, 17), (BasisKind::Tps, 10)] {
        let targets: Vec<Vec<f64>> = (0..m).map(|_| rest.iter().map(|p| p + 0.4 * rng.next()).collect()).collect();
        let positions: Vec<Vec<f64>> =
            (0..m).map(|_| mesh.positions().iter().flatten().map(|p| p + 0.3 * rng.next()).collect()).collect();
        let samples: Vec<Sample<'_>> =
            targets.iter().zip(&positions).map(|(t, p)| Sample { targets: t, positions: p }).collect();
        let scale = 0.4;
        let basis = if kind == BasisKind::Tps {
            let centres: Vec<f64> = targets.iter().flatten().copied().collect();
            HandleBasis::tps(&rest, scale, &centres).unwrap()
        } else {
            HandleBasis::polynomial(kind, &rest, scale).unwrap()
        };
        for spatial in &spatials {
            let options = FitOptions::default().with_kind(kind).with_scale(scale).with_rest_sample(false);
            let operator = fit(&mesh, spatial, &handles, &samples, &options).unwrap();
            assert_eq!(operator.solver(), Solver::Structured);
            let both = kkt_min_norm(&mesh, spatial, &handles, &samples, &basis);
            for (nu, expected) in both.iter().enumerate() {
                let size = expected.amax().max(1.0);
                for i in 0..spatial.len() {
                    for j in 0..basis.len() {
                        let found = operator.coefficient(nu, i, j).unwrap();
                        assert!(
                            (found - expected[(i, j)]).abs() <= 1e-9 * size,
                            "{kind:?}, |Φ| = {}, ν = {nu}, X[{i}, {j}]: {found} vs {}",
                            spatial.len(),
                            expected[(i, j)]
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn bad_inputs_are_typed_errors() {
    let mesh = shapes::grid_mesh(3, 3);
    let hat = SpatialBasis::hat(&mesh);
    let identity: Vec<f64> = mesh.positions().iter().flatten().copied().collect();
    let handles = [MeshPoint::Vertex(0), MeshPoint::Vertex(15)];
    let targets = [0.1, 0.0, 3.0, 3.2];
    let sample = [Sample { targets: &targets, positions: &identity }];
    let options = FitOptions::default();
    let fit_with = |handles: &[MeshPoint], samples: &[Sample<'_>], options: &FitOptions| {
        fit(&mesh, &hat, handles, samples, options).map(|_| ())
    };
    assert_eq!(fit_with(&[], &sample, &options), Err(FitError::NoHandles));
    assert_eq!(
        fit_with(&[MeshPoint::Vertex(16)], &sample, &options),
        Err(FitError::InvalidHandle(DeformError::VertexOutOfRange { handle: 0, vertex: 16, vertex_count: 16 }))
    );
    assert_eq!(
        fit_with(&[MeshPoint::Inside { triangle: 18, barycentric: [1.0, 0.0, 0.0] }], &sample, &options),
        Err(FitError::InvalidHandle(DeformError::TriangleOutOfRange { handle: 0, triangle: 18, triangle_count: 18 }))
    );
    assert!(matches!(
        fit_with(&[MeshPoint::Inside { triangle: 0, barycentric: [0.5, 0.6, -0.1] }], &sample, &options),
        Err(FitError::InvalidHandle(DeformError::InvalidBarycentric { handle: 0, .. }))
    ));
    // Vertex 0 and a point of triangle 0 at its first vertex (0) coincide.
    let coincident = [MeshPoint::Vertex(0), MeshPoint::Inside { triangle: 0, barycentric: [1.0, 0.0, 0.0] }];
    assert_eq!(fit_with(&coincident, &sample, &options), Err(FitError::CoincidentHandles { first: 0, second: 1 }));
    let short = [Sample { targets: &targets[..3], positions: &identity }];
    assert_eq!(
        fit_with(&handles, &short, &options),
        Err(FitError::Length { what: "sample targets", expected: 4, found: 3 })
    );
    let nan = [0.1, f64::NAN, 3.0, 3.2];
    let bad = [Sample { targets: &nan, positions: &identity }];
    assert_eq!(fit_with(&handles, &bad, &options), Err(FitError::NonFinite { what: "sample targets", index: 1 }));
    // A quadratic basis in 4 coordinates has 15 functions: 2 samples (with the rest pose)
    // are too few without a ridge; with one, the 5 linear functions need 5 samples.
    let quadratic = FitOptions::default().with_kind(BasisKind::Quadratic);
    assert_eq!(fit_with(&handles, &sample, &quadratic), Err(FitError::TooFewSamples { samples: 2, basis_size: 15 }));
    let ridge = quadratic.clone().with_regularisation(1e-3);
    assert_eq!(fit_with(&handles, &sample, &ridge), Err(FitError::TooFewSamples { samples: 2, basis_size: 5 }));
    let more: Vec<Vec<f64>> = (1..5)
        .map(|k| targets.iter().enumerate().map(|(a, t)| t + 0.1 * (1.7 * k as f64 * (a + 1) as f64).sin()).collect())
        .collect();
    let five: Vec<Sample<'_>> =
        more.iter().map(|t| Sample { targets: t, positions: &identity }).chain(sample).collect();
    assert_eq!(fit_with(&handles, &five, &ridge), Ok(()));
    assert!(matches!(
        fit_with(&handles, &sample, &quadratic.with_regularisation(-1.0)),
        Err(FitError::InvalidOption { name: "regularisation", .. })
    ));
    // Linear basis: 5 functions; five copies of one sample do not determine it.
    let linear = FitOptions::default().with_kind(BasisKind::Linear);
    let repeated = [sample[0]; 5];
    assert_eq!(fit_with(&handles, &repeated, &linear), Err(FitError::Singular { what: "samples" }));
    assert_eq!(fit_with(&handles, &[], &options.clone().with_rest_sample(false)), Err(FitError::NoSamples));
    assert!(matches!(
        fit_with(&handles, &sample, &options.with_scale(-1.0)),
        Err(FitError::InvalidOption { name: "scale", .. })
    ));

    // The operator refuses bad targets and buffers.
    let mut operator = fit(&mesh, &hat, &handles, &five, &FitOptions::default()).unwrap();
    let mut out = vec![0.0; 32];
    assert_eq!(
        operator.evaluate_into(&[0.0; 3], &mut out),
        Err(FitError::Length { what: "targets", expected: 4, found: 3 })
    );
    assert_eq!(
        operator.evaluate_into(&[0.0, 0.0, f64::INFINITY, 0.0], &mut out),
        Err(FitError::NonFinite { what: "targets", index: 2 })
    );
    assert!(matches!(operator.evaluate_into(&targets, &mut out[..30]), Err(FitError::Length { what: "output", .. })));
    let mut single = vec![0.0f32; 32];
    assert!(operator.evaluate_into_f32(&targets, &mut single).is_ok());
    operator.evaluate_into(&targets, &mut out).unwrap();
    assert!(out.iter().zip(&single).all(|(a, b)| (a - *b as f64).abs() <= 1e-6 * a.abs().max(1.0)));
    assert_eq!(operator.coefficient(2, 0, 0), None);
}
