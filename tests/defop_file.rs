//! Operator files: a trained operator written and read back poses its mesh to the same bits
//! (hat and reduced spatial bases, polynomial and TPS handle bases, canonical coordinates,
//! fixed handles); a version-1 file still reads; a truncated, extended or altered file is
//! refused with an error, never a panic. Runs natively and as wasm.

use akap::defop::{
    read_operator, write_operator, BasisKind, Energy, MeshPoint, Operator, OperatorFileError, TrainOptions, Trainer,
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
        assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 2, "version 2 is written");
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
    // Written again: version 2, the same operator.
    let again = write_operator(&mesh, &operator).unwrap();
    assert_eq!(u32::from_le_bytes(again[8..12].try_into().unwrap()), 2);
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
    for cut in [0, 7, 8, 30, 47, 48, 100, bytes.len() / 2, bytes.len() - 8, bytes.len() - 1] {
        assert!(read_operator(&bytes[..cut]).is_err(), "{cut} bytes read");
    }
    let mut longer = bytes.clone();
    longer.push(0);
    assert!(matches!(read_operator(&longer), Err(OperatorFileError::Length { .. })));
    for at in (0..bytes.len()).step_by(13) {
        let mut altered = bytes.clone();
        altered[at] ^= 0x10;
        assert!(read_operator(&altered).is_err(), "a flip at byte {at} was not noticed");
    }
    let mut future = bytes.clone();
    future[8] = 4;
    assert_eq!(read_operator(&future).unwrap_err(), OperatorFileError::Version { found: 4 });
    assert_eq!(read_operator(b"PNG\x0d\x0a").unwrap_err(), OperatorFileError::NotAnOperator);
    let other = akap::shapes::grid_mesh(3, 3);
    assert!(write_operator(&other, &operator).is_err(), "an operator is written with its own mesh");
}
