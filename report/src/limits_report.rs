//! The report's joint-limit section (docs/limits.md): the scenes of `scenarios::limits` in PGA and CGA with
//! DOP853-body at a tolerance of 1e-12, the limited coordinate over time against its bounds, the energy, and a table
//! of the transitions, the first impact against its closed form, how far a bound was passed and the energy drift net
//! of the impacts.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

use dynamics::limits::{energy_changed_by, LimitChange, LimitTransition};
use dynamics::{simulate, Algebra, Cga, Dynamics, Method, Pga, Schedule, State, Tolerance};
use scenarios::limits::LimitScene;

use crate::markdown::scientific;
use crate::plot::{figure_with_caption, Labels, Panel, PlotError, Series};
use crate::sweep::AlgebraKind;

/// The tolerance the limit scenes run at.
const TOLERANCE: f64 = 1e-12;

/// One scene run in one algebra.
struct LimitRun {
    scene: LimitScene,
    algebra: AlgebraKind,
    /// (t, the limited coordinate, the energy) per sample.
    samples: Vec<(f64, f64, f64)>,
    transitions: Vec<LimitTransition>,
    steps: usize,
    stepping_time: Duration,
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
    fn passed(&self) -> f64 {
        let limit = self.scene.limit();
        (self.samples.iter())
            .map(|(_, q, _)| (limit.lower() - q).max(q - limit.upper()).max(0.0))
            .fold(0.0, f64::max)
    }

    /// The largest |E(t) − E₀ − L(t)| (J), L(t) what the impacts took up to t.
    fn drift(&self) -> f64 {
        drift_net_of_impacts(
            self.samples.iter().map(|&(t, _, energy)| (t, energy)),
            &self.transitions,
        )
    }
}

/// The largest |E(t) − E₀ − L(t)| (J) over `(t, E)` samples, L(t) what the `transitions` changed the energy by up to t.
pub(crate) fn drift_net_of_impacts(samples: impl Iterator<Item = (f64, f64)>, transitions: &[LimitTransition]) -> f64 {
    let mut start = None;
    samples
        .map(|(t, energy)| {
            let start = *start.get_or_insert(energy);
            (energy - start - energy_changed_by(transitions, t)).abs()
        })
        .fold(0.0, f64::max)
}

/// The table cells of a run's transitions: bounces, holds, releases and the first transition's time (s).
pub(crate) fn transition_cells(transitions: &[LimitTransition]) -> String {
    let count = |kind: fn(&LimitChange) -> bool| transitions.iter().filter(|t| kind(&t.change)).count();
    let first = transitions.first().map_or("–".to_owned(), |t| format!("{:.15}", t.t));
    format!(
        "{} | {} | {} | {first}",
        count(|c| matches!(c, LimitChange::Bounced { .. })),
        count(|c| matches!(c, LimitChange::Held { .. })),
        count(|c| matches!(c, LimitChange::Released { .. })),
    )
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

/// The section: every limit scene in both algebras, a figure and a table.
pub(crate) fn limits_section(dir: &Path) -> Result<String, PlotError> {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "## Joint limits (docs/limits.md)\n\nJoint limits are one-sided constraints, enforced exactly: a bound is met \
         in an impact located to round-off (Newton's restitution, an impulse through the joint-space mass matrix); \
         the joint is held on it by a joint-space row while the bound pushes, and released where the bound would \
         pull. The scenes of `scenarios::limits` run with DOP853-body at a tolerance of {TOLERANCE:e}, PGA and CGA.\n"
    );
    let run = |scene, algebra| match algebra {
        AlgebraKind::Pga => run_in::<Pga>(scene, algebra),
        AlgebraKind::Cga => run_in::<Cga>(scene, algebra),
    };
    let runs = in_both_algebras(&LimitScene::ALL, LimitScene::label, run, &mut out);
    let (mut angles, mut energies) = (Vec::new(), Vec::new());
    for scene in LimitScene::ALL {
        let of_scene: Vec<&LimitRun> = runs.iter().filter(|run| run.scene == scene).collect();
        let Some(first) = of_scene.first() else {
            continue;
        };
        let end = scene.duration();
        let limit = scene.limit();
        let mut series: Vec<Series> = (of_scene.iter())
            .map(|run| Series {
                dashed: run.algebra == AlgebraKind::Cga,
                ..Series::line(
                    run.algebra.name(),
                    run.samples.iter().map(|&(t, q, _)| (t, q)).collect(),
                )
            })
            .collect();
        // The bounds within the swing, as one path (a box from the start to the end when both are).
        let bounds: Vec<f64> = [limit.lower(), limit.upper()]
            .into_iter()
            .filter(|b| b.abs() <= 1.0)
            .collect();
        let mut path = Vec::new();
        for (k, bound) in bounds.iter().enumerate() {
            let (from, to) = if k % 2 == 0 { (0.0, end) } else { (end, 0.0) };
            path.extend([(from, *bound), (to, *bound)]);
        }
        series.push(Series::reference_line("bounds", path));
        if let Some(Ok(exact)) = scene.exact_first_impact() {
            series.push(Series {
                markers_only: true,
                ..Series::line("closed-form impact", vec![(exact, limit.upper())])
            });
        }
        let title = match scene {
            LimitScene::StoppingPendulum => "Pendulum stopping at a limit: its angle",
            LimitScene::BouncingDoublePendulum => "Double pendulum bouncing off a limit: the elbow",
        };
        angles.push(Panel::new(Labels::new(title, "time (s)", "joint angle (rad)"), series));
        let start = first.samples.first().map_or(0.0, |s| s.2);
        let change = first.samples.iter().map(|&(t, _, e)| (t, e - start)).collect();
        let title = match scene {
            LimitScene::StoppingPendulum => "Pendulum stopping at a limit: energy change",
            LimitScene::BouncingDoublePendulum => "Double pendulum bouncing off a limit: energy change",
        };
        energies.push(Panel::new(
            Labels::new(title, "time (s)", "E(t) − E₀ (J)"),
            vec![Series::line(first.algebra.name(), change)],
        ));
    }
    for (name, title, panels, caption) in [
        (
            "limits.png",
            "Joint limits: the limited joint's angle",
            angles,
            "The limited joint's angle and its bounds within the swing (dashed black): the pendulum meets its bound at \
             the time the incomplete elliptic integral gives (the marker) and stays there; the elbow bounces off \
             ±0.3 rad at restitution 0.5.",
        ),
        (
            "limits_energy.png",
            "Joint limits: the energy",
            energies,
            "The energy drops at each impact (restitution 0 for the pendulum, 0.5 for the elbow) by what the impact \
             takes, and holds between them.",
        ),
    ] {
        if panels.is_empty() {
            continue;
        }
        figure_with_caption(&dir.join(name), title, &panels, caption)?;
        let _ = writeln!(out, "![{name}]({name})\n");
    }
    let _ = writeln!(
        out,
        "| scene | algebra | bounces | holds | releases | first impact (s) | closed form (s) | past a bound (rad) | \
         energy drift net of impacts (J) | steps | CPU (s) |\n|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for run in &runs {
        let exact = match run.scene.exact_first_impact() {
            Some(Ok(exact)) => format!("{exact:.15}"),
            Some(Err(error)) => error.to_string(),
            None => "–".to_owned(),
        };
        let _ = writeln!(
            out,
            "| {} | {} | {} | {exact} | {} | {} | {} | {} |",
            run.scene.label(),
            run.algebra.name(),
            transition_cells(&run.transitions),
            scientific(run.passed()),
            scientific(run.drift()),
            run.steps,
            scientific(run.stepping_time.as_secs_f64()),
        );
    }
    let _ = writeln!(out);
    Ok(out)
}
