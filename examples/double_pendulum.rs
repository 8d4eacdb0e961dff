//! A 3D double pendulum written with the mechanism API: two cuboid links, the first hinged to the world about
//! world x, the second hinged to the first's bottom end about the first's body y (docs/scenes.md's M1, its
//! parameters from `reference::multibody`), by virtual-power hinges, in PGA and CGA. Prints the end state's
//! error against the reference (reduced coordinates, DOP853), the energy drift and the hinge violation; writes
//! `double_pendulum.png`: the lower link's end seen from the side and from below, and the two joint angles.
//!
//! ```sh
//! cargo run --release --example double_pendulum [output folder, default out/examples]
//! ```

mod output;

use std::sync::Arc;

use dynamics::constraints::{PinningAlgebra, Stabilisation, VirtualPower};
use dynamics::{simulate, Body, Cga, Force, Mechanism, Method, Pga, Reference, Schedule, Simulation};
use nalgebra::Vector3;
use reference::multibody::DOUBLE_PENDULUM;
use report::plot::{figure, Labels, Panel, Series};
use scenarios::mechanism_measures::measure;
use scenarios::mechanisms::state;
use scenarios::MechanismId;

/// The lower link's free end, link 2's body coordinates.
const LOWER_END: Vector3<f64> = Vector3::new(0.0, 0.0, -0.4);

fn double_pendulum<A: PinningAlgebra>() -> output::Result<Simulation<A>> {
    let m1 = DOUBLE_PENDULUM;
    let mut pendulum = Mechanism::<A>::new();
    let body = |k: usize| Body::cuboid(m1.links[k].mass, m1.links[k].extents);
    let (upper_body, lower_body) = (body(0)?, body(1)?);
    let upper = pendulum.add_body("upper", upper_body)?;
    let lower = pendulum.add_body("lower", lower_body)?;
    pendulum.add_force(upper, Force::gravity())?;
    pendulum.add_force(lower, Force::gravity())?;
    // A hinge holds a body point and axis (body coordinates) on a point and axis of the reference (world or
    // body coordinates): 3 reaction forces and 2 couples.
    let shoulder = VirtualPower::hinge(
        "shoulder",
        (m1.hinge_1_on_link_1, Vector3::x()),
        (m1.pivot, Vector3::x()),
    )?;
    let elbow = VirtualPower::hinge(
        "elbow",
        (m1.hinge_2_on_link_2, Vector3::y()),
        (m1.hinge_2_on_link_1, Vector3::y()),
    )?;
    pendulum.add_joint(upper, Reference::World, Arc::new(shoulder))?;
    pendulum.add_joint(lower, upper, Arc::new(elbow))?;
    pendulum.set_stabilisation(Stabilisation::PROJECTION)?;

    // The initial state from the joint coordinates q = (1.0, 0.6) rad, q̇ = (1.0, −0.5) rad/s.
    let [first, second] = m1.initial_state();
    let mut initial = vec![state::<A>(&upper_body, &first), state::<A>(&lower_body, &second)];
    pendulum.project(0.0, &mut initial)?;
    Ok(simulate(
        &pendulum,
        &initial,
        Method::Rkmk6Body,
        &Schedule::new(2e-3, m1.duration)?,
    )?)
}

/// (t, value) points of a plot.
type Curve = Vec<(f64, f64)>;

/// Joint angles from the poses: q1 of link 1 about world x, q2 of link 2 about link 1's y.
fn angles(run: &Simulation<Pga>) -> (Curve, Curve) {
    run.body(0)
        .iter()
        .zip(run.body(1))
        .map(|(a, b)| {
            let down = a.orientation * Vector3::z();
            let q1 = down.y.atan2(down.z).to_degrees();
            let relative = a.orientation.inverse() * b.orientation;
            let axis = relative * Vector3::z();
            let q2 = (-axis.x).atan2(axis.z).to_degrees();
            ((a.t, q1), (a.t, q2))
        })
        .unzip()
}

fn main() -> output::Result<()> {
    let folder = output::output_folder()?;
    let pga = double_pendulum::<Pga>()?;
    let cga = double_pendulum::<Cga>()?;
    for (name, bodies) in [("PGA", &pga.bodies), ("CGA", &cga.bodies)] {
        let m = measure(MechanismId::DoublePendulum, bodies)?;
        let (orientation, position) = (
            m.orientation_end.unwrap_or(f64::NAN),
            m.position_end.unwrap_or(f64::NAN),
        );
        println!(
            "{name}: at T = 10 s {orientation:.1e} rad and {position:.1e} m from the reference; energy drift \
             {:.1e} J; hinges held to {:.1e} m",
            m.energy_drift, m.violation
        );
        assert!(orientation < 1e-9 && position < 1e-9, "{name} left the reference");
        assert!(m.violation < 1e-12 && m.energy_drift < 1e-10, "{name}: {m:?}");
    }
    let difference = pga
        .bodies
        .iter()
        .zip(&cga.bodies)
        .flat_map(|(p, c)| p.iter().zip(c).map(|(a, b)| (a.position - b.position).norm()))
        .fold(0.0, f64::max);
    println!("PGA and CGA trajectories differ by at most {difference:.1e} m");

    let tip: Vec<Vector3<f64>> = pga
        .body(1)
        .iter()
        .map(|s| s.position + s.orientation * LOWER_END)
        .collect();
    let (q1, q2) = angles(&pga);
    figure(
        &folder.join("double_pendulum.png"),
        "Double pendulum (docs/scenes.md M1), two hinges, PGA, RKMK6-body at dt = 2e-3 s",
        &[
            Panel::new(
                Labels::new("Lower end, seen along x", "world y (m)", "world z (m)"),
                vec![Series::line("lower end", tip.iter().map(|p| (p.y, p.z)).collect())],
            )
            .equal_aspect(),
            Panel::new(
                Labels::new("Lower end, seen from below", "world x (m)", "world y (m)"),
                vec![Series::line("lower end", tip.iter().map(|p| (p.x, p.y)).collect())],
            )
            .equal_aspect(),
            Panel::new(
                Labels::new("Joint angles", "time t (s)", "angle (degrees)"),
                vec![Series::line("q1 (shoulder)", q1), Series::line("q2 (elbow)", q2)],
            ),
        ],
    )?;
    println!("wrote {}", folder.join("double_pendulum.png").display());
    Ok(())
}
