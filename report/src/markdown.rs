//! `report.md`: per scene a work-precision table (a line per configuration), the CGA-vs-PGA agreement
//! and the MuJoCo anchor, with where every number comes from.

use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;

use dynamics::simulate::Sample;
use reference::SceneId;

use crate::mujoco;
use crate::sweep::{AlgebraKind, Config, Outcome, RunError};

/// A run's result as the report sees it.
pub type RunResult = (Config, Result<Outcome, RunError>);

/// User text (a scene's title, body and joint names, a path) as inline Markdown that shows as written: line
/// breaks and other control characters become spaces (no new block, so no heading or list can start), and the
/// characters that open emphasis, code, links, HTML or table cells are backslash-escaped.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.push(' ');
        } else {
            if matches!(c, '\\' | '`' | '*' | '_' | '[' | ']' | '<' | '>' | '#' | '|') {
                out.push('\\');
            }
            out.push(c);
        }
    }
    out
}

/// A number for a table: two significant digits, or a plain 0.
pub fn scientific(value: f64) -> String {
    if value == 0.0 {
        "0".to_string()
    } else {
        format!("{value:.1e}")
    }
}

/// The largest orientation (rad) and position (m) difference over the samples of two runs.
pub fn agreement(first: &[Sample], second: &[Sample]) -> (f64, f64) {
    first
        .iter()
        .zip(second)
        .fold((0.0f64, 0.0f64), |(angle, distance), (a, b)| {
            (
                angle.max(a.orientation.angle_to(&b.orientation)),
                distance.max((a.position - b.position).norm()),
            )
        })
}

fn scene_table(out: &mut String, results: &[&RunResult]) {
    let feature_names: Vec<(&str, &str)> = results
        .iter()
        .find_map(|(_, r)| r.as_ref().ok())
        .map(|o| o.measurements.features.iter().map(|f| (f.name, f.unit)).collect())
        .unwrap_or_default();
    let constrained = results.iter().any(|(c, _)| c.formulation.is_some());
    let mut header = vec![
        "configuration".to_string(),
        "dt (s)".into(),
        "CPU per simulated s (s)".into(),
        "µs/step".into(),
        "orientation error at T (rad)".into(),
        "max (rad)".into(),
        "position error at T (m)".into(),
        "energy drift at T".into(),
    ];
    if constrained {
        header.push("max constraint violation (m)".into());
    }
    header.extend(
        feature_names
            .iter()
            .map(|(name, unit)| format!("{name} error ({unit})")),
    );
    let _ = writeln!(out, "| {} |", header.join(" | "));
    let _ = writeln!(out, "|{}|", vec!["---"; header.len()].join("|"));
    for (config, result) in results {
        let mut row = vec![config.series_label(), format!("{:.0e}", config.dt)];
        match result {
            Ok(o) => {
                let m = &o.measurements;
                row.extend([
                    scientific(o.cpu_per_simulated_second),
                    format!("{:.2}", o.time_per_step * 1e6),
                    scientific(m.orientation_end),
                    scientific(m.orientation_max),
                    scientific(m.position_end),
                    scientific(m.energy_drift_end),
                ]);
                if constrained {
                    row.push(m.violation_max.map_or("–".into(), scientific));
                }
                row.extend(m.features.iter().map(|f| scientific(f.error())));
            }
            Err(error) => row.push(format!("failed: {error}")),
        }
        let _ = writeln!(out, "| {} |", row.join(" | "));
    }
}

fn agreement_table(out: &mut String, results: &[&RunResult]) {
    // Pair each CGA run with the PGA run of the same configuration.
    let mut worst: BTreeMap<String, (f64, f64)> = BTreeMap::new();
    for (config, result) in results.iter().filter(|(c, _)| c.algebra == AlgebraKind::Cga) {
        let twin = config.same_but(AlgebraKind::Pga);
        let Some((_, Ok(pga))) = results.iter().find(|(c, _)| *c == twin) else {
            continue;
        };
        let Ok(cga) = result else { continue };
        let (angle, distance) = agreement(&cga.samples, &pga.samples);
        let label = format!(
            "{}, dt = {:.0e}",
            config.series_label().trim_start_matches("CGA, "),
            config.dt
        );
        worst.insert(label, (angle, distance));
    }
    if worst.is_empty() {
        let _ = writeln!(out, "No configuration runs in both algebras.\n");
        return;
    }
    let _ = writeln!(
        out,
        "| configuration | max orientation difference (rad) | max position difference (m) |"
    );
    let _ = writeln!(out, "|---|---|---|");
    for (label, (angle, distance)) in worst {
        let _ = writeln!(out, "| {label} | {} | {} |", scientific(angle), scientific(distance));
    }
    let _ = writeln!(out);
}

/// The configurations of one scene ranked by their CPU per simulated second at MuJoCo's error at dt = 1e-3
/// (see [`mujoco::cost_at_error`]): (label, cost, the cheapest measured run that reaches it as (dt, error,
/// cost)). Only configurations that reach it.
fn costs_at_mujoco_error(scene: SceneId, runs: &[&RunResult]) -> Vec<Ranked> {
    let Some(anchor) = mujoco::anchor(scene) else {
        return Vec::new();
    };
    let target = anchor.reference_error();
    let mut series: BTreeMap<String, Vec<(f64, f64, f64)>> = BTreeMap::new();
    for (config, result) in runs {
        if let Ok(outcome) = result {
            let error = mujoco::anchored_error(scene, &outcome.measurements);
            series
                .entry(config.series_label())
                .or_default()
                .push((config.dt, error, outcome.cpu_per_simulated_second));
        }
    }
    let mut ranked: Vec<Ranked> = series
        .into_iter()
        .filter_map(|(label, points)| {
            let curve: Vec<(f64, f64)> = points.iter().map(|&(_, error, cost)| (cost, error)).collect();
            let cost = mujoco::cost_at_error(&curve, target)?;
            let cheapest = points
                .iter()
                .copied()
                .filter(|&(_, error, _)| error <= target)
                .min_by(|a, b| a.2.total_cmp(&b.2))?;
            Some((label, cost, cheapest))
        })
        .collect();
    ranked.sort_by(|a, b| a.1.total_cmp(&b.1));
    ranked
}

/// A configuration's label, its CPU per simulated second at MuJoCo's error and its cheapest run that meets
/// that error as (dt, error, CPU per simulated second).
type Ranked = (String, f64, (f64, f64, f64));

/// Per anchored scene, the cheapest configuration at MuJoCo's accuracy and the ratio of the costs.
fn mujoco_summary(out: &mut String, rankings: &HashMap<SceneId, Vec<Ranked>>) {
    let mut rows = Vec::new();
    for scene in SceneId::ALL {
        let (Some(anchor), Some((label, cost, (dt, error, measured)))) = (
            mujoco::anchor(scene),
            rankings.get(&scene).and_then(|ranked| ranked.first()),
        ) else {
            continue;
        };
        rows.push(format!(
            "| {} | {} | {label} | {} | {:.1}× | {dt:.0e}: {} at {} |",
            scene.label(),
            scientific(anchor.reference_error()),
            scientific(*cost),
            anchor.reference_cost() / cost,
            scientific(*error),
            scientific(*measured),
        ));
    }
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(out, "## Speed at MuJoCo's accuracy\n");
    let _ = writeln!(
        out,
        "For each scene with a MuJoCo anchor: the configuration that reaches MuJoCo 4.0's error at dt = 1e-3 (RK4, \
         measured by the team on this machine) with the least CPU per simulated second, its cost there \
         (interpolated log–log between the two runs of the sweep that bracket the error), and MuJoCo's cost at \
         that error divided by ours. Our costs are measured with runs in parallel, so they are if anything high. \
         Last column: the cheapest run of the sweep that meets the error outright (dt: error at CPU per simulated s).\n"
    );
    let _ = writeln!(
        out,
        "| scene | MuJoCo's error at dt = 1e-3 | cheapest configuration | its CPU per simulated s (s) | MuJoCo's / ours | measured run |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|");
    for row in rows {
        let _ = writeln!(out, "{row}");
    }
    let _ = writeln!(out);
}

/// The whole report.
pub fn report(results: &[RunResult], threads: usize, figures: &HashMap<SceneId, Vec<String>>) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# Work-precision report\n");
    let _ = writeln!(
        out,
        "Every reference scene of SCENES.md, simulated in CGA and PGA from one generic source, with each integrator \
         over a sweep of step sizes. Errors are measured against the reference trajectories (scipy DOP853, \
         rtol = atol = 1e-13, classical Newton–Euler equations; no GA code) and the analytic values of SCENES.md, \
         sampled every 0.01 s. CPU time is the stepping time of each run (sampling and metrics excluded) on this \
         machine, with {threads} runs in parallel; \"CPU per simulated s\" is that time divided by the simulated \
         time. Energy drift is |E(T) − E₀| / E_scale (SCENES.md). Constrained scenes use the stabilisation chosen \
         for the sweep; \"virtual power\" and \"pinning\" are the two constraint formulations (SPEC §6, §7–§9).\n"
    );
    let runs_by_scene: Vec<(SceneId, Vec<&RunResult>)> = SceneId::ALL
        .into_iter()
        .map(|scene| (scene, results.iter().filter(|(c, _)| c.scene == scene).collect()))
        .collect();
    let rankings: HashMap<SceneId, Vec<Ranked>> = runs_by_scene
        .iter()
        .map(|(scene, runs)| (*scene, costs_at_mujoco_error(*scene, runs)))
        .collect();
    mujoco_summary(&mut out, &rankings);
    for (scene, runs) in runs_by_scene {
        if runs.is_empty() {
            continue;
        }
        let _ = writeln!(out, "## Scene {}\n", scene.label());
        for figure in figures.get(&scene).into_iter().flatten() {
            let _ = writeln!(out, "![{figure}]({figure})\n");
        }
        scene_table(&mut out, &runs);
        let _ = writeln!(out);
        if let Some(anchor) = mujoco::anchor(scene) {
            let points: Vec<String> = anchor
                .points
                .iter()
                .map(|(dt, error)| format!("dt = {dt:.0e}: {error:.0e}"))
                .collect();
            let _ = writeln!(
                out,
                "MuJoCo 4.0 RK4 on this scene and machine (issue tracker): {:.1} µs/step; error at T {}.\n",
                anchor.time_per_step * 1e6,
                points.join(", ")
            );
            let ranked = &rankings[&scene];
            if !ranked.is_empty() {
                let _ = writeln!(
                    out,
                    "At MuJoCo's error at dt = 1e-3 ({}; MuJoCo: {} s of CPU per simulated s), the five cheapest \
                     configurations:\n",
                    scientific(anchor.reference_error()),
                    scientific(anchor.reference_cost())
                );
                let _ = writeln!(out, "| configuration | CPU per simulated s (s) | MuJoCo's / ours |");
                let _ = writeln!(out, "|---|---|---|");
                for (label, cost, _) in ranked.iter().take(5) {
                    let _ = writeln!(
                        out,
                        "| {label} | {} | {:.1}× |",
                        scientific(*cost),
                        anchor.reference_cost() / cost
                    );
                }
                let _ = writeln!(out);
            }
        }
        let _ = writeln!(out, "### CGA vs PGA (same configuration, same steps)\n");
        agreement_table(&mut out, &runs);
    }
    out
}
