//! Operator files: a trained operator written and read back poses its mesh to the same bits
//! (hat and reduced spatial bases, polynomial and TPS handle bases); a truncated, extended
//! or altered file is refused with an error, never a panic. Runs natively and as wasm.

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
    let handles = [MeshPoint::Vertex(0), MeshPoint::Inside { triangle: 5, barycentric: [0.5, 0.25, 0.25] }];
    let options =
        TrainOptions { energy: Energy::Arap, basis, samples: 16, spatial, seed: 2, ..TrainOptions::default() };
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
    future[8] = 2;
    assert_eq!(read_operator(&future).unwrap_err(), OperatorFileError::Version { found: 2 });
    assert_eq!(read_operator(b"PNG\x0d\x0a").unwrap_err(), OperatorFileError::NotAnOperator);
    let other = akap::shapes::grid_mesh(3, 3);
    assert!(write_operator(&other, &operator).is_err(), "an operator is written with its own mesh");
}
