//! A trained operator on the GPU (src/defop/gpu.rs): the basis texture and the frame, read
//! as the vertex shader reads them (`www/src/widget/view/gl-renderer.ts`), give every
//! vertex's position within the rounding bound of single precision of the double
//! evaluation, for the hat and a reduced basis, with and without canonical coordinates; the
//! watched vertices' positions are the single-precision copy's to the bit; bad targets are
//! refused, leaving the frame as it was. The shader itself is checked against the double
//! evaluation in Chromium (`tests/browser/rig-gpu.spec.ts`). Runs natively and as wasm.

use akap::defop::gpu::{basis_texture, RIGID_TEXELS, TEXEL};
use akap::defop::{fit, BasisKind, FitOptions, GpuLayout, GpuRig, Operator, SpatialBasis};
use akap::Mesh;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::Rng;
use crate::defop_fit::{disc_targets, grid, rest_of, samples_of, shepard, vertex_handles};

/// For each coordinate of each vertex, the sum of the magnitudes of the terms of the triple
/// sum `Σ_i D_iv Σ_j X_ij ψ_j(Q̂)` at the (canonical) targets: the scale of its rounding.
fn scales(operator: &Operator, spatial: &SpatialBasis, targets: &[f64]) -> Vec<f64> {
    let basis = operator.handle_basis();
    let mut at = targets.to_vec();
    basis.coordinates().canonicalise(targets, &mut at);
    let mut psi = vec![0.0; basis.len()];
    basis.evaluate_into(&at, &mut psi).unwrap();
    let n = operator.vertex_count();
    let mut out = vec![0.0; 2 * n];
    for nu in 0..2 {
        let nodal: Vec<f64> = (0..operator.spatial_len())
            .map(|i| psi.iter().enumerate().map(|(j, p)| (operator.coefficient(nu, i, j).unwrap() * p).abs()).sum())
            .collect();
        for v in 0..n {
            out[2 * v + nu] = match spatial.reduction() {
                None => nodal[v],
                Some(d) => nodal.iter().enumerate().map(|(i, s)| d[(i, v)].abs() * s).sum(),
            };
        }
    }
    out
}

/// Vertex `v`'s position as the shader forms it from the texture and the frame, here in
/// double precision (so only the numbers' rounding to `f32` shows), and the size of the
/// rigid motion's terms `|p̂| + |from| + |to|` per coordinate.
fn shader_position(layout: &GpuLayout, texture: &[f32], frame: &[f32], v: usize) -> ([f64; 2], f64) {
    let texel = |data: &[f32], t: usize| -> [f64; 4] { std::array::from_fn(|k| f64::from(data[TEXEL * t + k])) };
    let dot = |a: [f64; 4], b: [f64; 4]| (0..4).map(|k| a[k] * b[k]).sum::<f64>();
    let (mut x, mut y) = (0.0, 0.0);
    for t in 0..layout.terms {
        x += dot(texel(texture, v * layout.stride + t), texel(frame, RIGID_TEXELS + t));
        y += dot(
            texel(texture, v * layout.stride + layout.basis_y + t),
            texel(frame, RIGID_TEXELS + layout.frame_y + t),
        );
    }
    let ([cos, sin, fx, fy], [tx, ty, _, _]) = (texel(frame, 0), texel(frame, 1));
    let (dx, dy) = (x - fx, y - fy);
    let size = x.abs().max(y.abs()) + fx.abs().max(fy.abs()) + tx.abs().max(ty.abs());
    ([cos * dx - sin * dy + tx, sin * dx + cos * dy + ty], size)
}

fn spatial_bases(mesh: &Mesh) -> Vec<SpatialBasis> {
    let extra: Vec<Vec<f64>> = (1..11)
        .map(|k| {
            mesh.positions().iter().map(|p| (0.6 * k as f64 * p[0] - 0.25 * p[1] * p[1] / k as f64).cos()).collect()
        })
        .collect();
    vec![SpatialBasis::hat(mesh), SpatialBasis::orthonormalised(mesh, &extra).unwrap()]
}

#[test]
fn the_shaders_sums_over_texture_and_frame_give_the_operators_pose_to_single_precision() {
    let (mesh, vertices) = grid();
    let handles = vertex_handles(&vertices);
    let rest = rest_of(&mesh, &vertices);
    let mut rng = Rng::new(36);
    let targets = disc_targets(&mut rng, &rest, 0.6, 100);
    let positions: Vec<Vec<f64>> = targets.iter().map(|t| shepard(&mesh, &vertices, t)).collect();
    let samples = samples_of(&targets, &positions);
    let queries = disc_targets(&mut rng, &rest, 1.5, 6);
    let n = mesh.vertex_count();
    let eps = f64::from(f32::EPSILON);
    for spatial in spatial_bases(&mesh) {
        for kind in [BasisKind::Quadratic, BasisKind::Cubic, BasisKind::Tps] {
            for canonical in [false, true] {
                let options = FitOptions::default().with_kind(kind).with_canonical(canonical);
                let mut operator = fit(&mesh, &spatial, &handles, &samples, &options).unwrap();
                let what = format!("{kind:?}, |Φ| = {}, canonical {canonical}", spatial.len());
                // The layout, from the sizes alone.
                let layout = GpuLayout::of(&operator);
                let (k, len) = (spatial.len(), operator.handle_basis().len());
                let reduced = spatial.reduction().is_some();
                let terms = if reduced { k.div_ceil(4) } else { len.div_ceil(4) };
                assert_eq!(layout.terms, terms, "{what}");
                assert_eq!(layout.stride, if reduced { terms } else { 2 * terms }, "{what}");
                assert_eq!(layout.frame_texels, 2 + if reduced { 2 * terms } else { terms }, "{what}");
                let texture = basis_texture(&operator);
                assert_eq!(texture.len(), 4 * n * layout.stride, "{what}");

                let mut gpu = GpuRig::new(&operator);
                let watched: Vec<u32> = (0..n as u32).step_by(3).collect();
                gpu.watch(&operator, &watched).unwrap();
                let mut copy = operator.single_precision();
                let mut single = vec![0.0f32; 2 * n];
                // Every term carries the rounding of its coefficient, ψ_j and D_iv; the
                // sums of the frame and the shader add theirs (Higham §3.1, k ε per sum of
                // k terms); the rigid motion rounds a few times its terms' size.
                let sum_terms = (len + if reduced { k } else { 0 }) as f64;
                for q in &queries {
                    let expected = operator.evaluate(q).unwrap();
                    let scale = scales(&operator, &spatial, q);
                    let frame = gpu.frame(q).unwrap().to_vec();
                    for v in 0..n {
                        let (found, size) = shader_position(&layout, &texture, &frame, v);
                        for nu in 0..2 {
                            let bound = 2.0 * (sum_terms + 6.0) * eps * scale[2 * v + nu] + 8.0 * eps * size;
                            let error = (found[nu] - expected[2 * v + nu]).abs();
                            assert!(
                                error <= bound,
                                "{what}: vertex {v}, coordinate {nu} off by {error:e} (bound {bound:e})"
                            );
                        }
                    }
                    copy.evaluate_into(q, &mut single).unwrap();
                    let watched_positions = gpu.watched_positions();
                    for &v in &watched {
                        let v = v as usize;
                        for nu in 0..2 {
                            assert_eq!(
                                watched_positions[2 * v + nu],
                                f64::from(single[2 * v + nu]),
                                "{what}: watched vertex {v}"
                            );
                        }
                    }
                }
                // Bad targets change nothing.
                let before = gpu.frame_values().to_vec();
                assert!(gpu.frame(&rest[1..]).is_err(), "{what}");
                let mut nan = rest.clone();
                nan[2] = f64::NAN;
                assert!(gpu.frame(&nan).is_err(), "{what}");
                assert_eq!(gpu.frame_values(), &before[..], "{what}");
                assert!(gpu.watch(&operator, &[0, n as u32]).is_err(), "{what}");
                assert_eq!(gpu.watched(), &watched[..], "{what}");
            }
        }
    }
}

#[test]
fn the_rest_frame_poses_the_rest_mesh() {
    // At the rest targets the operator is the identity: the frame read through the texture
    // gives the rest positions (an independent check of the layout: no operator evaluated).
    let (mesh, vertices) = grid();
    let handles = vertex_handles(&vertices);
    let rest = rest_of(&mesh, &vertices);
    let mut rng = Rng::new(7);
    let targets = disc_targets(&mut rng, &rest, 0.5, 100);
    let positions: Vec<Vec<f64>> = targets.iter().map(|t| shepard(&mesh, &vertices, t)).collect();
    let samples = samples_of(&targets, &positions);
    for spatial in spatial_bases(&mesh) {
        let options = FitOptions::default().with_kind(BasisKind::Cubic);
        let operator = fit(&mesh, &spatial, &handles, &samples, &options).unwrap();
        let layout = GpuLayout::of(&operator);
        let texture = basis_texture(&operator);
        let mut gpu = GpuRig::new(&operator);
        let frame = gpu.frame(&rest).unwrap().to_vec();
        for (v, p) in mesh.positions().iter().enumerate() {
            let (found, _) = shader_position(&layout, &texture, &frame, v);
            for nu in 0..2 {
                assert!((found[nu] - p[nu]).abs() <= 1e-4, "vertex {v}: {found:?} against {p:?}");
            }
        }
    }
}
