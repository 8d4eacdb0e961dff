//! The mechanisms of the main job (docs/scenes.md): the configurations of M1 (double pendulum) and M2 (four-bar
//! linkage) over algebra × joint formulation × integrator × step, the M3 chain's cost per step against its
//! length, and running one configuration (its measures come from [`scenarios::mechanism_measures`]).

use dynamics::constraints::Stabilisation;
use dynamics::integrate::{Integrator, Method};
use dynamics::simulate::{simulate, Schedule};
use dynamics::{Cga, Pga};
use reference::multibody::CHAIN_LENGTHS;
use scenarios::mechanism_measures::{measure, MechanismMeasures};
use scenarios::{build_mechanism, Formulation, MechanismId, SceneAlgebra};
use scene_file::AlgebraKind;
use std::collections::BTreeMap;

use crate::runs::{metrics_error, simulation_error, RunError};

/// M3's cost is measured as MuJoCo's is (`chain.py`): RK4 at dt = 1e-3, ball joints (virtual power: three
/// reaction forces per joint), here over this much simulated time.
pub(crate) const CHAIN_TIMING_DURATION: f64 = 1.0;

/// M3's long run: the longest chain over docs/scenes.md's 10 s with the most accurate method, for its energy
/// drift and joint violation.
pub(crate) const CHAIN_LONG_RUN: (usize, Method, f64) = (64, Method::Rkmk6Body, 1e-3);

/// Which mechanisms the job runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MechanismKind {
    /// M1, the double pendulum.
    DoublePendulum,
    /// M2, the four-bar linkage.
    FourBar,
    /// M3, the chain: its cost per step at each length, and the long run.
    Chain,
}

impl MechanismKind {
    /// M1, M2 and M3, in the report's order.
    pub const ALL: [MechanismKind; 3] = [
        MechanismKind::DoublePendulum,
        MechanismKind::FourBar,
        MechanismKind::Chain,
    ];
}

/// One mechanism run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MechanismConfig {
    /// The mechanism (a chain with its number of links).
    pub id: MechanismId,
    pub(crate) algebra: AlgebraKind,
    pub(crate) formulation: Formulation,
    pub(crate) method: Method,
    pub(crate) dt: f64,
    pub(crate) duration: f64,
    pub(crate) stabilisation: Stabilisation,
}

impl MechanismConfig {
    /// "PGA, pinning, RKMK6-body".
    pub fn series_label(&self) -> String {
        format!(
            "{}, {}, {}",
            self.algebra.name(),
            self.formulation.name(),
            self.method.name()
        )
    }

    /// A run of M3 that measures the cost per step (RK4), not the long run's drift.
    pub fn is_chain_timing(&self) -> bool {
        matches!(self.id, MechanismId::Chain(_)) && self.method == Method::Rk4
    }
}

/// What the mechanism part of the job covers (the integrators, duration and stabilisation are the job's).
#[derive(Clone, Debug, Default)]
pub struct MechanismPlan {
    /// The mechanisms to run; none if empty.
    pub mechanisms: Vec<MechanismKind>,
    /// Step sizes of the M1 and M2 sweeps.
    pub steps: Vec<f64>,
}

/// The M1 and M2 steps without `--steps`: from past MuJoCo's coarsest (the eighth-order method reaches MuJoCo's
/// accuracy at dt = 1e-3 only above 1e-2) to well past that accuracy for the fourth-order methods (the sixth-order
/// one reaches round-off near dt = 2e-3).
pub(crate) const DEFAULT_STEPS: [f64; 9] = [4e-2, 2.5e-2, 2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4];

impl MechanismPlan {
    /// Every run: M1 and M2 over algebra × formulation × method × step (splittings apply to free bodies only);
    /// M3 in both algebras at each chain length of docs/scenes.md (RK4, dt = 1e-3, for the cost), plus the long
    /// run. `duration` overrides every mechanism's.
    pub(crate) fn configurations(
        &self,
        integrators: &[Integrator],
        duration: Option<f64>,
        stabilisation: Stabilisation,
    ) -> Vec<MechanismConfig> {
        let methods: Vec<Method> = integrators
            .iter()
            .filter_map(|i| match i {
                Integrator::General(method) => Some(*method),
                // The reference mechanisms' joints are constraints, not joint models; splittings are for free bodies.
                Integrator::Splitting(_) | Integrator::Joint(_) => None,
            })
            .collect();
        let mut configs = Vec::new();
        for &kind in &self.mechanisms {
            for algebra in AlgebraKind::ALL {
                let config = |id: MechanismId, formulation, method, dt, own_duration: f64| MechanismConfig {
                    id,
                    algebra,
                    formulation,
                    method,
                    dt,
                    duration: duration.unwrap_or(own_duration),
                    stabilisation,
                };
                match kind {
                    MechanismKind::DoublePendulum | MechanismKind::FourBar => {
                        let id = if kind == MechanismKind::FourBar {
                            MechanismId::FourBar
                        } else {
                            MechanismId::DoublePendulum
                        };
                        for formulation in Formulation::ALL {
                            for &method in &methods {
                                // Steps past MuJoCo's coarsest serve the high-order methods; the fourth-order
                                // ones are far off at 1e-2 already, and the pinning formulation's stage
                                // states leave the joint manifold so far at 2e-2 that its acceleration
                                // conditions become inconsistent (a refused run, not a data point).
                                let steps = self.steps.iter().filter(|&&dt| dt <= 1e-2 || method.order() >= 6);
                                for &dt in steps {
                                    configs.push(config(id, formulation, method, dt, id.duration()));
                                }
                            }
                        }
                    }
                    MechanismKind::Chain => {
                        for n in CHAIN_LENGTHS {
                            let id = MechanismId::Chain(n);
                            configs.push(config(
                                id,
                                Formulation::VirtualPower,
                                Method::Rk4,
                                1e-3,
                                CHAIN_TIMING_DURATION,
                            ));
                        }
                        let (n, method, dt) = CHAIN_LONG_RUN;
                        let id = MechanismId::Chain(n);
                        configs.push(config(id, Formulation::VirtualPower, method, dt, id.duration()));
                    }
                }
            }
        }
        configs
    }
}

/// A finished mechanism run.
#[derive(Clone, Debug)]
pub struct MechanismOutcome {
    pub(crate) config: MechanismConfig,
    /// Stepping time divided by the simulated time (s/s).
    pub(crate) cpu_per_simulated_second: f64,
    /// Stepping time per step (s).
    pub(crate) time_per_step: f64,
    /// Errors against the references, energy drift and joint violation.
    pub measures: MechanismMeasures,
}

/// A mechanism run and its outcome, or why it failed.
pub type MechanismResult = (MechanismConfig, Result<MechanismOutcome, RunError>);

/// Runs one configuration.
pub(crate) fn run_mechanism(config: &MechanismConfig) -> Result<MechanismOutcome, RunError> {
    match config.algebra {
        AlgebraKind::Cga => run_in::<Cga>(config),
        AlgebraKind::Pga => run_in::<Pga>(config),
    }
}

fn run_in<A: SceneAlgebra>(config: &MechanismConfig) -> Result<MechanismOutcome, RunError> {
    // The four-bar is sampled every step, so its revolution times are interpolated to O(dt⁴) (Hermite); the
    // others every 0.01 s, the references' grid, or every step if the steps are longer (only the end state is
    // compared with the reference).
    let sample_interval = match config.id {
        MechanismId::FourBar => config.dt,
        _ => config.dt.max(0.01),
    };
    let schedule =
        Schedule::with_sample_interval(config.dt, config.duration, sample_interval).map_err(simulation_error)?;
    let scene = build_mechanism::<A>(config.id, config.formulation, config.stabilisation)?;
    let run = simulate(&scene.system, &scene.initial, config.method, &schedule).map_err(simulation_error)?;
    let measures = measure(config.id, &run.bodies).map_err(metrics_error)?;
    let stepping = run.stepping_time.as_secs_f64();
    Ok(MechanismOutcome {
        config: *config,
        cpu_per_simulated_second: stepping / schedule.duration(),
        time_per_step: stepping / run.statistics.accepted.max(1) as f64,
        measures,
    })
}

/// Why the runs of M1 or M2 cannot be compared with MuJoCo's error at the mechanism's T, if they cannot.
pub(crate) fn length_mismatch(results: &[MechanismResult], id: MechanismId) -> Option<String> {
    results
        .iter()
        .filter(|(c, _)| c.id == id)
        .find_map(|(c, _)| crate::measure::length_mismatch(c.duration, id.duration()))
}

/// The successful runs of one mechanism, by series label, each sorted by cost.
pub(crate) fn series_of(results: &[MechanismResult], id: MechanismId) -> BTreeMap<String, Vec<&MechanismOutcome>> {
    let mut groups: BTreeMap<String, Vec<&MechanismOutcome>> = BTreeMap::new();
    for (config, result) in results {
        if let (true, Ok(outcome)) = (config.id == id, result) {
            groups.entry(config.series_label()).or_default().push(outcome);
        }
    }
    for runs in groups.values_mut() {
        runs.sort_by(|a, b| a.cpu_per_simulated_second.total_cmp(&b.cpu_per_simulated_second));
    }
    groups
}

/// The error M1 and M2 are compared by: end orientation (M1, MuJoCo's measure), coupler position (M2).
pub(crate) fn headline_error(outcome: &MechanismOutcome) -> Option<f64> {
    match outcome.config.id {
        MechanismId::FourBar => outcome.measures.four_bar.map(|f| f.coupler_error),
        _ => outcome.measures.orientation_end,
    }
}
