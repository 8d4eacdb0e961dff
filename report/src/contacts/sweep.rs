//! The scenes of `scenarios::contacts` run in PGA and CGA with DOP853-body at a tolerance of 1e-12: the cube's lowest
//! corner and centre at every sample, the transitions, the deepest a corner went below the floor and the energy
//! drift net of the impacts.

use std::time::Duration;

use dynamics::limits::LimitTransition;
use dynamics::{simulate, Algebra, Cga, Method, Pga, Schedule, Tolerance};
use scenarios::contacts::ContactScene;
use scene_file::AlgebraKind;

use crate::measure::drift_net_of_impacts;

/// The tolerance the contact scenes run at.
pub(crate) const TOLERANCE: f64 = 1e-12;

/// One scene run in one algebra.
pub(crate) struct ContactRun {
    pub(crate) scene: ContactScene,
    pub(crate) algebra: AlgebraKind,
    /// (t, the lowest corner's height, the centre's height, the energy) per sample.
    pub(crate) samples: Vec<(f64, f64, f64, f64)>,
    pub(crate) transitions: Vec<LimitTransition>,
    pub(crate) steps: usize,
    pub(crate) stepping_time: Duration,
}

fn run_in<A: Algebra>(scene: ContactScene, algebra: AlgebraKind) -> Result<ContactRun, String> {
    let (system, start) = scene.build::<A>().map_err(|e| e.to_string())?;
    let tolerance = Tolerance::new(TOLERANCE, TOLERANCE).map_err(|e| e.to_string())?;
    let schedule = Schedule::adaptive(tolerance, scene.duration(), 0.005).map_err(|e| e.to_string())?;
    let run = simulate(&system, &start, Method::Dop853Body, &schedule).map_err(|e| e.to_string())?;
    let samples = (run.body(0).iter())
        .map(|s| {
            let lowest = (ContactScene::corners().iter())
                .map(|corner| (s.position + s.orientation * corner).z)
                .fold(f64::INFINITY, f64::min);
            (s.t, lowest, s.position.z, s.energy)
        })
        .collect();
    Ok(ContactRun {
        scene,
        algebra,
        samples,
        transitions: run.transitions,
        steps: run.statistics.accepted,
        stepping_time: run.stepping_time,
    })
}

impl ContactRun {
    /// The deepest a corner went below the floor at the samples (m; zero if none did).
    pub(crate) fn deepest(&self) -> f64 {
        self.samples.iter().map(|s| -s.1).fold(0.0, f64::max)
    }

    /// The largest |E(t) − E₀ − L(t)| (J), L(t) what the impacts took up to t.
    pub(crate) fn drift(&self) -> f64 {
        drift_net_of_impacts(
            self.samples.iter().map(|&(t, _, _, energy)| (t, energy)),
            &self.transitions,
        )
    }
}

/// Runs `scene` in `algebra`.
pub(crate) fn run(scene: ContactScene, algebra: AlgebraKind) -> Result<ContactRun, String> {
    match algebra {
        AlgebraKind::Pga => run_in::<Pga>(scene, algebra),
        AlgebraKind::Cga => run_in::<Cga>(scene, algebra),
    }
}
