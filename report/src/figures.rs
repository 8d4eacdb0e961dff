//! The report's plots per scene: work-precision (error against CPU per simulated second, with MuJoCo's
//! points), energy drift over time, constraint violation over time, and the traced paths of the paper's
//! figures (simulated against the reference).

use std::collections::BTreeMap;
use std::path::Path;

use nalgebra::Vector3;
use reference::{SceneConstraint, SceneId};

use crate::markdown::RunResult;
use crate::mujoco;
use crate::plot::{chart, Labels, Panel, PlotError, Series};
use crate::sweep::Outcome;

/// A file-name stem for a scene.
pub fn stem(scene: SceneId) -> &'static str {
    match scene {
        SceneId::Cuboid => "scene1_cuboid",
        SceneId::Pendulum => "scene2_pendulum",
        SceneId::TopCusp => "scene3a_top_cusp",
        SceneId::TopSteady => "scene3b_top_steady",
        SceneId::RodOnSphere => "scene4_rod_on_sphere",
        SceneId::RodOnCircle => "scene4_rod_on_circle",
    }
}

/// The work-precision error of a scene: orientation at T, except scene 4, whose anchor is a position.
fn work_precision_error(scene: SceneId, outcome: &Outcome) -> f64 {
    match scene {
        SceneId::RodOnSphere | SceneId::RodOnCircle => outcome.measurements.position_end,
        _ => outcome.measurements.orientation_end,
    }
}

/// The step closest to 1e-3 among those run: the one the over-time plots and CSVs show.
pub fn showcase_step(outcomes: &[&Outcome]) -> Option<f64> {
    outcomes
        .iter()
        .map(|o| o.config.dt)
        .min_by(|a, b| (a.ln() - 1e-3f64.ln()).abs().total_cmp(&(b.ln() - 1e-3f64.ln()).abs()))
}

/// Outcomes grouped by series label, in a stable order.
fn by_series<'a>(outcomes: &[&'a Outcome]) -> BTreeMap<String, Vec<&'a Outcome>> {
    let mut groups: BTreeMap<String, Vec<&Outcome>> = BTreeMap::new();
    for outcome in outcomes {
        groups.entry(outcome.config.series_label()).or_default().push(outcome);
    }
    groups
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
            "body angular velocity ω_y: the flips",
            "time (s)",
            "ω_y, body frame (rad/s)",
            Box::new(|s| (s.t, (s.orientation.inverse() * s.angular_velocity).y)),
            false,
        ),
    }
}

/// Draws every figure of one scene into `dir`; returns the file names.
pub fn scene_figures(dir: &Path, scene: SceneId, results: &[&RunResult]) -> Result<Vec<String>, PlotError> {
    let outcomes: Vec<&Outcome> = results.iter().filter_map(|(_, r)| r.as_ref().ok()).collect();
    let mut files = Vec::new();
    if outcomes.is_empty() {
        return Ok(files);
    }
    let stem = stem(scene);
    let groups = by_series(&outcomes);

    // Work-precision.
    let mut series: Vec<Series> = groups
        .iter()
        .map(|(label, runs)| {
            let mut points: Vec<(f64, f64)> = runs
                .iter()
                .map(|o| (o.cpu_per_simulated_second, work_precision_error(scene, o)))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series {
                markers: true,
                ..Series::line(label.clone(), points)
            }
        })
        .collect();
    if let Some(points) = mujoco::work_precision_points(scene) {
        series.push(Series {
            markers_only: true,
            ..Series::line("MuJoCo 4.0 RK4 (measured)", points)
        });
    }
    let y = match scene {
        SceneId::RodOnSphere | SceneId::RodOnCircle => "centre-of-mass position error at T (m)",
        _ => "orientation error at T (rad)",
    };
    let name = format!("{stem}_work_precision.png");
    let title = format!("Scene {}: error against CPU time", scene.label());
    let labels = Labels {
        title: &title,
        x: "CPU per simulated second (s)",
        y,
    };
    chart(&dir.join(&name), &Panel::new(labels, series).log_x().log_y())?;
    files.push(name);

    // Over time, at the showcase step.
    let Some(dt) = showcase_step(&outcomes) else {
        return Ok(files);
    };
    let showcase: Vec<&Outcome> = outcomes.iter().copied().filter(|o| o.config.dt == dt).collect();
    let over_time = |values: fn(&Outcome) -> &[f64]| -> Vec<Series> {
        showcase
            .iter()
            .map(|o| {
                let points = o.samples.iter().zip(values(o)).map(|(s, &v)| (s.t, v)).collect();
                Series::line(o.config.series_label(), points)
            })
            .collect()
    };
    let name = format!("{stem}_energy_drift.png");
    let title = format!("Scene {}: energy drift, dt = {dt:.0e} s", scene.label());
    let labels = Labels {
        title: &title,
        x: "time (s)",
        y: "|E(t) − E₀| / E_scale",
    };
    chart(
        &dir.join(&name),
        &Panel::new(labels, over_time(|o| &o.measurements.energy_drift)).log_y(),
    )?;
    files.push(name);
    if !matches!(scene.parameters().constraint, SceneConstraint::Free) {
        let name = format!("{stem}_violation.png");
        let title = format!("Scene {}: constraint violation, dt = {dt:.0e} s", scene.label());
        let labels = Labels {
            title: &title,
            x: "time (s)",
            y: "constraint violation (m)",
        };
        chart(
            &dir.join(&name),
            &Panel::new(labels, over_time(|o| &o.measurements.violation)).log_y(),
        )?;
        files.push(name);
    }

    // The paper-style traced path: the most accurate PGA run against the reference.
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
                })
            })
            .collect();
        let series = vec![
            Series::line("reference (DOP853)", reference),
            Series::line(
                format!("{}, dt = {:.0e} s", best.config.series_label(), best.config.dt),
                simulated,
            ),
        ];
        let name = format!("{stem}_path.png");
        let title = format!("Scene {}: {what}", scene.label());
        let panel = Panel::new(Labels { title: &title, x, y }, series);
        chart(&dir.join(&name), &if equal { panel.equal_aspect() } else { panel })?;
        files.push(name);
    }
    Ok(files)
}
