//! The reference robots of the main job (`reference::robots`: the UR5 arm on a fixed base, the Solo-12 quadruped on
//! a floating base, built from their URDFs by [`scenarios::build_robot`]): their configurations over algebra ×
//! integrator × step, and running one against Pinocchio's reference motion (1 s, sampled every 0.01 s).
//!
//! Each run is measured at every sample of the reference: the largest joint-position error, for a floating base the
//! base origin's and orientation's, and the largest energy change. Steps longer than the sample interval take the
//! samples between steps by partial steps of the method (its own output at those times); their cost is measured on
//! a run sampled only at its steps, so the partial steps do not count. Runs are repeated for the timing and the
//! fastest repeat is kept (at least 5 repeats), which filters the shared machine's interruptions out of short runs.

use std::collections::BTreeMap;

use dynamics::integrate::{Integrator, Method};
use dynamics::simulate::{simulate, Schedule};
use dynamics::JointMethod;
use dynamics::{Algebra, Cga, Pga};
use reference::robots::RobotId;
use scenarios::{build_robot, RobotScene};
use scene_file::AlgebraKind;

use super::measure::{measure_robot, StickFigure};
use crate::markdown::{integrator_rank, RowKey};
use crate::runs::{fastest_of_repeats, metrics_error, simulation_error, RunError};

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
    /// use report::robots::{RobotPlan, DEFAULT_STEPS};
    ///
    /// let plan = RobotPlan::all();
    /// assert_eq!((plan.robots.len(), plan.joint_methods.len()), (2, 4)); // UR5 and Solo-12; RKMK4, 6, 8, DOP853
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

/// An integrator's place in the tables: the general methods in their order, then the joint-coordinate ones.
pub(crate) fn rank(integrator: Integrator) -> usize {
    match integrator {
        Integrator::Joint(method) => 100 + JointMethod::ALL.iter().position(|&m| m == method).unwrap_or(0),
        other => integrator_rank(other),
    }
}

pub(crate) fn row_key(config: &RobotConfig) -> RowKey {
    (config.algebra, 0, rank(config.integrator), config.dt)
}

/// A robot's successful runs by series (algebra, method), each sorted by cost.
pub(crate) fn series_of(results: &[RobotResult], id: RobotId) -> BTreeMap<(AlgebraKind, usize), Vec<&RobotOutcome>> {
    let mut groups: BTreeMap<(AlgebraKind, usize), Vec<&RobotOutcome>> = BTreeMap::new();
    for (config, result) in results {
        if let (true, Ok(outcome)) = (config.robot == id, result) {
            let (algebra, _, method, _) = row_key(config);
            groups.entry((algebra, method)).or_default().push(outcome);
        }
    }
    for runs in groups.values_mut() {
        runs.sort_by(|a, b| a.cpu_per_simulated_second.total_cmp(&b.cpu_per_simulated_second));
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::super::measure::SNAPSHOT_TIMES;
    use super::*;

    #[test]
    fn the_plan_covers_robot_algebra_method_and_step() {
        let plan = RobotPlan::all();
        let integrators = crate::single_bodies::sweep::default_integrators();
        let configs = plan.configurations(&integrators);
        // Splittings are left out: five general methods and four joint-coordinate ones; Solo-12 by RK4 without 4e-2,
        // 2e-2 and 1e-2, by RKMK4 without 4e-2 and 2e-2.
        assert_eq!(configs.len(), 2 * (2 * 9 * DEFAULT_STEPS.len() - 5));
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
