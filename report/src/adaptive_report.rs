//! The adaptive runs' section of `report.md` and its plots: each scene's embedded pairs over the tolerances on the
//! work-precision axes of its fixed-step runs, the error achieved against the tolerance asked for, and the step
//! length over time.

use std::fmt::Write as _;
use std::path::Path;

use dynamics::integrate::{Integrator, Method};
use dynamics::JointMethod;
use reference::SceneId;
use scenarios::MechanismId;

use crate::adaptive_sweep::{mechanism_error, AdaptiveCase, AdaptiveConfig, AdaptiveOutcome, AdaptiveResult};
use crate::figures::headline_error;
use crate::markdown::{scientific, RunResult};
use crate::mechanism_sweep::MechanismResult;
use crate::plot::{figure_with_caption, Labels, Panel, PlotError, Series};
use crate::robot_sweep::RobotResult;
use crate::sweep::AlgebraKind;

/// The fixed-step runs a scene's adaptive runs are drawn beside.
pub(crate) struct FixedRuns<'a> {
    /// The single-body sweep.
    pub(crate) single: &'a [RunResult],
    /// The mechanism sweep.
    pub(crate) mechanisms: &'a [MechanismResult],
    /// The robot sweep.
    pub(crate) robots: &'a [RobotResult],
}

/// The fixed-step methods drawn beside the pairs: the body-momentum methods of orders 6 and 8 (and, for the
/// robots, the eighth-order method in joint coordinates).
const FIXED: [Integrator; 3] = [
    Integrator::General(Method::Rkmk6Body),
    Integrator::General(Method::Rkmk8Body),
    Integrator::Joint(JointMethod::Rkmk8),
];

/// The tolerance the step-length figure shows, or the closest one run.
const SHOWCASE_TOLERANCE: f64 = 1e-8;

/// The scenes whose motion's speed varies, for the step-length figure.
const VARYING: [AdaptiveCase; 3] = [
    AdaptiveCase::SingleBody(SceneId::Cuboid),
    AdaptiveCase::Mechanism(MechanismId::DoublePendulum),
    AdaptiveCase::Mechanism(MechanismId::Chain(64)),
];

impl FixedRuns<'_> {
    /// (CPU per simulated second, error) of each PGA fixed-step run of `integrator` on `case`, by step.
    fn points(&self, case: AdaptiveCase, integrator: Integrator) -> Vec<(f64, f64)> {
        let mut points: Vec<(f64, f64)> = match case {
            AdaptiveCase::SingleBody(scene) => (self.single.iter())
                .filter(|(c, _)| {
                    c.scene == scene
                        && c.algebra == AlgebraKind::Pga
                        && c.integrator == integrator
                        && c.formulation == case.formulation()
                })
                .filter_map(|(_, r)| r.as_ref().ok())
                .map(|o| (o.cpu_per_simulated_second, headline_error(scene, &o.measurements)))
                .collect(),
            AdaptiveCase::Mechanism(id) => (self.mechanisms.iter())
                .filter(|(c, _)| {
                    c.id == id
                        && c.algebra == AlgebraKind::Pga
                        && Integrator::General(c.method) == integrator
                        && Some(c.formulation) == case.formulation()
                        && !c.is_chain_timing()
                })
                .filter_map(|(_, r)| r.as_ref().ok())
                .filter_map(|o| Some((o.cpu_per_simulated_second, mechanism_error(id, &o.measures)?)))
                .collect(),
            AdaptiveCase::Robot(robot) => (self.robots.iter())
                .filter(|(c, _)| c.robot == robot && c.algebra == AlgebraKind::Pga && c.integrator == integrator)
                .filter_map(|(_, r)| r.as_ref().ok())
                .map(|o| (o.cpu_per_simulated_second, o.joint_error))
                .collect(),
        };
        points.retain(|&(x, y)| x > 0.0 && y > 0.0 && y.is_finite());
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        points
    }
}

/// The successful runs of `case` with `method`, by tolerance from the loosest.
fn runs_of(results: &[AdaptiveResult], case: AdaptiveCase, method: Method) -> Vec<&AdaptiveOutcome> {
    let mut runs: Vec<&AdaptiveOutcome> = (results.iter())
        .filter(|(c, _)| c.case == case && c.method == method)
        .filter_map(|(_, r)| r.as_ref().ok())
        .collect();
    runs.sort_by(|a, b| b.config.tolerance.total_cmp(&a.config.tolerance));
    runs
}

/// The methods and the scenes run, in the plan's order.
fn methods_and_cases(results: &[AdaptiveResult]) -> (Vec<Method>, Vec<AdaptiveCase>) {
    let (mut methods, mut cases) = (Vec::new(), Vec::new());
    for (config, _) in results {
        if !methods.contains(&config.method) {
            methods.push(config.method);
        }
        if !cases.contains(&config.case) {
            cases.push(config.case);
        }
    }
    (methods, cases)
}

/// One work-precision panel per scene of `cases`, titled by `titles`: the pairs over the tolerances, the fixed-step
/// methods over the steps.
fn work_precision_panels<'a>(
    results: &[AdaptiveResult],
    fixed: &FixedRuns,
    methods: &[Method],
    (cases, titles): (&[AdaptiveCase], &'a [String]),
) -> Vec<Panel<'a>> {
    cases
        .iter()
        .zip(titles)
        .map(|(&case, title)| {
            let mut series: Vec<Series> = methods
                .iter()
                .map(|&method| {
                    let points = (runs_of(results, case, method).iter())
                        .map(|o| (o.cpu_per_simulated_second, o.error))
                        .filter(|&(x, y)| x > 0.0 && y > 0.0)
                        .collect();
                    Series {
                        markers: true,
                        ..Series::line(format!("{}, tolerances", method.name()), points)
                    }
                })
                .collect();
            for integrator in FIXED {
                let points = fixed.points(case, integrator);
                if !points.is_empty() {
                    series.push(Series {
                        markers: true,
                        dashed: true,
                        ..Series::line(format!("{}, fixed steps", integrator.name()), points)
                    });
                }
            }
            Panel::new(
                Labels::new(title, "CPU per simulated second (s)", case.error_label()),
                series,
            )
            .log_x()
            .log_y()
        })
        .collect()
}

/// Achieved error over requested tolerance, one panel per method and group of scenes.
fn tolerance_panels(
    results: &[AdaptiveResult],
    methods: &[Method],
    groups: &[Vec<AdaptiveCase>],
) -> Vec<Panel<'static>> {
    let mut panels = Vec::new();
    for &method in methods {
        for group in groups.iter().filter(|g| g.iter().any(|c| c.error_in_tolerance_units())) {
            let series = (group.iter())
                .filter(|case| case.error_in_tolerance_units())
                .map(|&case| {
                    let points = (runs_of(results, case, method).iter())
                        .map(|o| (o.config.tolerance, o.error / o.config.tolerance))
                        .filter(|&(_, ratio)| ratio > 0.0)
                        .collect();
                    Series {
                        markers: true,
                        ..Series::line(case.label(), points)
                    }
                })
                .collect();
            panels.push(
                Panel::new(
                    Labels::new(method.name(), "tolerance asked for", "error achieved ÷ tolerance"),
                    series,
                )
                .log_x()
                .log_y(),
            );
        }
    }
    panels
}

/// The step length over time of the scenes of `shown` (titled by `titles`), at [`SHOWCASE_TOLERANCE`] or the
/// closest tolerance run.
fn step_panels<'a>(
    results: &[AdaptiveResult],
    methods: &[Method],
    (shown, titles): (&[AdaptiveCase], &'a [String]),
) -> Vec<Panel<'a>> {
    (shown.iter().zip(titles))
        .filter_map(|(&case, title)| {
            let series: Vec<Series> = methods
                .iter()
                .filter_map(|&method| {
                    let runs = runs_of(results, case, method);
                    let run = runs.iter().min_by(|a, b| {
                        let distance = |o: &AdaptiveOutcome| (o.config.tolerance.ln() - SHOWCASE_TOLERANCE.ln()).abs();
                        distance(a).total_cmp(&distance(b))
                    })?;
                    let label = format!("{}, tol {:.0e}", method.name(), run.config.tolerance);
                    Some(Series::line(label, run.steps.clone()))
                })
                .collect();
            (!series.is_empty()).then(|| Panel::new(Labels::new(title, "time (s)", "step length (s)"), series).log_y())
        })
        .collect()
}

/// A table of the runs of one scene.
fn table(out: &mut String, results: &[AdaptiveResult], case: AdaptiveCase) {
    let _ = writeln!(
        out,
        "| method | tolerance | {} | ÷ tolerance | steps kept (refused) | evaluations | shortest – longest step (s) | \
         CPU per simulated s (s) |\n|---|---|---|---|---|---|---|---|",
        case.error_label()
    );
    for (config, result) in results.iter().filter(|(c, _)| c.case == case) {
        let AdaptiveConfig { method, tolerance, .. } = *config;
        let _ = match result {
            Ok(o) => {
                let s = o.statistics;
                writeln!(
                    out,
                    "| {} | {tolerance:.0e} | {} | {} | {} ({}) | {} | {} – {} | {} |",
                    method.name(),
                    scientific(o.error),
                    if case.error_in_tolerance_units() {
                        scientific(o.error / tolerance)
                    } else {
                        "–".to_owned()
                    },
                    s.accepted,
                    s.rejected,
                    s.evaluations,
                    scientific(s.smallest_step),
                    scientific(s.largest_step),
                    scientific(o.cpu_per_simulated_second)
                )
            }
            Err(error) => writeln!(
                out,
                "| {} | {tolerance:.0e} | failed: {error} | | | | | |",
                method.name()
            ),
        };
    }
}

/// The adaptive runs' section of `report.md`, writing its plots into `dir`.
pub(crate) fn adaptive_section(dir: &Path, results: &[AdaptiveResult], fixed: &FixedRuns) -> Result<String, PlotError> {
    let mut out = String::new();
    if results.is_empty() {
        return Ok(out);
    }
    let (methods, cases) = methods_and_cases(results);
    let _ = writeln!(
        out,
        "## Adaptive steps (docs/dynamics.md)\n\nThe embedded pairs ({}) choose their steps by a tolerance (relative and \
         absolute alike) in place of `dt`, in PGA, sampled every 0.01 s from their continuous extensions. Each scene's \
         runs over the tolerances are drawn on the work-precision axes of its fixed-step runs (PGA, the same \
         formulation); the error is the one those figures plot (M3: the largest energy drift, as the chain is chaotic \
         and has no reference; the robots: the largest joint error against Pinocchio). CPU times are the fastest of \
         the repeats, the stepping alone.\n",
        methods.iter().map(|m| m.name()).collect::<Vec<_>>().join(", ")
    );
    let single: Vec<AdaptiveCase> = cases
        .iter()
        .copied()
        .filter(|c| matches!(c, AdaptiveCase::SingleBody(_)))
        .collect();
    let multi: Vec<AdaptiveCase> = cases
        .iter()
        .copied()
        .filter(|c| !matches!(c, AdaptiveCase::SingleBody(_)))
        .collect();
    let caption = "Solid: the embedded pairs, one point per tolerance; dashed: the fixed-step methods, one point per \
                   step. PGA.";
    for (group, name, title) in [
        (
            &single,
            "adaptive_single_bodies.png",
            "Single bodies: adaptive and fixed steps",
        ),
        (
            &multi,
            "adaptive_mechanisms_and_robots.png",
            "Mechanisms and robots: adaptive and fixed steps",
        ),
    ] {
        if group.is_empty() {
            continue;
        }
        let titles: Vec<String> = group.iter().map(|c| c.label()).collect();
        let panels = work_precision_panels(results, fixed, &methods, (group, &titles));
        figure_with_caption(&dir.join(name), title, &panels, caption)?;
        let _ = writeln!(out, "![{name}]({name})\n");
    }
    let panels = tolerance_panels(results, &methods, &[single.clone(), multi.clone()]);
    if !panels.is_empty() {
        let name = "adaptive_tolerance.png";
        figure_with_caption(
            &dir.join(name),
            "Error achieved against tolerance asked for",
            &panels,
            "Each scene's error (as in the work-precision figures) divided by the tolerance; within 0.1–10 the \
             tolerance is followed. M3 is left out: its error is an energy (J), not in the tolerance's units.",
        )?;
        let _ = writeln!(out, "![{name}]({name})\n");
    }
    let shown: Vec<AdaptiveCase> = VARYING.into_iter().filter(|case| cases.contains(case)).collect();
    let titles: Vec<String> = shown.iter().map(|c| c.label()).collect();
    let panels = step_panels(results, &methods, (&shown, &titles));
    if !panels.is_empty() {
        let name = "adaptive_steps.png";
        figure_with_caption(
            &dir.join(name),
            "Step length over time",
            &panels,
            "Each step kept, at its end time: the steps shorten where the motion is fast (scene 1's flips, the \
             pendulum's swings, the chain's whip).",
        )?;
        let _ = writeln!(out, "![{name}]({name})\n");
    }
    for &case in &cases {
        let _ = writeln!(out, "\n### {}: adaptive steps\n", case.label());
        table(&mut out, results, case);
    }
    Ok(out)
}
