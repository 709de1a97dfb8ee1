//! Rigs carried from a coarse simulation mesh to a fine mesh (src/defop/carry.rs): the
//! carried pose at every fine vertex is the coarse operator's pose interpolated in the
//! coarse triangle that holds the vertex (or extrapolated from the nearest one), computed
//! here by brute force over every coarse triangle; a fine vertex at a coarse vertex gets
//! that vertex's position to the bit; a canonical operator's rigid motions of all handles
//! carry over; a poser on the fine mesh poses with it; the operator file keeps it, and
//! refuses an embedding that does not put a fine vertex where it is. Runs natively and as
//! wasm.

use std::collections::HashMap;
use std::f64::consts::PI;

use akap::defop::{
    fit, handles_on, read_operator, simulation_mesh, write_operator, BasisKind, FitError, FitOptions, MeshPoint,
    Operator, OperatorFileError, SpatialBasis,
};
use akap::deform::{AkapOptions, Deformer};
use akap::geometry::Point;
use akap::pose::Poser;
use akap::triangulate::triangulate_to_about;
use akap::{shapes, Mesh, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::Rng;
use crate::defop_fit::{diagonal, disc_targets, max_difference, samples_of, shepard_about};

/// The figure at about 3,000 vertices, its simulation mesh at about 400, and three handles
/// in fine triangles (near the head, a hand and a foot; one on a boundary triangle).
fn meshes() -> (Mesh, Mesh, Vec<MeshPoint>) {
    let options = TriangulationOptions::default();
    let (fine, _) = triangulate_to_about(&shapes::gingerbread(), 3000, &options).unwrap();
    let coarse = simulation_mesh(&fine, 400, &options).unwrap();
    let centroid = |t: usize| {
        let c = fine.triangles()[t].map(|v| fine.positions()[v as usize]);
        [(c[0][0] + c[1][0] + c[2][0]) / 3.0, (c[0][1] + c[1][1] + c[2][1]) / 3.0]
    };
    let nearest = |p: Point| {
        (0..fine.triangle_count()).min_by(|&a, &b| dist(centroid(a), p).total_cmp(&dist(centroid(b), p))).unwrap()
            as u32
    };
    let (lo, hi) = bounds(fine.positions());
    let at = |u: f64, v: f64| [lo[0] + u * (hi[0] - lo[0]), lo[1] + v * (hi[1] - lo[1])];
    let boundary = fine.triangles().iter().position(|t| t.iter().all(|&v| fine.is_boundary_vertex(v as usize)));
    let boundary = boundary.map_or_else(|| nearest(at(0.5, 0.0)), |t| t as u32);
    let handles = [nearest(at(0.5, 0.9)), nearest(at(0.05, 0.6)), boundary]
        .map(|triangle| MeshPoint::Inside { triangle, barycentric: [0.2, 0.3, 0.5] });
    (fine, coarse, handles.to_vec())
}

fn dist(a: Point, b: Point) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

fn bounds(p: &[Point]) -> (Point, Point) {
    let lo = p.iter().fold([f64::INFINITY; 2], |m, q| [m[0].min(q[0]), m[1].min(q[1])]);
    let hi = p.iter().fold([f64::NEG_INFINITY; 2], |m, q| [m[0].max(q[0]), m[1].max(q[1])]);
    (lo, hi)
}

/// The rest position of a handle on `mesh`.
fn position(mesh: &Mesh, handle: &MeshPoint) -> Point {
    match *handle {
        MeshPoint::Vertex(v) => mesh.positions()[v as usize],
        MeshPoint::Inside { triangle, barycentric: w } => {
            let c = mesh.triangles()[triangle as usize].map(|v| mesh.positions()[v as usize]);
            [0, 1].map(|k| w[0] * c[0][k] + w[1] * c[1][k] + w[2] * c[2][k])
        }
    }
}

/// A coarse operator fitted to smooth samples about the coarse handles (TPS, hat functions).
fn coarse_operator(coarse: &Mesh, handles: &[MeshPoint], canonical: bool) -> (Operator, Vec<f64>) {
    let rest: Vec<f64> = handles.iter().flat_map(|h| position(coarse, h)).collect();
    let mut rng = Rng::new(7);
    let targets = disc_targets(&mut rng, &rest, 0.2 * diagonal(coarse), 30);
    let positions: Vec<Vec<f64>> = targets.iter().map(|t| shepard_about(coarse, &rest, t)).collect();
    let options = FitOptions::default().with_kind(BasisKind::Tps).with_canonical(canonical);
    let operator =
        fit(coarse, &SpatialBasis::hat(coarse), handles, &samples_of(&targets, &positions), &options).unwrap();
    (operator, rest)
}

/// Barycentric coordinates of `p` in the triangle `c` (Cramer's rule).
fn barycentric(c: [Point; 3], p: Point) -> [f64; 3] {
    let det = (c[1][0] - c[0][0]) * (c[2][1] - c[0][1]) - (c[2][0] - c[0][0]) * (c[1][1] - c[0][1]);
    let b = ((p[0] - c[0][0]) * (c[2][1] - c[0][1]) - (c[2][0] - c[0][0]) * (p[1] - c[0][1])) / det;
    let g = ((c[1][0] - c[0][0]) * (p[1] - c[0][1]) - (p[0] - c[0][0]) * (c[1][1] - c[0][1])) / det;
    [1.0 - b - g, b, g]
}

fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let t = (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1])).clamp(0.0, 1.0);
    dist(p, [a[0] + t * d[0], a[1] + t * d[1]])
}

/// Per fine vertex, the interpolations of `coarse_pose` it may have: in the coarse triangle
/// that contains it (every one, for a point on an edge), or else extrapolated from each of
/// the nearest coarse triangles (ties to rounding: a point nearest a boundary vertex).
fn expected_poses(coarse: &Mesh, fine: &Mesh, coarse_pose: &[f64]) -> Vec<Vec<Point>> {
    let corners = |t: &[u32; 3]| t.map(|v| coarse.positions()[v as usize]);
    let interpolate = |t: &[u32; 3], w: [f64; 3]| {
        [0, 1].map(|k| (0..3).map(|i| w[i] * coarse_pose[2 * t[i] as usize + k]).sum::<f64>())
    };
    fine.positions()
        .iter()
        .map(|&p| {
            let inside: Vec<Point> = coarse
                .triangles()
                .iter()
                .filter_map(|t| {
                    let w = barycentric(corners(t), p);
                    (w.iter().all(|&x| x >= -1e-12)).then(|| interpolate(t, w))
                })
                .collect();
            if !inside.is_empty() {
                return inside;
            }
            let distance = |t: &[u32; 3]| {
                let c = corners(t);
                (0..3).map(|i| segment_distance(p, c[i], c[(i + 1) % 3])).fold(f64::INFINITY, f64::min)
            };
            let nearest = coarse.triangles().iter().map(distance).fold(f64::INFINITY, f64::min);
            coarse
                .triangles()
                .iter()
                .filter(|t| distance(t) <= nearest * (1.0 + 1e-9) + 1e-15)
                .map(|t| interpolate(t, barycentric(corners(t), p)))
                .collect()
        })
        .collect()
}

#[test]
fn a_carried_rig_poses_the_fine_mesh_as_the_coarse_pose_interpolated() {
    let (fine, coarse, handles) = meshes();
    assert!(coarse.vertex_count() < fine.vertex_count() / 4, "{} coarse vertices", coarse.vertex_count());
    let coarse_handles = handles_on(&coarse, &fine, &handles).unwrap();
    let (mut operator, rest) = coarse_operator(&coarse, &coarse_handles, false);
    let mut carried = operator.clone().carried_to(&coarse, &fine, &handles).unwrap();
    assert_eq!(carried.vertex_count(), fine.vertex_count());
    assert_eq!(carried.handles(), handles.as_slice());
    assert_eq!(carried.trained_handles(), coarse_handles.as_slice());
    let size = diagonal(&fine);
    // Some fine boundary vertices lie outside the coarse mesh (the outline simplified).
    let outside = expected_poses(&coarse, &fine, coarse.positions().as_flattened())
        .iter()
        .zip(fine.positions())
        .filter(|(e, p)| e.len() == 1 && dist(e[0], **p) > 0.0)
        .count();
    assert!(outside > 0, "no fine vertex outside the coarse mesh: extrapolation is not tested");
    let mut rng = Rng::new(3);
    for targets in disc_targets(&mut rng, &rest, 0.15 * size, 3) {
        let coarse_pose = operator.evaluate(&targets).unwrap();
        let pose = carried.evaluate(&targets).unwrap();
        for (v, choices) in expected_poses(&coarse, &fine, &coarse_pose).iter().enumerate() {
            let got = [pose[2 * v], pose[2 * v + 1]];
            let error = choices.iter().map(|&e| dist(e, got)).fold(f64::INFINITY, f64::min);
            assert!(error <= 1e-9 * size, "fine vertex {v}: {got:?}, expected one of {choices:?}");
        }
        // The single-precision copy carries the same way.
        let mut single = carried.single_precision();
        let mut out = vec![0.0f32; pose.len()];
        single.evaluate_into(&targets, &mut out).unwrap();
        let wide: Vec<f64> = out.iter().map(|&x| f64::from(x)).collect();
        assert!(max_difference(&wide, &pose) <= 1e-5 * size);
    }
    // A fine vertex exactly at a coarse vertex (the outline's points both meshes keep) gets
    // the coarse vertex's position, to the bit.
    let coarse_at: HashMap<[u64; 2], usize> =
        coarse.positions().iter().enumerate().map(|(v, p)| (p.map(f64::to_bits), v)).collect();
    let shared: Vec<(usize, usize)> = fine
        .positions()
        .iter()
        .enumerate()
        .filter_map(|(v, p)| coarse_at.get(&p.map(f64::to_bits)).map(|&c| (v, c)))
        .collect();
    assert!(shared.len() >= 10, "only {} fine vertices at coarse vertices", shared.len());
    let targets = &disc_targets(&mut rng, &rest, 0.15 * size, 1)[0];
    let (coarse_pose, pose) = (operator.evaluate(targets).unwrap(), carried.evaluate(targets).unwrap());
    for (v, c) in shared {
        assert_eq!(pose[2 * v].to_bits(), coarse_pose[2 * c].to_bits(), "fine vertex {v} at coarse vertex {c}");
        assert_eq!(pose[2 * v + 1].to_bits(), coarse_pose[2 * c + 1].to_bits());
    }
}

#[test]
fn a_carried_canonical_rig_moves_rigidly_with_all_its_handles() {
    let (fine, coarse, handles) = meshes();
    let (operator, _) = coarse_operator(&coarse, &handles_on(&coarse, &fine, &handles).unwrap(), true);
    let mut carried = operator.carried_to(&coarse, &fine, &handles).unwrap();
    let size = diagonal(&fine);
    let rest: Vec<Point> = handles.iter().map(|h| position(&fine, h)).collect();
    let mut rng = Rng::new(5);
    for _ in 0..20 {
        let (theta, t) = (PI * (2.0 * rng.unit() - 1.0), [rng.unit() - 0.5, rng.unit() - 0.5]);
        let (s, c) = theta.sin_cos();
        let motion = |p: &Point| [c * p[0] - s * p[1] + t[0], s * p[0] + c * p[1] + t[1]];
        let targets: Vec<f64> = rest.iter().flat_map(motion).collect();
        let expected: Vec<f64> = fine.positions().iter().flat_map(motion).collect();
        let error = max_difference(&carried.evaluate(&targets).unwrap(), &expected);
        assert!(error <= 1e-9 * size, "a rigid motion carried off by {error:e}");
    }
}

#[test]
fn a_poser_on_the_fine_mesh_poses_with_a_carried_rig() {
    let (fine, coarse, handles) = meshes();
    let (operator, _) = coarse_operator(&coarse, &handles_on(&coarse, &fine, &handles).unwrap(), false);
    let mut carried = operator.carried_to(&coarse, &fine, &handles).unwrap();
    let mut deformer = Deformer::new(fine.clone(), AkapOptions::default()).unwrap();
    let (triangles, barycentric): (Vec<u32>, Vec<[f64; 3]>) = handles
        .iter()
        .map(|h| match *h {
            MeshPoint::Inside { triangle, barycentric } => (triangle, barycentric),
            MeshPoint::Vertex(_) => unreachable!("handles in triangles"),
        })
        .unzip();
    deformer.set_handle_points(&triangles, &barycentric).unwrap();
    let mut poser = Poser::new(deformer);
    poser.set_rig(Some(carried.clone())).unwrap();
    assert_eq!(poser.rig_points(), Some(handles.as_slice()));
    let targets: Vec<Point> = poser.targets().enumerate().map(|(i, t)| [t[0] + 0.05 * i as f64, t[1] - 0.1]).collect();
    poser.set_targets(&targets).unwrap();
    assert_eq!(poser.advance().unwrap().steps, 1);
    let expected = carried.evaluate(targets.as_flattened()).unwrap();
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(poser.deformer().positions().as_flattened()), bits(&expected));
}

/// FNV-1a 64, the operator file's checksum.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
}

#[test]
fn the_operator_file_keeps_a_carried_rig_and_checks_its_embedding() {
    let (fine, coarse, handles) = meshes();
    let coarse_handles = handles_on(&coarse, &fine, &handles).unwrap();
    let (operator, rest) = coarse_operator(&coarse, &coarse_handles, false);
    let plain = write_operator(&coarse, &operator).unwrap();
    let mut carried = operator.carried_to(&coarse, &fine, &handles).unwrap();
    let bytes = write_operator(&fine, &carried).unwrap();
    // The coarse operator's file, then the carried section: 8 + 8 + 16 N + 12 F + 32 n + 28 N.
    let (n, f) = (fine.vertex_count(), fine.triangle_count());
    assert_eq!(bytes.len(), plain.len() + 16 + 16 * n + 12 * f + 32 * handles.len() + 28 * n);
    assert_eq!(bytes[..plain.len() - 8], plain[..plain.len() - 8]);
    let (mesh, mut read) = read_operator(&bytes).unwrap();
    assert_eq!(mesh, fine);
    assert_eq!(read.handles(), handles.as_slice());
    assert_eq!(read.carried().unwrap().mesh(), &coarse);
    let targets: Vec<f64> = rest.iter().enumerate().map(|(i, x)| x + 0.03 * (i as f64).sin()).collect();
    let bits = |x: Vec<f64>| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(read.evaluate(&targets).unwrap()), bits(carried.evaluate(&targets).unwrap()));
    // A weight altered (the checksum made right again): the vertex is no longer where its
    // coordinates put it.
    let mut altered = bytes.clone();
    let at = altered.len() - 8 - 24;
    let w = f64::from_le_bytes(altered[at..at + 8].try_into().unwrap());
    altered[at..at + 8].copy_from_slice(&(w + 0.25).to_le_bytes());
    let body = altered.len() - 8;
    let checksum = fnv1a(&altered[..body]);
    altered[body..].copy_from_slice(&checksum.to_le_bytes());
    match read_operator(&altered) {
        Err(OperatorFileError::Invalid(why)) => assert!(why.contains("fine vertex"), "{why}"),
        other => panic!("expected an invalid embedding, got {:?}", other.map(|_| ())),
    }
    // Cut short inside the carried section.
    let mut short = bytes[..bytes.len() - 8 - 100].to_vec();
    let checksum = fnv1a(&short);
    short.extend_from_slice(&checksum.to_le_bytes());
    assert!(matches!(read_operator(&short), Err(OperatorFileError::Length { .. })));
}

#[test]
fn carrying_refuses_what_does_not_fit() {
    let (fine, coarse, handles) = meshes();
    let coarse_handles = handles_on(&coarse, &fine, &handles).unwrap();
    let (operator, _) = coarse_operator(&coarse, &coarse_handles, false);
    // Handles elsewhere than those trained.
    let mut moved = handles.clone();
    moved.swap(0, 1);
    let error = operator.clone().carried_to(&coarse, &fine, &moved).unwrap_err();
    assert!(matches!(&error, FitError::Carry { reason } if reason.contains("handle 0")), "{error}");
    assert!(matches!(
        operator.clone().carried_to(&coarse, &fine, &handles[..2]),
        Err(FitError::Length { what: "carried handles", .. })
    ));
    // Another coarse mesh, and carrying twice.
    assert!(matches!(operator.clone().carried_to(&fine, &fine, &handles), Err(FitError::Length { .. })));
    let carried = operator.carried_to(&coarse, &fine, &handles).unwrap();
    assert!(matches!(carried.carried_to(&coarse, &fine, &handles), Err(FitError::Carry { .. })));
}

/// `simulation` snaps handles onto vertices of the simulation mesh: each handle that is a
/// vertex sits exactly at the fine handle's rest position, no two handles share a vertex,
/// every coarse triangle stays counter-clockwise, and a rig trained there carries back to
/// the fine mesh with the fine handles.
#[test]
fn simulation_snaps_handles_onto_its_vertices() {
    let (fine, _, handles) = meshes();
    let (coarse, placed) = akap::defop::simulation(&fine, &handles, 400, &TriangulationOptions::default()).unwrap();
    assert_eq!(placed.len(), handles.len());
    let at = |mesh: &Mesh, h: &MeshPoint| match *h {
        MeshPoint::Vertex(v) => mesh.positions()[v as usize],
        MeshPoint::Inside { triangle, barycentric } => {
            let c = mesh.triangles()[triangle as usize].map(|v| mesh.positions()[v as usize]);
            [0, 1].map(|k| barycentric[0] * c[0][k] + barycentric[1] * c[1][k] + barycentric[2] * c[2][k])
        }
    };
    let vertices: Vec<u32> =
        placed.iter().filter_map(|h| if let MeshPoint::Vertex(v) = h { Some(*v) } else { None }).collect();
    assert!(vertices.len() >= 2, "most handles snap: {placed:?}");
    let mut unique = vertices.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(unique.len(), vertices.len(), "no vertex holds two handles");
    for (h, p) in handles.iter().zip(&placed) {
        if matches!(p, MeshPoint::Vertex(_)) {
            assert_eq!(at(&coarse, p), at(&fine, h), "a snapped handle is exactly at its fine position");
        } else {
            assert!(dist(at(&coarse, p), at(&fine, h)) < 1e-9 * diagonal(&fine));
        }
    }
    for t in coarse.triangles() {
        assert!(coarse.signed_triangle_area(t) > 0.0);
    }
    // A rig trained there carries to the fine mesh with the fine handles (the carried
    // operator's checks: the handles where the coarse operator's are).
    let (operator, _) = coarse_operator(&coarse, &placed, false);
    let carried = operator.carried_to(&coarse, &fine, &handles).unwrap();
    assert_eq!((carried.vertex_count(), carried.trained_vertex_count()), (fine.vertex_count(), coarse.vertex_count()));
}
