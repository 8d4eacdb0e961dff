//! The robots' part of `report.md` ("Robots (URDF)") and its figures: per robot a model line, the CPU per simulated
//! second at MuJoCo's accuracy at dt = 1e-3 against MuJoCo's cost (recorded, or measured beside the run), a work-precision figure with MuJoCo's
//! points, a picture of the motion, and a table of every run.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use dynamics::integrate::Integrator;
use dynamics::Pga;
use reference::robots::{RobotId, RobotReference};
use scene_file::AlgebraKind;

use super::figures::{motion_picture, work_precision_figure};
use super::sweep::{robot_label, row_key, series_of, RobotOutcome, RobotResult, LEFT_OUT};
use crate::markdown::{compare_rows, scientific, table_header};
use crate::measure::cost_at_error;
use crate::measured_anchors::{mujoco_time, Anchors, SPREAD_NOTE};
use crate::plot::PlotError;
use crate::recorded_anchors::{MUJOCO, PINOCCHIO, RECORDED_WHEN};
use crate::runs::{LONG_TIMING, MAX_REPEATS, MIN_REPEATS, MIN_TIMING};

/// The step of MuJoCo's run whose error the costs are compared at (s).
const MUJOCO_DT: f64 = 1e-3;

fn file_stem(id: RobotId) -> String {
    format!("robot_{}", id.name())
}

/// A cost ratio: one decimal from 1 up, two below.
fn ratio(r: f64) -> String {
    if r >= 1.0 {
        format!("{r:.1}×")
    } else {
        format!("{r:.2}×")
    }
}

/// "6 moving bodies (11 URDF links, …), 6 revolute joints, 6 degrees of freedom, root `world` fixed to the world;
/// 17.0 kg moving".
fn model_line(id: RobotId) -> String {
    let scene = match scenarios::build_robot::<Pga>(id) {
        Ok(scene) => scene,
        Err(error) => return format!("the model did not build: {error}"),
    };
    let robot = &scene.robot;
    let model = robot.model();
    let mechanism = robot.mechanism();
    let bodies = mechanism.body_names().count();
    let links: usize = model.bodies.iter().map(|b| b.links.len()).sum();
    let joints = model
        .joint_counts()
        .iter()
        .map(|(kind, n)| format!("{n} {kind}"))
        .collect::<Vec<_>>()
        .join(", ");
    let dof = mechanism.joint_space().map_or(0, |s| s.velocity_count());
    let fixed = usize::from(!scene.reference.free_base);
    let mass: f64 = model.bodies.iter().skip(fixed).map(|b| b.mass).sum();
    let root = if scene.reference.free_base {
        format!("root `{}` floating (6 coordinates of its own)", model.bodies[0].name)
    } else {
        format!("root `{}` fixed to the world", model.bodies[0].name)
    };
    format!(
        "{bodies} moving bodies ({links} URDF links, those joined by fixed joints merged into one body), {joints} \
         joints, {dof} degrees of freedom, {root}; {mass:.2} kg moving"
    )
}

/// MuJoCo's run at `dt`, if recorded.
fn mujoco_run(reference: &RobotReference, dt: f64) -> Option<reference::robots::MujocoRun> {
    reference
        .mujoco
        .iter()
        .copied()
        .find(|r| (r.dt - dt).abs() <= 1e-9 * dt)
}

/// Per series: the cheapest run at or below MuJoCo's error, and the cost interpolated log–log between the runs that
/// bracket it.
fn speed_table(out: &mut String, results: &[RobotResult], id: RobotId, reference: &RobotReference, anchors: &Anchors) {
    let Some(anchor) = mujoco_run(reference, MUJOCO_DT) else {
        let _ = writeln!(out, "No MuJoCo run at dt = {MUJOCO_DT:.0e} was recorded.\n");
        return;
    };
    let time = mujoco_time(anchors, id, &anchor);
    let (theirs, flag) = (time.seconds / anchor.dt, time.source.flag());
    let target = anchor.max_joint_error;
    let _ = writeln!(
        out,
        "**CPU per simulated second at MuJoCo's accuracy**: {MUJOCO} at dt = {:.0e} s is off by at most {} rad over \
         the samples (recorded {RECORDED_WHEN}) at {:.2}{flag} µs per step, {} s per simulated second — {}. Per \
         configuration: the cheapest of its runs at or below that error, and the cost interpolated log–log between \
         the two runs that bracket it (a fixed-step method's error is a power of its cost).\n",
        anchor.dt,
        scientific(target),
        time.seconds * 1e6,
        scientific(theirs),
        time.source.short()
    );
    table_header(
        out,
        &[
            "configuration",
            "cheapest run at or below: dt (s), error (rad)",
            "its CPU per simulated s (s)",
            "MuJoCo's / ours",
            "interpolated CPU per simulated s (s)",
            "MuJoCo's / ours (interpolated)",
        ],
    );
    let groups = series_of(results, id);
    let mut best: BTreeMap<AlgebraKind, (String, f64)> = BTreeMap::new();
    for runs in groups.values() {
        let config = runs[0].config;
        let label = config.series_label();
        let cheapest = runs.iter().find(|o| o.joint_error <= target);
        let points: Vec<(f64, f64)> = runs
            .iter()
            .map(|o| (o.cpu_per_simulated_second, o.joint_error))
            .collect();
        let interpolated = cost_at_error(&points, target);
        let run_cell = match cheapest {
            Some(o) => format!("{:e}, {}", o.config.dt, scientific(o.joint_error)),
            None => {
                let smallest = runs.iter().min_by(|a, b| a.joint_error.total_cmp(&b.joint_error));
                smallest.map_or("none".to_owned(), |o| {
                    format!(
                        "none (smallest: {} at dt = {:e})",
                        scientific(o.joint_error),
                        o.config.dt
                    )
                })
            }
        };
        let ratio = |cost: f64| format!("{}{flag}", ratio(theirs / cost));
        let _ = writeln!(
            out,
            "| {label} | {run_cell} | {} | {} | {} | {} |",
            cheapest.map_or("–".into(), |o| scientific(o.cpu_per_simulated_second)),
            cheapest.map_or("–".into(), |o| ratio(o.cpu_per_simulated_second)),
            interpolated.map_or("–".into(), scientific),
            interpolated.map_or("–".into(), ratio),
        );
        if let Some(cost) = interpolated {
            let entry = best.entry(config.algebra).or_insert((label.clone(), cost));
            if cost < entry.1 {
                *entry = (label, cost);
            }
        }
    }
    let _ = writeln!(out);
    write_cheapest(out, &best, &groups, (target, anchor.dt), (theirs, flag));
    if time.source.uncertain() {
        let _ = writeln!(out, "{SPREAD_NOTE}.\n");
    }
}

/// The cheapest configuration at MuJoCo's error `target` at its step `dt` in each algebra (`best`: label and
/// interpolated cost), or, if none reaches it, the cheapest run at our floor; MuJoCo's cost `theirs`, `flag`ged if
/// uncertain.
fn write_cheapest(
    out: &mut String,
    best: &BTreeMap<AlgebraKind, (String, f64)>,
    groups: &BTreeMap<(AlgebraKind, usize), Vec<&RobotOutcome>>,
    (target, dt): (f64, f64),
    (theirs, flag): (f64, &str),
) {
    if best.is_empty() {
        let _ = write!(
            out,
            "No run reaches MuJoCo's {} rad at dt = {:.0e}",
            scientific(target),
            dt
        );
        // At our floor: the cheapest run within 1.5× of the smallest error of any run.
        let smallest = groups.values().flatten().map(|o| o.joint_error).min_by(f64::total_cmp);
        let closest = groups
            .values()
            .flatten()
            .filter(|o| smallest.is_some_and(|e| o.joint_error <= 1.5 * e))
            .min_by(|a, b| a.cpu_per_simulated_second.total_cmp(&b.cpu_per_simulated_second));
        if let Some(o) = closest {
            let _ = write!(
                out,
                "; at our floor, the cheapest run within 1.5× of the smallest error, {} at dt = {:e}, is off by {} \
                 rad at {} s per simulated second (MuJoCo's / ours: {}{flag})",
                o.config.series_label(),
                o.config.dt,
                scientific(o.joint_error),
                scientific(o.cpu_per_simulated_second),
                ratio(theirs / o.cpu_per_simulated_second),
            );
        }
        let _ = writeln!(out, ".\n");
    } else {
        let summary: Vec<String> = best
            .iter()
            .rev()
            .map(|(_, (label, cost))| {
                format!(
                    "{label}, {} s per simulated second (interpolated), {:.1}×{flag} less than MuJoCo's",
                    scientific(*cost),
                    theirs / cost
                )
            })
            .collect();
        let _ = writeln!(out, "Cheapest at MuJoCo's accuracy: {}.\n", summary.join("; "));
    }
}

/// Every run of one robot.
fn runs_table(out: &mut String, results: &[RobotResult], id: RobotId, free_base: bool) {
    let mut columns = vec![
        "configuration",
        "dt (s)",
        "steps",
        "CPU per simulated s (s)",
        "µs/step",
        "largest joint error (rad)",
    ];
    if free_base {
        columns.extend(["largest base origin error (m)", "largest base orientation error (rad)"]);
    }
    columns.push("largest \\|E − E₀\\| (J)");
    table_header(out, &columns);
    let mut rows: Vec<&RobotResult> = results.iter().filter(|(c, _)| c.robot == id).collect();
    rows.sort_by(|a, b| compare_rows(&row_key(&a.0), &row_key(&b.0)));
    for (config, result) in rows {
        let mut row = vec![config.series_label(), format!("{:e}", config.dt)];
        match result {
            Ok(o) => {
                row.extend([
                    o.steps.to_string(),
                    scientific(o.cpu_per_simulated_second),
                    format!("{:.2}", o.time_per_step * 1e6),
                    scientific(o.joint_error),
                ]);
                if free_base {
                    row.push(o.base_position_error.map_or("–".into(), scientific));
                    row.push(o.base_orientation_error.map_or("–".into(), scientific));
                }
                row.push(scientific(o.energy_change));
            }
            Err(error) => row.push(format!("failed: {error}")),
        }
        let _ = writeln!(out, "| {} |", row.join(" | "));
    }
}

/// Solo-12's error floors: the methods that step the bodies' motors against those that step in joint coordinates.
fn floors(results: &[RobotResult], id: RobotId, accuracy: f64) -> String {
    let smallest = |joint: bool| {
        results
            .iter()
            .filter(|(c, _)| c.robot == id && matches!(c.integrator, Integrator::Joint(_)) == joint)
            .filter_map(|(_, r)| r.as_ref().ok())
            .map(|o| o.joint_error)
            .min_by(f64::total_cmp)
    };
    let mut text = String::new();
    if let Some(floor) = smallest(false) {
        let _ = write!(
            text,
            "The methods that step the bodies' motors and momenta reach {} rad at best: round-off of the poses in \
             world axes, which grows as the base falls away from the origin (4.6 m in the second) and which the light \
             lower legs turn into joint angles when the next step reads them back (the same run started 10 m along x \
             is off by 4.4e-10 rad, `scenarios/tests/integration/robots.rs`).",
            scientific(floor)
        );
    }
    if let Some(floor) = smallest(true) {
        let _ = write!(
            text,
            " Stepping in joint coordinates (the RKMK-joint methods, docs/mechanisms.md §M9), which carry the \
             coordinates from step to step as MuJoCo and Pinocchio do, reach {} rad, near the reference's own \
             accuracy ({} rad).",
            scientific(floor),
            scientific(accuracy)
        );
    }
    text.trim_start().to_owned()
}

/// The robots' section of `report.md`, writing its figures into `dir`.
pub(crate) fn robot_section(dir: &Path, results: &[RobotResult], anchors: &Anchors) -> Result<String, PlotError> {
    let mut out = String::new();
    if results.is_empty() {
        return Ok(out);
    }
    let _ = writeln!(
        out,
        "\n## Robots (URDF)\n\nTwo real robots imported from their URDFs (example-robot-data 6.0.0; `urdf-import`, \
         `scenarios::build_robot`), moving passively under gravity for 1 s from the reference's start — no joint \
         torques, damping, limits or contacts — against {PINOCCHIO}'s articulated-body algorithm integrated by DOP853 \
         at rtol = atol = 1e-13 (`reference/data/robots/`, accurate to 2e-14–3e-14). Errors are the largest over the \
         reference's 101 samples every 0.01 s; steps longer than 0.01 s take the samples in between by a partial step \
         of the method, and their cost is timed on a run sampled at its steps only. CPU: the stepping time in this job, two \
         runs in parallel, the fastest of {MIN_REPEATS} timed runs (fewer where they take over {LONG_TIMING} s) and \
         of at least {MIN_TIMING} s of stepping (at most {MAX_REPEATS} runs). MuJoCo's and \
         Pinocchio's figures were recorded {RECORDED_WHEN}{}.\n",
        if anchors.is_empty() {
            ""
        } else {
            ", except MuJoCo's times per step where they say they were measured in this run"
        }
    );
    for id in RobotId::ALL {
        if !results.iter().any(|(c, _)| c.robot == id) {
            continue;
        }
        let reference = match id.reference() {
            Ok(reference) => reference,
            Err(error) => {
                let _ = writeln!(out, "### {}\n\nThe reference did not read: {error}\n", robot_label(id));
                continue;
            }
        };
        let _ = writeln!(out, "### {}\n\nModel: {}.\n", robot_label(id), model_line(id));
        speed_table(&mut out, results, id, &reference, anchors);
        let evaluation = reference.pinocchio_aba_microseconds;
        let _ = writeln!(
            out,
            "{PINOCCHIO}'s C++ ABA: {evaluation:.2} µs per evaluation of the accelerations; RK4 needs four per step, \
             {:.2} µs, or {} s per simulated second at dt = 1e-3 — recorded {RECORDED_WHEN}.\n",
            4.0 * evaluation,
            scientific(4.0 * evaluation * 1e-6 / 1e-3)
        );
        if id == RobotId::Solo12 {
            let _ = writeln!(out, "{}\n\n{LEFT_OUT}.\n", floors(results, id, reference.accuracy));
        }
        let stem = file_stem(id);
        let name = format!("{stem}_work_precision.png");
        if work_precision_figure(dir, results, id, &reference, &name, anchors)? {
            let _ = writeln!(out, "![{name}]({name})\n");
        }
        let name = format!("{stem}_motion.png");
        if let Some(label) = motion_picture(dir, results, id, &name)? {
            let _ = writeln!(out, "The motion ({label}):\n\n![{name}]({name})\n");
        }
        runs_table(&mut out, results, id, reference.free_base);
        let _ = writeln!(out);
    }
    Ok(out)
}
