//! The reference robots of the main job (`reference::robots`: the UR5 arm on a fixed base, the Solo-12 quadruped on
//! a floating base, built from their URDFs by [`scenarios::build_robot`]): their configurations over algebra ×
//! integrator × step, and running one against Pinocchio's reference motion (1 s, sampled every 0.01 s).
//!
//! Each run is measured at every sample of the reference: the largest joint-position error, for a floating base the
//! base origin's and orientation's, and the largest energy change. Steps longer than the sample interval take the
//! samples between steps by partial steps of the method (its own output at those times); their cost is measured on
//! a run sampled only at its steps, so the partial steps do not count. Runs are repeated for the timing and the
//! fastest repeat is kept (at least 5 repeats), which filters the shared machine's interruptions out of short runs.

use dynamics::integrate::{Integrator, Method};
use dynamics::joint_integration::JointMethod;
use dynamics::simulate::{simulate, Schedule, Simulation};
use dynamics::{Algebra, Cga, Dynamics, Mechanism, Pga, Reference, State};
use nalgebra::{Isometry3, Quaternion, UnitQuaternion, Vector3};
use reference::robots::{RobotId, RobotReference};
use scenarios::{build_robot, RobotScene};

use crate::sweep::{AlgebraKind, RunError};

/// The robots' steps without `--steps` (s): from where only the eighth-order method is still accurate to where the
/// fourth-order ones reach MuJoCo's accuracy at dt = 1e-3. Steps above 0.01 s are whole divisors of the 1 s run.
pub const DEFAULT_STEPS: [f64; 8] = [4e-2, 2e-2, 1e-2, 5e-3, 2.5e-3, 1e-3, 5e-4, 2.5e-4];

/// The longest step a method runs a robot at, where the plan's steps go beyond what it survives: Solo-12 by the
/// world-momentum methods, whose runs diverge at longer steps ([`LEFT_OUT`], measured on the default steps). These
/// pairs are left out of the plan rather than reported as failed runs.
pub(crate) fn longest_step(robot: RobotId, integrator: Integrator) -> Option<f64> {
    match (robot, integrator) {
        (RobotId::Solo12, Integrator::General(Method::Rk4)) => Some(5e-3),
        (RobotId::Solo12, Integrator::General(Method::Rkmk4)) => Some(1e-2),
        _ => None,
    }
}

/// Why [`longest_step`] leaves pairs out, for the report.
pub(crate) const LEFT_OUT: &str = "RK4 runs Solo-12 only at dt ≤ 5e-3 and RKMK4 at dt ≤ 1e-2 (both carry the \
     momentum in the world frame): at longer steps they diverge within the second (RK4 at dt = 1e-2 had spun a lower leg up to 238 rad/s \
     by t = 0.87 s when the step guard stopped it; at 2e-2 and 4e-2, and RKMK4 at 2e-2 and 4e-2, the runs stopped \
     between 0.16 and 0.45 s with a leg turning more than a radian per step or a joint residual no longer finite), \
     while the body-momentum methods stay within 1e-5 rad at dt = 4e-2";

/// The times of the stick figures of the motion (s).
pub(crate) const SNAPSHOT_TIMES: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// Each configuration is timed over at least [`MIN_REPEATS`] runs unless these take [`LONG_TIMING`] s of stepping,
/// and over at least [`MIN_TIMING`] s of stepping, in at most [`MAX_REPEATS`] runs; the fastest run counts.
pub(crate) const MIN_REPEATS: usize = 5;
/// See [`MIN_REPEATS`] (s).
pub(crate) const LONG_TIMING: f64 = 0.4;
/// See [`MIN_REPEATS`] (s).
pub(crate) const MIN_TIMING: f64 = 0.05;
/// See [`MIN_REPEATS`].
pub(crate) const MAX_REPEATS: usize = 25;

/// The robot's name in the report.
pub fn robot_label(id: RobotId) -> &'static str {
    match id {
        RobotId::Ur5 => "UR5",
        RobotId::Solo12 => "Solo-12",
    }
}

/// What the robot part of the job covers: the job's general and joint-coordinate integrators and
/// [`RobotPlan::joint_methods`], each run over the reference's 1 s whatever the job's duration.
#[derive(Clone, Debug, Default)]
pub struct RobotPlan {
    /// The robots to run; none if empty.
    pub robots: Vec<RobotId>,
    /// The steps (s); each must divide the 0.01 s sample interval or be a whole number of them dividing 1 s.
    pub steps: Vec<f64>,
    /// Joint-coordinate methods to run besides the job's integrators (among the job's systems only the robots are
    /// trees of joint models, where they apply).
    pub joint_methods: Vec<JointMethod>,
}

impl RobotPlan {
    /// Both robots over [`DEFAULT_STEPS`], with every joint-coordinate method.
    ///
    /// ```
    /// use report::robot_sweep::{RobotPlan, DEFAULT_STEPS};
    ///
    /// let plan = RobotPlan::all();
    /// assert_eq!((plan.robots.len(), plan.joint_methods.len()), (2, 3)); // UR5 and Solo-12; RKMK4, 6 and 8
    /// assert_eq!(plan.steps, DEFAULT_STEPS);
    /// ```
    pub fn all() -> Self {
        RobotPlan {
            robots: RobotId::ALL.to_vec(),
            steps: DEFAULT_STEPS.to_vec(),
            joint_methods: JointMethod::ALL.to_vec(),
        }
    }

    /// Every run: robot × algebra × integrator × step, the integrators being the general and joint-coordinate ones
    /// of `integrators`, then [`RobotPlan::joint_methods`] (splittings apply to free bodies only), less the pairs
    /// [`longest_step`] leaves out.
    pub(crate) fn configurations(&self, integrators: &[Integrator]) -> Vec<RobotConfig> {
        let mut methods: Vec<Integrator> = integrators
            .iter()
            .copied()
            .filter(|i| matches!(i, Integrator::General(_) | Integrator::Joint(_)))
            .collect();
        for &method in &self.joint_methods {
            if !methods.contains(&Integrator::Joint(method)) {
                methods.push(Integrator::Joint(method));
            }
        }
        let mut configs = Vec::new();
        for &robot in &self.robots {
            for algebra in AlgebraKind::ALL {
                for &integrator in &methods {
                    let runs =
                        |dt: f64| longest_step(robot, integrator).is_none_or(|longest| dt <= longest * (1.0 + 1e-9));
                    for &dt in self.steps.iter().filter(|&&dt| runs(dt)) {
                        configs.push(RobotConfig {
                            robot,
                            algebra,
                            integrator,
                            dt,
                        });
                    }
                }
            }
        }
        configs
    }
}

/// One robot run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotConfig {
    /// The robot.
    pub robot: RobotId,
    /// The algebra it runs in.
    pub algebra: AlgebraKind,
    /// The integrator: a general method or a joint-coordinate one.
    pub integrator: Integrator,
    /// The step (s).
    pub dt: f64,
}

impl RobotConfig {
    /// "PGA, RKMK8-body".
    pub fn series_label(&self) -> String {
        format!("{}, {}", self.algebra.name(), self.integrator.name())
    }

    /// How much stepping the run does (for the scheduling: the slowest first).
    pub(crate) fn work(&self) -> f64 {
        let bodies = match self.robot {
            RobotId::Ur5 => 6.0,
            RobotId::Solo12 => 13.0,
        };
        bodies * f64::from(self.integrator.order()) / self.dt
    }
}

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

/// A finished robot run.
#[derive(Clone, Debug)]
pub struct RobotOutcome {
    pub(crate) config: RobotConfig,
    /// Stepping time divided by the simulated time (s/s): the fastest of `repeats` runs.
    pub cpu_per_simulated_second: f64,
    /// Stepping time per step (s), of the same run.
    pub time_per_step: f64,
    /// Whole steps.
    pub steps: usize,
    /// How many times the run was timed.
    pub repeats: usize,
    /// The largest joint-position error against the reference over every sample (rad).
    pub joint_error: f64,
    /// For a floating base, the largest error of the base frame's origin (m).
    pub base_position_error: Option<f64>,
    /// For a floating base, the largest angle between the base frame's orientation and the reference's (rad).
    pub base_orientation_error: Option<f64>,
    /// The largest |E − E₀| over the samples (J).
    pub energy_change: f64,
    /// The robot at the snapshot times (0, 0.25, 0.5, 0.75 and 1 s).
    pub figures: Vec<StickFigure>,
}

/// A robot run and its outcome, or why it failed.
pub type RobotResult = (RobotConfig, Result<RobotOutcome, RunError>);

/// Runs one configuration.
pub(crate) fn run_robot(config: &RobotConfig) -> Result<RobotOutcome, RunError> {
    match config.algebra {
        AlgebraKind::Cga => run_in::<Cga>(config),
        AlgebraKind::Pga => run_in::<Pga>(config),
    }
}

fn simulation_error(error: impl std::fmt::Display) -> RunError {
    RunError::Simulation(error.to_string())
}

fn metrics_error(error: impl std::fmt::Display) -> RunError {
    RunError::Metrics(error.to_string())
}

fn run_in<A: Algebra>(config: &RobotConfig) -> Result<RobotOutcome, RunError> {
    let scene: RobotScene<A> =
        build_robot::<A>(config.robot).map_err(|e| RunError::Simulation(format!("building the robot: {e}")))?;
    let mechanism = scene.robot.mechanism();
    let reference = &scene.reference;
    let (Some(first), Some(last)) = (reference.samples.first(), reference.samples.last()) else {
        return Err(metrics_error("the reference has no samples"));
    };
    let duration = last.t - first.t;
    let interval = duration / (reference.samples.len() - 1).max(1) as f64;
    // The timed run: samples at the reference's times, or at the steps if these are longer.
    let timed =
        Schedule::with_sample_interval(config.dt, duration, config.dt.max(interval)).map_err(simulation_error)?;
    let run = || simulate(mechanism, &scene.initial, config.integrator, &timed).map_err(simulation_error);
    let (first_run, best, repeats) = fastest_of_repeats(run)?;
    let steps = first_run.statistics.accepted;
    let sampled = if config.dt > interval * (1.0 + 1e-9) {
        // Every reference time, between the steps by partial steps of the method.
        let times = reference.samples[1..].iter().map(|s| s.t);
        let schedule = Schedule::at_times(config.dt, times).map_err(simulation_error)?;
        simulate(mechanism, &scene.initial, config.integrator, &schedule).map_err(simulation_error)?
    } else {
        first_run
    };
    let measured = measure_robot(&scene, &sampled)?;
    Ok(RobotOutcome {
        config: *config,
        cpu_per_simulated_second: best / duration,
        time_per_step: best / steps.max(1) as f64,
        steps,
        repeats,
        joint_error: measured.joint_error,
        base_position_error: measured.base.map(|b| b.0),
        base_orientation_error: measured.base.map(|b| b.1),
        energy_change: measured.energy_change,
        figures: measured.figures,
    })
}

/// Runs `run` until the timing rule of [`MIN_REPEATS`] is met: the first run, the fastest stepping time (s) and
/// the number of runs.
pub(crate) fn fastest_of_repeats<A: Algebra>(
    mut run: impl FnMut() -> Result<Simulation<A>, RunError>,
) -> Result<(Simulation<A>, f64, usize), RunError> {
    let first_run = run()?;
    let mut best = first_run.stepping_time.as_secs_f64();
    let (mut total, mut repeats) = (best, 1);
    while repeats < MAX_REPEATS && (total < MIN_TIMING || (repeats < MIN_REPEATS && total < LONG_TIMING)) {
        let again = run()?.stepping_time.as_secs_f64();
        best = best.min(again);
        total += again;
        repeats += 1;
    }
    Ok((first_run, best, repeats))
}

/// A run's errors against the reference and its stick figures.
pub(crate) struct Measured {
    /// The largest joint-position error against the reference over every sample (rad).
    pub(crate) joint_error: f64,
    /// Base origin (m) and orientation (rad) errors.
    base: Option<(f64, f64)>,
    energy_change: f64,
    figures: Vec<StickFigure>,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plan_covers_robot_algebra_method_and_step() {
        let plan = RobotPlan::all();
        let integrators = crate::sweep::default_integrators();
        let configs = plan.configurations(&integrators);
        // Splittings are left out: five general methods and three joint-coordinate ones; Solo-12 by RK4 without 4e-2,
        // 2e-2 and 1e-2, by RKMK4 without 4e-2 and 2e-2.
        assert_eq!(configs.len(), 2 * (2 * 8 * DEFAULT_STEPS.len() - 5));
        // Every default step gives a schedule of the reference's 1 s.
        for dt in DEFAULT_STEPS {
            assert!(Schedule::with_sample_interval(dt, 1.0, dt.max(0.01)).is_ok(), "{dt}");
        }
    }

    #[test]
    fn a_coarse_run_is_sampled_at_every_reference_time_and_near_it() {
        for id in RobotId::ALL {
            let config = RobotConfig {
                robot: id,
                algebra: AlgebraKind::Pga,
                integrator: Integrator::General(Method::Rkmk8Body),
                dt: 2e-2,
            };
            let outcome = run_robot(&config).unwrap();
            assert_eq!(outcome.steps, 50);
            assert_eq!(outcome.figures.len(), SNAPSHOT_TIMES.len());
            assert!(outcome.joint_error < 1e-3, "{id:?}: {}", outcome.joint_error);
            assert_eq!(outcome.base_position_error.is_some(), id == RobotId::Solo12);
            // UR5: six joints and the base link to the first; Solo-12: twelve joints and four feet.
            let segments = outcome.figures[0].segments.len();
            assert!(
                segments >= if id == RobotId::Ur5 { 6 } else { 16 },
                "{id:?}: {segments}"
            );
        }
    }
}
