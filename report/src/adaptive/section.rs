//! The adaptive runs' section of `report.md` and its plots: each scene's embedded pairs over the tolerances on the
//! work-precision axes of its fixed-step runs, the error achieved against the tolerance asked for, and the step
//! length over time.

use std::fmt::Write as _;
use std::path::Path;

use dynamics::integrate::Integrator;
use reference::SceneId;
use scenarios::MechanismId;

use super::figures::{step_panels, tolerance_panels, work_precision_panels, FixedRuns};
use super::sweep::{AdaptiveCase, AdaptiveConfig, AdaptiveResult};
use crate::markdown::scientific;
use crate::plot::{figure_with_caption, PlotError};

/// The scenes whose motion's speed varies, for the step-length figure.
const VARYING: [AdaptiveCase; 3] = [
    AdaptiveCase::SingleBody(SceneId::Cuboid),
    AdaptiveCase::Mechanism(MechanismId::DoublePendulum),
    AdaptiveCase::Mechanism(MechanismId::Chain(64)),
];

/// The methods and the scenes run, in the plan's order.
fn methods_and_cases(results: &[AdaptiveResult]) -> (Vec<Integrator>, Vec<AdaptiveCase>) {
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
