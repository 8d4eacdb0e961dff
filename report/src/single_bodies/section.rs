//! `report.md`: per scene a work-precision table (a line per configuration), the CGA-vs-PGA agreement
//! and the MuJoCo anchor, with where every number comes from.

use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;

use reference::SceneId;
use scene_file::AlgebraKind;

use super::measure::headline_error;
use super::sweep::{Config, RunResult};
use crate::markdown::{compare_rows, formulation_rank, integrator_rank, scientific, table_header, RowKey};
use crate::measure::{agreement, cost_at_error};
use crate::measured_anchors::{single_body_anchor, single_body_provenance as mujoco_provenance, Anchors, Source};
use crate::recorded_anchors::{self, Anchor};

/// A run's [`RowKey`].
pub(crate) fn row_key(config: &Config) -> RowKey {
    (
        config.algebra,
        formulation_rank(config.formulation),
        integrator_rank(config.integrator),
        config.dt,
    )
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
    table_header(out, &header);
    let mut rows: Vec<&RunResult> = results.to_vec();
    rows.sort_by(|a, b| compare_rows(&row_key(&a.0), &row_key(&b.0)));
    for (config, result) in rows {
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

/// The CGA-vs-PGA rows: per configuration run in both algebras, its label and the largest orientation (rad) and
/// position (m) difference, sorted by configuration and then numerically by step (coarse to fine).
pub(crate) fn agreement_rows(results: &[&RunResult]) -> Vec<(String, f64, f64)> {
    let mut rows: Vec<(RowKey, String, f64, f64)> = Vec::new();
    for (config, result) in results.iter().filter(|(c, _)| c.algebra == AlgebraKind::Cga) {
        // Pair each CGA run with the PGA run of the same configuration.
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
        rows.push((row_key(config), label, angle, distance));
    }
    rows.sort_by(|a, b| compare_rows(&a.0, &b.0));
    rows.into_iter().map(|(_, label, a, d)| (label, a, d)).collect()
}

fn agreement_table(out: &mut String, results: &[&RunResult]) {
    let rows = agreement_rows(results);
    if rows.is_empty() {
        let _ = writeln!(out, "No configuration runs in both algebras.\n");
        return;
    }
    let _ = writeln!(
        out,
        "| configuration | max orientation difference (rad) | max position difference (m) |"
    );
    let _ = writeln!(out, "|---|---|---|");
    for (label, angle, distance) in rows {
        let _ = writeln!(out, "| {label} | {} | {} |", scientific(angle), scientific(distance));
    }
    let _ = writeln!(out);
}

/// The configurations of one scene ranked by their CPU per simulated second at MuJoCo's error at dt = 1e-3
/// (see [`cost_at_error`]): (label, cost, the cheapest measured run that reaches it as (dt, error,
/// cost)). Only configurations that reach it.
fn costs_at_mujoco_error(scene: SceneId, runs: &[&RunResult]) -> Vec<Ranked> {
    // The errors are the recorded ones whether or not the time was measured in this run.
    let Some(anchor) = recorded_anchors::anchor(scene) else {
        return Vec::new();
    };
    if length_mismatch(scene, runs).is_some() {
        // MuJoCo's error is at the scene's full T: no cost is compared at it for a run of another length.
        return Vec::new();
    }
    let target = anchor.reference_error();
    let mut series: BTreeMap<String, Vec<(f64, f64, f64)>> = BTreeMap::new();
    for (config, result) in runs {
        if let Ok(outcome) = result {
            let error = headline_error(scene, &outcome.measurements);
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
            let cost = cost_at_error(&curve, target)?;
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

/// Why the runs of a scene cannot be compared with MuJoCo's error at the scene's T, if they cannot
/// ([`measure::length_mismatch`]): the job's `--duration` makes every run of a scene that long.
pub(crate) fn length_mismatch(scene: SceneId, runs: &[&RunResult]) -> Option<String> {
    let full = scene.parameters().duration;
    runs.iter()
        .find_map(|(config, _)| crate::measure::length_mismatch(config.duration, full))
}

/// A configuration's label, its CPU per simulated second at MuJoCo's error and its cheapest run that meets
/// that error as (dt, error, CPU per simulated second).
type Ranked = (String, f64, (f64, f64, f64));

/// The anchored scenes' MuJoCo figures, the time measured in this run where `anchors` has it.
fn scene_anchors(anchors: &Anchors) -> Vec<(SceneId, Anchor, Source<'_>)> {
    SceneId::ALL
        .into_iter()
        .filter_map(|scene| single_body_anchor(anchors, scene).map(|(anchor, source)| (scene, anchor, source)))
        .collect()
}

/// Per anchored scene, the cheapest configuration at MuJoCo's accuracy and the ratio of the costs; for a run
/// of another length than the scene's T, "n/a" instead.
fn mujoco_summary(
    out: &mut String,
    (rankings, mismatches): (&HashMap<SceneId, Vec<Ranked>>, &HashMap<SceneId, String>),
    anchors: &Anchors,
) {
    let mut rows = Vec::new();
    let mut provenances: Vec<String> = Vec::new();
    let mut whens: Vec<String> = Vec::new();
    for (scene, anchor, source) in scene_anchors(anchors) {
        for (list, item) in [
            (&mut provenances, mujoco_provenance(&source)),
            (&mut whens, source.short()),
        ] {
            if !list.contains(&item) {
                list.push(item);
            }
        }
        if let Some(why) = mismatches.get(&scene) {
            rows.push(format!(
                "| {} | {} | – | – | {why} | – |",
                scene.label(),
                scientific(anchor.reference_error()),
            ));
            continue;
        }
        let Some((label, cost, (dt, error, measured))) = rankings.get(&scene).and_then(|ranked| ranked.first()) else {
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
        "For each scene with a MuJoCo anchor: the configuration that reaches MuJoCo 4.0's error at dt = 1e-3 (RK4) \
         with the least CPU per simulated second, its cost there (interpolated log–log between the two runs of the \
         sweep that bracket the error), and MuJoCo's cost at that error divided by ours. Our costs are measured by \
         this run with runs in parallel, so they are if anything high. Last column: the cheapest run of the sweep \
         that meets the error outright (dt: error at CPU per simulated s). MuJoCo's errors are at each scene's full \
         T, so a shortened run (`--duration`) is not compared with them (n/a).\n"
    );
    let _ = writeln!(
        out,
        "| scene | MuJoCo's error at dt = 1e-3 (recorded {date}) | cheapest configuration | its CPU per simulated s (s) \
         | MuJoCo's / ours (MuJoCo's time {when}) | measured run |",
        date = recorded_anchors::SINGLE_BODY_RECORDED,
        when = whens.join(" or ")
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|");
    for row in rows {
        let _ = writeln!(out, "{row}");
    }
    let _ = writeln!(out, "\n{}.\n", provenances.join("; "));
}

/// The whole report.
pub(crate) fn report(
    results: &[RunResult],
    threads: usize,
    figures: &HashMap<SceneId, Vec<String>>,
    anchors: &Anchors,
) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# Work-precision report\n");
    let _ = writeln!(
        out,
        "Every reference scene of docs/scenes.md, simulated in CGA and PGA from one generic source, with each integrator \
         over a sweep of step sizes. Errors are measured against the reference trajectories (scipy DOP853, \
         rtol = atol = 1e-13, classical Newton–Euler equations; no GA code) and the analytic values of docs/scenes.md, \
         sampled every 0.01 s. CPU time is the stepping time of each run (sampling and metrics excluded) on this \
         machine, with {threads} runs in parallel; \"CPU per simulated s\" is that time divided by the simulated \
         time. Energy drift is |E(T) − E₀| divided by the scene's energy scale (docs/scenes.md). Constrained scenes use the stabilisation chosen \
         for the sweep; \"virtual power\" and \"pinning\" are the two constraint formulations (docs/theory.md §6, §7–§9).\n"
    );
    let runs_by_scene: Vec<(SceneId, Vec<&RunResult>)> = SceneId::ALL
        .into_iter()
        .map(|scene| (scene, results.iter().filter(|(c, _)| c.scene == scene).collect()))
        .collect();
    let rankings: HashMap<SceneId, Vec<Ranked>> = runs_by_scene
        .iter()
        .map(|(scene, runs)| (*scene, costs_at_mujoco_error(*scene, runs)))
        .collect();
    let mismatches: HashMap<SceneId, String> = runs_by_scene
        .iter()
        .filter_map(|(scene, runs)| Some((*scene, length_mismatch(*scene, runs)?)))
        .collect();
    mujoco_summary(&mut out, (&rankings, &mismatches), anchors);
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
        if let Some((anchor, source)) = single_body_anchor(anchors, scene) {
            let points: Vec<String> = anchor
                .points
                .iter()
                .map(|(dt, error)| format!("{error:.0e} (dt = {dt:.0e})"))
                .collect();
            let _ = writeln!(
                out,
                "MuJoCo 4.0 RK4 on this scene: {:.1} µs/step; error at T = {} s of {}. {}.\n",
                anchor.time_per_step * 1e6,
                scene.parameters().duration,
                points.join(", "),
                mujoco_provenance(&source),
            );
            let ranked = &rankings[&scene];
            if let Some(why) = mismatches.get(&scene) {
                let _ = writeln!(
                    out,
                    "No cost is compared at MuJoCo's accuracy for this run — {why}: MuJoCo's errors are at T.\n"
                );
            } else if !ranked.is_empty() {
                let _ = writeln!(
                    out,
                    "At MuJoCo's error at dt = 1e-3 ({}; MuJoCo: {} s of CPU per simulated s, {}), the five \
                     cheapest configurations:\n",
                    scientific(anchor.reference_error()),
                    scientific(anchor.reference_cost()),
                    source.short()
                );
                let _ = writeln!(
                    out,
                    "| configuration | CPU per simulated s (s) | MuJoCo's / ours (MuJoCo's time {}) |",
                    source.short()
                );
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

#[cfg(test)]
mod tests {
    use std::cmp::Ordering;

    use super::super::measure::Measurements;
    use super::super::sweep::Outcome;
    use super::*;
    use dynamics::constraints::Stabilisation;
    use dynamics::integrate::{Integrator, Method};

    fn config(algebra: AlgebraKind, dt: f64, duration: f64) -> Config {
        Config {
            scene: SceneId::Cuboid,
            algebra,
            formulation: None,
            integrator: Integrator::General(Method::Rk4),
            dt,
            duration,
            stabilisation: Stabilisation::PROJECTION,
        }
    }

    /// A cuboid run whose error falls as dt⁴ from 1e-8 rad at dt = 1e-2 and whose cost is 1e-6 s per step.
    fn run(algebra: AlgebraKind, dt: f64, duration: f64) -> RunResult {
        let error = 1e-8 * (dt / 1e-2).powi(4);
        let measurements = Measurements {
            orientation_end: error,
            orientation_max: error,
            position_end: 0.0,
            position_max: 0.0,
            energy_drift_end: 0.0,
            energy_drift_max: 0.0,
            violation_max: None,
            features: vec![],
            energy_drift: vec![],
            violation: vec![],
        };
        let config = config(algebra, dt, duration);
        let outcome = Outcome {
            config,
            samples: vec![],
            cpu_per_simulated_second: 1e-6 / dt,
            time_per_step: 1e-6,
            measurements,
        };
        (config, Ok(outcome))
    }

    /// The steps in an order that sorts differently as text.
    const STEPS: [f64; 5] = [1e-4, 2e-3, 1e-2, 5e-4, 1e-3];

    fn runs(duration: f64) -> Vec<RunResult> {
        AlgebraKind::ALL
            .iter()
            .flat_map(|&algebra| STEPS.iter().map(move |&dt| run(algebra, dt, duration)))
            .collect()
    }

    #[test]
    fn rows_sort_by_step_as_numbers() {
        let results = runs(10.0);
        let refs: Vec<&RunResult> = results.iter().collect();
        let labels: Vec<String> = agreement_rows(&refs).into_iter().map(|(label, _, _)| label).collect();
        assert_eq!(
            labels,
            ["1e-2", "2e-3", "1e-3", "5e-4", "1e-4"].map(|dt| format!("RK4, dt = {dt}"))
        );
        // The work-precision table: CGA's rows, then PGA's, each from the coarsest step to the finest.
        let mut table = String::new();
        scene_table(&mut table, &refs);
        let rows: Vec<(&str, &str)> = table
            .lines()
            .skip(2)
            .map(|line| {
                let cells: Vec<&str> = line.split(" | ").collect();
                (cells[0].trim_start_matches("| "), cells[1])
            })
            .collect();
        let expected: Vec<(&str, &str)> = ["CGA, RK4", "PGA, RK4"]
            .iter()
            .flat_map(|&c| ["1e-2", "2e-3", "1e-3", "5e-4", "1e-4"].map(|dt| (c, dt)))
            .collect();
        assert_eq!(rows, expected);
        // As text, "1e-4" < "2e-3"; as numbers the coarser step comes first.
        let key = |dt| row_key(&config(AlgebraKind::Pga, dt, 10.0));
        assert_eq!(compare_rows(&key(2e-3), &key(1e-4)), Ordering::Less);
        assert_eq!(compare_rows(&key(1e-2), &key(5e-3)), Ordering::Less);
    }

    #[test]
    fn mujoco_ratio_is_omitted_for_a_shortened_run() {
        // At the scene's T = 10 s the runs reach MuJoCo's 2e-10 rad and the ratio is reported.
        let full = report(&runs(10.0), 2, &HashMap::new(), &Anchors::none());
        let summary_row = |text: &str| {
            text.lines()
                .find(|l| l.starts_with("| 1 cuboid"))
                .map(str::to_owned)
                .expect("a summary row for scene 1")
        };
        assert!(summary_row(&full).contains('×'), "{}", summary_row(&full));
        assert!(full.contains("the five cheapest configurations"));
        assert!(full.contains(recorded_anchors::SINGLE_BODY_MEASURED));
        // Shortened to 2 s: no cost at MuJoCo's accuracy, and the row says why.
        let short = report(&runs(2.0), 2, &HashMap::new(), &Anchors::none());
        let row = summary_row(&short);
        assert!(row.contains("n/a: shortened run (2 s of T = 10 s)"), "{row}");
        assert!(!row.contains('×'), "{row}");
        assert!(!short.contains("the five cheapest configurations"));
        assert!(short.contains("No cost is compared at MuJoCo's accuracy for this run"));
    }
}
