//! No foldovers (`deform::foldover`): a step that flips nothing is the plain step to the
//! bit; rigid motions are still reproduced; an extreme drag that folds the bar with plain
//! steps folds nothing with the guard, for every method; the plain steps a guarded step
//! reports replay to the same bits; a checkpoint restores every method exactly; errors
//! leave the deformer unchanged; the clamp finds the flip fraction of one triangle pushed
//! through its opposite edge, which is known by hand. Runs natively and as wasm.

use akap::deform::foldover::newly_flipped;
use akap::deform::{
    step_without_foldovers, AkapOptions, ArapOptions, CauchyGreenOptions, Checkpoint, DeformError, Deformer,
    FoldoverGuard, FoldoverStepper, GuardedStep, Method, MethodOptions, MlsOptions, Undoable,
};
use akap::geometry::Point;
use akap::shapes::grid_mesh;
use akap::Mesh;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

const COLUMNS: usize = 20;
const ROWS: usize = 4;

fn methods() -> [MethodOptions; 4] {
    [
        MethodOptions::Akap(AkapOptions::default()),
        MethodOptions::Arap(ArapOptions::default().with_iterations(10)),
        MethodOptions::Mls(MlsOptions::default()),
        MethodOptions::CauchyGreen(CauchyGreenOptions::default().with_cage(32)),
    ]
}

fn bits(points: &[Point]) -> Vec<u64> {
    points.iter().flatten().map(|x| x.to_bits()).collect()
}

/// Everything a caller can read of a deformer's state, as bits.
fn state(deformer: &Deformer) -> Vec<Vec<u64>> {
    vec![
        bits(deformer.positions()),
        bits(deformer.field()),
        bits(deformer.soft_field()),
        bits(&deformer.handle_positions()),
        bits(deformer.cage_image().unwrap_or_default()),
    ]
}

/// The bar `[0, 20] x [0, 4]` with its left end held (a handle on each vertex of the
/// column x = 0) and a handle on the middle of its right end, last.
fn bar(method: MethodOptions) -> Deformer {
    let mut deformer = Deformer::new(grid_mesh(COLUMNS, ROWS), method).unwrap();
    let index = |x: usize, y: usize| (y * (COLUMNS + 1) + x) as u32;
    let mut handles: Vec<u32> = (0..=ROWS).map(|y| index(0, y)).collect();
    handles.push(index(COLUMNS, ROWS / 2));
    deformer.set_handle_vertices(&handles).unwrap();
    deformer
}

/// Velocities that hold every handle but the last, which moves by `d`.
fn drag(deformer: &Deformer, d: [f64; 2]) -> Vec<[f64; 2]> {
    let mut velocities = vec![[0.0; 2]; deformer.handle_count()];
    *velocities.last_mut().unwrap() = d;
    velocities
}

/// Frames of the extreme drag: the right end's middle pulled back through the bar to
/// `(2, 2)`, beside the held end, each frame asking for the rest of the way in the frames
/// left (as the widget's drag does), so a guarded drag that lags catches up if it can.
const FRAMES: usize = 8;

fn drag_frame(deformer: &Deformer, frame: usize) -> Vec<[f64; 2]> {
    let goal = [2.0, ROWS as f64 / 2.0];
    let at = *deformer.handle_positions().last().unwrap();
    let share = 1.0 / (FRAMES - frame) as f64;
    drag(deformer, [share * (goal[0] - at[0]), share * (goal[1] - at[1])])
}

#[test]
fn a_step_that_flips_nothing_is_the_plain_step_to_the_bit() {
    for method in methods() {
        let (mut plain, mut guarded) = (bar(method), bar(method));
        let mut stepper = FoldoverStepper::new(FoldoverGuard::default()).unwrap();
        for frame in 0..4 {
            let velocities = drag(&plain, [0.1 * frame as f64, 0.4]);
            plain.step(&velocities).unwrap();
            let report = stepper.step(&mut guarded, &velocities).unwrap();
            assert_eq!(report, &GuardedStep { steps: vec![1.0], clamped: false, attempts: 1 }, "{method:?}");
            assert_eq!(state(&guarded), state(&plain), "{method:?} frame {frame}");
            assert_eq!(plain.metrics().flipped, 0, "{method:?}: the bending flips nothing");
        }
    }
}

#[test]
fn rigid_motions_are_still_reproduced() {
    // A rotation by 2 radians about c and a shift: no triangle turns over, so the guard
    // takes the plain step, which reproduces it (AKAP from the Killing field, Appendix A;
    // MLS and Cauchy-Green from the handles' displacements).
    let (angle, c, shift) = (2.0f64, [7.0, -3.0], [0.5, 1.5]);
    let (s, co) = angle.sin_cos();
    let moved = |p: Point| {
        let (x, y) = (p[0] - c[0], p[1] - c[1]);
        [c[0] + co * x - s * y + shift[0], c[1] + s * x + co * y + shift[1]]
    };
    for method in [methods()[0], methods()[2], methods()[3]] {
        let mut deformer = bar(method);
        let velocities: Vec<[f64; 2]> = deformer
            .handle_positions()
            .iter()
            .map(|&p| match method {
                // The infinitesimal rigid motion whose spiral is that rotation and shift:
                // u(p) = a i (p - c') with c' its fixed point.
                MethodOptions::Akap(_) => {
                    let fixed = fixed_point(angle, c, shift);
                    [-angle * (p[1] - fixed[1]), angle * (p[0] - fixed[0])]
                }
                _ => {
                    let q = moved(p);
                    [q[0] - p[0], q[1] - p[1]]
                }
            })
            .collect();
        let report = step_without_foldovers(&mut deformer, &velocities, &FoldoverGuard::default()).unwrap();
        assert_eq!(report.steps, [1.0], "{method:?}");
        let size = 30.0;
        for (p, q) in deformer.mesh().positions().iter().zip(deformer.positions()) {
            let want = moved(*p);
            assert!((q[0] - want[0]).hypot(q[1] - want[1]) <= 1e-9 * size, "{method:?}: {q:?} vs {want:?}");
        }
    }
}

/// The point the rotation by `angle` about `c` followed by `shift` keeps fixed.
fn fixed_point(angle: f64, c: Point, shift: [f64; 2]) -> Point {
    // f = c + R (p - c) + s = p  <=>  (I - R)(p - c) = s.
    let (s, co) = angle.sin_cos();
    let (a, b) = (1.0 - co, s);
    let det = a * a + b * b;
    [c[0] + (a * shift[0] - b * shift[1]) / det, c[1] + (b * shift[0] + a * shift[1]) / det]
}

/// The extreme drag with plain steps: the most triangles flipped at any frame.
fn plain_drag(method: MethodOptions) -> usize {
    let mut deformer = bar(method);
    let mut most = 0;
    for frame in 0..FRAMES {
        let velocities = drag_frame(&deformer, frame);
        if deformer.step(&velocities).is_err() {
            break;
        }
        most = most.max(deformer.metrics().flipped);
    }
    most
}

/// The extreme drag with guarded steps.
struct GuardedDrag {
    deformer: Deformer,
    /// Every plain step taken: the velocities times its fraction.
    taken: Vec<Vec<[f64; 2]>>,
    /// Whether a guarded step was split, and whether one was clamped.
    split: bool,
    clamped: bool,
}

fn guarded_drag(method: MethodOptions) -> GuardedDrag {
    let mut deformer = bar(method);
    let rest = deformer.mesh().positions().to_vec();
    let mut stepper = FoldoverStepper::new(FoldoverGuard::default()).unwrap();
    let (mut taken, mut split, mut clamped) = (Vec::new(), false, false);
    for frame in 0..FRAMES {
        let velocities = drag_frame(&deformer, frame);
        let report = stepper.step(&mut deformer, &velocities).unwrap();
        split |= report.steps != [1.0];
        clamped |= report.clamped;
        for &f in &report.steps {
            taken.push(velocities.iter().map(|v| [v[0] * f, v[1] * f]).collect());
        }
        let triangles = deformer.mesh().triangles();
        assert_eq!(newly_flipped(&rest, deformer.positions(), triangles), 0, "{method:?} frame {frame}");
        assert_eq!(deformer.metrics().flipped, 0, "{method:?} frame {frame}");
    }
    GuardedDrag { deformer, taken, split, clamped }
}

#[test]
fn an_extreme_drag_flips_triangles_with_plain_steps_and_none_guarded() {
    for method in methods() {
        let flipped = plain_drag(method);
        let GuardedDrag { deformer, split, clamped, .. } = guarded_drag(method);
        let end = *deformer.handle_positions().last().unwrap();
        eprintln!("{method:?}: plain drag flips {flipped}; guarded: split {split}, clamped {clamped}, end {end:?}");
        assert!(flipped > 0, "{method:?}: the plain drag should fold the bar");
        assert!(split, "{method:?}: the guard should have split a step");
        // The handle went a good part of the way (from x = 20 towards 2) before the guard
        // held it.
        assert!(end[0] < 15.0, "{method:?}: the guarded drag stopped at {end:?}");
    }
}

#[test]
fn the_reported_plain_steps_replay_to_the_same_bits() {
    for method in methods() {
        let GuardedDrag { deformer: guarded, taken, split, clamped } = guarded_drag(method);
        let mut replayed = bar(method);
        for velocities in &taken {
            replayed.step(velocities).unwrap();
        }
        assert!(split, "{method:?}: the drag should split a step");
        assert_eq!(state(&replayed), state(&guarded), "{method:?} (clamped: {clamped})");
    }
}

#[test]
fn a_restored_checkpoint_makes_the_next_step_as_if_nothing_happened() {
    for method in methods() {
        let (mut undone, mut direct) = (bar(method), bar(method));
        for d in [&mut undone, &mut direct] {
            for k in 0..3 {
                let velocities = drag(d, [-1.0, 0.5 * k as f64]);
                d.step(&velocities).unwrap();
            }
        }
        let mut checkpoint = Checkpoint::new();
        undone.save_checkpoint(&mut checkpoint);
        assert_eq!(checkpoint.method(), Some(method.method()));
        // A step to undo: large, a different direction.
        let velocities = drag(&undone, [-9.0, -4.0]);
        undone.step(&velocities).unwrap();
        assert_ne!(bits(undone.positions()), bits(direct.positions()));
        undone.restore_checkpoint(&checkpoint).unwrap();
        assert_eq!(state(&undone), state(&direct), "{method:?} restored");
        assert_eq!(undone.metrics(), direct.metrics());
        for d in [&mut undone, &mut direct] {
            let velocities = drag(d, [0.7, 0.3]);
            d.step(&velocities).unwrap();
        }
        assert_eq!(state(&undone), state(&direct), "{method:?} stepped after the restore");
    }
}

#[test]
fn arap_restores_its_targets_rotations_and_report() {
    let options = ArapOptions::default().with_iterations(5);
    let (mut undone, mut direct) = (
        Deformer::new(grid_mesh(COLUMNS, ROWS), options).unwrap(),
        Deformer::new(grid_mesh(COLUMNS, ROWS), options).unwrap(),
    );
    for d in [&mut undone, &mut direct] {
        d.set_handle_vertices(&[0, 62]).unwrap();
        d.step(&[[0.0, 0.0], [-3.0, 2.0]]).unwrap();
    }
    let checkpoint = undone.checkpoint();
    undone.step(&[[1.0, 0.0], [-6.0, -4.0]]).unwrap();
    undone.restore_checkpoint(&checkpoint).unwrap();
    assert_eq!(undone.arap().unwrap().targets(), direct.arap().unwrap().targets());
    assert_eq!(bits(undone.arap().unwrap().rotations()), bits(direct.arap().unwrap().rotations()));
    assert_eq!(undone.arap().unwrap().report(), direct.arap().unwrap().report());
    assert_eq!(undone.energy().unwrap().to_bits(), direct.energy().unwrap().to_bits());
    for d in [&mut undone, &mut direct] {
        d.iterate(7, 0.0).unwrap();
    }
    assert_eq!(bits(undone.positions()), bits(direct.positions()));
}

#[test]
fn a_checkpoint_of_another_deformer_is_refused_and_changes_nothing() {
    let akap = bar(methods()[0]);
    let mut arap = bar(methods()[1]);
    let velocities = drag(&arap, [-1.0, 1.0]);
    arap.step(&velocities).unwrap();
    let before = state(&arap);
    let error = arap.restore_checkpoint(&akap.checkpoint()).unwrap_err();
    assert_eq!(error, DeformError::ForeignCheckpoint { method: Method::Arap, saved: Some(Method::Akap) });
    assert!(error.to_string().contains("method akap, not arap"), "{error}");
    let error = arap.restore_checkpoint(&Checkpoint::new()).unwrap_err();
    assert_eq!(error, DeformError::ForeignCheckpoint { method: Method::Arap, saved: None });
    // The same method with another handle count, and another mesh.
    let saved = arap.checkpoint();
    arap.set_handle_vertices(&[0, 1]).unwrap();
    assert!(matches!(arap.restore_checkpoint(&saved), Err(DeformError::ForeignCheckpoint { .. })));
    for method in methods() {
        let mut small = Deformer::new(grid_mesh(3, 2), method).unwrap();
        let error = small.restore_checkpoint(&bar(method).checkpoint()).unwrap_err();
        assert_eq!(error.code().as_str(), "invalid-argument");
        assert_eq!(bits(small.positions()), bits(small.mesh().positions()), "{method:?}");
    }
    assert_eq!(state(&arap)[0], before[0]);
}

#[test]
fn errors_leave_the_deformer_unchanged() {
    for method in methods() {
        let mut deformer = bar(method);
        let velocities = drag(&deformer, [-2.0, 1.0]);
        deformer.step(&velocities).unwrap();
        let before = state(&deformer);
        let guard = FoldoverGuard::default();
        let short = &velocities[1..];
        assert!(matches!(step_without_foldovers(&mut deformer, short, &guard), Err(DeformError::Length { .. })));
        let mut nan = velocities.clone();
        nan[2][1] = f64::NAN;
        let error = step_without_foldovers(&mut deformer, &nan, &guard).unwrap_err();
        assert_eq!(error, DeformError::NonFiniteVelocity { handle: 2 });
        let error = step_without_foldovers(&mut deformer, &velocities, &guard.with_max_splits(11)).unwrap_err();
        assert!(matches!(error, DeformError::InvalidOption { name: "maxSplits", .. }), "{error}");
        assert!(FoldoverStepper::new(guard.with_clamp_trials(31)).is_err());
        assert_eq!(state(&deformer), before, "{method:?}");

        // A plain step failing after the guard has taken pieces: everything is undone. The
        // first frame of the extreme drag whose guarded step is split, and its plain steps:
        let mut probe = bar(method);
        let mut stepper = FoldoverStepper::new(guard).unwrap();
        let (frame, attempts) = (0..FRAMES)
            .find_map(|frame| {
                let velocities = drag_frame(&probe, frame);
                let attempts = stepper.step(&mut probe, &velocities).unwrap().attempts;
                (attempts >= 4).then_some((frame, attempts))
            })
            .expect("the drag splits a step");
        for fail_at in [2, 3, attempts] {
            let mut failing = FailsAt { inner: bar(method), steps: 0, fail_at: 0 };
            for earlier in 0..frame {
                let velocities = drag_frame(&failing.inner, earlier);
                step_without_foldovers(&mut failing, &velocities, &guard).unwrap();
            }
            let before = state(&failing.inner);
            (failing.steps, failing.fail_at) = (0, fail_at);
            let velocities = drag_frame(&failing.inner, frame);
            let error = step_without_foldovers(&mut failing, &velocities, &guard).unwrap_err();
            assert_eq!(error, DeformError::NonFiniteResult);
            assert_eq!(state(&failing.inner), before, "{method:?}: failing at plain step {fail_at} of {attempts}");
        }
    }
}

#[test]
fn the_clamp_finds_where_one_triangle_turns_over() {
    // One triangle (0,0), (1,0), (0,1), a handle on each vertex (MLS and ARAP then put each
    // vertex on its handle's target: the pose is linear in the steps), its apex pushed
    // down by 3. The apex is at height 1 - 3 f after a fraction f of the push: the triangle
    // collapses at f = 1/3. By hand: the whole push, then its first half and the half of
    // that (C at -0.5) turn it over; the first quarter is taken (C at 0.25); the second
    // quarter, then its first eighth (C at -0.125) turn it over; a sixteenth is taken (C at
    // 0.0625); the next sixteenth would reach -0.125, and is clamped at the share t of it
    // that leaves C above 0: t = 0.0625 / 0.1875 = 1/3. Twelve bisections of [0, 1] find
    // the first twelve bits of 1/3 = 0.010101..._2, t = 1365 / 4096, within 2^-12 below
    // it, the last trial (bit 12, a 1) flip-free. Every number here is dyadic and exact.
    let mesh = Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[0, 1, 2]]).unwrap();
    let push = [[0.0, 0.0], [0.0, 0.0], [0.0, -3.0]];
    for method in [MethodOptions::Mls(MlsOptions::default()), MethodOptions::Arap(ArapOptions::default())] {
        let mut deformer = Deformer::new(mesh.clone(), method).unwrap();
        deformer.set_handle_vertices(&[0, 1, 2]).unwrap();
        let report = step_without_foldovers(&mut deformer, &push, &FoldoverGuard::default()).unwrap();
        assert!(report.clamped, "{method:?}");
        assert_eq!(report.steps, [0.25, 0.0625, 0.0625 * 1365.0 / 4096.0], "{method:?}");
        // Seven steps (the whole, 1/2, 1/4, 1/4, 1/8, 1/16, 1/16) and twelve trials.
        assert_eq!(report.attempts, 19, "{method:?}");
        // Within 2^-16 (2^-12 of a sixteenth) below the true limit.
        let f = report.fraction();
        assert!(f < 1.0 / 3.0 && 1.0 / 3.0 - f <= 2f64.powi(-16), "{method:?}: fraction {f}");
        // The apex at 1 - 3 f = 2^-16: just above the base.
        assert_eq!(deformer.positions()[2], [0.0, 2f64.powi(-16)], "{method:?}");
        assert_eq!(deformer.metrics().flipped, 0);

        // From there, a push that lifts the apex is taken whole; and a triangle already
        // turned over cannot block a step: pushed further down it stays so, in one step.
        let lift = [[0.0, 0.0], [0.0, 0.0], [0.0, 1.0]];
        let report = step_without_foldovers(&mut deformer, &lift, &FoldoverGuard::default()).unwrap();
        assert_eq!(report.steps, [1.0]);
        deformer.set_positions(&[[0.0, 0.0], [1.0, 0.0], [0.0, -1.0]]).unwrap();
        let report = step_without_foldovers(&mut deformer, &push, &FoldoverGuard::default()).unwrap();
        assert_eq!((report.steps.as_slice(), report.clamped), ([1.0].as_slice(), false), "{method:?}");
        assert_eq!(deformer.positions()[2], [0.0, -4.0]);
    }
}

#[test]
fn no_splits_clamps_the_whole_step_and_no_trials_take_nothing() {
    let mesh = Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[0, 1, 2]]).unwrap();
    let push = [[0.0, 0.0], [0.0, 0.0], [0.0, -3.0]];
    let mut deformer = Deformer::new(mesh, MethodOptions::Mls(MlsOptions::default())).unwrap();
    deformer.set_handle_vertices(&[0, 1, 2]).unwrap();
    let guard = FoldoverGuard::default().with_max_splits(0);
    let report = step_without_foldovers(&mut deformer, &push, &guard).unwrap();
    // The whole push clamped: twelve bits of 1/3, after the whole push and twelve trials.
    assert_eq!(report, GuardedStep { steps: vec![1365.0 / 4096.0], clamped: true, attempts: 13 });
    assert_eq!(deformer.positions()[2], [0.0, 1.0 / 4096.0]);
    let before = bits(deformer.positions());
    let report = step_without_foldovers(&mut deformer, &push, &guard.with_clamp_trials(0)).unwrap();
    assert_eq!(report, GuardedStep { steps: vec![], clamped: true, attempts: 1 });
    assert_eq!(bits(deformer.positions()), before);
}

/// A deformer whose step number `fail_at` (counted from 1 in `steps`; never with 0) fails
/// as a step that overflows would: the deformer unchanged, [`DeformError::NonFiniteResult`].
#[derive(Debug)]
struct FailsAt {
    inner: Deformer,
    steps: usize,
    fail_at: usize,
}

impl Undoable for FailsAt {
    fn mesh(&self) -> &Mesh {
        self.inner.mesh()
    }
    fn positions(&self) -> &[Point] {
        self.inner.positions()
    }
    fn handle_count(&self) -> usize {
        self.inner.handle_count()
    }
    fn step(&mut self, velocities: &[[f64; 2]]) -> Result<(), DeformError> {
        self.steps += 1;
        if self.steps == self.fail_at {
            return Err(DeformError::NonFiniteResult);
        }
        self.inner.step(velocities)
    }
    fn step_turning(&mut self, velocities: &[[f64; 2]], turns: &[f64]) -> Result<(), DeformError> {
        self.steps += 1;
        if self.steps == self.fail_at {
            return Err(DeformError::NonFiniteResult);
        }
        self.inner.step_turning(velocities, turns)
    }
    fn save_checkpoint(&self, checkpoint: &mut Checkpoint) {
        self.inner.save_checkpoint(checkpoint);
    }
    fn restore_checkpoint(&mut self, checkpoint: &Checkpoint) -> Result<(), DeformError> {
        self.inner.restore_checkpoint(checkpoint)
    }
}
