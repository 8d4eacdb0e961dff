//! What the sweeps share about running: why a run failed ([`RunError`]), how a run's CPU time is taken (the fastest of
//! repeated timings), and a list of scenes run in both algebras.

use std::fmt::Write as _;

use dynamics::simulate::Simulation;
use dynamics::Algebra;
use scene_file::AlgebraKind;

/// Why a run failed (reported in the table; the sweep goes on).
#[derive(Clone, Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RunError {
    /// The scene could not be built.
    #[error("scene: {0}")]
    Scene(#[from] scenarios::SceneError),
    /// The schedule, the body or the run failed: the simulator's message.
    #[error("simulation: {0}")]
    Simulation(String),
    /// The samples could not be measured: the metric's message.
    #[error("metrics: {0}")]
    Metrics(String),
}

/// A [`RunError::Simulation`] with the simulator's message.
pub(crate) fn simulation_error(error: impl std::fmt::Display) -> RunError {
    RunError::Simulation(error.to_string())
}

/// A [`RunError::Metrics`] with the metric's message.
pub(crate) fn metrics_error(error: impl std::fmt::Display) -> RunError {
    RunError::Metrics(error.to_string())
}

/// Each configuration is timed over at least [`MIN_REPEATS`] runs unless these take [`LONG_TIMING`] s of stepping,
/// and over at least [`MIN_TIMING`] s of stepping, in at most [`MAX_REPEATS`] runs; the fastest run counts.
pub(crate) const MIN_REPEATS: usize = 5;

/// See [`MIN_REPEATS`] (s).
pub(crate) const LONG_TIMING: f64 = 0.4;

/// See [`MIN_REPEATS`] (s).
pub(crate) const MIN_TIMING: f64 = 0.05;

/// See [`MIN_REPEATS`].
pub(crate) const MAX_REPEATS: usize = 25;

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

/// Every scene run by `run` in PGA and in CGA; a failed run is a line of `out` naming the scene, the algebra and why.
pub(crate) fn in_both_algebras<S: Copy, R>(
    scenes: &[S],
    label: fn(S) -> &'static str,
    run: impl Fn(S, AlgebraKind) -> Result<R, String>,
    out: &mut String,
) -> Vec<R> {
    let mut runs = Vec::new();
    for &scene in scenes {
        for algebra in [AlgebraKind::Pga, AlgebraKind::Cga] {
            match run(scene, algebra) {
                Ok(result) => runs.push(result),
                Err(error) => {
                    let _ = writeln!(out, "{} in {}: failed: {error}\n", label(scene), algebra.name());
                }
            }
        }
    }
    runs
}
