//! What the scene examples share: the output folder (first command-line argument, default `out/examples/`),
//! running a constrained system and tracing a body point. The CSV trajectories and PNG figures are written by
//! the `report` crate (`report::csv`, `report::plot`), as in the main job.

// Each example compiles this module on its own and uses a subset of it.
#![allow(dead_code)]

use std::error::Error;
use std::path::PathBuf;

use dynamics::{simulate, Algebra, Mechanism, Method, Schedule, Simulation, SimulationError, State};
use nalgebra::Vector3;

pub type Result<T> = std::result::Result<T, Box<dyn Error>>;

/// The folder from the command line (default `out/examples/`), created if missing.
pub fn output_folder() -> Result<PathBuf> {
    let folder = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "out/examples".to_owned()));
    std::fs::create_dir_all(&folder)?;
    Ok(folder)
}

/// Runs a system with RK4, sampled every 0.01 s.
pub fn run<A: Algebra>(
    system: &Mechanism<A>,
    initial: State<A>,
    dt: f64,
    duration: f64,
) -> std::result::Result<Simulation<A>, SimulationError> {
    simulate(system, &[initial], Method::Rk4, &Schedule::new(dt, duration)?)
}

/// The world positions of a point of a single-body run's body (body coordinates).
pub fn traced(simulation: &Simulation<impl Algebra>, body_point: Vector3<f64>) -> Vec<Vector3<f64>> {
    simulation
        .body(0)
        .iter()
        .map(|s| s.position + s.orientation * body_point)
        .collect()
}
