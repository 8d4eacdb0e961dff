//! The report's plots per scene: work-precision (error against CPU per simulated second, with MuJoCo's
//! points), energy drift over time, constraint violation over time, and the traced paths of the paper's
//! figures (simulated against the reference).
//!
//! The sweep's runs are drawn as small multiples: one panel per integrator [`Family`] (and per constraint
//! formulation), so an axis carries at most four curves (two integrators in two algebras) and MuJoCo's points.
//! A colour means the same in every panel ([`slot`]): the hue is the integrator's place in its family, the dark
//! shade PGA (solid, circles), the light shade CGA (dashed, squares).

use std::collections::BTreeMap;
use std::path::Path;

use dynamics::integrate::Integrator;
use nalgebra::Vector3;
use reference::{SceneConstraint, SceneId};
use scenarios::Formulation;
use scene_file::AlgebraKind;

use super::measure::headline_error;
use super::sweep::{Outcome, RunResult};
use crate::markdown::formulation_rank;
use crate::measured_anchors::{single_body_anchor, single_body_provenance, Anchors};
use crate::panels::{panel_title, running_max, slot, styled, Family, LOG_FLOOR};
use crate::plot::{chart, figure_with_caption, Labels, Panel, PlotError, Series};
use crate::recorded_anchors;

/// A file-name stem for a scene.
pub(crate) fn stem(scene: SceneId) -> &'static str {
    match scene {
        SceneId::Cuboid => "scene1_cuboid",
        SceneId::Pendulum => "scene2_pendulum",
        SceneId::TopCusp => "scene3a_top_cusp",
        SceneId::TopSteady => "scene3b_top_steady",
        SceneId::RodOnSphere => "scene4_rod_on_sphere",
        SceneId::RodOnCircle => "scene4_rod_on_circle",
    }
}

/// One panel's runs: per palette slot, the series' algebra, integrator and runs.
struct PanelRuns<'a> {
    formulation: Option<Formulation>,
    family: Family,
    series: BTreeMap<usize, (AlgebraKind, Integrator, Vec<&'a Outcome>)>,
}

/// The runs grouped into panels (by family, then formulation) and series (by algebra and integrator).
fn panels_of<'a>(outcomes: &[&'a Outcome]) -> Vec<PanelRuns<'a>> {
    let mut panels: BTreeMap<(Family, usize), PanelRuns<'a>> = BTreeMap::new();
    for &outcome in outcomes {
        let config = &outcome.config;
        let (family, member) = Family::of(config.integrator);
        let panel = panels
            .entry((family, formulation_rank(config.formulation)))
            .or_insert_with(|| PanelRuns {
                formulation: config.formulation,
                family,
                series: BTreeMap::new(),
            });
        panel
            .series
            .entry(slot(config.algebra, member))
            .or_insert_with(|| (config.algebra, config.integrator, Vec::new()))
            .2
            .push(outcome);
    }
    panels.into_values().collect()
}

/// A series label within a panel: "PGA, RK4" (the panel's title gives the formulation and family).
fn short_label(algebra: AlgebraKind, integrator: Integrator) -> String {
    format!("{}, {}", algebra.name(), integrator.name())
}

/// The step closest to 1e-3 among those run: the one the over-time plots and CSVs show.
pub(crate) fn showcase_step(outcomes: &[&Outcome]) -> Option<f64> {
    outcomes
        .iter()
        .map(|o| o.config.dt)
        .min_by(|a, b| (a.ln() - 1e-3f64.ln()).abs().total_cmp(&(b.ln() - 1e-3f64.ln()).abs()))
}

/// The world position of a body point in a sample.
fn world_point(sample: &dynamics::simulate::Sample, body_point: Vector3<f64>) -> Vector3<f64> {
    sample.position + sample.orientation * body_point
}

/// The 2-D point a paper-style figure traces for a sample.
type Projection = Box<dyn Fn(&dynamics::simulate::Sample) -> (f64, f64)>;

/// What the paper-style figure of a scene traces: title, axis labels, the projection, and whether the
/// axes share a scale.
fn traced_path(scene: SceneId) -> (&'static str, &'static str, &'static str, Projection, bool) {
    match scene.parameters().constraint {
        SceneConstraint::PointOnSphere { body_anchor, .. } | SceneConstraint::PointOnCircle { body_anchor, .. } => (
            "rod end P (top view)",
            "x (m)",
            "y (m)",
            Box::new(move |s| {
                let p = world_point(s, body_anchor);
                (p.x, p.y)
            }),
            true,
        ),
        SceneConstraint::Hinge { .. } => (
            "centre of mass path (side view)",
            "x (m)",
            "z (m)",
            Box::new(|s| (s.position.x, s.position.z)),
            true,
        ),
        SceneConstraint::BallJoint { .. } => (
            "centre of mass path (top view): precession and nutation",
            "x (m)",
            "y (m)",
            Box::new(|s| (s.position.x, s.position.y)),
            true,
        ),
        SceneConstraint::Free => (
            "angular velocity about the body y axis: the flips",
            "time (s)",
            "ω about the body y axis (rad/s)",
            Box::new(|s| (s.t, (s.orientation.inverse() * s.angular_velocity).y)),
            false,
        ),
    }
}

/// Draws every figure of one scene into `dir`, MuJoCo's points at the time `anchors` measured where it has one;
/// returns the file names.
pub(crate) fn scene_figures(
    dir: &Path,
    scene: SceneId,
    results: &[&RunResult],
    anchors: &Anchors,
) -> Result<Vec<String>, PlotError> {
    let outcomes: Vec<&Outcome> = results.iter().filter_map(|(_, r)| r.as_ref().ok()).collect();
    let mut files = Vec::new();
    if outcomes.is_empty() {
        return Ok(files);
    }
    let groups = panels_of(&outcomes);
    let titles: Vec<String> = groups.iter().map(|g| panel_title(g.formulation, g.family)).collect();
    files.push(work_precision_figure(
        dir,
        (scene, anchors),
        &outcomes,
        (&groups, &titles),
    )?);
    // Over time, at the showcase step.
    let Some(dt) = showcase_step(&outcomes) else {
        return Ok(files);
    };
    files.extend(over_time_figures(dir, scene, dt, (&groups, &titles))?);
    files.extend(path_figure(dir, scene, &outcomes)?);
    Ok(files)
}

/// The work-precision figure, a panel per group of `groups` titled by `titles`, MuJoCo's points in every panel where
/// they compare (runs of the scene's full length); returns its file name.
fn work_precision_figure(
    dir: &Path,
    (scene, anchors): (SceneId, &Anchors),
    outcomes: &[&Outcome],
    (groups, titles): (&[PanelRuns], &[String]),
) -> Result<String, PlotError> {
    let full = scene.parameters().duration;
    let mismatch = outcomes
        .iter()
        .find_map(|o| crate::measure::length_mismatch(o.config.duration, full));
    let anchor = single_body_anchor(anchors, scene);
    let mujoco_points = anchor
        .as_ref()
        .filter(|_| mismatch.is_none())
        .map(|(anchor, source)| (anchor.work_precision_points(), source.short()));
    let y = match scene {
        SceneId::RodOnSphere | SceneId::RodOnCircle => "centre-of-mass position error at T (m)",
        _ => "orientation error at T (rad)",
    };
    let panels: Vec<Panel> = groups
        .iter()
        .zip(titles)
        .map(|(group, title)| {
            let mut series: Vec<Series> = group
                .series
                .values()
                .map(|(algebra, integrator, runs)| {
                    let mut points: Vec<(f64, f64)> = runs
                        .iter()
                        .map(|o| (o.cpu_per_simulated_second, headline_error(scene, &o.measurements)))
                        .collect();
                    points.sort_by(|a, b| a.0.total_cmp(&b.0));
                    let (_, member) = Family::of(*integrator);
                    let line = Series {
                        markers: true,
                        ..Series::line(short_label(*algebra, *integrator), points)
                    };
                    styled(line, *algebra, member)
                })
                .collect();
            if let Some((points, when)) = &mujoco_points {
                series.push(Series::reference_points(
                    recorded_anchors::single_body_legend(when),
                    points.clone(),
                ));
            }
            Panel::new(Labels::new(title, "CPU per simulated second (s)", y), series)
                .log_x()
                .log_y()
        })
        .collect();
    let caption = match (&anchor, &mismatch) {
        (None, _) => "No MuJoCo figures for this scene.".to_owned(),
        (Some(_), Some(why)) => format!(
            "MuJoCo's points are not drawn, {why}: its errors were measured at the scene's full T. Dark, solid: \
             PGA; light, dashed: CGA."
        ),
        (Some((_, source)), None) => format!(
            "Black triangles: {}, at dt = 1e-2, 1e-3, 1e-4. Dark, solid: PGA; light, dashed: CGA.",
            single_body_provenance(source)
        ),
    };
    let name = format!("{}_work_precision.png", stem(scene));
    let title = format!("Scene {}: error against CPU time", scene.label());
    figure_with_caption(&dir.join(&name), &title, &panels, &caption)?;
    Ok(name)
}

/// The energy drift and, for a constrained scene, the constraint violation over time at the step `dt`, a panel per
/// group of `groups` titled by `titles`; returns their file names.
fn over_time_figures(
    dir: &Path,
    scene: SceneId,
    dt: f64,
    (groups, titles): (&[PanelRuns], &[String]),
) -> Result<Vec<String>, PlotError> {
    let over_time = |values: &dyn Fn(&Outcome) -> Vec<f64>, y: &'static str| -> Vec<Panel> {
        groups
            .iter()
            .zip(titles)
            .map(|(group, title)| {
                let series = group
                    .series
                    .values()
                    .filter_map(|(algebra, integrator, runs)| {
                        let run = runs.iter().find(|o| o.config.dt == dt)?;
                        let points = run.samples.iter().zip(values(run)).map(|(s, v)| (s.t, v)).collect();
                        let (_, member) = Family::of(*integrator);
                        Some(styled(
                            Series::line(short_label(*algebra, *integrator), points),
                            *algebra,
                            member,
                        ))
                    })
                    .collect();
                Panel::new(Labels::new(title, "time (s)", y), series).log_y_with_floor(LOG_FLOOR)
            })
            .collect()
    };
    let stem = stem(scene);
    let mut files = Vec::new();
    let name = format!("{stem}_energy_drift.png");
    let title = format!("Scene {}: energy drift, dt = {dt:.0e} s", scene.label());
    let panels = over_time(
        &|o| o.measurements.energy_drift.clone(),
        "|E(t) − E₀| ÷ the scene's energy scale",
    );
    figure_with_caption(
        &dir.join(&name),
        &title,
        &panels,
        "Energy drift per sample (every 0.01 s) relative to the scene's energy scale (docs/scenes.md). Dark, solid: \
             PGA; light, dashed: CGA.",
    )?;
    files.push(name);
    if !matches!(scene.parameters().constraint, SceneConstraint::Free) {
        let name = format!("{stem}_violation.png");
        let title = format!("Scene {}: constraint violation, dt = {dt:.0e} s", scene.label());
        let panels = over_time(
            &|o| running_max(&o.measurements.violation),
            "largest violation up to t (m)",
        );
        figure_with_caption(
            &dir.join(&name),
            &title,
            &panels,
            "The largest constraint violation from the start up to each time (running maximum of the violation \
                 sampled every 0.01 s). Dark, solid: PGA; light, dashed: CGA.",
        )?;
        files.push(name);
    }
    Ok(files)
}

/// The paper-style traced path: the most accurate PGA run against the reference; returns its file name, if there is
/// a run and a reference.
fn path_figure(dir: &Path, scene: SceneId, outcomes: &[&Outcome]) -> Result<Option<String>, PlotError> {
    let (what, x, y, project, equal) = traced_path(scene);
    let best = outcomes.iter().min_by(|a, b| {
        a.config
            .dt
            .total_cmp(&b.config.dt)
            .then(a.config.algebra.cmp(&b.config.algebra).reverse())
    });
    let reference = scene.reference_trajectory().ok();
    if let (Some(best), Some(reference)) = (best, reference) {
        let simulated: Vec<(f64, f64)> = best.samples.iter().map(&project).collect();
        let reference: Vec<(f64, f64)> = reference
            .samples()
            .iter()
            .take(best.samples.len())
            .map(|s| {
                project(&dynamics::simulate::Sample {
                    t: s.t,
                    position: s.position,
                    orientation: s.orientation,
                    velocity: s.velocity,
                    angular_velocity: s.angular_velocity,
                    energy: 0.0,
                    work: 0.0,
                })
            })
            .collect();
        let series = vec![
            Series {
                slot: Some(0),
                thick: true,
                ..Series::line(
                    format!(
                        "{}, dt\u{a0}=\u{a0}{:.0e}\u{a0}s",
                        best.config.series_label(),
                        best.config.dt
                    ),
                    simulated,
                )
            },
            Series::reference_line("reference (scipy DOP853)", reference),
        ];
        let name = format!("{}_path.png", stem(scene));
        let title = format!("Scene {}: {what}", scene.label());
        let panel = Panel::new(Labels { title: &title, x, y }, series).note(
            "The reference (black, dashed) is drawn over the simulated run (blue), which shows through its gaps.",
        );
        chart(&dir.join(&name), &if equal { panel.equal_aspect() } else { panel })?;
        return Ok(Some(name));
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::super::sweep::{default_integrators, SweepPlan, DEFAULT_STEPS};
    use super::*;
    use dynamics::constraints::Stabilisation;

    #[test]
    fn every_panel_of_the_default_sweep_keeps_to_four_curves_in_distinct_colours() {
        let plan = SweepPlan {
            scenes: SceneId::ALL.to_vec(),
            integrators: default_integrators(),
            steps: DEFAULT_STEPS.to_vec(),
            duration: None,
            stabilisation: Stabilisation::PROJECTION,
        };
        let configs = plan.configurations();
        for scene in SceneId::ALL {
            // Panels as `panels_of` forms them, from the configurations alone.
            let mut panels: BTreeMap<(Family, usize), Vec<usize>> = BTreeMap::new();
            for config in configs.iter().filter(|c| c.scene == scene) {
                let (family, member) = Family::of(config.integrator);
                let slots = panels
                    .entry((family, formulation_rank(config.formulation)))
                    .or_default();
                let slot = slot(config.algebra, member);
                if !slots.contains(&slot) {
                    slots.push(slot);
                }
            }
            for (key, slots) in &panels {
                // Four curves and MuJoCo's points at most: within the palette's six colours.
                assert!(slots.len() <= 4, "{scene:?} {key:?}: {slots:?}");
                let mut series: Vec<Series> = slots
                    .iter()
                    .map(|&s| Series {
                        slot: Some(s),
                        ..Series::line("run", vec![])
                    })
                    .collect();
                series.push(Series::reference_points("MuJoCo", vec![]));
                let colours = crate::plot::series_colours(&series).unwrap();
                for (i, c) in colours.iter().enumerate() {
                    assert!(!colours[..i].contains(c), "{scene:?} {key:?}: colour {c:?} repeats");
                }
            }
        }
    }

    #[test]
    fn running_max_never_falls() {
        assert_eq!(running_max(&[0.0, 2.0, 1.0, 3.0]), vec![0.0, 2.0, 2.0, 3.0]);
        assert!(running_max(&[]).is_empty());
    }
}
