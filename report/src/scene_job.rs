//! Running a scene file (`--scene-file`, [`scene_file`]): the scene in each requested algebra, then
//! its trajectories (CSV), energy and constraint-violation plots and `summary.md` in the output folder.
//!
//! The trajectory `<stem>_<algebra>.csv` of named `[[body]]` entries or a robot has the columns `t`, then per body in
//! the mechanism's order (the robot's bodies, named after their links, first) `NAME.x, NAME.y, NAME.z` (centre of
//! mass, world, m) and `NAME.qw, NAME.qx, NAME.qy, NAME.qz` (orientation quaternion, body → world), then `energy`
//! (the whole system's, J); a single `[body]` keeps the reference files' columns ([`csv::HEADER`]). With a robot,
//! `<stem>_joints_<algebra>.csv` has the columns of `reference/data/robots/*.csv`: `t`, every non-fixed joint's
//! position in URDF file order (rad or m, continuous joints unwrapped), for a free root `base.x, base.y, base.z,
//! base.qw, base.qx, base.qy, base.qz` (the root link frame, world ← root, the quaternion continuous in time), then
//! `energy`. The summary gives per algebra the energy change, the largest joint violation over all joints, and the
//! work done by the force elements against the energy change.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use dynamics::constraints::Stabilisation;
use dynamics::integrate::Integrator;
use dynamics::limits::{energy_changed_by, LimitChange, LimitTransition};
use dynamics::simulate::Sample;
use dynamics::{Cga, Correction, Dynamics, Pga, State, StepStatistics};

use crate::csv;
use crate::figures::{running_max, styled, LOG_FLOOR};
use crate::markdown::{agreement, escape, scientific};
use crate::plot::{chart, Labels, Panel, PlotError, Series};
use crate::sweep::AlgebraKind;
use scene_file::syntax::elements::{DriveSpec, TimeValue};
use scene_file::syntax::robot::{JointDynamicsName, LimitsName, MimicName, RootName};
use scene_file::{CheckedScene, End, FileAlgebra, Layout, LoadedRobot, Pose, Scene, SceneFileError, Stepping};

/// Why a scene file's run or output failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneJobError {
    /// The file cannot run, or its run failed.
    #[error(transparent)]
    Scene(#[from] SceneFileError),
    /// An output folder or file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The folder or file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A plot could not be drawn.
    #[error(transparent)]
    Plot(#[from] PlotError),
}

/// The run in one algebra, with what the summary states about it.
#[derive(Clone, Debug)]
pub struct AlgebraRun {
    pub(crate) algebra: AlgebraKind,
    /// Every body's samples, `bodies[i][k]`; the energy in each sample is the whole system's.
    pub bodies: Vec<Vec<Sample>>,
    /// Stepping time divided by the simulated time (s/s).
    pub(crate) cpu_per_simulated_second: f64,
    /// Stepping time per step (s).
    pub(crate) time_per_step: f64,
    /// The energy change per sample, |E(t) − E₀ − L(t)| relative to |E₀| (absolute, in J, if |E₀| is below
    /// [`ABSOLUTE_ENERGY_BELOW`]), L(t) what the joint limits' impacts changed it by up to t (zero without limits).
    pub energy_change: Vec<f64>,
    /// The joint limits' impacts, holds and releases.
    pub transitions: Vec<LimitTransition>,
    /// The deepest any contact point went below its plane over the samples (m); 0 without contacts.
    pub deepest: f64,
    /// The largest joint violation per sample (m).
    pub(crate) violation: Vec<f64>,
    /// The work done by the force elements from the start to each sample (J; `Sample::work`).
    pub work: Vec<f64>,
    /// Every body's name, in the order of [`AlgebraRun::bodies`].
    pub names: Vec<String>,
    /// With a robot: the joints CSV's headers between `t` and `energy`, and per sample its values between them.
    pub joints: Option<(Vec<String>, Vec<Vec<f64>>)>,
    /// How far putting the file's start on the joints moved each body.
    pub start_correction: Correction,
    /// The steps kept and refused, the evaluations, the shortest and longest step.
    pub statistics: StepStatistics,
}

/// Energy changes are relative to |E₀| unless it is below this (J): a chain released from z = 0 starts at
/// E₀ = round-off.
pub const ABSOLUTE_ENERGY_BELOW: f64 = 1e-6;

impl AlgebraRun {
    /// The largest of [`AlgebraRun::energy_change`].
    pub fn max_energy_change(&self) -> f64 {
        self.energy_change.iter().copied().fold(0.0, f64::max)
    }

    /// The largest joint violation over the run (m); 0 without joints.
    pub fn max_violation(&self) -> f64 {
        self.violation.iter().copied().fold(0.0, f64::max)
    }
}

/// The largest energy change (relative, or in J, as [`AlgebraRun::energy_change`]) a scene whose forces all have
/// a potential may show before its run is flagged: well above what the integrators drift at sensible steps
/// (1e-12 … 1e-8 on the reference scenes at dt = 1e-3), well below a step too large for the motion (a cuboid
/// spinning at 300 rad/s with RK4 at dt = 1e-2 doubles its energy in a second).
pub const ENERGY_WARNING: f64 = 1e-6;

/// What the job wrote.
#[derive(Clone, Debug)]
pub struct SceneJobSummary {
    /// One per requested algebra, PGA first.
    pub runs: Vec<AlgebraRun>,
    /// Runs whose result is suspect (a conservative scene whose energy changed by more than
    /// [`ENERGY_WARNING`]), said in words; also in `summary.md`.
    pub warnings: Vec<String>,
}

fn run_in<A: FileAlgebra>(algebra: AlgebraKind, scene: &Scene) -> Result<AlgebraRun, SceneFileError> {
    let system = scene.system::<A>()?;
    let simulation = scene.simulate::<A>()?;
    let contacts = !scene.checked().contacts.is_empty();
    let bodies = simulation.bodies;
    let samples = &bodies[0];
    let duration = scene.checked().schedule.duration();
    let stepping = simulation.stepping_time.as_secs_f64();
    let initial_energy = samples.first().map_or(0.0, |s| s.energy);
    let scale = if initial_energy.abs() < ABSOLUTE_ENERGY_BELOW {
        1.0
    } else {
        initial_energy.abs()
    };
    let transitions = simulation.transitions;
    let energy_change = samples
        .iter()
        .map(|s| (s.energy - initial_energy - energy_changed_by(&transitions, s.t)).abs() / scale)
        .collect();
    let mechanism = system.mechanism();
    let robot = system.joint_columns().is_some();
    let mut violation = Vec::with_capacity(samples.len());
    let mut deepest = 0.0f64;
    let mut rows = Vec::new();
    let mut previous: Option<Vec<f64>> = None;
    for k in 0..samples.len() {
        let poses: Vec<Pose> = bodies.iter().map(|b| (b[k].position, b[k].orientation)).collect();
        // The sampled states, for the joint positions of a robot and the heights of contacts.
        let states: Vec<State<A>> = if robot || contacts {
            (bodies.iter().enumerate())
                .map(|(i, b)| b[k].state(mechanism.body(i)))
                .collect()
        } else {
            Vec::new()
        };
        let failed = |what: &str, e: &dyn std::fmt::Display| SceneFileError::Run {
            algebra: A::NAME,
            message: format!("{what} at t = {}: {e}", samples[k].t),
        };
        let q = if robot {
            // The joint positions from the sampled poses, angles nearest the previous sample's.
            Some(
                mechanism
                    .joint_positions(&states, previous.as_deref())
                    .map_err(|e| failed("the joint positions", &e))?,
            )
        } else {
            None
        };
        violation.push(system.joint_violation(&poses, q.as_deref()));
        if contacts {
            let heights = mechanism
                .contact_heights(&states)
                .map_err(|e| failed("the contact heights", &e))?;
            deepest = heights.into_iter().fold(deepest, |d, h| d.max(-h));
        }
        if let Some(q) = q {
            rows.extend(system.joint_row(&q));
            previous = Some(q);
        }
    }
    let work = samples.iter().map(|s| s.work).collect();
    let joints = system.joint_columns().map(|headers| (headers.to_vec(), rows));
    Ok(AlgebraRun {
        algebra,
        cpu_per_simulated_second: stepping / duration,
        time_per_step: stepping / simulation.statistics.accepted.max(1) as f64,
        energy_change,
        violation,
        work,
        names: system.body_names().to_vec(),
        joints,
        bodies,
        start_correction: system.start_correction().clone(),
        statistics: simulation.statistics,
        transitions,
        deepest,
    })
}

/// Writes a robot's joints CSV: `t`, the columns, `energy`.
fn write_joints(path: &Path, headers: &[String], rows: &[Vec<f64>], samples: &[Sample]) -> std::io::Result<()> {
    let mut text = String::from("t");
    for header in headers {
        let _ = write!(text, ",{header}");
    }
    text.push_str(",energy\n");
    for (row, sample) in rows.iter().zip(samples) {
        let _ = write!(text, "{:e}", sample.t);
        for value in row {
            let _ = write!(text, ",{value:e}");
        }
        let _ = writeln!(text, ",{:e}", sample.energy);
    }
    std::fs::write(path, text)
}

/// Loads the scene file at `path`, runs it and writes the output into `output`.
pub fn run_scene_file(path: &Path, output: &Path) -> Result<SceneJobSummary, SceneJobError> {
    let scene = Scene::load(path)?;
    let checked = scene.checked();
    let layout = &checked.layout;
    let runs = checked
        .algebra
        .algebras()
        .into_iter()
        .map(|algebra| match algebra {
            AlgebraKind::Pga => run_in::<Pga>(algebra, &scene),
            AlgebraKind::Cga => run_in::<Cga>(algebra, &scene),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let robot = checked.robot.as_ref().map(|robot| robot_summary(&robot.loaded));

    let write_error = |path: &Path| {
        let path = path.to_path_buf();
        move |source| SceneJobError::Write { path, source }
    };
    std::fs::create_dir_all(output).map_err(write_error(output))?;
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
    let title = checked.title.clone().unwrap_or_else(|| stem.to_owned());
    let mut files = Vec::new();
    for run in &runs {
        let csv_path = output.join(format!("{stem}_{}.csv", run.algebra.name().to_lowercase()));
        let written = if layout.named {
            let names: Vec<&str> = run.names.iter().map(String::as_str).collect();
            csv::write_bodies(&csv_path, &names, &run.bodies)
        } else {
            csv::write(&csv_path, &run.bodies[0])
        };
        written.map_err(write_error(&csv_path))?;
        files.push(csv_path);
        if let Some((headers, rows)) = &run.joints {
            let joints_path = output.join(format!("{stem}_joints_{}.csv", run.algebra.name().to_lowercase()));
            write_joints(&joints_path, headers, rows, &run.bodies[0]).map_err(write_error(&joints_path))?;
            files.push(joints_path);
        }
    }

    let over_time = |values: fn(&AlgebraRun) -> Vec<f64>| -> Vec<Series> {
        runs.iter()
            .map(|run| {
                let points = run.bodies[0].iter().zip(values(run)).map(|(s, v)| (s.t, v)).collect();
                // PGA dark and solid, CGA light and dashed, as in the main job's plots.
                styled(Series::line(run.algebra.name(), points), run.algebra, 0)
            })
            .collect()
    };
    // Relative to E₀ unless it is (nearly) zero (every run starts from the same state, so the same E₀).
    let relative = runs
        .first()
        .and_then(|r| r.bodies[0].first())
        .is_some_and(|s| s.energy.abs() >= ABSOLUTE_ENERGY_BELOW);
    let energy_title = format!("{title}: energy change, {}", stepping(checked));
    let energy_axis = if relative {
        "|E(t) − E₀| / |E₀|"
    } else {
        "|E(t) − E₀| (J)"
    };
    let energy_path = output.join(format!("{stem}_energy.png"));
    let labels = Labels::new(&energy_title, "time (s)", energy_axis);
    chart(
        &energy_path,
        &Panel::new(labels, over_time(|r| r.energy_change.clone())).log_y_with_floor(LOG_FLOOR),
    )?;
    files.push(energy_path);
    if !layout.joints.is_empty() || robot.is_some() {
        let violation_title = format!("{title}: constraint violation, {}", stepping(checked));
        let violation_path = output.join(format!("{stem}_violation.png"));
        // The running maximum: per-sample violations at round-off are noise that hides the curves.
        let labels = Labels::new(&violation_title, "time (s)", "largest constraint violation up to t (m)");
        let panel = Panel::new(labels, over_time(|r| running_max(&r.violation)))
            .log_y_with_floor(LOG_FLOOR)
            .note("The largest violation over all joints from the start up to each sample (running maximum).");
        chart(&violation_path, &panel)?;
        files.push(violation_path);
    }

    let summary_path = output.join("summary.md");
    let file_names: Vec<String> = files
        .iter()
        .filter_map(|f| f.file_name().and_then(|n| n.to_str()).map(str::to_owned))
        .collect();
    let conservative = checked.conservative;
    let warnings: Vec<String> = runs
        .iter()
        .filter(|run| conservative && run.max_energy_change() > ENERGY_WARNING)
        .map(|run| {
            format!(
                "{}: the energy of this conservative scene changed by {}{} (more than {ENERGY_WARNING:e}): the \
                 steps ({}) are probably too coarse for its motion",
                run.algebra.name(),
                scientific(run.max_energy_change()),
                if relative { "" } else { " J" },
                stepping(checked)
            )
        })
        .collect();
    let setup = Setup {
        scene: checked,
        layout,
        conservative,
        path,
        title: &title,
        stabilisation: checked.stabilisation,
        relative_energy: relative,
        robot: robot.as_deref(),
        elements: element_list(checked),
        splitting: matches!(Integrator::from(checked.integrator), Integrator::Splitting(_)),
    };
    let mut text = summary(&setup, &runs, &file_names);
    for warning in &warnings {
        let _ = writeln!(text, "\n**Warning**: {warning}.");
    }
    std::fs::write(&summary_path, text).map_err(write_error(&summary_path))?;
    Ok(SceneJobSummary { runs, warnings })
}

/// What `summary.md` says about the scene besides the runs.
struct Setup<'a> {
    scene: &'a CheckedScene,
    layout: &'a Layout,
    /// Whether every force has a potential.
    conservative: bool,
    path: &'a Path,
    title: &'a str,
    stabilisation: Stabilisation,
    /// Whether the energy change is relative to |E₀| (else in J).
    relative_energy: bool,
    /// The robot's part, with a robot.
    robot: Option<&'a str>,
    /// The force elements and drives, described.
    elements: Vec<String>,
    /// Whether a splitting method steps (it integrates no power: W stays 0).
    splitting: bool,
}

/// Items joined by commas, or "none".
fn listed(items: Vec<String>) -> String {
    if items.is_empty() {
        "none".to_owned()
    } else {
        items.join(", ")
    }
}

/// `summary.md`: the setup, then per algebra the energy change, the largest violation and the CPU time.
fn summary(setup: &Setup, runs: &[AlgebraRun], files: &[String]) -> String {
    let Setup {
        scene,
        layout,
        path,
        title,
        ..
    } = *setup;
    let mut out = String::new();
    let body_name = |end: &End| match end {
        End::World => "the world".to_owned(),
        End::Body(i) => layout.bodies[*i].name.clone(),
        End::Link(link) => format!("the robot link {link}"),
    };
    let constraints: Vec<String> = layout
        .joints
        .iter()
        .map(|j| {
            let what = format!("{} by {}", j.kind, j.formulation.name());
            if layout.named {
                format!(
                    "{} ({what}, {} to {})",
                    escape(&j.name),
                    escape(&layout.bodies[j.body].name),
                    escape(&body_name(&j.reference))
                )
            } else {
                what
            }
        })
        .collect();
    let forces: Vec<String> = layout
        .bodies
        .iter()
        .flat_map(|b| {
            b.forces.iter().map(|f| {
                if layout.named {
                    format!("{} on {}", f.kind(), escape(&b.name))
                } else {
                    f.kind().to_owned()
                }
            })
        })
        .collect();
    let _ = writeln!(out, "# {}\n", escape(title));
    let _ = writeln!(
        out,
        "From {}: {}forces: {}; constraints: {}. {}, {}, {} s simulated, sampled every {} s{}.\n",
        escape(&path.display().to_string()),
        if layout.named {
            format!(
                "{}bodies: {}; ",
                if setup.robot.is_some() {
                    "a robot (below); further "
                } else {
                    ""
                },
                listed(layout.bodies.iter().map(|b| escape(&b.name)).collect())
            )
        } else {
            String::new()
        },
        listed(forces),
        listed(constraints),
        Integrator::from(scene.integrator).name(),
        stepping(scene),
        scene.duration,
        scene.sample_interval,
        match setup.stabilisation {
            _ if layout.joints.is_empty() && setup.robot.is_none() => String::new(),
            Stabilisation::Projection { .. } => ", stabilised by projection".to_owned(),
            Stabilisation::Baumgarte { alpha, beta } => format!(", stabilised by Baumgarte (α = {alpha}, β = {beta})"),
            Stabilisation::None => ", without stabilisation".to_owned(),
        },
    );
    if let Some(robot) = setup.robot {
        let _ = writeln!(out, "{robot}");
    }
    if !scene.contacts.is_empty() {
        let _ = writeln!(
            out,
            "Contacts, each a body point kept above the world plane n · x = d (docs/contacts.md):\n"
        );
        for (k, contact) in scene.contacts.iter().enumerate() {
            let _ = writeln!(
                out,
                "- {}: the point {:?} m of {}, n = {:?}, d = {} m, restitution {}",
                escape(&contact.name(k)),
                contact.point,
                escape(contact.body.as_deref().unwrap_or("the body")),
                contact.normal,
                contact.offset,
                contact.restitution
            );
        }
        let _ = writeln!(out);
    }
    if !setup.elements.is_empty() {
        let _ = writeln!(out, "Force elements and drives:\n");
        for element in &setup.elements {
            let _ = writeln!(out, "- {}", escape(element));
        }
        let _ = writeln!(out);
    }
    let _ = writeln!(
        out,
        "| algebra | energy change at T | largest energy change | largest constraint violation (m) | CPU per \
         simulated second (s) | µs per step |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|");
    for run in runs {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {:.2} |",
            run.algebra.name(),
            scientific(run.energy_change.last().copied().unwrap_or(0.0)),
            scientific(run.max_energy_change()),
            if layout.joints.is_empty() && setup.robot.is_none() {
                "–".to_owned()
            } else {
                scientific(run.max_violation())
            },
            scientific(run.cpu_per_simulated_second),
            run.time_per_step * 1e6,
        );
    }
    let _ = writeln!(out);
    for run in runs {
        let steps = run.statistics;
        let _ = writeln!(
            out,
            "Steps ({}): {} kept, {} refused, {} evaluations of the equations of motion, from {} s to {} s.",
            run.algebra.name(),
            steps.accepted,
            steps.rejected,
            steps.evaluations,
            scientific(steps.smallest_step),
            scientific(steps.largest_step),
        );
    }
    let _ = writeln!(out);
    if !layout.joints.is_empty() || setup.robot.is_some() {
        let corrections: Vec<String> = runs
            .iter()
            .filter_map(|run| {
                let (body, _) = run.start_correction.largest()?;
                Some(format!(
                    "{} moved `{}` by {} m and turned it by {} rad",
                    run.algebra.name(),
                    escape(&run.names[body]),
                    scientific(run.start_correction.moved[body]),
                    scientific(run.start_correction.turned[body]),
                ))
            })
            .collect();
        let _ = writeln!(
            out,
            "Putting the start on the joints (at most max_start_correction = {} m and rad) {}.\n",
            scene.max_start_correction,
            corrections.join("; ")
        );
    }
    let limited = runs.iter().any(|run| !run.transitions.is_empty());
    for run in runs.iter().filter(|run| !run.transitions.is_empty()) {
        let count = |kind: fn(&LimitChange) -> bool| run.transitions.iter().filter(|t| kind(&t.change)).count();
        let taken: f64 = run.transitions.iter().map(|t| t.energy_change).sum();
        let _ =
            writeln!(
            out,
            "{} ({}): {} bounces, {} holds, {} releases, the first at t = {:.6} s; the impacts changed the energy by \
             {} J{}.",
            {
                let contacts: Vec<String> = (scene.contacts.iter().enumerate()).map(|(k, c)| c.name(k)).collect();
                let on_contact = |t: &LimitTransition| contacts.contains(&t.constraint);
                match (run.transitions.iter().any(on_contact), run.transitions.iter().all(on_contact)) {
                    (false, _) => "Joint limits",
                    (true, true) => "Contacts",
                    (true, false) => "Joint limits and contacts",
                }
            },
            run.algebra.name(),
            count(|c| matches!(c, LimitChange::Bounced { .. })),
            count(|c| matches!(c, LimitChange::Held { .. })),
            count(|c| matches!(c, LimitChange::Released { .. })),
            run.transitions[0].t,
            scientific(taken),
            if scene.contacts.is_empty() {
                String::new()
            } else {
                format!(
                    "; the deepest a contact point went below its plane at the samples: {} m",
                    scientific(run.deepest)
                )
            },
        );
    }
    if limited {
        let _ = writeln!(out);
    }
    let _ = writeln!(
        out,
        "Energy change: {}{}.",
        if setup.relative_energy {
            "|E(t) − E₀| / |E₀|"
        } else {
            "|E(t) − E₀| in J (|E₀| < 1e-6 J, where a relative change means nothing)"
        },
        if limited {
            ", less what the impacts at limits and contacts changed it by up to t (recorded at each impact)"
        } else {
            ""
        }
    );
    if setup.conservative {
        let _ = writeln!(
            out,
            "Every force has a potential, so the energy change is the integrator's drift."
        );
    } else {
        let _ = writeln!(
            out,
            "Forces without a potential (constant forces or couples, dampers, torques, controllers, drives) do work, \
             so the energy change is physical, not only drift."
        );
    }
    let _ = writeln!(
        out,
        "The violation is the largest distance of a constrained body point from where it must be (for axis \
         joints also of the point 1 m along the body axis, for prismatic and planar joints of the point 1 m along \
         the body normal, for universal joints how far the point 1 m along the body axis is off the plane normal to \
         the reference axis, for fixed joints the turn's angle in rad{}). CPU time is the stepping alone.\n",
        if setup.robot.is_some() {
            "; for the robot's joints the distance of each child's joint origin from where its joint coordinates \
             put it, and the angle of the turn between them"
        } else {
            ""
        }
    );
    if !setup.conservative {
        let _ = writeln!(
            out,
            "| algebra | E(T) − E₀ (J) | work W(T) (J) | E(T) − E₀ − W(T) (J) |"
        );
        let _ = writeln!(out, "|---|---|---|---|");
        for run in runs {
            let (first, last) = (run.bodies[0].first(), run.bodies[0].last());
            let change = match (first, last) {
                (Some(a), Some(b)) => b.energy - a.energy,
                _ => 0.0,
            };
            let work = run.work.last().copied().unwrap_or(0.0);
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} |",
                run.algebra.name(),
                scientific(change),
                scientific(work),
                scientific(change - work)
            );
        }
        let _ = writeln!(
            out,
            "\nW is the work of the forces without a potential (force elements, drives, constant forces and couples) \
             from the start, integrated with the method's own weights, so E(T) − E₀ − W(T) is the integration \
             error.{}\n",
            if setup.splitting {
                " The splitting methods integrate no power: here W stays 0."
            } else {
                ""
            }
        );
    }
    if let [first, second] = runs {
        let (angle, distance) = first
            .bodies
            .iter()
            .zip(&second.bodies)
            .map(|(a, b)| agreement(a, b))
            .fold((0.0f64, 0.0f64), |(a, d), (x, y)| (a.max(x), d.max(y)));
        let _ = writeln!(
            out,
            "{} vs {}: largest orientation difference {} rad, largest position difference {} m.\n",
            first.algebra.name(),
            second.algebra.name(),
            scientific(angle),
            scientific(distance)
        );
    }
    for file in files {
        if file.ends_with(".png") {
            let _ = writeln!(out, "![{file}]({file})\n");
        } else if file.contains("_joints_") {
            let _ = writeln!(
                out,
                "Joint coordinates: [{file}]({file}) (columns: t, every non-fixed joint in URDF file order (rad or m, \
                 continuous joints unwrapped){}, then the energy of the whole system (J)).\n",
                if file_has_base(runs) {
                    ", base.x, base.y, base.z, base.qw, base.qx, base.qy, base.qz (the root link frame, world ← root)"
                } else {
                    ""
                }
            );
        } else {
            let columns = if layout.named {
                "t, then per body NAME.x, NAME.y, NAME.z (centre of mass, world, m), NAME.qw, NAME.qx, NAME.qy, \
                 NAME.qz (orientation body → world), then the energy of the whole system (J)"
                    .to_owned()
            } else {
                csv::HEADER.to_owned()
            };
            let _ = writeln!(out, "Trajectory: [{file}]({file}) (columns: {columns}).\n");
        }
    }
    out
}

/// How the run steps, for titles and summaries: "dt = 0.001 s", or "tolerance = 1e-8 (adaptive steps)".
fn stepping(scene: &CheckedScene) -> String {
    match scene.stepping {
        Stepping::Adaptive { tolerance } => format!("tolerance = {tolerance:e} (adaptive steps)"),
        Stepping::Fixed { dt } => format!("dt = {dt:e} s"),
    }
}

/// The force elements, for the summary: "spring 1 (spring-damper, k = 100 N/m, …)".
fn element_list(scene: &CheckedScene) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(robot) = scene.robot.as_ref().map(|robot| &robot.loaded) {
        if robot.spec.joint_dynamics == JointDynamicsName::Urdf {
            for j in robot.model.joints.iter().filter(|j| j.damping > 0.0) {
                out.push(format!("{} damping (URDF): {} on {}", j.name, j.damping, j.name));
            }
        }
        for (name, value) in &robot.spec.torque {
            out.push(format!("torque on {name}: {value} (constant)"));
        }
    }
    for (k, s) in scene.springs.iter().enumerate() {
        out.push(format!(
            "{} (spring-damper {} – {}: k = {} N/m, c = {} N s/m, rest length {} m)",
            s.name.clone().unwrap_or_else(|| format!("spring {}", k + 1)),
            s.between[0],
            s.between[1],
            s.stiffness,
            s.damping,
            s.rest_length
        ));
    }
    for (k, c) in scene.couples.iter().enumerate() {
        out.push(format!(
            "{} (couple {:?} N m on {}, its opposite on {})",
            c.name.clone().unwrap_or_else(|| format!("couple {}", k + 1)),
            c.moment,
            c.between[0],
            c.between[1]
        ));
    }
    for t in &scene.joint_torques {
        out.push(format!(
            "{} (joint torque {} on {})",
            t.name.clone().unwrap_or_else(|| format!("torque on {}", t.joint)),
            describe_time_value(&t.torque),
            t.joint
        ));
    }
    for d in &scene.joint_dampings {
        out.push(format!(
            "{} (joint damping {} on {})",
            d.name.clone().unwrap_or_else(|| format!("damping on {}", d.joint)),
            d.damping,
            d.joint
        ));
    }
    for (k, pd) in scene.pds.iter().enumerate() {
        let targets: Vec<String> = pd.target.iter().map(|(j, v)| format!("{j} → {v}")).collect();
        out.push(format!(
            "{} (PD, kp = {}, kd = {}{}: {})",
            pd.name.clone().unwrap_or_else(|| format!("pd {}", k + 1)),
            pd.kp,
            pd.kd,
            if pd.gravity_compensation {
                ", with the bias forces h(q, v) added"
            } else {
                ""
            },
            targets.join(", ")
        ));
    }
    for j in &scene.layout.joints {
        if let Some(drive) = j.drive {
            out.push(format!("drive of {}: q(t) = {}", j.name, describe_drive(&drive)));
        }
    }
    out
}

/// "2 N m" or "sine", for the summary.
fn describe_time_value(value: &TimeValue) -> String {
    match value {
        TimeValue::Constant(value) => format!("{value}"),
        TimeValue::Sine(s) => format!(
            "{} + {} sin(2π {} Hz t + {})",
            s.offset, s.amplitude, s.frequency, s.phase
        ),
    }
}

/// For the summary.
fn describe_drive(drive: &DriveSpec) -> String {
    match drive {
        DriveSpec::ConstantRate { start, rate } => format!("{start} + {rate} t"),
        DriveSpec::Sine(s) => format!(
            "{} + {} sin(2π {} Hz t + {})",
            s.offset, s.amplitude, s.frequency, s.phase
        ),
    }
}

/// What the summary says about the robot: the model, the repairs and warnings, what of the URDF is not modelled.
fn robot_summary(robot: &LoadedRobot) -> String {
    let (model, spec) = (&robot.model, &robot.spec);
    let mut out = String::new();
    let links: usize = model.bodies.iter().map(|b| b.links.len()).sum();
    let kinds: Vec<String> = model
        .joint_counts()
        .iter()
        .map(|(kind, n)| format!("{n} {kind}"))
        .collect();
    let joint_dof: usize = model.joints.iter().map(|j| j.kind.degrees_of_freedom()).sum();
    let free = spec.root == RootName::Free;
    let _ = writeln!(
        out,
        "Robot `{}` from {}: {links} links, {} merged into other links' bodies (fixed joints), so {} bodies ({} \
         moving); root {}; joints: {}; {} degrees of freedom{}.\n",
        escape(&model.name),
        escape(&robot.path.display().to_string()),
        model.merged_links,
        model.bodies.len(),
        robot.body_count(),
        if free {
            "free (a floating base)"
        } else {
            "fixed to the world"
        },
        if kinds.is_empty() {
            "none".to_owned()
        } else {
            kinds.join(", ")
        },
        joint_dof + if free { 6 } else { 0 },
        if free { " (6 of them the base's)" } else { "" },
    );
    let list = |title: &str, items: Vec<String>, out: &mut String| {
        if items.is_empty() {
            let _ = writeln!(out, "- {title}: none");
        } else {
            let _ = writeln!(out, "- {title}:");
            for item in items {
                let _ = writeln!(out, "  - {}", escape(&item));
            }
        }
    };
    list(
        "Repairs",
        model.repairs.iter().map(ToString::to_string).collect(),
        &mut out,
    );
    list(
        "Frozen joints (massless subtrees, coordinate 0)",
        model
            .frozen_joints
            .iter()
            .map(|f| format!("{} ({}, line {})", f.name, f.kind, f.line))
            .collect(),
        &mut out,
    );
    list("Importer warnings", model.warnings.clone(), &mut out);
    let damped: Vec<String> = model
        .joints
        .iter()
        .filter(|j| j.damping > 0.0)
        .map(|j| format!("{}: {}", j.name, j.damping))
        .collect();
    let friction: Vec<String> = model
        .joints
        .iter()
        .filter(|j| j.friction != 0.0)
        .map(|j| format!("{}: {} (not modelled)", j.name, j.friction))
        .collect();
    match spec.joint_dynamics {
        JointDynamicsName::Urdf => {
            list(
                "URDF joint damping, applied as joint damping (N m s/rad or N s/m)",
                damped,
                &mut out,
            );
            list("URDF Coulomb friction, not modelled", friction, &mut out);
        }
        JointDynamicsName::Ignore => {
            list(
                "URDF joint damping, ignored (joint_dynamics = \"ignore\")",
                damped,
                &mut out,
            );
            list(
                "URDF Coulomb friction, ignored (joint_dynamics = \"ignore\"; never modelled)",
                friction,
                &mut out,
            );
        }
    }
    let limited = model
        .joints
        .iter()
        .filter(|j| j.limit.is_some_and(|l| l.lower.is_some() || l.upper.is_some()))
        .count();
    let _ = match spec.limits {
        LimitsName::Ignore => writeln!(
            out,
            "- Joint limits: not enforced (limits = \"ignore\"); {limited} joints have position limits in the URDF"
        ),
        LimitsName::Enforce => writeln!(
            out,
            "- Joint limits: enforced on the {limited} joints with position limits in the URDF (restitution {})",
            spec.limit_restitution.unwrap_or(0.0)
        ),
    };
    let mimics: Vec<String> = model
        .joints
        .iter()
        .filter_map(|j| {
            j.mimic
                .as_ref()
                .map(|m| format!("{} = {} {} + {}", j.name, m.multiplier, m.joint, m.offset))
        })
        .collect();
    list(
        match spec.mimic {
            MimicName::Constraint => "Mimics, coupled (mimic = \"constraint\")",
            MimicName::Independent => "Mimics, independent joints (mimic = \"independent\")",
        },
        mimics,
        &mut out,
    );
    if !model.ignored.is_empty() {
        let ignored: Vec<String> = model.ignored.iter().map(|(tag, n)| format!("<{tag}> × {n}")).collect();
        let _ = writeln!(out, "- Ignored elements: {}", escape(&ignored.join(", ")));
    }
    let _ = writeln!(out, "- Gravity on the robot's bodies: {:?} m/s²\n", spec.gravity);
    out
}

/// Whether the joints CSV has the floating base's columns.
fn file_has_base(runs: &[AlgebraRun]) -> bool {
    runs.iter().any(|r| {
        r.joints
            .as_ref()
            .is_some_and(|(headers, _)| headers.iter().any(|h| h == "base.x"))
    })
}
