//! Fig. 1 of the paper: the Dzhanibekov (tennis-racket) flips of a free cuboid spinning about its intermediate
//! axis (SCENES.md scene 1), in PGA and CGA. Writes `dzhanibekov_{pga,cga}.csv` and `dzhanibekov.png`
//! (body angular velocity over time; the path traced by the tip of the intermediate axis).
//!
//! ```sh
//! cargo run --release --example dzhanibekov [output folder, default out/examples]
//! ```

mod output;

use dynamics::constraints::Stabilisation;
use dynamics::scenes::{build, Formulation, SceneAlgebra};
use dynamics::{Cga, Pga, Simulation};
use nalgebra::Vector3;
use output::{plot, run, write_trajectory, Curve, Panel};
use reference::SceneId;

fn simulate<A: SceneAlgebra>(folder: &std::path::Path) -> output::Result<Simulation<A>> {
    let scene = build::<A>(SceneId::Cuboid, Formulation::VirtualPower, Stabilisation::None)?;
    let simulation = run(&scene.system, scene.initial, 1e-3, scene.duration)?;
    write_trajectory(
        &folder.join(format!("dzhanibekov_{}.csv", A::NAME.to_lowercase())),
        &simulation,
    )?;
    Ok(simulation)
}

fn main() -> output::Result<()> {
    let folder = output::output_folder()?;
    let pga = simulate::<Pga>(&folder)?;
    let cga = simulate::<Cga>(&folder)?;
    let difference = pga
        .samples
        .iter()
        .zip(&cga.samples)
        .map(|(p, c)| p.orientation.angle_to(&c.orientation))
        .fold(0.0, f64::max);
    println!("PGA vs CGA: max orientation difference {difference:.1e} rad");

    let body_rates: Vec<Vector3<f64>> = pga
        .samples
        .iter()
        .map(|s| s.orientation.inverse() * s.angular_velocity)
        .collect();
    let component = |i: usize, name: &str| {
        Curve::new(
            name,
            pga.samples.iter().zip(&body_rates).map(|(s, w)| (s.t, w[i])).collect(),
        )
    };
    // The intermediate (body y) axis in the world: it turns over at every flip.
    let axis_tip: Vec<(f64, f64)> = pga
        .samples
        .iter()
        .map(|s| {
            let tip = s.orientation * Vector3::y();
            (tip.y, tip.z)
        })
        .collect();
    plot(
        &folder.join("dzhanibekov.png"),
        "Free cuboid (1 × 2 × 3 m, 1 kg) spun about its intermediate axis",
        &[
            Panel {
                title: "Body angular velocity".into(),
                x_label: "time t (s)".into(),
                y_label: "ω, body axes (rad/s)".into(),
                curves: vec![
                    component(0, "ω_x (largest I)"),
                    component(1, "ω_y (intermediate)"),
                    component(2, "ω_z (smallest I)"),
                ],
                equal_axes: false,
                y_range: None,
            },
            Panel {
                title: "Path of the intermediate axis tip".into(),
                x_label: "world y".into(),
                y_label: "world z".into(),
                curves: vec![Curve::new("R e_y, 0–10 s", axis_tip)],
                equal_axes: true,
                y_range: None,
            },
        ],
    )?;
    println!("wrote {}", folder.display());
    Ok(())
}
