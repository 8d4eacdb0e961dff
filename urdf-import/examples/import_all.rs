//! Imports every `.urdf` under a folder, with default options and with every repair on, and prints per file what
//! came out (bodies, moving joints by kind, merged links, repairs) or the error; builds each imported model as a
//! mechanism (root fixed to the world, PGA) and evaluates its joint accelerations at rest in the zero pose (finite,
//! or the error); then a summary, and the import time of the file with the most links and of the one closest to 60
//! links.
//!
//! ```sh
//! cargo run --release -p urdf-import --example import_all -- DIR [--verbose]
//! ```
//!
//! `--verbose` also lists every repair and warning. The repairs use `bound_mass` = 1 g and `bound_inertia` =
//! 1e-6 kg m² (a 1 g, 5 cm part), the values the Pinocchio survey used to make massless subtrees finite.

use std::path::{Path, PathBuf};
use std::time::Instant;

use dynamics::Pga;
use urdf_import::{read, BuildOptions, ImportOptions, Robot, RobotModel, RobotStart};

const BOUND_MASS: f64 = 1e-3; // kg
const BOUND_INERTIA: f64 = 1e-6; // kg m²

fn urdf_files(dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.is_dir() {
            urdf_files(&path, out)?;
        } else if path.extension().is_some_and(|e| e == "urdf") {
            out.push(path);
        }
    }
    Ok(())
}

fn describe(model: &RobotModel) -> String {
    let kinds: Vec<String> = model.joint_counts().iter().map(|(k, n)| format!("{n} {k}")).collect();
    let kinds = if kinds.is_empty() {
        "none".to_owned()
    } else {
        kinds.join(", ")
    };
    let mut text = format!(
        "ok: {} bodies, moving joints {}, {} merged links, {} repairs",
        model.bodies.len(),
        kinds,
        model.merged_links,
        model.repairs.len()
    );
    if !model.frozen_joints.is_empty() {
        text += &format!(" ({} frozen)", model.frozen_joints.len());
    }
    if model.root_fixed_only {
        text += ", root fixed only";
    }
    text
}

/// Builds the model with a fixed root and evaluates q̈ at rest in the zero pose: "finite q̈ (n)" or the error.
fn evaluate(model: RobotModel) -> Result<String, String> {
    let robot = Robot::<Pga>::build(model, &BuildOptions::default()).map_err(|e| e.to_string())?;
    let states = robot
        .initial_states(&RobotStart::default())
        .map_err(|e| e.to_string())?;
    let q_ddot = robot
        .mechanism()
        .joint_accelerations(0.0, &states)
        .map_err(|e| e.to_string())?;
    if q_ddot.iter().all(|a| a.is_finite()) {
        Ok(format!("finite q̈ ({} coordinates)", q_ddot.len()))
    } else {
        Err(format!("non-finite q̈ {q_ddot:?}"))
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let verbose = args.iter().any(|a| a == "--verbose");
    let Some(dir) = args.iter().find(|a| !a.starts_with("--")) else {
        return Err("usage: import_all DIR [--verbose]".into());
    };
    let mut files = Vec::new();
    urdf_files(Path::new(dir), &mut files)?;
    files.sort();
    let options = [
        ("default", ImportOptions::default()),
        ("repairs", ImportOptions::repair_all(BOUND_MASS, BOUND_INERTIA)),
    ];
    let mut ok = [0; 2];
    let mut evaluated = [0; 2];
    // The file with the most links, and the one closest to 60 links (the timing target's size).
    let mut largest: Option<(usize, PathBuf, String)> = None;
    let mut near_60: Option<(usize, PathBuf, String)> = None;
    for path in &files {
        let text = std::fs::read_to_string(path)?;
        let name = path.strip_prefix(dir).unwrap_or(path).display();
        println!("{name}");
        for (i, (label, option)) in options.iter().enumerate() {
            match read(&text, option) {
                Ok(model) => {
                    ok[i] += 1;
                    println!("  {label}: {}", describe(&model));
                    if verbose {
                        model.repairs.iter().for_each(|r| println!("    repair: {r}"));
                        model.warnings.iter().for_each(|w| println!("    warning: {w}"));
                    }
                    match evaluate(model) {
                        Ok(text) => {
                            evaluated[i] += 1;
                            println!("    built: {text}");
                        }
                        Err(e) => println!("    built: ERROR {e}"),
                    }
                }
                Err(e) => println!("  {label}: ERROR {e}"),
            }
        }
        if let Ok(raw) = urdf_import::parse::parse(&text) {
            let n = raw.links.len();
            if largest.as_ref().is_none_or(|(m, _, _)| n > *m) {
                largest = Some((n, path.clone(), text.clone()));
            }
            if near_60.as_ref().is_none_or(|(m, _, _)| n.abs_diff(60) < m.abs_diff(60)) {
                near_60 = Some((n, path.clone(), text));
            }
        }
    }
    println!(
        "SUMMARY: {} URDF files; default options: {} ok, {} errors; all repairs: {} ok, {} errors",
        files.len(),
        ok[0],
        files.len() - ok[0],
        ok[1],
        files.len() - ok[1]
    );
    println!(
        "BUILT: finite joint accelerations at rest: default options {} of {} imported, all repairs {} of {}",
        evaluated[0], ok[0], evaluated[1], ok[1]
    );
    for (links, path, text) in [largest, near_60].into_iter().flatten() {
        let option = ImportOptions::repair_all(BOUND_MASS, BOUND_INERTIA);
        let runs = 200;
        let (mut times, mut built) = (Vec::with_capacity(runs), Vec::with_capacity(runs));
        for _ in 0..runs {
            let start = Instant::now();
            let model = read(&text, &option);
            times.push(start.elapsed().as_secs_f64());
            if let Ok(model) = model {
                let robot = Robot::<Pga>::build(model, &BuildOptions::default());
                built.push(start.elapsed().as_secs_f64());
                std::hint::black_box(robot).ok();
            }
        }
        times.sort_by(f64::total_cmp);
        built.sort_by(f64::total_cmp);
        println!(
            "TIMING: {} ({links} links, {} bytes), all repairs: import median {:.3} ms (min {:.3}); import and build \
             as a mechanism median {:.3} ms over {runs} runs",
            path.display(),
            text.len(),
            times[runs / 2] * 1e3,
            times[0] * 1e3,
            built.get(built.len() / 2).map_or(f64::NAN, |t| t * 1e3),
        );
    }
    Ok(())
}
