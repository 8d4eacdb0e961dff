//! The pendulum end on a sphere and on a circle (docs/scenes.md scene 4): a free rod whose end P slides on a sphere
//! of radius 0.5 m about the origin, or on the horizontal circle of that sphere. By virtual power (force lines
//! through P, theory §6) in PGA and CGA, and by pinning the incidences `P ∧ S = 0`, `P ∧ C = 0` (theory §9) in
//! CGA. Writes `rod_on_{sphere,circle}_{virtual_power,pinning}_{pga,cga}.csv` and
//! `rod_on_{sphere,circle}.png` (the paths of P and of the centre of mass, from above and from the side).
//!
//! ```sh
//! cargo run --release --example rod_on_sphere_and_circle [output folder, default out/examples]
//! ```

mod output;

use dynamics::constraints::Stabilisation;
use dynamics::{Cga, Pga, Simulation};
use nalgebra::Vector3;
use output::{run, traced};
use reference::SceneId;
use report::plot::{figure, Labels, Panel, Series};
use scenarios::{build, Formulation, SceneAlgebra, SceneError};

/// The constrained rod end P, body coordinates.
const END: Vector3<f64> = Vector3::new(0.0, 0.0, 0.5);

/// The run, or `None` where the algebra cannot express the formulation (PGA has no spheres or circles).
fn simulate<A: SceneAlgebra>(
    id: SceneId,
    formulation: Formulation,
    folder: &std::path::Path,
) -> output::Result<Option<Simulation<A>>> {
    let scene = match build::<A>(id, formulation, Stabilisation::PROJECTION) {
        Ok(scene) => scene,
        Err(SceneError::NotExpressible { .. }) => return Ok(None),
        Err(error) => return Err(error.into()),
    };
    let simulation = run(&scene.system, scene.initial, 1e-3, scene.duration)?;
    let name = if id == SceneId::RodOnSphere { "sphere" } else { "circle" };
    let formulation_name = formulation.name().replace(' ', "_");
    report::csv::write(
        &folder.join(format!(
            "rod_on_{name}_{formulation_name}_{}.csv",
            A::NAME.to_lowercase()
        )),
        simulation.body(0),
    )?;
    let violation = traced(&simulation, END)
        .iter()
        .map(|p| {
            (p.norm() - 0.5)
                .abs()
                .max(if name == "circle" { p.z.abs() } else { 0.0 })
        })
        .fold(0.0, f64::max);
    println!(
        "{} by {} in {}: max constraint violation {violation:.1e} m",
        id.label(),
        formulation.name(),
        A::NAME
    );
    Ok(Some(simulation))
}

fn main() -> output::Result<()> {
    let folder = output::output_folder()?;
    for id in [SceneId::RodOnSphere, SceneId::RodOnCircle] {
        let mut curves_top = Vec::new();
        let mut curves_side = Vec::new();
        for formulation in Formulation::ALL {
            simulate::<Pga>(id, formulation, &folder)?;
            let Some(cga) = simulate::<Cga>(id, formulation, &folder)? else {
                continue;
            };
            if formulation == Formulation::VirtualPower {
                let end = traced(&cga, END);
                let centre: Vec<Vector3<f64>> = cga.body(0).iter().map(|s| s.position).collect();
                curves_top.push(Series::line("rod end P", end.iter().map(|p| (p.x, p.y)).collect()));
                curves_top.push(Series::line(
                    "centre of mass",
                    centre.iter().map(|p| (p.x, p.y)).collect(),
                ));
                curves_side.push(Series::line("rod end P", end.iter().map(|p| (p.x, p.z)).collect()));
                curves_side.push(Series::line(
                    "centre of mass",
                    centre.iter().map(|p| (p.x, p.z)).collect(),
                ));
            }
        }
        let name = if id == SceneId::RodOnSphere { "sphere" } else { "circle" };
        let title = format!("Rod (1 kg, 1 m) with its end on a {name} of radius 0.5 m, 5 s, CGA, virtual power");
        figure(
            &folder.join(format!("rod_on_{name}.png")),
            &title,
            &[
                Panel::new(Labels::new("Seen from above", "world x (m)", "world y (m)"), curves_top).equal_aspect(),
                Panel::new(
                    Labels::new("Seen from the side", "world x (m)", "world z (m)"),
                    curves_side,
                )
                .equal_aspect(),
            ],
        )?;
    }
    println!("wrote {}", folder.display());
    Ok(())
}
