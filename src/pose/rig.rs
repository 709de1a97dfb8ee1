//! Posing with a trained rig ([`Rig`]): the operator evaluated at the handles' targets, and,
//! with [`super::Tracking::no_foldovers`], the rig's guard, which the step guard of
//! [`crate::deform::foldover`] cannot be (a rig has no step to split: it maps targets to a
//! pose, with no history).
//!
//! The guard keeps every *watched* triangle positive: one positive in the rig's rest pose
//! (its pose for the handles' rest places) and in the pose the way starts from. A frame
//! evaluates the rig at the new targets; if a watched triangle is not positive there, it
//! bisects the fraction `t` of the way from the targets the pose is for (the last accepted)
//! to the new ones, `start + t (new - start)`, to `2^-k` of the way, `k` the step guard's
//! [`crate::deform::FoldoverGuard::clamp_trials`] (as it bisects its clamp; `2^-k` itself is
//! tried first, so that a drag held on past a fold costs two evaluations a frame), and poses
//! at the largest `t` found whose pose turns no watched triangle over: possibly 0, the pose
//! it had. Orientation is the step
//! guard's ([`positive_triangles`]: exact on the pose scaled by a power of two), so a
//! triangle the rig's rest pose has flipped or degenerate never blocks, nor one already
//! turned over where the way starts. When the pose is not the rig's (the rig just set, the
//! pose set otherwise or reset), the way starts at the rig's rest pose, where nothing watched
//! is turned over, so the guard always finds a pose.
//!
//! A session names the rig by the checksum of its operator file ([`session_rig`]) and records
//! each frame as the targets the pose is for, which the rig evaluates again to the same bits.

use crate::defop::file::write_operator;
use crate::defop::{FitError, GpuRig, Operator};
use crate::deform::foldover::positive_triangles;
use crate::deform::{DeformError, Deformer};
use crate::geometry::{self, Point};
use crate::mesh::Mesh;
use crate::session::SessionRig;

/// How a session names `operator` posing `mesh`: the FNV-1a 64 checksum of the operator
/// file [`write_operator`] writes for them (its last 8 bytes). Refused as `write_operator`
/// refuses (another vertex count, a puppet that does not fit the mesh).
pub fn session_rig(mesh: &Mesh, operator: &Operator) -> Result<SessionRig, FitError> {
    let bytes = write_operator(mesh, operator)?;
    let tail = bytes.last_chunk::<8>().expect("an operator file ends with its checksum");
    Ok(SessionRig { checksum: u64::from_le_bytes(*tail) })
}

/// A trained rig posing the shape: the operator, the targets it was asked for and
/// those its pose is for, and what its no-foldover guard keeps. Targets are x and y
/// interleaved, one pair per handle.
#[derive(Debug, Clone)]
pub(super) struct Rig {
    pub(super) operator: Operator,
    /// The targets of the last frame that evaluated (empty: none yet): a frame with the same
    /// targets does nothing.
    pub(super) asked: Vec<f64>,
    /// The targets the pose is the rig's for, where a guard left them (empty: the pose is
    /// not the rig's).
    pub(super) posed: Vec<f64>,
    /// The targets to evaluate at (scratch).
    pub(super) targets: Vec<f64>,
    // The guard's: the targets and the pose of a trial, which triangles are positive in the
    // rig's rest pose, which it keeps positive, and which a trial has positive.
    way: Vec<f64>,
    trial: Vec<Point>,
    at_rest: Vec<bool>,
    watched: Vec<bool>,
    positive: Vec<bool>,
    /// Whether the recording has named the rig (a `rig` event): its frames are then recorded
    /// as `rigPose` events, else as poses.
    pub(super) announced: bool,
    /// The rig on the GPU (`Poser::set_rig_on_gpu`): each pose also computes its frame.
    pub(super) gpu: Option<GpuRig>,
    /// Whether the deformer's positions are behind `posed` (a frame on the GPU only since).
    pub(super) stale: bool,
}

impl Rig {
    pub(super) fn new(operator: Operator, handles: usize) -> Self {
        Self {
            operator,
            asked: Vec::new(),
            posed: Vec::new(),
            targets: vec![0.0; 2 * handles],
            way: Vec::new(),
            trial: Vec::new(),
            at_rest: Vec::new(),
            watched: Vec::new(),
            positive: Vec::new(),
            announced: false,
            gpu: None,
            stale: false,
        }
    }

    /// The pose is not the rig's any more (set otherwise, reset, stepped, other handles):
    /// the next frame evaluates afresh, its way from the rig's rest pose.
    pub(super) fn forget_pose(&mut self) {
        self.asked.clear();
        self.posed.clear();
        self.watched.clear();
        self.stale = false;
    }

    /// The rig's pose for `targets`, straight into the deformer's positions (no guard).
    pub(super) fn pose(&mut self, deformer: &mut Deformer) -> Result<(), DeformError> {
        let Self { operator, targets, .. } = self;
        deformer
            .set_positions_with(|out| operator.evaluate_into(targets, out).map_err(|_| DeformError::NonFiniteResult))?;
        self.posed.clone_from(&self.targets);
        self.watched.clear();
        self.frame()
    }

    /// On the GPU: the rig's frame for `targets` only, the deformer's positions left behind
    /// (`stale`) until `Poser::settle`.
    pub(super) fn frame_on_gpu(&mut self) -> Result<(), DeformError> {
        let gpu = self.gpu.as_mut().expect("a rig on the GPU");
        gpu.frame(&self.targets).map_err(|_| DeformError::NonFiniteResult)?;
        self.posed.clone_from(&self.targets);
        self.watched.clear();
        self.stale = true;
        Ok(())
    }

    /// After the deformer's positions became the rig's pose for `posed`: the frame on the
    /// GPU for the same targets, if the rig is there.
    fn frame(&mut self) -> Result<(), DeformError> {
        self.stale = false;
        match &mut self.gpu {
            Some(gpu) => gpu.frame(&self.posed).map(drop).map_err(|_| DeformError::NonFiniteResult),
            None => Ok(()),
        }
    }

    /// The rig's pose for `targets`, or pulled back along the way to them until no watched
    /// triangle turns over (see the module's description), to `2^-trials` of the way.
    /// Returns whether the pose changed and whether it stopped short. On error the deformer
    /// is unchanged and the rig forgets its pose.
    pub(super) fn pose_without_foldovers(
        &mut self,
        deformer: &mut Deformer,
        trials: u32,
    ) -> Result<(bool, bool), DeformError> {
        let result = self.guarded(deformer, trials);
        if result.is_err() {
            self.forget_pose();
        }
        result
    }

    fn guarded(&mut self, deformer: &mut Deformer, trials: u32) -> Result<(bool, bool), DeformError> {
        let triangles = deformer.mesh().triangles();
        self.way.resize(self.targets.len(), 0.0);
        self.trial.resize(deformer.positions().len(), [0.0; 2]);
        if self.at_rest.is_empty() {
            // Once per rig: which triangles its rest pose has positive.
            self.way.copy_from_slice(self.operator.handle_basis().rest());
            self.evaluate_way()?;
            positive_triangles(&self.trial, triangles, &mut self.at_rest);
        }
        let from_rest = self.posed.is_empty();
        if from_rest {
            self.posed.extend_from_slice(self.operator.handle_basis().rest());
            self.watched.clone_from(&self.at_rest);
        } else if self.watched.is_empty() {
            positive_triangles(deformer.positions(), triangles, &mut self.positive);
            self.watched.clear();
            self.watched.extend(self.at_rest.iter().zip(&self.positive).map(|(&r, &p)| r && p));
        }
        if self.try_at(1.0, triangles)? {
            self.accept(deformer)?;
            return Ok((true, false));
        }
        // The bisection to `least` = 2^-trials of the way, its smallest fraction tried first:
        // a drag held on past a fold stops there frame after frame, each frame then two
        // evaluations, not a whole bisection.
        let least = geometry::power_of_two(-(trials as i32));
        let (mut good, mut bad, mut at_good) = (0.0, 1.0, false);
        if trials > 0 {
            at_good = self.try_at(least, triangles)?;
            (good, bad) = if at_good { (least, bad) } else { (good, least) };
        }
        while bad - good > least {
            let t = 0.5 * (good + bad);
            at_good = self.try_at(t, triangles)?;
            (good, bad) = if at_good { (t, bad) } else { (good, t) };
        }
        if good == 0.0 && !from_rest {
            return Ok((false, true));
        }
        if !at_good {
            // The same targets again: the same bits, turning nothing watched over (for
            // `t` 0 from rest, the rig's rest pose).
            self.try_at(good, triangles)?;
        }
        self.accept(deformer)?;
        Ok((true, true))
    }

    /// Whether the rig's pose at the fraction `t` of the way from `posed` to `targets` (into
    /// `way` and `trial`) keeps every watched triangle positive.
    fn try_at(&mut self, t: f64, triangles: &[[u32; 3]]) -> Result<bool, DeformError> {
        for ((w, &p), &q) in self.way.iter_mut().zip(&self.posed).zip(&self.targets) {
            *w = if t == 1.0 { q } else { p + t * (q - p) };
        }
        self.evaluate_way()?;
        positive_triangles(&self.trial, triangles, &mut self.positive);
        Ok(!self.watched.iter().zip(&self.positive).any(|(&watched, &positive)| watched && !positive))
    }

    fn evaluate_way(&mut self) -> Result<(), DeformError> {
        (self.operator.evaluate_into(&self.way, self.trial.as_flattened_mut()))
            .map_err(|_| DeformError::NonFiniteResult)
    }

    /// The last trial becomes the pose, its targets those the pose is for.
    fn accept(&mut self, deformer: &mut Deformer) -> Result<(), DeformError> {
        deformer.set_positions(&self.trial)?;
        self.posed.clone_from(&self.way);
        self.watched.clear();
        self.watched.extend(self.at_rest.iter().zip(&self.positive).map(|(&r, &p)| r && p));
        self.frame()
    }
}
