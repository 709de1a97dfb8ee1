//! Operator files: a trained operator written and read back poses its mesh to the same bits
//! (hat and reduced spatial bases, polynomial and TPS handle bases, canonical coordinates,
//! fixed handles) and keeps its training's settings (version 4); in single precision its
//! numbers are the f32 roundings of the operator's; files of versions 1, 2 and 3, written
//! by those versions' writers, still read; a truncated, extended or altered file, or a
//! header field no writer writes, is refused with an error, never a panic. Runs natively
//! and as wasm.

use akap::defop::sampling::Sampling;
use akap::defop::{
    read_operator, write_operator, write_operator_in, BasisKind, Energy, MeshPoint, Operator, OperatorFileError,
    Precision, TrainOptions, Trainer, Training,
};
use akap::shapes::toothed_bar;
use akap::{triangulate, Mesh, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

fn bar() -> Mesh {
    triangulate(&toothed_bar(), &TriangulationOptions::default().with_target_edge_length(0.2)).unwrap()
}

fn frozen() -> f64 {
    0.0
}

fn trained(mesh: &Mesh, basis: BasisKind, spatial: usize) -> Operator {
    trained_with(mesh, TrainOptions { basis, spatial, ..TrainOptions::default() })
}

/// An ARAP operator of 16 samples with `options`' basis, spatial basis and coordinates.
fn trained_with(mesh: &Mesh, options: TrainOptions) -> Operator {
    let handles = [MeshPoint::Vertex(0), MeshPoint::Inside { triangle: 5, barycentric: [0.5, 0.25, 0.25] }];
    let options = TrainOptions { energy: Energy::Arap, samples: 16, seed: 2, ..options };
    let mut trainer = Trainer::new(mesh, &handles, options).unwrap();
    trainer.advance(f64::INFINITY, frozen).unwrap();
    trainer.finish().unwrap()
}

/// Targets around the handles' rest positions.
fn queries(operator: &Operator) -> Vec<Vec<f64>> {
    let rest = operator.handle_basis().rest().to_vec();
    (0..5).map(|k| rest.iter().enumerate().map(|(i, x)| x + 0.1 * ((k * 7 + i) as f64).sin()).collect()).collect()
}

#[test]
fn operators_read_back_pose_to_the_same_bits() {
    let mesh = bar();
    for (basis, spatial) in [(BasisKind::Tps, 0), (BasisKind::Quadratic, 0), (BasisKind::Tps, 12)] {
        let mut operator = trained(&mesh, basis, spatial);
        let bytes = write_operator(&mesh, &operator).unwrap();
        let (read_mesh, mut read) = read_operator(&bytes).unwrap();
        assert_eq!(read_mesh, mesh);
        for q in queries(&operator) {
            assert_eq!(read.evaluate(&q).unwrap(), operator.evaluate(&q).unwrap(), "{basis:?}, spatial {spatial}");
        }
        assert_eq!(write_operator(&read_mesh, &read).unwrap(), bytes, "written again, the same bytes");
    }
}

#[test]
fn canonical_and_fixed_operators_read_back_pose_to_the_same_bits() {
    let mesh = bar();
    let canonical = TrainOptions { canonical: true, ..TrainOptions::default() };
    let fixed = TrainOptions { fixed: vec![1], basis: BasisKind::Quadratic, ..TrainOptions::default() };
    for options in [canonical, fixed] {
        let what = format!("canonical {}, fixed {:?}", options.canonical, options.fixed);
        let mut operator = trained_with(&mesh, options);
        let bytes = write_operator(&mesh, &operator).unwrap();
        assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 4, "version 4 is written");
        let (_, mut read) = read_operator(&bytes).unwrap();
        assert_eq!(read.handle_basis(), operator.handle_basis(), "{what}");
        for q in queries(&operator) {
            assert_eq!(read.evaluate(&q).unwrap(), operator.evaluate(&q).unwrap(), "{what}");
        }
        assert_eq!(write_operator(&mesh, &read).unwrap(), bytes, "{what}: written again, the same bytes");
    }
}

/// `tests/fixtures/defop-v1-linear.defop` was written by the version-1 writer (commit
/// 49b8b23): a linear operator on the 2 × 2 grid with handles at vertices 0, (0, 0), and 8,
/// (2, 2), fitted with hat functions to the ground truth g(x, Q) = x + (1 − w)(q_0 − p_0) +
/// w (q_1 − p_1), w = (x + y) / 4, which lies in its span: the operator is g exactly.
#[test]
fn a_version_1_file_still_reads() {
    let bytes = include_bytes!("fixtures/defop-v1-linear.defop");
    assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 1);
    let (mesh, mut operator) = read_operator(bytes).unwrap();
    assert_eq!(mesh, akap::shapes::grid_mesh(2, 2));
    assert_eq!(operator.handle_basis().kind(), BasisKind::Linear);
    assert!(!operator.handle_basis().coordinates().is_canonical());
    let truth = |q: &[f64]| -> Vec<f64> {
        mesh.positions()
            .iter()
            .flat_map(|x| {
                let w = (x[0] + x[1]) / 4.0;
                [x[0] + (1.0 - w) * q[0] + w * (q[2] - 2.0), x[1] + (1.0 - w) * q[1] + w * (q[3] - 2.0)]
            })
            .collect()
    };
    for q in [[0.0, 0.0, 2.0, 2.0], [0.3, -0.2, 2.5, 1.1], [-4.0, 7.0, 3.0, -9.0]] {
        let error =
            operator.evaluate(&q).unwrap().iter().zip(truth(&q)).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(error < 1e-12 * (1.0 + q.iter().map(|x| x.abs()).fold(0.0, f64::max)), "{q:?}: off by {error:e}");
    }
    // Written again: version 4 (the training not known), the same operator.
    let again = write_operator(&mesh, &operator).unwrap();
    assert_eq!(u32::from_le_bytes(again[8..12].try_into().unwrap()), 4);
    assert_eq!(read_operator(&again).unwrap().1.training(), None);
    let (_, mut read) = read_operator(&again).unwrap();
    let q = [0.3, -0.2, 2.5, 1.1];
    assert_eq!(read.evaluate(&q).unwrap(), operator.evaluate(&q).unwrap());
    // Version 1 has zeros where version 2 has the coordinates' fields.
    let mut odd = bytes.to_vec();
    odd[35] = 1;
    assert_eq!(read_operator(&odd).unwrap_err(), OperatorFileError::Field { what: "reserved bytes" });
}

#[test]
fn damaged_files_are_refused() {
    let mesh = bar();
    let operator = trained(&mesh, BasisKind::Tps, 0);
    let bytes = write_operator(&mesh, &operator).unwrap();
    // Every prefix of a few lengths, one byte more, and single flipped bits throughout.
    for cut in [0, 7, 8, 11, 12, 30, 47, 48, 55, 79, 80, 87, 88, 100, bytes.len() / 2, bytes.len() - 8, bytes.len() - 1]
    {
        assert!(read_operator(&bytes[..cut]).is_err(), "{cut} bytes read");
    }
    let mut longer = bytes.clone();
    longer.push(0);
    assert!(matches!(read_operator(&longer), Err(OperatorFileError::Length { .. })));
    let single = write_operator_in(&mesh, &operator, Precision::Single).unwrap();
    for file in [&bytes, &single] {
        for at in (0..file.len()).step_by(13) {
            let mut altered = file.clone();
            altered[at] ^= 0x10;
            assert!(read_operator(&altered).is_err(), "a flip at byte {at} was not noticed");
        }
        for cut in [80, 88, file.len() / 3, file.len() - 9] {
            assert!(read_operator(&file[..cut]).is_err(), "{cut} bytes read");
        }
    }
    let mut future = bytes.clone();
    future[8] = 5;
    assert_eq!(read_operator(&future).unwrap_err(), OperatorFileError::Version { found: 5 });
    let message = read_operator(&future).unwrap_err().to_string();
    assert!(message.contains("version 5") && message.contains("newer"), "{message}");
    future[8] = 0;
    assert_eq!(read_operator(&future).unwrap_err(), OperatorFileError::Version { found: 0 });
    assert_eq!(read_operator(b"PNG\x0d\x0a").unwrap_err(), OperatorFileError::NotAnOperator);
    let other = akap::shapes::grid_mesh(3, 3);
    assert!(write_operator(&other, &operator).is_err(), "an operator is written with its own mesh");
}

/// FNV-1a 64, written here from its definition (offset basis 0xcbf29ce484222325, prime
/// 0x100000001b3), to re-seal a file whose header a test changed.
fn sealed(mut bytes: Vec<u8>) -> Vec<u8> {
    let body = bytes.len() - 8;
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in &bytes[..body] {
        h = (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
    }
    bytes[body..].copy_from_slice(&h.to_le_bytes());
    bytes
}

#[test]
fn a_version_4_file_keeps_the_training() {
    let mesh = bar();
    for (sampling, spatial) in [(Sampling::Voronoi, 0), (Sampling::Mixed, 12), (Sampling::Disc, 0)] {
        let options = TrainOptions { sampling, spatial, radius: Some(0.37), ..TrainOptions::default() };
        let operator = trained_with(&mesh, options);
        // trained_with: ARAP, 16 samples, seed 2.
        let training = Training { energy: Energy::Arap, sampling, samples: 16, radius: 0.37, seed: 2 };
        assert_eq!(operator.training(), Some(&training));
        let bytes = write_operator(&mesh, &operator).unwrap();
        // The header as the layout says: version 4, double, no puppet, the training known.
        assert_eq!(bytes[8..12], [4, 0, 0, 0]);
        assert_eq!(bytes[48..53], [0, 0, 1, 1, [0, 1, 2][sampling as usize]]);
        assert_eq!(u32::from_le_bytes(bytes[56..60].try_into().unwrap()), 16);
        assert_eq!(u64::from_le_bytes(bytes[64..72].try_into().unwrap()), 2);
        assert_eq!(f64::from_le_bytes(bytes[72..80].try_into().unwrap()), 0.37);
        let (_, read) = read_operator(&bytes).unwrap();
        assert_eq!(read.training(), Some(&training));
        assert_eq!(write_operator(&mesh, &read).unwrap(), bytes);
    }
    // Without a training (an operator fitted directly): byte 50 is 0 and 51..80 are zeros.
    let operator = trained(&mesh, BasisKind::Linear, 0).with_training(None);
    let bytes = write_operator(&mesh, &operator).unwrap();
    assert!(bytes[48..80].iter().all(|&b| b == 0));
    assert_eq!(read_operator(&bytes).unwrap().1.training(), None);
    // A training a file cannot keep is refused on writing.
    let bad = Training { energy: Energy::SArap, sampling: Sampling::Disc, samples: 0, radius: 1.0, seed: 0 };
    assert!(write_operator(&mesh, &operator.clone().with_training(Some(bad))).is_err());
    let bad = Training { samples: 5, radius: f64::NAN, ..bad };
    assert!(write_operator(&mesh, &operator.with_training(Some(bad))).is_err());
}

#[test]
fn the_regions_an_operator_reports_hold_every_target_its_training_drew_and_its_file_keeps_them() {
    let mesh = bar();
    let handles = [MeshPoint::Vertex(0), MeshPoint::Inside { triangle: 5, barycentric: [0.5, 0.25, 0.25] }];
    let radius = 0.2;
    for sampling in [Sampling::Disc, Sampling::Voronoi, Sampling::Mixed] {
        let options = TrainOptions {
            energy: Energy::Arap,
            samples: 16,
            seed: 2,
            sampling,
            radius: Some(radius),
            ..TrainOptions::default()
        };
        let mut trainer = Trainer::new(&mesh, &handles, options).unwrap();
        trainer.advance(f64::INFINITY, frozen).unwrap();
        let targets: Vec<Vec<f64>> =
            (0..trainer.sample_count()).map(|i| trainer.sample(i).unwrap().0.to_vec()).collect();
        let operator = trainer.finish().unwrap();
        let regions = operator.sampling_regions(&mesh).unwrap();
        let rest = operator.handle_basis().rest();
        let mut beyond_disc = 0;
        for q in &targets {
            for (l, region) in regions.iter().enumerate() {
                let t = [q[2 * l], q[2 * l + 1]];
                assert!(region.contains(t), "{sampling:?}: target {t:?} of handle {l} outside its region");
                beyond_disc += usize::from((t[0] - rest[2 * l]).hypot(t[1] - rest[2 * l + 1]) > radius);
            }
        }
        // Discs: every target within the radius; cells reach far beyond it (the bar's two
        // halves, grown by the radius), and so do half of the mixed samples' targets.
        assert_eq!(beyond_disc == 0, sampling == Sampling::Disc, "{sampling:?}: {beyond_disc} beyond the disc");
        assert_eq!(regions.iter().all(|r| r.cell.is_some()), sampling != Sampling::Disc);
        assert_eq!(regions.iter().all(|r| r.radius == Some(radius)), sampling != Sampling::Voronoi);
        // The file keeps what the regions are made of.
        let (read_mesh, read) = read_operator(&write_operator(&mesh, &operator).unwrap()).unwrap();
        assert_eq!(read.sampling_regions(&read_mesh).unwrap(), regions);
    }
    // A training not known: the discs of radius the coordinates' scale (a trainer's radius).
    let operator = trained(&mesh, BasisKind::Linear, 0).with_training(None);
    let regions = operator.sampling_regions(&mesh).unwrap();
    let scale = operator.handle_basis().scale();
    assert!(regions.iter().all(|r| r.radius == Some(scale) && r.cell.is_none()));
}

#[test]
fn a_single_precision_file_holds_the_f32_roundings_of_the_coefficients_in_half_the_bytes() {
    let mesh = bar();
    for (basis, spatial) in [(BasisKind::Tps, 0), (BasisKind::Quadratic, 12)] {
        let mut operator = trained(&mesh, basis, spatial);
        let double = write_operator(&mesh, &operator).unwrap();
        let single = write_operator_in(&mesh, &operator, Precision::Single).unwrap();
        assert_eq!(single[48], 1, "the precision flag");
        // The operator's numbers, 4 bytes each instead of 8.
        let (phi, psi) = (operator.spatial_len(), operator.handle_basis().len());
        let numbers = 2 * phi * psi + if spatial > 0 { phi * mesh.vertex_count() } else { 0 };
        assert_eq!(double.len() - single.len(), 4 * numbers, "{basis:?}");
        let (read_mesh, mut read) = read_operator(&single).unwrap();
        assert_eq!(read_mesh, mesh);
        assert_eq!(read.training(), operator.training());
        for c in 0..2 {
            for i in 0..phi {
                for j in 0..psi {
                    let x = operator.coefficient(c, i, j).unwrap();
                    assert_eq!(read.coefficient(c, i, j).unwrap(), f64::from(x as f32), "X^{c}_{i}{j}");
                }
            }
        }
        // It poses as the operator does, to single precision of the coefficients: each
        // position is a sum of |Ψ| (hat) products, each coefficient off by 2^-24 of itself.
        for q in queries(&operator) {
            let (a, b) = (operator.evaluate(&q).unwrap(), read.evaluate(&q).unwrap());
            let off = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
            assert!(off > 0.0 && off < 1e-4, "{basis:?}: off by {off:e}");
        }
        // Written again in single precision: the same bytes (an f32 read back is exact).
        assert_eq!(write_operator_in(&mesh, &read, Precision::Single).unwrap(), single);
    }
}

/// `tests/fixtures/defop-v2-fixed.defop` was written by the version-2 writer (commit
/// d92f1ec): a linear operator on the 2 × 2 grid with handles at vertices 0, (0, 0), 8,
/// (2, 2), and 2, (2, 0), held fixed, fitted with hat functions to g(x, Q) = x + (1 − x/2)
/// (q_0 − p_0) + (y/2)(q_1 − p_1), whose weights are 1 and 0 at the handles as they must be
/// and 0 at the fixed one, and which lies in the operator's span: the operator is g.
#[test]
fn a_version_2_file_still_reads() {
    let bytes = include_bytes!("fixtures/defop-v2-fixed.defop");
    assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 2);
    let (mesh, mut operator) = read_operator(bytes).unwrap();
    assert_eq!(mesh, akap::shapes::grid_mesh(2, 2));
    assert_eq!(operator.handles(), [MeshPoint::Vertex(0), MeshPoint::Vertex(8), MeshPoint::Vertex(2)]);
    assert_eq!(operator.handle_basis().kind(), BasisKind::Linear);
    assert_eq!(operator.handle_basis().coordinates().fixed(), [2]);
    assert_eq!((operator.training(), operator.puppet()), (None, None));
    let truth = |q: &[f64]| -> Vec<f64> {
        mesh.positions()
            .iter()
            .flat_map(|x| {
                let (a, b) = (1.0 - x[0] / 2.0, x[1] / 2.0);
                [x[0] + a * q[0] + b * (q[2] - 2.0), x[1] + a * q[1] + b * (q[3] - 2.0)]
            })
            .collect()
    };
    // The fixed handle's target is ignored, whatever it is.
    for q in [[0.0, 0.0, 2.0, 2.0, 2.0, 0.0], [0.3, -0.2, 2.5, 1.1, 9.0, -9.0], [-4.0, 7.0, 3.0, -9.0, 2.0, 0.1]] {
        let error =
            operator.evaluate(&q).unwrap().iter().zip(truth(&q)).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(error < 1e-12 * (1.0 + q.iter().map(|x| x.abs()).fold(0.0, f64::max)), "{q:?}: off by {error:e}");
    }
    // Written again: version 4, the same file from byte 48 on (shifted by the new fields).
    let again = write_operator(&mesh, &operator).unwrap();
    assert_eq!(again[8], 4);
    assert_eq!(again[12..48], bytes[12..48]);
    assert_eq!(again[80..again.len() - 8], bytes[48..bytes.len() - 8]);
}

/// `tests/fixtures/defop-v3-puppet.defop` was written by the version-3 writer (commit
/// d92f1ec): a puppet of two squares, "left" [0, 1]² (depth 0) and "right" [0.5, 1.5] ×
/// [0.25, 0.75] (depth 1), joined at (0.75, 0.5), with handles at vertex 0, (0, 0), of the
/// left and vertex 5, (1.5, 0.25), of the right, a linear operator fitted to each part
/// translated by its handle (in its span: the operator is that).
#[test]
fn a_version_3_file_still_reads_with_its_puppet() {
    let bytes = include_bytes!("fixtures/defop-v3-puppet.defop");
    assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 3);
    let (mesh, mut operator) = read_operator(bytes).unwrap();
    assert_eq!(mesh.vertex_count(), 8);
    let puppet = operator.puppet().unwrap().clone();
    let names: Vec<_> = puppet.parts.iter().map(|p| (p.name.as_str(), p.triangles.clone(), p.depth)).collect();
    assert_eq!(names, [("left", vec![0, 1], 0), ("right", vec![2, 3], 1)]);
    assert_eq!(puppet.joints.len(), 1);
    assert_eq!((puppet.joints[0].point, puppet.joints[0].parts), ([0.75, 0.5], [1, 0]));
    assert_eq!(operator.training(), None);
    let q = [0.3, -0.2, 1.0, 0.75];
    let posed = operator.evaluate(&q).unwrap();
    for (v, p) in mesh.positions().iter().enumerate() {
        let d = if v < 4 { [0.3, -0.2] } else { [1.0 - 1.5, 0.75 - 0.25] };
        for c in 0..2 {
            assert!((posed[2 * v + c] - (p[c] + d[c])).abs() < 1e-12, "vertex {v}");
        }
    }
    // Written again: version 4 with the puppet flag, and the same puppet read back.
    let again = write_operator(&mesh, &operator).unwrap();
    assert_eq!((again[8], again[49]), (4, 1));
    assert_eq!(read_operator(&again).unwrap().1.puppet(), Some(&puppet));
    assert_eq!(again[80..again.len() - 8], bytes[48..bytes.len() - 8]);
}

#[test]
fn header_fields_no_writer_writes_are_refused() {
    let mesh = bar();
    let operator = trained_with(&mesh, TrainOptions { sampling: Sampling::Mixed, ..TrainOptions::default() });
    let bytes = write_operator(&mesh, &operator).unwrap();
    let field = |what| Err(OperatorFileError::Field { what });
    let cases: [(usize, u8, Result<(), OperatorFileError>); 10] = [
        (48, 2, field("precision")),
        (49, 2, field("puppet flag")),
        (50, 2, field("training flag")),
        (51, 2, field("training energy")),
        (52, 3, field("training sampling")),
        (54, 1, field("reserved bytes")),
        (61, 1, field("reserved bytes")),
        (56, 0, Err(OperatorFileError::Count { what: "training's sample count", value: 0 })),
        (33, 2, field("spatial basis kind")),
        (34, 7, field("solver")),
    ];
    for (at, value, expected) in cases {
        let mut altered = bytes.clone();
        altered[at] = value;
        if at == 56 {
            altered[57] = 0;
        }
        assert_eq!(read_operator(&sealed(altered)).map(drop), expected, "byte {at} = {value}");
    }
    // A negative radius; a training not known whose fields are not zero.
    let mut altered = bytes.clone();
    altered[72..80].copy_from_slice(&(-1.0f64).to_le_bytes());
    let error = read_operator(&sealed(altered)).unwrap_err();
    assert!(error.to_string().contains("radius is -1"), "{error}");
    let mut altered = bytes.clone();
    altered[50] = 0;
    assert_eq!(read_operator(&sealed(altered)).map(drop), field("unknown training's bytes"));
    // A puppet flag with no puppet's section: the section's counts run past the file.
    let mut altered = bytes.clone();
    altered[49] = 1;
    assert!(matches!(read_operator(&sealed(altered)), Err(OperatorFileError::Length { .. })));
    // Single precision flagged on a double file: the length no longer matches.
    let mut altered = bytes;
    altered[48] = 1;
    assert!(matches!(read_operator(&sealed(altered)), Err(OperatorFileError::Length { .. })));
}
