//! The adaptive runs' plots: each scene's embedded pairs over the tolerances on the work-precision axes of its
//! fixed-step runs, the error achieved against the tolerance asked for, and the step length over time.

use dynamics::integrate::{Integrator, Method};
use dynamics::JointMethod;
use scene_file::AlgebraKind;

use super::sweep::{mechanism_error, AdaptiveCase, AdaptiveOutcome, AdaptiveResult};
use crate::mechanisms::sweep::MechanismResult;
use crate::plot::{Labels, Panel, Series};
use crate::robots::sweep::RobotResult;
use crate::single_bodies::measure::headline_error;
use crate::single_bodies::sweep::RunResult;

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
pub(crate) fn runs_of(results: &[AdaptiveResult], case: AdaptiveCase, method: Integrator) -> Vec<&AdaptiveOutcome> {
    let mut runs: Vec<&AdaptiveOutcome> = (results.iter())
        .filter(|(c, _)| c.case == case && c.method == method)
        .filter_map(|(_, r)| r.as_ref().ok())
        .collect();
    runs.sort_by(|a, b| b.config.tolerance.total_cmp(&a.config.tolerance));
    runs
}

/// One work-precision panel per scene of `cases`, titled by `titles`: the pairs over the tolerances, the fixed-step
/// methods over the steps.
pub(crate) fn work_precision_panels<'a>(
    results: &[AdaptiveResult],
    fixed: &FixedRuns,
    methods: &[Integrator],
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
pub(crate) fn tolerance_panels(
    results: &[AdaptiveResult],
    methods: &[Integrator],
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
pub(crate) fn step_panels<'a>(
    results: &[AdaptiveResult],
    methods: &[Integrator],
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
