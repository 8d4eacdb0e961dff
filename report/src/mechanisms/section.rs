//! The mechanisms' part of `report.md` and its plots: M1's and M2's work-precision (tables and plots, MuJoCo's
//! points as markers), the four-bar's revolution period, energy and joint violation per run, and M3's cost per
//! step against the chain's length beside MuJoCo's and Pinocchio's.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use dynamics::integrate::Integrator;
use scenarios::MechanismId;
use scene_file::AlgebraKind;

use super::figures::{chain_figure, work_precision_figure};
use super::sweep::{
    headline_error, length_mismatch, series_of, MechanismConfig, MechanismOutcome, MechanismResult, CHAIN_LONG_RUN,
    CHAIN_TIMING_DURATION,
};
use crate::markdown::{compare_rows, formulation_rank, integrator_rank, scientific, table_header, RowKey};
use crate::measure::cost_at_error;
use crate::measured_anchors::{
    chain_times, double_pendulum_time, four_bar_time, pinocchio_chain_times, sources_short, Anchors, Time, SPREAD_NOTE,
};
use crate::plot::PlotError;
use crate::recorded_anchors;

/// M2 is exact when every sample's loop violation is at most this (m): round-off, for links a metre long.
const EXACT_LOOP: f64 = 1e-12;

/// The coupler accuracy (m) at which M2's cost is compared with MuJoCo's (whose soft loop is off by 4.5e-2 m).
const FOUR_BAR_TARGET: f64 = 1e-9;

/// Where a mechanism run's row goes in its table ([`compare_rows`]).
fn row_key(config: &MechanismConfig) -> RowKey {
    (
        config.algebra,
        formulation_rank(Some(config.formulation)),
        integrator_rank(Integrator::General(config.method)),
        config.dt,
    )
}

/// Writes [`SPREAD_NOTE`] if any of `times` is flagged.
fn spread_note(out: &mut String, times: &[Time]) {
    if times.iter().any(|t| t.source.uncertain()) {
        let _ = writeln!(out, "\n{SPREAD_NOTE}.");
    }
}

/// The series reaching `target` most cheaply (interpolated log–log): (label, CPU per simulated second). For M2
/// only series whose every run holds the loop exactly count.
fn cheapest(
    groups: &BTreeMap<String, Vec<&MechanismOutcome>>,
    target: f64,
    algebra: AlgebraKind,
) -> Option<(String, f64)> {
    groups
        .iter()
        .filter(|(_, runs)| runs.first().is_some_and(|o| o.config.algebra == algebra))
        .filter(|(_, runs)| {
            runs.iter()
                .all(|o| o.config.id != MechanismId::FourBar || o.measures.violation <= EXACT_LOOP)
        })
        .filter_map(|(label, runs)| {
            let points: Vec<(f64, f64)> = runs
                .iter()
                .filter_map(|o| Some((o.cpu_per_simulated_second, headline_error(o)?)))
                .collect();
            Some((label.clone(), cost_at_error(&points, target)?))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// Every run of M1 or M2: a line per configuration and step.
fn work_precision_table(out: &mut String, results: &[MechanismResult], id: MechanismId) {
    let four_bar = id == MechanismId::FourBar;
    let mut columns = vec!["configuration", "dt (s)", "CPU per simulated s (s)", "µs/step"];
    if four_bar {
        columns.extend([
            "coupler error at T (m)",
            "largest loop violation (m)",
            "revolutions",
            "period error (relative)",
            "link angles at T (rad)",
        ]);
    } else {
        columns.extend([
            "orientation error at T (rad)",
            "position error at T (m)",
            "largest hinge violation (m)",
        ]);
    }
    columns.push("largest energy drift (J)");
    table_header(out, &columns);
    let mut rows: Vec<&MechanismResult> = results.iter().filter(|(c, _)| c.id == id).collect();
    rows.sort_by(|a, b| compare_rows(&row_key(&a.0), &row_key(&b.0)));
    for (config, result) in rows {
        let mut row = vec![config.series_label(), format!("{:e}", config.dt)];
        match result {
            Ok(o) => {
                let m = &o.measures;
                row.extend([
                    scientific(o.cpu_per_simulated_second),
                    format!("{:.2}", o.time_per_step * 1e6),
                ]);
                match (four_bar, m.four_bar) {
                    (true, Some(f)) => row.extend([
                        scientific(f.coupler_error),
                        scientific(m.violation),
                        f.revolutions.to_string(),
                        scientific(f.period_error),
                        scientific(f.angle_error),
                    ]),
                    _ => row.extend([
                        m.orientation_end.map_or("–".into(), scientific),
                        m.position_end.map_or("–".into(), scientific),
                        scientific(m.violation),
                    ]),
                }
                row.push(scientific(m.energy_drift));
            }
            Err(error) => row.push(format!("failed: {error}")),
        }
        let _ = writeln!(out, "| {} |", row.join(" | "));
    }
}

/// Per chain length: our time per RK4 step in each algebra beside MuJoCo's and Pinocchio's.
fn chain_table(out: &mut String, results: &[MechanismResult], anchors: &Anchors) {
    let time = |n: usize, algebra: AlgebraKind| {
        results.iter().find_map(|(c, r)| {
            let timing = c.id == MechanismId::Chain(n) && c.algebra == algebra && c.is_chain_timing();
            r.as_ref().ok().filter(|_| timing).map(|o| o.time_per_step)
        })
    };
    let (ball, hinge) = (chain_times(anchors, true), chain_times(anchors, false));
    let pinocchio = pinocchio_chain_times(anchors);
    let sources = |times: &[(usize, Time)]| sources_short(&times.iter().map(|(_, t)| t.source).collect::<Vec<_>>());
    table_header(
        out,
        &[
            "links N",
            "PGA µs/step",
            "CGA µs/step",
            &format!("MuJoCo ball µs/step ({})", sources(&ball)),
            "MuJoCo / PGA",
            &format!("MuJoCo hinge µs/step ({})", sources(&hinge)),
            &format!("Pinocchio ABA µs/evaluation ({})", sources(&pinocchio)),
            "PGA µs per evaluation per degree of freedom",
        ],
    );
    let micro = |x: Option<f64>| x.map_or("–".into(), |x| format!("{:.2}", x * 1e6));
    for (&(n, ball), &(_, hinge)) in ball.iter().zip(&hinge) {
        let pga = time(n, AlgebraKind::Pga);
        let pinocchio = pinocchio.iter().find(|(m, _)| *m == n).map(|p| p.1);
        let _ = writeln!(
            out,
            "| {n} | {} | {} | {:.1}{} | {} | {:.1}{} | {} | {} |",
            micro(pga),
            micro(time(n, AlgebraKind::Cga)),
            ball.seconds * 1e6,
            ball.source.flag(),
            pga.map_or("–".into(), |t| format!(
                "{:.1}×{}",
                ball.seconds / t,
                ball.source.flag()
            )),
            hinge.seconds * 1e6,
            hinge.source.flag(),
            pinocchio.map_or("–".into(), |p| format!(
                "{}{}",
                micro(Some(p.seconds)),
                p.source.flag()
            )),
            // RK4: four evaluations per step; a ball joint leaves 3 degrees of freedom per link.
            pga.map_or("–".into(), |t| format!("{:.3}", t * 1e6 / 4.0 / (3 * n) as f64)),
        );
    }
    let ratio = |algebra| Some(time(64, algebra)? / time(8, algebra)?);
    let _ = writeln!(
        out,
        "\nt(64)/t(8): PGA {}, CGA {}; MuJoCo's ball chain {:.0} (its dense mass-matrix factorisation).",
        ratio(AlgebraKind::Pga).map_or("–".into(), |r| format!("{r:.1}")),
        ratio(AlgebraKind::Cga).map_or("–".into(), |r| format!("{r:.1}")),
        ball[6].1.seconds / ball[3].1.seconds
    );
    let shown: Vec<Time> = [ball, hinge, pinocchio].iter().flatten().map(|(_, t)| *t).collect();
    spread_note(out, &shown);
}

/// The speed summary: M1 and M2 at MuJoCo's accuracy (or exact), M3 at N = 64.
fn summary(out: &mut String, results: &[MechanismResult], anchors: &Anchors) {
    let m1 = recorded_anchors::DOUBLE_PENDULUM;
    let (m1_time, m2_time) = (double_pendulum_time(anchors), four_bar_time(anchors));
    let _ = writeln!(
        out,
        "| mechanism | target | algebra | cheapest configuration | its CPU per simulated s (s) | MuJoCo's ({source}) \
         | MuJoCo's / ours (MuJoCo {source}) |",
        source = sources_short(&[m1_time.source, m2_time.source])
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|");
    let rows = [
        (
            MechanismId::DoublePendulum,
            m1.reference_error(),
            format!("orientation {:.1e} rad (MuJoCo at dt = 1e-3)", m1.reference_error()),
            m1_time,
        ),
        (
            MechanismId::FourBar,
            FOUR_BAR_TARGET,
            format!(
                "coupler {FOUR_BAR_TARGET:.0e} m, loop ≤ {EXACT_LOOP:.0e} m (MuJoCo: {:.1e} m, loop {:.1e} m)",
                recorded_anchors::FOUR_BAR_COUPLER_ERROR,
                recorded_anchors::FOUR_BAR_VIOLATION
            ),
            m2_time,
        ),
    ];
    // Both MuJoCo times are per step at dt = 1e-3.
    for (id, target, what, time) in rows {
        let (theirs, flag) = (time.seconds / 1e-3, time.source.flag());
        let groups = series_of(results, id);
        if groups.is_empty() {
            continue;
        }
        if let Some(why) = length_mismatch(results, id) {
            // The targets are errors at the mechanism's T: a run of another length is not compared with them.
            let _ = writeln!(
                out,
                "| {} | {what} | both | – | – | {}{flag} | {why} |",
                id.label(),
                scientific(theirs)
            );
            continue;
        }
        for algebra in [AlgebraKind::Pga, AlgebraKind::Cga] {
            let (label, ours) =
                cheapest(&groups, target, algebra).map_or(("none reaches it".to_string(), None), |(l, c)| (l, Some(c)));
            let _ = writeln!(
                out,
                "| {} | {what} | {} | {label} | {} | {}{flag} | {} |",
                id.label(),
                algebra.name(),
                ours.map_or("–".into(), scientific),
                scientific(theirs),
                ours.map_or("–".into(), |c| format!("{:.1}×{flag}", theirs / c)),
            );
        }
    }
    spread_note(out, &[m1_time, m2_time]);
}

/// The mechanisms' section of `report.md`, writing its plots into `dir`.
pub(crate) fn mechanism_section(
    dir: &Path,
    results: &[MechanismResult],
    anchors: &Anchors,
) -> Result<String, PlotError> {
    let mut out = String::new();
    if results.is_empty() {
        return Ok(out);
    }
    let _ = writeln!(
        out,
        "## Mechanisms (docs/scenes.md)\n\nSeveral bodies joined by hinges or ball joints, each body its own motor and \
         momentum, the reactions solved for the whole system in the kinetic metric (docs/mechanisms.md). Errors are \
         against the GA-independent references of `reference::multibody` (M1: reduced coordinates, DOP853; M2: the \
         crank angle ODE); violations are measured from the sampled poses. MuJoCo and Pinocchio: {}\n",
        match anchors.occasion_note() {
            Some(note) => format!(
                "their errors and the figures marked recorded, {}. {note}",
                recorded_anchors::MECHANISMS_MEASURED
            ),
            None => format!("{}.", recorded_anchors::MECHANISMS_MEASURED),
        }
    );
    let _ = writeln!(out, "### Speed at MuJoCo's accuracy\n");
    summary(&mut out, results, anchors);
    for (id, stem, what) in [
        (MechanismId::DoublePendulum, "m1_double_pendulum", "the two hinges hold"),
        (
            MechanismId::FourBar,
            "m2_four_bar",
            "the loop (20 hinge rows of rank 17) holds; revolution period against docs/scenes.md's 0.7906242901366745 s",
        ),
    ] {
        if !results.iter().any(|(c, _)| c.id == id) {
            continue;
        }
        // The table lists failed runs with their reasons, so it is written even when no run succeeded.
        let name = format!("{stem}_work_precision.png");
        let figure = if work_precision_figure(dir, results, id, &name, anchors)? {
            format!("![{name}]({name})\n")
        } else {
            "No run succeeded.\n".to_owned()
        };
        let _ = writeln!(out, "\n### {}: work-precision; {what}\n\n{figure}", id.label());
        work_precision_table(&mut out, results, id);
    }
    let name = "m3_chain_cost.png";
    if chain_figure(dir, results, name, anchors)? {
        let _ = writeln!(
            out,
            "\n### M3 chain: cost per step against N\n\nRK4 at dt = 1e-3 over {CHAIN_TIMING_DURATION} s, \
             projection after each step.\n\n![{name}]({name})\n"
        );
        chain_table(&mut out, results, anchors);
        let (n, _, dt) = CHAIN_LONG_RUN;
        for (config, result) in results
            .iter()
            .filter(|(c, _)| c.id == MechanismId::Chain(n) && !c.is_chain_timing())
        {
            let _ = match result {
                Ok(o) => writeln!(
                    out,
                    "\n{} links, {}, dt = {dt:.0e} s over {} s: largest energy drift {} J, largest joint violation {} m.",
                    n,
                    config.series_label(),
                    config.duration,
                    scientific(o.measures.energy_drift),
                    scientific(o.measures.violation)
                ),
                Err(error) => writeln!(out, "\n{n} links, {}: failed: {error}", config.series_label()),
            };
        }
    }
    Ok(out)
}
