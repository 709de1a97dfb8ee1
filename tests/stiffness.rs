//! Painted stiffness (issue 23, its core): a triangle's stiffness multiplies its energy
//! (AKAP's Killing energy, ARAP's element energy). A bar whose middle third is 100 times
//! stiffer, bent by its ends, keeps that third within 1% of rigid (its triangles'
//! Jacobians, measured against the rest mesh, have singular values within 1% of 1) where
//! the unpainted bar stretches and squeezes it more; stiffness 1 everywhere is the
//! unpainted deformer to the bit; bad values change nothing; MLS and Cauchy-Green, with
//! no per-triangle energy, refuse it; a switch between AKAP and ARAP keeps it. Runs
//! natively and as wasm.

use akap::deform::metrics::{deformation_gradient, singular_values};
use akap::deform::{AkapOptions, ArapOptions, CauchyGreenOptions, DeformError, Deformer, MethodOptions, MlsOptions};
use akap::geometry::Point;
use akap::shapes::grid_mesh;
use akap::Mesh;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

const COLUMNS: usize = 30;
const ROWS: usize = 6;

/// The bar's two ends: the vertex columns at x = 0 and x = 30.
fn ends() -> (Vec<u32>, Vec<u32>) {
    let column = |x: usize| (0..=ROWS).map(|y| (y * (COLUMNS + 1) + x) as u32).collect();
    (column(0), column(COLUMNS))
}

/// The left end held, the right end turned by 90 degrees about its middle and lifted, in
/// 60 steps that each go a share of the way that is left.
fn bend(method: MethodOptions, stiffness: Option<&[f64]>) -> (Mesh, Deformer) {
    let mesh = grid_mesh(COLUMNS, ROWS);
    let mut deformer = Deformer::new(mesh.clone(), method).unwrap();
    deformer.set_stiffness(stiffness).unwrap();
    let (left, right) = ends();
    let handles: Vec<u32> = left.iter().chain(&right).copied().collect();
    deformer.set_handle_vertices(&handles).unwrap();
    let (s, c) = std::f64::consts::FRAC_PI_2.sin_cos();
    let target = |p: Point, moved: bool| {
        if !moved {
            return p;
        }
        let (dx, dy) = (p[0] - COLUMNS as f64, p[1] - ROWS as f64 / 2.0);
        [COLUMNS as f64 - 6.0 + c * dx - s * dy, ROWS as f64 / 2.0 + 12.0 + s * dx + c * dy]
    };
    let goals: Vec<Point> =
        handles.iter().enumerate().map(|(k, &v)| target(mesh.positions()[v as usize], k >= left.len())).collect();
    let steps = 60;
    for step in 0..steps {
        let share = 1.0 / (steps - step) as f64;
        let velocities: Vec<[f64; 2]> = deformer
            .handle_positions()
            .iter()
            .zip(&goals)
            .map(|(p, q)| [share * (q[0] - p[0]), share * (q[1] - p[1])])
            .collect();
        deformer.step(&velocities).unwrap();
    }
    (mesh, deformer)
}

/// The middle third's triangles (centroid between x = 10 and x = 20).
fn middle(mesh: &Mesh) -> Vec<bool> {
    mesh.triangles()
        .iter()
        .map(|t| {
            let x = t.iter().map(|&v| mesh.positions()[v as usize][0]).sum::<f64>() / 3.0;
            (COLUMNS as f64 / 3.0..2.0 * COLUMNS as f64 / 3.0).contains(&x)
        })
        .collect()
}

/// The largest `|sigma - 1|` over the chosen triangles of the pose.
fn worst_stretch(mesh: &Mesh, positions: &[Point], chosen: &[bool]) -> f64 {
    mesh.triangles()
        .iter()
        .zip(chosen)
        .filter(|(_, &c)| c)
        .map(|(t, _)| {
            let f = deformation_gradient(t.map(|v| mesh.positions()[v as usize]), t.map(|v| positions[v as usize]));
            let (s1, s2, _) = singular_values(f[0][0], f[0][1], f[1][0], f[1][1]);
            (s1 - 1.0).abs().max((s2 - 1.0).abs())
        })
        .fold(0.0, f64::max)
}

fn akap() -> MethodOptions {
    MethodOptions::Akap(AkapOptions::default())
}

fn arap() -> MethodOptions {
    MethodOptions::Arap(ArapOptions::default().with_iterations(30))
}

#[test]
fn a_stiff_middle_stays_within_one_percent_of_rigid() {
    for method in [akap(), arap()] {
        let (mesh, plain) = bend(method, None);
        let chosen = middle(&mesh);
        let painted: Vec<f64> = chosen.iter().map(|&c| if c { 100.0 } else { 1.0 }).collect();
        let (_, stiff) = bend(method, Some(&painted));
        let soft = worst_stretch(&mesh, plain.positions(), &chosen);
        let hard = worst_stretch(&mesh, stiff.positions(), &chosen);
        eprintln!("{method:?}: middle third unpainted {soft:.4}, painted {hard:.4}");
        assert!(hard <= 0.01, "{method:?}: the painted third is {hard} from rigid");
        assert!(soft > 2.0 * hard, "{method:?}: the unpainted bar deforms its middle only {soft}, painted {hard}");
    }
}

#[test]
fn stiffness_one_everywhere_is_the_unpainted_deformer_and_bad_values_change_nothing() {
    let bits = |p: &[Point]| p.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
    for method in [akap(), arap()] {
        let (mesh, plain) = bend(method, None);
        let ones = vec![1.0; mesh.triangle_count()];
        let (_, painted) = bend(method, Some(&ones));
        assert_eq!(bits(painted.positions()), bits(plain.positions()), "{method:?}");

        let mut deformer = Deformer::new(mesh.clone(), method).unwrap();
        deformer.set_handle_vertices(&[0, 40]).unwrap();
        let mut bad = ones.clone();
        bad[7] = f64::NAN;
        assert!(matches!(deformer.set_stiffness(Some(&bad)), Err(DeformError::InvalidStiffness { triangle: 7, .. })));
        bad[7] = 1e4;
        let error = deformer.set_stiffness(Some(&bad)).unwrap_err();
        assert_eq!(error.to_string(), "the stiffness of triangle 7 is 10000, expected a number from 0.001 to 1000");
        assert!(matches!(deformer.set_stiffness(Some(&ones[1..])), Err(DeformError::Length { .. })));
        assert_eq!(deformer.stiffness(), None);
        // Nothing was changed: a step is the unpainted one.
        let mut unpainted = Deformer::new(mesh, method).unwrap();
        unpainted.set_handle_vertices(&[0, 40]).unwrap();
        for d in [&mut deformer, &mut unpainted] {
            d.step(&[[0.0, 0.0], [0.5, 0.3]]).unwrap();
        }
        assert_eq!(bits(deformer.positions()), bits(unpainted.positions()), "{method:?}");
    }
}

#[test]
fn methods_without_a_per_triangle_energy_refuse_it_and_a_switch_keeps_it() {
    let mesh = grid_mesh(COLUMNS, ROWS);
    let stiffness: Vec<f64> = (0..mesh.triangle_count()).map(|t| 1.0 + (t % 7) as f64).collect();
    for method in [MethodOptions::Mls(MlsOptions::default()), MethodOptions::CauchyGreen(CauchyGreenOptions::default())]
    {
        let mut deformer = Deformer::new(mesh.clone(), method).unwrap();
        let error = deformer.set_stiffness(Some(&stiffness)).unwrap_err();
        assert!(matches!(error, DeformError::Unsupported { what: "stiffness", .. }), "{error}");
        deformer.set_stiffness(None).unwrap();
    }
    let mut deformer = Deformer::new(mesh.clone(), akap()).unwrap();
    deformer.set_stiffness(Some(&stiffness)).unwrap();
    deformer.set_options(arap()).unwrap();
    assert_eq!(deformer.stiffness(), Some(&stiffness[..]));
    deformer.set_options(MethodOptions::Mls(MlsOptions::default())).unwrap();
    assert_eq!(deformer.stiffness(), None);
}
