//! Work–precision table of the constrained scenes (docs/scenes.md 1–4): for every scene, formulation (virtual power,
//! pinning), algebra (PGA, CGA), general integrator and step dt = 1e-2, 1e-3, 1e-4, with projection (theory §10):
//! the CPU time per step and per simulated second, the error against the reference trajectory and the largest
//! constraint violation. Prints a Markdown table (about a minute in release).
//!
//! Errors: end orientation (rad) for scenes 1–3, end position of the centre of mass (m) for scene 4;
//! violation: scene 2 |pivot distance|, scene 3 |tip − pivot|, scene 4 ||P − c| − r| and |P_z| (m).
//!
//! ```sh
//! cargo run --release --example constraint_accuracy
//! ```

use std::error::Error;

use dynamics::constraints::Stabilisation;
use dynamics::{Cga, Method, Pga, Schedule};
use reference::{trajectory_errors, SceneConstraint, SceneId};
use scenarios::{build, Formulation, SceneAlgebra, SceneError};

/// The largest violation of a scene's constraint over the samples (0 for a free body).
fn violation(constraint: &SceneConstraint, samples: &[reference::Sample]) -> f64 {
    let worst = |f: &dyn Fn(&reference::Sample) -> f64| samples.iter().map(f).fold(0.0, f64::max);
    match *constraint {
        SceneConstraint::Free => 0.0,
        SceneConstraint::Hinge { pivot, body_anchor, .. } | SceneConstraint::BallJoint { pivot, body_anchor } => {
            worst(&|s| (s.world_point(&body_anchor) - pivot).norm())
        }
        SceneConstraint::PointOnSphere {
            body_anchor,
            centre,
            radius,
        } => worst(&|s| ((s.world_point(&body_anchor) - centre).norm() - radius).abs()),
        SceneConstraint::PointOnCircle {
            body_anchor,
            centre,
            radius,
            normal,
        } => worst(&|s| {
            let offset = s.world_point(&body_anchor) - centre;
            ((offset.norm() - radius).abs()).max(offset.dot(&normal.normalize()).abs())
        }),
    }
}

fn row<A: SceneAlgebra>(id: SceneId, formulation: Formulation, method: Method, dt: f64) -> Result<(), Box<dyn Error>> {
    let scene = match build::<A>(id, formulation, Stabilisation::PROJECTION) {
        Ok(scene) => scene,
        Err(SceneError::NotExpressible { .. }) => return Ok(()),
        Err(error) => return Err(error.into()),
    };
    let schedule = Schedule::new(dt, scene.duration)?;
    let simulation = dynamics::simulate(&scene.system, &[scene.initial], method, &schedule)?;
    let trajectory = scenarios::trajectory(simulation.body(0))?;
    let samples = trajectory.samples();
    let errors = trajectory_errors(&id.reference_trajectory()?, &trajectory)?;
    let (error, unit) = match id {
        SceneId::RodOnSphere | SceneId::RodOnCircle => (errors.end_position, "m"),
        _ => (errors.end_orientation, "rad"),
    };
    let per_step = simulation.time_per_step().as_secs_f64();
    println!(
        "| {} | {} | {} | {} | {dt:.0e} | {:.2} | {:.2} | {error:.1e} {unit} | {:.1e} |",
        id.label(),
        if scene.system.joint_count() == 0 {
            "free"
        } else {
            formulation.name()
        },
        A::NAME,
        method.name(),
        per_step * 1e6,
        per_step / dt * 1e3,
        violation(&scene.parameters.constraint, samples),
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    println!("| scene | constraint by | algebra | integrator | dt (s) | CPU µs/step | CPU ms per simulated s | error | max violation (m) |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for id in SceneId::ALL {
        // The free cuboid has no constraint: one formulation is enough.
        let formulations: &[Formulation] = if id == SceneId::Cuboid {
            &[Formulation::VirtualPower]
        } else {
            &Formulation::ALL
        };
        for &formulation in formulations {
            for method in Method::ALL {
                for dt in [1e-2, 1e-3, 1e-4] {
                    row::<Pga>(id, formulation, method, dt)?;
                    row::<Cga>(id, formulation, method, dt)?;
                }
            }
        }
    }
    Ok(())
}
