//! Fig. 1 of the paper: the Dzhanibekov (tennis-racket) flips of a free cuboid spinning about its intermediate
//! axis (docs/scenes.md scene 1), in PGA and CGA. Writes `dzhanibekov_{pga,cga}.csv` and `dzhanibekov.png`
//! (body angular velocity over time; the path of the centre of a face on the intermediate axis, relative to
//! the centre of mass).
//!
//! ```sh
//! cargo run --release --example dzhanibekov [output folder, default out/examples]
//! ```

mod output;

use dynamics::constraints::Stabilisation;
use dynamics::{Cga, Pga, Simulation};
use nalgebra::Vector3;
use output::run;
use reference::SceneId;
use report::plot::{figure, Labels, Panel, Series};
use scenarios::{build, Formulation, SceneAlgebra};

fn simulate<A: SceneAlgebra>(folder: &std::path::Path) -> output::Result<Simulation<A>> {
    let scene = build::<A>(SceneId::Cuboid, Formulation::VirtualPower, Stabilisation::None)?;
    let simulation = run(&scene.system, scene.initial, 1e-3, scene.duration)?;
    report::csv::write(
        &folder.join(format!("dzhanibekov_{}.csv", A::NAME.to_lowercase())),
        simulation.body(0),
    )?;
    Ok(simulation)
}

fn main() -> output::Result<()> {
    let folder = output::output_folder()?;
    let pga = simulate::<Pga>(&folder)?;
    let cga = simulate::<Cga>(&folder)?;
    let difference = pga
        .body(0)
        .iter()
        .zip(cga.body(0))
        .map(|(p, c)| p.orientation.angle_to(&c.orientation))
        .fold(0.0, f64::max);
    println!("PGA vs CGA: max orientation difference {difference:.1e} rad");

    let body_rates: Vec<Vector3<f64>> = pga
        .body(0)
        .iter()
        .map(|s| s.orientation.inverse() * s.angular_velocity)
        .collect();
    let component = |i: usize, name: &str| {
        Series::line(
            name,
            pga.body(0).iter().zip(&body_rates).map(|(s, w)| (s.t, w[i])).collect(),
        )
    };
    // The centre of the +y face (1 m out along the intermediate axis) seen from the centre of mass: it turns
    // over at every flip.
    let face_centre: Vec<(f64, f64)> = pga
        .body(0)
        .iter()
        .map(|s| {
            let offset = s.orientation * Vector3::y();
            (offset.y, offset.z)
        })
        .collect();
    figure(
        &folder.join("dzhanibekov.png"),
        "Free cuboid (1 × 2 × 3 m, 1 kg) spun about its intermediate axis, PGA",
        &[
            Panel::new(
                Labels::new("Body angular velocity", "time t (s)", "ω, body axes (rad/s)"),
                vec![
                    component(0, "ω_x (largest I)"),
                    component(1, "ω_y (intermediate I)"),
                    component(2, "ω_z (smallest I)"),
                ],
            ),
            Panel::new(
                Labels::new(
                    "Centre of the +y face relative to the centre of mass, 0–10 s",
                    "world y offset (m)",
                    "world z offset (m)",
                ),
                vec![Series::line("R (0, 1 m, 0)", face_centre)],
            )
            .equal_aspect(),
        ],
    )?;
    println!("wrote {}", folder.display());
    Ok(())
}
