//! The error types: `source()` chains from `akap::Error` down to the innermost error, and
//! the stable codes (`ErrorCode`) of errors produced by real calls.

use std::error::Error as _;
use std::sync::Arc;

use akap::animation::{read_animation, AnimationError};
use akap::deform::{AkapOptions, DeformError, Deformer};
use akap::import::mesh_file::read_obj;
use akap::import::{ImportError, Limits};
use akap::sparse::{FactorError, Numeric, Ordering, Symbolic};
use akap::{
    triangulate, Error, ErrorCode, MeshError, Outline, OutlineError, Ring, TriangulationError, TriangulationOptions,
};
use sprs::TriMat;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

/// The chain of `source()`s after `error`, as the names of their types (found by
/// downcasting, so a link of another type than expected shows as "other").
fn chain(error: &(dyn std::error::Error + 'static)) -> Vec<&'static str> {
    let mut names = Vec::new();
    let mut next = error.source();
    while let Some(e) = next {
        names.push(if e.is::<AnimationError>() {
            "AnimationError"
        } else if e.is::<TriangulationError>() {
            "TriangulationError"
        } else if e.is::<OutlineError>() {
            "OutlineError"
        } else if e.is::<ImportError>() {
            "ImportError"
        } else if e.is::<MeshError>() {
            "MeshError"
        } else if e.is::<DeformError>() {
            "DeformError"
        } else if e.is::<FactorError>() {
            "FactorError"
        } else {
            "other"
        });
        next = e.source();
    }
    names
}

/// A 2 x 2 matrix that is symmetric but not positive definite, factored: the factorisation's
/// own error.
fn indefinite() -> FactorError {
    let mut a = TriMat::new((2, 2));
    a.add_triplet(0, 0, 1.0);
    a.add_triplet(1, 0, 2.0);
    a.add_triplet(0, 1, 2.0);
    a.add_triplet(1, 1, 1.0);
    let a = a.to_csc::<usize>();
    let symbolic = Arc::new(Symbolic::analyse(a.view(), &Ordering::Natural).unwrap());
    Numeric::factor(symbolic, a.view()).unwrap_err()
}

#[test]
fn an_outline_error_is_reached_through_the_triangulation_error() {
    // A unit square with a "hole" two units to its right.
    let square = |x: f64| vec![[x, 0.0], [x + 1.0, 0.0], [x + 1.0, 1.0], [x, 1.0]];
    let outline = Outline { outer: square(0.0), holes: vec![square(2.0)] };
    let error = Error::from(triangulate(&outline, &TriangulationOptions::default()).unwrap_err());
    assert_eq!(chain(&error), ["TriangulationError", "OutlineError"]);
    let outline = error.source().unwrap().source().unwrap().downcast_ref::<OutlineError>().unwrap();
    assert_eq!(outline, &OutlineError::HoleOutside { hole: Ring(1) });
    assert_eq!(error.code(), ErrorCode::InvalidOutline);
    assert_eq!(error.to_string(), outline.to_string());
}

#[test]
fn a_mesh_error_in_a_file_is_reached_through_the_import_error() {
    // A clockwise triangle.
    let error = Error::from(read_obj("v 0 0\nv 1 0\nv 0 1\nf 1 3 2\n", &Limits::default()).unwrap_err());
    assert_eq!(chain(&error), ["ImportError", "MeshError"]);
    let mesh = error.source().unwrap().source().unwrap().downcast_ref::<MeshError>().unwrap();
    assert_eq!(mesh, &MeshError::Clockwise { triangle: 0 });
    assert_eq!(error.code(), ErrorCode::InvalidMesh);
}

#[test]
fn a_mesh_error_in_an_animation_file_is_reached_through_two_layers() {
    let text = r#"{"format": "akap-animation", "version": 1, "fps": 30, "keys": [], "frames": [[0, 0, 1, 0, 0, 1]],
        "mesh": {"positions": [0, 0, 1, 0, 0, 1], "triangles": [0, 2, 1]}}"#;
    let error = Error::from(read_animation(text, &Limits::default()).unwrap_err());
    assert_eq!(chain(&error), ["AnimationError", "ImportError", "MeshError"]);
    assert_eq!(error.code(), ErrorCode::InvalidMesh);
    // With the mesh made counter-clockwise, a file error, which ends the chain.
    let error = Error::from(
        read_animation(&text.replace("30", "0").replace("[0, 2, 1]", "[0, 1, 2]"), &Limits::default()).unwrap_err(),
    );
    assert_eq!(chain(&error), ["AnimationError"]);
    assert_eq!(error.code(), ErrorCode::Import);
    assert_eq!(error.to_string(), "the animation file is not valid: fps is 0, expected a number from 1 to 120");
}

#[test]
fn a_factorisation_error_is_reached_through_the_deform_error() {
    let factor = indefinite();
    assert!(matches!(factor, FactorError::NotPositiveDefinite { column: 1, .. }), "{factor:?}");
    let error = Error::from(DeformError::from(factor.clone()));
    assert_eq!(chain(&error), ["DeformError", "FactorError"]);
    assert_eq!(error.source().unwrap().source().unwrap().downcast_ref::<FactorError>(), Some(&factor));
    assert_eq!(error.code(), ErrorCode::NotPositiveDefinite);
    // On its own, wrapped once.
    let error = Error::from(factor.clone());
    assert_eq!(chain(&error), ["FactorError"]);
    assert_eq!(error.code(), ErrorCode::NotPositiveDefinite);
}

#[test]
fn a_deformer_error_without_a_cause_ends_the_chain() {
    // Two triangles apart: two pieces.
    let positions = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 0.0], [6.0, 0.0], [5.0, 1.0]];
    let mesh = akap::Mesh::new(positions, vec![[0, 1, 2], [3, 4, 5]]).unwrap();
    let error = Error::from(Deformer::new(mesh, AkapOptions::default()).unwrap_err());
    assert_eq!(chain(&error), ["DeformError"]);
    assert_eq!(error.code(), ErrorCode::InvalidMesh);
}

#[test]
fn codes_are_distinct_lowercase_words_joined_by_hyphens() {
    let names: Vec<&str> = ErrorCode::ALL.iter().map(|c| c.as_str()).collect();
    for (i, name) in names.iter().enumerate() {
        assert!(!names[..i].contains(name), "{name} twice");
        assert!(name.split('-').all(|w| !w.is_empty() && w.bytes().all(|b| b.is_ascii_lowercase())), "{name}");
        assert_eq!(ErrorCode::ALL[i].to_string(), *name);
    }
}
