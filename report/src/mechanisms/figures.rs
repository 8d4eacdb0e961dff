//! The mechanisms' plots: M1's and M2's work-precision (MuJoCo's points as markers) and M3's cost per step against
//! the chain's length beside MuJoCo's and Pinocchio's.

use std::collections::BTreeMap;
use std::path::Path;

use dynamics::integrate::Integrator;
use scenarios::MechanismId;
use scene_file::AlgebraKind;

use super::sweep::{headline_error, length_mismatch, series_of, MechanismOutcome, MechanismResult};
use crate::markdown::formulation_rank;
use crate::measured_anchors::{
    chain_times, double_pendulum_time, four_bar_time, pinocchio_chain_times, sources_short, Anchors, Source, Time,
};
use crate::panels::{panel_title, slot, styled, Family};
use crate::plot::{figure_with_caption, Labels, Panel, PlotError, Series, Shape};
use crate::recorded_anchors;

/// The legend of the mechanisms' MuJoCo points, `source` saying where their times come from.
fn mechanism_legend(what: &str, source: &str) -> String {
    // No-break spaces: the legend wraps before the source, not inside it.
    format!("MuJoCo 4.0 RK4{what} ({})", source.replace(' ', "\u{a0}"))
}

/// Where a figure caption's MuJoCo points come from.
fn provenance(source: Source) -> String {
    match source {
        Source::Measured(occasion, _) => format!(
            "their time per step measured in this run ({}{}), their errors recorded {} with the reference set's \
             scripts (errors do not depend on the machine)",
            occasion.when,
            source.flag(),
            recorded_anchors::MECHANISMS_DATE
        ),
        Source::Recorded(date) => format!(
            "measured {date} with the reference set's scripts on the project's 2-core machine type (thread CPU \
             time); constants, not measured by this run"
        ),
    }
}

/// Work-precision of M1 or M2: a panel per integrator family and joint formulation (two integrators in two
/// algebras each), MuJoCo's points as black triangles where the runs are of the mechanism's full length.
pub(crate) fn work_precision_figure(
    dir: &Path,
    results: &[MechanismResult],
    id: MechanismId,
    name: &str,
    anchors: &Anchors,
) -> Result<bool, PlotError> {
    let groups = series_of(results, id);
    if groups.is_empty() {
        return Ok(false);
    }
    let (y, time, what) = match id {
        MechanismId::FourBar => (
            "coupler centre-of-mass error at T (m)",
            four_bar_time(anchors),
            "at dt = 1e-3, its loop closed by a soft equality constraint",
        ),
        _ => (
            "orientation error at T (rad)",
            double_pendulum_time(anchors),
            "at dt = 1e-2, 1e-3, 1e-4",
        ),
    };
    // MuJoCo's time per step is that at dt = 1e-3, taken for every step as the recorded constants are.
    let mujoco_points: Vec<(f64, f64)> = match id {
        MechanismId::FourBar => vec![(time.seconds / 1e-3, recorded_anchors::FOUR_BAR_COUPLER_ERROR)],
        _ => recorded_anchors::DOUBLE_PENDULUM
            .points
            .iter()
            .map(|&(dt, e)| (time.seconds / dt, e))
            .collect(),
    };
    let mismatch = length_mismatch(results, id);
    // Panels by family, then formulation; in each, a series per palette slot (algebra and integrator).
    type PanelSeries<'a> = BTreeMap<usize, (AlgebraKind, Integrator, &'a Vec<&'a MechanismOutcome>)>;
    let mut panels_runs: BTreeMap<(Family, usize), (scenarios::Formulation, PanelSeries)> = BTreeMap::new();
    for runs in groups.values() {
        let config = runs[0].config;
        let integrator = Integrator::General(config.method);
        let (family, member) = Family::of(integrator);
        panels_runs
            .entry((family, formulation_rank(Some(config.formulation))))
            .or_insert_with(|| (config.formulation, BTreeMap::new()))
            .1
            .insert(slot(config.algebra, member), (config.algebra, integrator, runs));
    }
    let titles: Vec<String> = panels_runs
        .iter()
        .map(|((family, _), (formulation, _))| panel_title(Some(*formulation), *family))
        .collect();
    let panels: Vec<Panel> = panels_runs
        .values()
        .zip(&titles)
        .map(|((_, series), title)| {
            let mut series: Vec<Series> = series
                .values()
                .map(|(algebra, integrator, runs)| {
                    let points = runs
                        .iter()
                        .filter_map(|o| Some((o.cpu_per_simulated_second, headline_error(o)?)))
                        .collect();
                    let (_, member) = Family::of(*integrator);
                    let line = Series {
                        markers: true,
                        ..Series::line(format!("{}, {}", algebra.name(), integrator.name()), points)
                    };
                    styled(line, *algebra, member)
                })
                .collect();
            if mismatch.is_none() {
                series.push(Series::reference_points(
                    mechanism_legend("", &time.source.short()),
                    mujoco_points.clone(),
                ));
            }
            Panel::new(Labels::new(title, "CPU per simulated second (s)", y), series)
                .log_x()
                .log_y()
        })
        .collect();
    let caption = match &mismatch {
        Some(why) => format!(
            "MuJoCo's points are not drawn, {why}: its errors were measured at the mechanism's full T. Dark, solid: \
             PGA; light, dashed: CGA."
        ),
        None => format!(
            "Black triangles: MuJoCo 4.0 RK4 {what}, {}. Dark, solid: PGA; light, dashed: CGA.",
            provenance(time.source)
        ),
    };
    figure_with_caption(
        &dir.join(name),
        &format!("{}: error against CPU time", id.label()),
        &panels,
        &caption,
    )?;
    Ok(true)
}

/// M3's cost per step against N, log–log, with MuJoCo's and Pinocchio's.
pub(crate) fn chain_figure(
    dir: &Path,
    results: &[MechanismResult],
    name: &str,
    anchors: &Anchors,
) -> Result<bool, PlotError> {
    let ours = |algebra: AlgebraKind| -> Vec<(f64, f64)> {
        let mut points: Vec<(f64, f64)> = results
            .iter()
            .filter(|(c, _)| c.algebra == algebra && c.is_chain_timing())
            .filter_map(|(c, r)| match (c.id, r) {
                (MechanismId::Chain(n), Ok(o)) => Some((n as f64, o.time_per_step * 1e6)),
                _ => None,
            })
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        points
    };
    let (pga, cga) = (ours(AlgebraKind::Pga), ours(AlgebraKind::Cga));
    if pga.is_empty() && cga.is_empty() {
        return Ok(false);
    }
    let points = |table: &[(usize, Time)], factor: f64| {
        table
            .iter()
            .map(|(n, t)| (*n as f64, t.seconds * 1e6 * factor))
            .collect()
    };
    let sources = |table: &[(usize, Time)]| sources_short(&table.iter().map(|(_, t)| t.source).collect::<Vec<_>>());
    let (ball, hinge) = (chain_times(anchors, true), chain_times(anchors, false));
    let pinocchio = pinocchio_chain_times(anchors);
    let series = vec![
        styled(
            Series {
                markers: true,
                ..Series::line("PGA, ball joints by virtual power, RK4", pga)
            },
            AlgebraKind::Pga,
            0,
        ),
        styled(
            Series {
                markers: true,
                ..Series::line("CGA, the same", cga)
            },
            AlgebraKind::Cga,
            0,
        ),
        Series::reference_points(mechanism_legend(", ball joints", &sources(&ball)), points(&ball, 1.0)),
        Series {
            markers_only: true,
            shape: Shape::Triangle,
            slot: Some(4),
            ..Series::line(mechanism_legend(", hinges", &sources(&hinge)), points(&hinge, 1.0))
        },
        Series {
            markers_only: true,
            shape: Shape::Diamond,
            slot: Some(2),
            ..Series::line(
                format!(
                    "Pinocchio 4.1 ABA × 4 evaluations ({})",
                    sources(&pinocchio).replace(' ', "\u{a0}")
                ),
                points(&pinocchio, 4.0),
            )
        },
    ];
    let panel = Panel::new(
        Labels::new("M3 chain: cost per RK4 step at dt = 1e-3", "links N", "µs per step"),
        series,
    )
    .log_x()
    .log_y();
    figure_with_caption(
        &dir.join(name),
        "M3 chain: cost against the number of links",
        &[panel],
        &format!(
            "MuJoCo and Pinocchio: {} (thread CPU time); ours: this run.",
            match anchors.occasion() {
                Some(occasion) => format!("{} ({})", sources(&[ball, hinge, pinocchio].concat()), occasion.when),
                None => format!(
                    "constants measured {} with the reference set's scripts on the project's 2-core machine type, \
                     not by this run",
                    recorded_anchors::MECHANISMS_DATE
                ),
            }
        ),
    )?;
    Ok(true)
}
