//! Replaying a session's events on a poser: as recorded ([`replay`], the recorded
//! method, switching methods where the recording did; [`replay_with_rigs`] with the trained
//! rigs it names), or driving another method to the recorded targets
//! ([`replay_to_targets`]).

use super::{session_rig, Poser};
use crate::defop::Operator;
use crate::deform::{DeformError, Deformer};
use crate::geometry::Point;
use crate::session::{Event, Session, SessionError, SessionJoint};

/// What a replay did.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Replay {
    /// For every step, the handles' targets: position before the step plus velocity.
    pub targets: Vec<Vec<Point>>,
    /// For every step, the milliseconds the deformer's timings report (all stages).
    pub frame_ms: Vec<f64>,
    /// Mean distance of the shape's points under the handles from the targets of the last
    /// event, if it was a step.
    pub handle_error: Option<f64>,
}

/// Replays the events as recorded, the velocities as given, on `deformer` (normally
/// [`Session::recorded_deformer`]), through a [`Poser`] of it. An `options` event is put
/// into effect by [`Poser::set_options`], as the widget does: one of another method puts a
/// solver of that method behind the deformer, the pose and the handles carried over. With
/// the recorded method and options this repeats the recording exactly. A session that
/// names a trained rig needs [`replay_with_rigs`].
pub fn replay(session: &Session, deformer: &mut Deformer) -> Result<Replay, SessionError> {
    run(session, &mut Poser::new(deformer), None, &[])
}

/// [`replay`] with the trained rigs the session may name: a `rig` event poses with the one
/// of `rigs` it names ([`super::session_rig`] with the deformer's mesh), each `rigPose`
/// evaluates it at the recorded targets ([`Poser::pose_with_rig`]), to the same bits as
/// recorded. A `rig` event naming none of them is refused ([`SessionError::MissingRig`]).
pub fn replay_with_rigs(session: &Session, deformer: &mut Deformer, rigs: &[Operator]) -> Result<Replay, SessionError> {
    run(session, &mut Poser::new(deformer), None, rigs)
}

/// Replays the events driving every handle to the recorded targets (see [`Replay::targets`]
/// of a [`replay`] with the recorded deformer): each step is [`Poser::step_toward`] the
/// targets in one step,
/// its velocity the target minus the handle's current position. `options` events are
/// passed over: the method compared keeps its settings. `positions` events put it into the
/// recorded pose. `stiffness` and `bones` events paint it or set them, or are passed over
/// by a method without stiffness or bones. `rig` events are passed over, and each
/// `rigPose` is a step toward its targets.
pub fn replay_to_targets(
    session: &Session,
    targets: &[Vec<Point>],
    deformer: &mut Deformer,
) -> Result<Replay, SessionError> {
    run(session, &mut Poser::new(deformer), Some(targets), &[])
}

/// Sets stiffness or bones with `set`; a compared method (`compared`) without them passes
/// over it and poses the shape as it can.
fn set<P>(
    poser: &mut P,
    compared: bool,
    set: impl FnOnce(&mut P) -> Result<(), DeformError>,
) -> Result<(), DeformError> {
    match set(poser) {
        Err(DeformError::Unsupported { .. }) if compared => Ok(()),
        result => result,
    }
}

fn run(
    session: &Session,
    poser: &mut Poser<&mut Deformer>,
    targets: Option<&[Vec<Point>]>,
    rigs: &[Operator],
) -> Result<Replay, SessionError> {
    let compared = targets.is_some();
    // How the session would name each rig given (one that cannot be named is none).
    let named: Vec<_> = rigs.iter().map(|rig| session_rig(poser.deformer().mesh(), rig).ok()).collect();
    let mut replay = Replay::default();
    let mut last_was_step = false;
    for (index, event) in session.events.iter().enumerate() {
        let refused = |error| SessionError::Event { index, error };
        last_was_step &=
            matches!(event, Event::Reset(false) | Event::Options(_) | Event::Stiffness(_) | Event::Bones { .. });
        match event {
            Event::Handles { triangles, barycentric } => {
                let weights = triples(barycentric, triangles.len(), "barycentric", "handles").map_err(refused)?;
                poser.set_handle_points(triangles, weights).map_err(refused)?;
            }
            Event::Step(flat) | Event::Turn { velocities: flat, .. } => {
                let turns = match event {
                    Event::Turn { turns, .. } => Some(turns),
                    _ => None,
                };
                let before = poser.deformer().handle_positions();
                let pairs = pairs(flat, "velocities", before.len(), "handles").map_err(refused)?;
                let goal: Vec<Point> = match targets {
                    None => before.iter().zip(pairs).map(|(p, v)| [p[0] + v[0], p[1] + v[1]]).collect(),
                    Some(all) => all.get(replay.targets.len()).ok_or(SessionError::MissingTargets { index })?.clone(),
                };
                match targets {
                    None => poser.step(pairs, turns.map(Vec::as_slice)),
                    Some(_) => {
                        if goal.len() != before.len() {
                            return Err(SessionError::MissingTargets { index });
                        }
                        poser.set_targets(&goal).and_then(|()| poser.step_toward(1.0, turns.map(Vec::as_slice)))
                    }
                }
                .map_err(refused)?;
                let t = poser.deformer().timings();
                replay.frame_ms.push(t.assembly + t.factorisation + t.solve + t.integration);
                replay.targets.push(goal);
                last_was_step = true;
            }
            Event::Positions(flat) => {
                let count = poser.deformer().mesh().vertex_count();
                let pairs = pairs(flat, "positions", count, "vertices").map_err(refused)?;
                poser.set_positions(pairs).map_err(refused)?;
            }
            Event::Options(recorded) => {
                if compared {
                    continue;
                }
                let options = recorded.over(poser.deformer().options(), Some(index))?;
                poser.set_options(options).map_err(refused)?;
            }
            Event::Stiffness(values) => {
                set(poser, compared, |p| p.set_stiffness(values.as_deref())).map_err(refused)?;
            }
            Event::Bones { triangles, barycentric } => {
                let ends = triples(barycentric, triangles.len(), "bone barycentric", "bone ends").map_err(refused)?;
                set(poser, compared, |p| p.set_bones(triangles, ends)).map_err(refused)?;
            }
            Event::Joints(joints) => poser.set_joints(SessionJoint::joints(joints)).map_err(refused)?,
            Event::Rig(_) if compared => {}
            Event::Rig(None) => poser.set_rig(None).map_err(refused)?,
            Event::Rig(Some(rig)) => {
                let given = named.iter().position(|n| n.as_ref() == Some(rig));
                let operator = given.map(|k| rigs[k].clone()).ok_or(SessionError::MissingRig { index, rig: *rig })?;
                poser.set_rig(Some(operator)).map_err(refused)?;
            }
            Event::RigPose(flat) => {
                let count = poser.handle_count();
                let goal = pairs(flat, "targets", count, "handles").map_err(refused)?;
                match compared {
                    false => poser.pose_with_rig(goal),
                    true => poser.set_targets(goal).and_then(|()| poser.step_toward(1.0, None)),
                }
                .map_err(refused)?;
            }
            Event::Reset(true) => poser.reset(),
            Event::Reset(false) => {}
        }
    }
    if last_was_step {
        let goal = replay.targets.last().expect("a step was replayed");
        // The shape's points under the handles (Cauchy-Green's handle positions are its
        // targets, which it meets in the least-squares sense only).
        let handles = poser.deformer().shape_under_handles();
        let total: f64 = handles.iter().zip(goal).map(|(p, t)| libm::hypot(p[0] - t[0], p[1] - t[1])).sum();
        replay.handle_error = Some(if handles.is_empty() { 0.0 } else { total / handles.len() as f64 });
    }
    Ok(replay)
}

/// `flat` as pairs (an x and a y each), or the error a deformer gives for an odd count:
/// `expected` pairs, one per item.
fn pairs<'a>(
    flat: &'a [f64],
    what: &'static str,
    expected: usize,
    items: &'static str,
) -> Result<&'a [[f64; 2]], DeformError> {
    match flat.as_chunks::<2>() {
        (pairs, []) => Ok(pairs),
        _ => Err(DeformError::Length { what, expected: 2 * expected, found: flat.len(), per: 2, items }),
    }
}

/// `flat` as `count` triples of barycentric coordinates (`what`, one triple per `items`).
fn triples<'a>(
    flat: &'a [f64],
    count: usize,
    what: &'static str,
    items: &'static str,
) -> Result<&'a [[f64; 3]], DeformError> {
    match flat.as_chunks::<3>() {
        (triples, []) if triples.len() == count => Ok(triples),
        _ => Err(DeformError::Length { what, expected: 3 * count, found: flat.len(), per: 3, items }),
    }
}
