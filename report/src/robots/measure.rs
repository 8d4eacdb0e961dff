//! A robot run measured against Pinocchio's reference motion at every sample: the largest joint-position error, for a
//! floating base the base origin's and orientation's, the largest energy change, and the robot drawn as a stick figure
//! at the snapshot times.

use dynamics::simulate::Simulation;
use dynamics::{Algebra, Dynamics, Mechanism, Reference, State};
use nalgebra::{Isometry3, Quaternion, UnitQuaternion, Vector3};
use reference::robots::RobotReference;
use scenarios::RobotScene;

use crate::runs::{metrics_error, RunError};

/// The times of the stick figures of the motion (s).
pub(crate) const SNAPSHOT_TIMES: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// The robot drawn as a stick figure at one instant: segments between joint origins, and the bodies' centres of
/// mass (m, world).
#[derive(Clone, Debug, PartialEq)]
pub struct StickFigure {
    /// The time (s).
    pub t: f64,
    /// Each joint origin joined to its parent's (the base frame origin for joints on the root), then each end body's
    /// joint origin joined to its farthest merged link frame (a foot, the tool flange).
    pub segments: Vec<[Vector3<f64>; 2]>,
    /// The bodies' centres of mass.
    pub centres: Vec<Vector3<f64>>,
    /// The whole robot's centre of mass.
    pub centre: Vector3<f64>,
}

/// A run's errors against the reference and its stick figures.
pub(crate) struct Measured {
    /// The largest joint-position error against the reference over every sample (rad).
    pub(crate) joint_error: f64,
    /// Base origin (m) and orientation (rad) errors.
    pub(crate) base: Option<(f64, f64)>,
    pub(crate) energy_change: f64,
    pub(crate) figures: Vec<StickFigure>,
}

/// The bodies' states at sample `k` of a run, from its recorded poses and velocities.
fn states_at<A: Algebra>(mechanism: &Mechanism<A>, run: &Simulation<A>, k: usize) -> Vec<State<A>> {
    run.bodies
        .iter()
        .enumerate()
        .map(|(i, samples)| {
            let s = &samples[k];
            State::from_world_twist(
                Dynamics::body(mechanism, i),
                s.position,
                &s.orientation,
                s.angular_velocity,
                s.velocity,
            )
        })
        .collect()
}

/// The angle (rad) of the turn between the reference's orientation and the quaternion `q` (w, x, y, z).
fn angle_between(reference: &UnitQuaternion<f64>, q: &[f64]) -> f64 {
    let ours = UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]));
    reference.rotation_to(&ours).angle()
}

/// A run's errors against the reference: the run must be sampled at the reference's times.
pub(crate) fn measure_robot<A: Algebra>(scene: &RobotScene<A>, run: &Simulation<A>) -> Result<Measured, RunError> {
    let mechanism = scene.robot.mechanism();
    let reference: &RobotReference = &scene.reference;
    let space = mechanism.joint_space().map_err(metrics_error)?;
    let offsets: Vec<usize> = reference
        .joints
        .iter()
        .map(|name| {
            space
                .group(name)
                .map(|g| g.position_offset())
                .ok_or_else(|| metrics_error(format!("no joint `{name}` in the mechanism")))
        })
        .collect::<Result<_, _>>()?;
    // A floating base's coordinates: its frame's origin and orientation (x, y, z, qw, qx, qy, qz).
    let base = space
        .groups()
        .iter()
        .find(|g| g.joint().is_none())
        .map(|g| g.position_offset());
    let recorded = run.bodies.first().map_or(0, Vec::len);
    if recorded != reference.samples.len() {
        return Err(metrics_error(format!(
            "{recorded} samples, the reference has {}",
            reference.samples.len()
        )));
    }
    let energy_start = run.bodies[0][0].energy;
    let (mut joint_error, mut energy_change) = (0.0f64, 0.0f64);
    let mut base_error: Option<(f64, f64)> = None;
    let mut previous: Option<Vec<f64>> = None;
    let mut figures = Vec::new();
    for (k, expected) in reference.samples.iter().enumerate() {
        let t = run.bodies[0][k].t;
        if (t - expected.t).abs() > 1e-9 {
            return Err(metrics_error(format!(
                "sample {k} at t = {t}, the reference's at {}",
                expected.t
            )));
        }
        let states = states_at(mechanism, run, k);
        let q = mechanism
            .joint_positions(&states, previous.as_deref())
            .map_err(metrics_error)?;
        for (&at, value) in offsets.iter().zip(&expected.joints) {
            joint_error = joint_error.max((q[at] - value).abs());
        }
        if let (Some(at), Some((position, orientation))) = (base, &expected.base) {
            let origin = (Vector3::new(q[at], q[at + 1], q[at + 2]) - position).norm();
            let turn = angle_between(orientation, &q[at + 3..at + 7]);
            let (o, r) = base_error.unwrap_or((0.0, 0.0));
            base_error = Some((o.max(origin), r.max(turn)));
        }
        energy_change = energy_change.max((run.bodies[0][k].energy - energy_start).abs());
        if !joint_error.is_finite() {
            return Err(metrics_error(format!("the joint positions are not finite at t = {t}")));
        }
        if SNAPSHOT_TIMES.iter().any(|&s| (s - expected.t).abs() < 1e-9) {
            figures.push(stick_figure(scene, run, k));
        }
        previous = Some(q);
    }
    Ok(Measured {
        joint_error,
        base: base_error,
        energy_change,
        figures,
    })
}

/// The robot at sample `k` as a stick figure (see [`StickFigure`]).
fn stick_figure<A: Algebra>(scene: &RobotScene<A>, run: &Simulation<A>, k: usize) -> StickFigure {
    let mechanism = scene.robot.mechanism();
    let poses: Vec<Isometry3<f64>> = run
        .bodies
        .iter()
        .map(|samples| Isometry3::from_parts(samples[k].position.into(), samples[k].orientation))
        .collect();
    let mut segments = Vec::new();
    // Each group's origin: the joint origin (the child's joint frame), or a free root's base frame origin.
    let mut origins: Vec<Option<Vector3<f64>>> = vec![None; poses.len()];
    let mut has_children = vec![false; poses.len()];
    if let Ok(space) = mechanism.joint_space() {
        for group in space.groups() {
            let body = group.body().index();
            origins[body] = Some((poses[body] * group.model().child_frame()).translation.vector);
        }
        for group in space.groups() {
            let Some(joint) = group.joint() else { continue };
            let parent = match mechanism.joint(joint) {
                Some((_, _, Reference::Body(parent))) => {
                    has_children[parent.index()] = true;
                    origins[parent.index()]
                }
                // A joint on a fixed root: the base frame is the world's.
                _ => Some(Vector3::zeros()),
            };
            if let (Some(from), Some(to)) = (parent, origins[group.body().index()]) {
                segments.push([from, to]);
            }
        }
    }
    // The end bodies: their joint origin joined to their farthest merged link frame (a foot, the tool flange).
    for (body, name) in mechanism.body_names().enumerate() {
        let (Some(origin), false) = (origins[body], has_children[body]) else {
            continue;
        };
        let Some(rigid) = scene.robot.model().bodies.iter().find(|b| b.name == name) else {
            continue;
        };
        let farthest = rigid
            .links
            .iter()
            .filter_map(|link| scene.robot.link_frame(&link.name))
            .filter(|(reference, _)| matches!(reference, Reference::Body(b) if b.index() == body))
            .map(|(_, frame)| (poses[body] * frame).translation.vector)
            .max_by(|a, b| (a - origin).norm().total_cmp(&(b - origin).norm()));
        if let Some(end) = farthest.filter(|end| (end - origin).norm() > 0.01) {
            segments.push([origin, end]);
        }
    }
    let centres: Vec<Vector3<f64>> = poses.iter().map(|p| p.translation.vector).collect();
    let total: f64 = (0..poses.len()).map(|i| Dynamics::body(mechanism, i).mass()).sum();
    let centre = centres
        .iter()
        .enumerate()
        .map(|(i, c)| c * Dynamics::body(mechanism, i).mass())
        .sum::<Vector3<f64>>()
        / total;
    StickFigure {
        t: run.bodies[0][k].t,
        segments,
        centres,
        centre,
    }
}
