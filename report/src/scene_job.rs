//! Running a scene file (`--scene-file`, [`crate::scene_file`]): the scene in each requested algebra, then
//! its trajectories (CSV), energy and constraint-violation plots and `summary.md` in the output folder.
//!
//! The trajectory `<stem>_<algebra>.csv` of named `[[body]]` entries has the columns `t`, then per body in file
//! order `NAME.x, NAME.y, NAME.z` (centre of mass, world, m) and `NAME.qw, NAME.qx, NAME.qy, NAME.qz`
//! (orientation quaternion, body → world), then `energy` (the whole system's, J); a single `[body]` keeps the
//! reference files' columns ([`csv::HEADER`]). The summary gives per algebra the energy change and the largest
//! joint violation over all joints.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use dynamics::constraints::Stabilisation;
use dynamics::integrate::Integrator;
use dynamics::simulate::Sample;
use dynamics::{Cga, Pga};

use crate::csv;
use crate::figures::{running_max, styled, LOG_FLOOR};
use crate::markdown::{agreement, escape, scientific};
use crate::plot::{chart, Labels, Panel, PlotError, Series};
use crate::scene_file::{joint_violations, FileAlgebra, JointGeometry, Layout, Pose, SceneFile, SceneFileError};
use crate::sweep::AlgebraKind;

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
    /// The energy change per sample, |E(t) − E₀| relative to |E₀| (absolute, in J, if |E₀| is below
    /// [`ABSOLUTE_ENERGY_BELOW`]).
    pub energy_change: Vec<f64>,
    /// The largest joint violation per sample (m).
    pub(crate) violation: Vec<f64>,
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

fn run_in<A: FileAlgebra>(
    algebra: AlgebraKind,
    scene: &SceneFile,
    joints: &[JointGeometry],
) -> Result<AlgebraRun, SceneFileError> {
    let simulation = scene.simulate::<A>()?;
    let bodies = simulation.bodies;
    let samples = &bodies[0];
    let duration = scene.schedule()?.duration();
    let stepping = simulation.stepping_time.as_secs_f64();
    let initial_energy = samples.first().map_or(0.0, |s| s.energy);
    let scale = if initial_energy.abs() < ABSOLUTE_ENERGY_BELOW {
        1.0
    } else {
        initial_energy.abs()
    };
    let energy_change = samples
        .iter()
        .map(|s| (s.energy - initial_energy).abs() / scale)
        .collect();
    let violation = (0..samples.len())
        .map(|k| {
            let poses: Vec<Pose> = bodies.iter().map(|b| (b[k].position, b[k].orientation)).collect();
            joint_violations(joints, &poses).fold(0.0, f64::max)
        })
        .collect();
    Ok(AlgebraRun {
        algebra,
        cpu_per_simulated_second: stepping / duration,
        time_per_step: stepping / simulation.steps.max(1) as f64,
        energy_change,
        violation,
        bodies,
    })
}

/// Loads the scene file at `path`, runs it and writes the output into `output`.
pub fn run_scene_file(path: &Path, output: &Path) -> Result<SceneJobSummary, SceneJobError> {
    let scene = SceneFile::load(path)?;
    let layout = scene.layout()?;
    let joints = layout.joint_geometries()?;
    let runs = scene
        .algebra
        .algebras()
        .into_iter()
        .map(|algebra| match algebra {
            AlgebraKind::Pga => run_in::<Pga>(algebra, &scene, &joints),
            AlgebraKind::Cga => run_in::<Cga>(algebra, &scene, &joints),
        })
        .collect::<Result<Vec<_>, _>>()?;

    let write_error = |path: &Path| {
        let path = path.to_path_buf();
        move |source| SceneJobError::Write { path, source }
    };
    std::fs::create_dir_all(output).map_err(write_error(output))?;
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
    let title = scene.title.clone().unwrap_or_else(|| stem.to_owned());
    let mut files = Vec::new();
    for run in &runs {
        let csv_path = output.join(format!("{stem}_{}.csv", run.algebra.name().to_lowercase()));
        let written = if layout.named {
            let names: Vec<&str> = layout.bodies.iter().map(|b| b.name.as_str()).collect();
            csv::write_bodies(&csv_path, &names, &run.bodies)
        } else {
            csv::write(&csv_path, &run.bodies[0])
        };
        written.map_err(write_error(&csv_path))?;
        files.push(csv_path);
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
    let energy_title = format!("{title}: energy change, dt = {:e} s", scene.dt);
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
    if !layout.joints.is_empty() {
        let violation_title = format!("{title}: constraint violation, dt = {:e} s", scene.dt);
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
    let conservative = scene.conservative()?;
    let warnings: Vec<String> = runs
        .iter()
        .filter(|run| conservative && run.max_energy_change() > ENERGY_WARNING)
        .map(|run| {
            format!(
                "{}: the energy of this conservative scene changed by {}{} (more than {ENERGY_WARNING:e}): the \
                 step dt = {:e} s is probably too large for its motion",
                run.algebra.name(),
                scientific(run.max_energy_change()),
                if relative { "" } else { " J" },
                scene.dt
            )
        })
        .collect();
    let setup = Setup {
        scene: &scene,
        layout: &layout,
        conservative,
        path,
        title: &title,
        stabilisation: scene.stabilisation()?,
        relative_energy: relative,
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
    scene: &'a SceneFile,
    layout: &'a Layout,
    /// Whether every force has a potential.
    conservative: bool,
    path: &'a Path,
    title: &'a str,
    stabilisation: Stabilisation,
    /// Whether the energy change is relative to |E₀| (else in J).
    relative_energy: bool,
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
    let body_name = |index: Option<usize>| index.map_or("the world", |i| layout.bodies[i].name.as_str());
    let constraints: Vec<String> = layout
        .joints
        .iter()
        .map(|j| {
            let what = format!(
                "{} by {}",
                j.geometry.kind(),
                scenarios::Formulation::from(j.formulation).name()
            );
            if layout.named {
                format!(
                    "{} ({what}, {} to {})",
                    escape(&j.name),
                    escape(body_name(Some(j.body))),
                    escape(body_name(j.reference))
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
        "From {}: {}forces: {}; constraints: {}. {}, dt = {:e} s, {} s simulated, sampled every {} s{}.\n",
        escape(&path.display().to_string()),
        if layout.named {
            format!(
                "bodies: {}; ",
                listed(layout.bodies.iter().map(|b| escape(&b.name)).collect())
            )
        } else {
            String::new()
        },
        listed(forces),
        listed(constraints),
        Integrator::from(scene.integrator).name(),
        scene.dt,
        scene.duration,
        scene.sample_interval,
        match setup.stabilisation {
            _ if layout.joints.is_empty() => String::new(),
            Stabilisation::Projection { .. } => ", stabilised by projection".to_owned(),
            Stabilisation::Baumgarte { alpha, beta } => format!(", stabilised by Baumgarte (α = {alpha}, β = {beta})"),
            Stabilisation::None => ", without stabilisation".to_owned(),
        },
    );
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
            if layout.joints.is_empty() {
                "–".to_owned()
            } else {
                scientific(run.max_violation())
            },
            scientific(run.cpu_per_simulated_second),
            run.time_per_step * 1e6,
        );
    }
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "Energy change: {}.",
        if setup.relative_energy {
            "|E(t) − E₀| / |E₀|"
        } else {
            "|E(t) − E₀| in J (|E₀| < 1e-6 J, where a relative change means nothing)"
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
            "A constant force or couple does work, so the energy change is physical, not only drift."
        );
    }
    let _ = writeln!(
        out,
        "The violation is the largest distance of a constrained body point from where it must be (for axis \
         joints also of the point 1 m along the body axis, for prismatic and planar joints of the point 1 m along \
         the body normal). CPU time is the stepping alone.\n"
    );
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
