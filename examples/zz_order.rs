use dynamics::constraints::{simulate_constrained, Stabilisation};
use dynamics::scenes::{build, Formulation};
use dynamics::{Method, Pga, Schedule};
use reference::{trajectory_errors, SceneId, Trajectory};
fn main() {
    let methods = [Method::Rkmk4Body, Method::Rkmk6Body];
    for id in [
        SceneId::Pendulum,
        SceneId::TopCusp,
        SceneId::RodOnCircle,
        SceneId::RodOnSphere,
        SceneId::Cuboid,
    ] {
        for formulation in [Formulation::VirtualPower, Formulation::Pinning] {
            let Ok(scene) = build::<Pga>(id, formulation, Stabilisation::PROJECTION) else {
                continue;
            };
            for method in methods {
                for dt in [1e-2, 5e-3, 0.01 / 3.0, 2.5e-3, 2e-3, 1e-3] {
                    let schedule = Schedule::new(dt, scene.duration).unwrap();
                    let Ok(sim) = simulate_constrained(&scene.system, scene.initial, method, &schedule) else {
                        println!("fail");
                        continue;
                    };
                    let samples: Vec<reference::Sample> = sim
                        .samples
                        .iter()
                        .map(|s| reference::Sample {
                            t: s.t,
                            position: s.position,
                            orientation: s.orientation,
                            velocity: s.velocity,
                            angular_velocity: s.angular_velocity,
                        })
                        .collect();
                    let e = trajectory_errors(&id.reference_trajectory().unwrap(), &Trajectory::new(samples).unwrap())
                        .unwrap();
                    let per = sim.time_per_step().as_secs_f64();
                    println!(
                        "{:>12} {:>14} {:>11} dt={dt:.0e} {:.2} us/step {:.3} ms/s  orient {:.1e} pos {:.1e}",
                        &id.label()[..12.min(id.label().len())],
                        formulation.name(),
                        method.name(),
                        per * 1e6,
                        per / dt * 1e3,
                        e.end_orientation,
                        e.end_position
                    );
                }
            }
        }
    }
}
