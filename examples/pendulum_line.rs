//! The pendulum pinned by a line (theory §7, E7): pinning the rod's hinge line alone makes a **cylindrical**
//! joint — the rod also slides along the line — while the line plus a point on it makes a hinge. The rod of
//! docs/scenes.md scene 2 is released horizontally with a sliding velocity of 0.3 m/s along the axis, in PGA and
//! CGA. Writes `pendulum_{line,hinge}_{pga,cga}.csv` and `pendulum_line.png` (the free end's path seen along
//! the axis, and its slide along the axis).
//!
//! ```sh
//! cargo run --release --example pendulum_line [output folder, default out/examples]
//! ```

mod output;

use dynamics::constraints::{pinning, PinningAlgebra, Stabilisation};
use dynamics::{Body, Cga, Force, Mechanism, Pga, Simulation, State};
use nalgebra::{UnitQuaternion, Vector3};
use output::{run, traced};
use report::plot::{figure, Labels, Panel, Series};

/// The rod end at the hinge and the free end, body coordinates (rod axis = body z, CoM at the origin).
const HINGE_END: Vector3<f64> = Vector3::new(0.0, 0.0, 0.5);
const FREE_END: Vector3<f64> = Vector3::new(0.0, 0.0, -0.5);

fn simulate<A: PinningAlgebra>(hinge: bool, folder: &std::path::Path) -> output::Result<Simulation<A>> {
    let rod = Body::rod(1.0, 1.0, 1e-3)?;
    let orientation = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2);
    // The hinge axis is world y through the origin; in the body it is R₀⁻¹ e_y = e_y.
    let axis = (HINGE_END, orientation.inverse() * Vector3::y());
    let world = (Vector3::zeros(), Vector3::y());
    let system = Mechanism::<A>::single(rod).with_force(Force::gravity())?;
    let system = if hinge {
        system.with_constraint(pinning::hinge::<A>("hinge (line + point)", axis, world)?)?
    } else {
        system.with_constraint(pinning::line::<A>("line (cylindrical joint)", axis, world)?)?
    };
    let system = system.with_stabilisation(Stabilisation::PROJECTION)?;
    let centre = -(orientation * HINGE_END);
    let initial = State::<A>::new(
        &rod,
        centre,
        &orientation,
        Vector3::zeros(),
        Vector3::new(0.0, 0.3, 0.0),
    );
    // The hinge forbids the slide: projecting the initial state removes it (theory §10).
    let mut initial = [initial];
    system.project(0.0, &mut initial)?;
    let [initial] = initial;
    let simulation = run(&system, initial, 1e-3, 4.0)?;
    let name = if hinge { "hinge" } else { "line" };
    report::csv::write(
        &folder.join(format!("pendulum_{name}_{}.csv", A::NAME.to_lowercase())),
        simulation.body(0),
    )?;
    Ok(simulation)
}

fn main() -> output::Result<()> {
    let folder = output::output_folder()?;
    let line = simulate::<Pga>(false, &folder)?;
    let hinge = simulate::<Pga>(true, &folder)?;
    for (name, pga) in [("line", &line), ("hinge", &hinge)] {
        let cga = simulate::<Cga>(name == "hinge", &folder)?;
        let difference = pga
            .body(0)
            .iter()
            .zip(cga.body(0))
            .map(|(p, c)| (p.position - c.position).norm())
            .fold(0.0, f64::max);
        println!("{name}: PGA vs CGA max position difference {difference:.1e} m");
    }
    let side_view = |simulation: &Simulation<Pga>| traced(simulation, FREE_END).iter().map(|p| (p.x, p.z)).collect();
    let slide = |simulation: &Simulation<Pga>| {
        simulation
            .body(0)
            .iter()
            .zip(traced(simulation, FREE_END))
            .map(|(s, p)| (s.t, p.y))
            .collect()
    };
    figure(
        &folder.join("pendulum_line.png"),
        "Rod pinned by its hinge line (cylindrical joint) vs line + point (hinge), PGA",
        &[
            Panel::new(
                Labels::new("Free end, seen along the axis", "world x (m)", "world z (m)"),
                vec![
                    Series::line("line pinned (same swing, hidden)", side_view(&line)),
                    Series::line("line + point pinned", side_view(&hinge)),
                ],
            )
            .equal_aspect(),
            Panel::new(
                Labels::new("Free end, along the axis", "time t (s)", "world y (m)"),
                vec![
                    Series::line("line pinned: slides at 0.3 m/s", slide(&line)),
                    Series::line("line + point pinned", slide(&hinge)),
                ],
            ),
        ],
    )?;
    println!("wrote {}", folder.display());
    Ok(())
}
