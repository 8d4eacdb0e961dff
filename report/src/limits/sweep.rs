//! The scenes of `scenarios::limits` run in PGA and CGA with DOP853-body at a tolerance of 1e-12: the limited
//! coordinate and the energy at every sample, the transitions, how far a bound was passed and the energy drift net
//! of the impacts.

use std::time::Duration;

use dynamics::limits::LimitTransition;
use dynamics::{simulate, Algebra, Cga, Dynamics, Method, Pga, Schedule, State, Tolerance};
use scenarios::limits::LimitScene;
use scene_file::AlgebraKind;

use crate::measure::drift_net_of_impacts;

/// The tolerance the limit scenes run at.
pub(crate) const TOLERANCE: f64 = 1e-12;

/// One scene run in one algebra.
pub(crate) struct LimitRun {
    pub(crate) scene: LimitScene,
    pub(crate) algebra: AlgebraKind,
    /// (t, the limited coordinate, the energy) per sample.
    pub(crate) samples: Vec<(f64, f64, f64)>,
    pub(crate) transitions: Vec<LimitTransition>,
    pub(crate) steps: usize,
    pub(crate) stepping_time: Duration,
}

fn run_in<A: Algebra>(scene: LimitScene, algebra: AlgebraKind) -> Result<LimitRun, String> {
    let (system, start) = scene.build::<A>().map_err(|e| e.to_string())?;
    let tolerance = Tolerance::new(TOLERANCE, TOLERANCE).map_err(|e| e.to_string())?;
    let schedule = Schedule::adaptive(tolerance, scene.duration(), 0.01).map_err(|e| e.to_string())?;
    let run = simulate(&system, &start, Method::Dop853Body, &schedule).map_err(|e| e.to_string())?;
    let mut previous: Option<Vec<f64>> = None;
    let mut samples = Vec::with_capacity(run.body(0).len());
    for k in 0..run.body(0).len() {
        let states: Vec<State<A>> = (0..run.bodies.len())
            .map(|i| run.body(i)[k].state(system.body(i)))
            .collect();
        let q = system
            .joint_positions(&states, previous.as_deref())
            .map_err(|e| e.to_string())?;
        let sample = &run.body(0)[k];
        samples.push((sample.t, q[scene.limited_coordinate()], sample.energy));
        previous = Some(q);
    }
    Ok(LimitRun {
        scene,
        algebra,
        samples,
        transitions: run.transitions,
        steps: run.statistics.accepted,
        stepping_time: run.stepping_time,
    })
}

impl LimitRun {
    /// How far the coordinate went past a bound (rad; zero if it never did).
    pub(crate) fn passed(&self) -> f64 {
        let limit = self.scene.limit();
        (self.samples.iter())
            .map(|(_, q, _)| (limit.lower() - q).max(q - limit.upper()).max(0.0))
            .fold(0.0, f64::max)
    }

    /// The largest |E(t) − E₀ − L(t)| (J), L(t) what the impacts took up to t.
    pub(crate) fn drift(&self) -> f64 {
        drift_net_of_impacts(
            self.samples.iter().map(|&(t, _, energy)| (t, energy)),
            &self.transitions,
        )
    }
}

/// Runs `scene` in `algebra`.
pub(crate) fn run(scene: LimitScene, algebra: AlgebraKind) -> Result<LimitRun, String> {
    match algebra {
        AlgebraKind::Pga => run_in::<Pga>(scene, algebra),
        AlgebraKind::Cga => run_in::<Cga>(scene, algebra),
    }
}
