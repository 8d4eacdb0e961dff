//! The spinning cone pinned at its tip (the heavy symmetric top, docs/scenes.md scenes 3a and 3b), by virtual power
//! (a ball joint of three forces) and by pinning the tip point, in PGA and CGA. Writes
//! `heavy_top_{cusp,steady}_{virtual_power,pinning}_{pga,cga}.csv` and `heavy_top.png`: the path of the
//! centre of the cone's base seen from above (cusped nutation from rest, and steady precession) and the tilt
//! over time between the analytic nutation bounds.
//!
//! ```sh
//! cargo run --release --example heavy_top [output folder, default out/examples]
//! ```

mod output;

use dynamics::constraints::Stabilisation;
use dynamics::{Cga, Pga, Simulation};
use nalgebra::Vector3;
use output::{run, traced};
use reference::scenes::HEAVY_TOP_VALUES;
use reference::SceneId;
use report::plot::{figure, Labels, Panel, Series};
use scenarios::{build, Formulation, SceneAlgebra};

/// The centre of the cone's base: on the axis, h/4 = 0.25 m beyond the centre of mass (the tip is 0.75 m
/// before it).
const BASE_CENTRE: Vector3<f64> = Vector3::new(0.0, 0.0, 0.25);

fn simulate<A: SceneAlgebra>(
    id: SceneId,
    formulation: Formulation,
    folder: &std::path::Path,
) -> output::Result<Simulation<A>> {
    let scene = build::<A>(id, formulation, Stabilisation::PROJECTION)?;
    let simulation = run(&scene.system, scene.initial, 1e-3, scene.duration)?;
    let name = if id == SceneId::TopCusp { "cusp" } else { "steady" };
    let formulation_name = formulation.name().replace(' ', "_");
    report::csv::write(
        &folder.join(format!(
            "heavy_top_{name}_{formulation_name}_{}.csv",
            A::NAME.to_lowercase()
        )),
        simulation.body(0),
    )?;
    Ok(simulation)
}

fn tilt(simulation: &Simulation<Pga>) -> Vec<(f64, f64)> {
    simulation
        .body(0)
        .iter()
        .map(|s| {
            let axis = s.orientation * Vector3::z();
            (s.t, axis.z.acos().to_degrees())
        })
        .collect()
}

fn main() -> output::Result<()> {
    let folder = output::output_folder()?;
    let mut runs = Vec::new();
    for id in [SceneId::TopCusp, SceneId::TopSteady] {
        for formulation in Formulation::ALL {
            let pga = simulate::<Pga>(id, formulation, &folder)?;
            let cga = simulate::<Cga>(id, formulation, &folder)?;
            let difference = pga
                .body(0)
                .iter()
                .zip(cga.body(0))
                .map(|(p, c)| p.orientation.angle_to(&c.orientation))
                .fold(0.0, f64::max);
            println!(
                "{} by {}: PGA vs CGA max orientation difference {difference:.1e} rad",
                id.label(),
                formulation.name()
            );
            runs.push((id, formulation, pga));
        }
    }
    let pinned = |id: SceneId| {
        runs.iter()
            .find(|(run_id, formulation, _)| *run_id == id && *formulation == Formulation::Pinning)
            .map(|(_, _, simulation)| simulation)
            .ok_or("missing run")
    };
    let (cusp, steady) = (pinned(SceneId::TopCusp)?, pinned(SceneId::TopSteady)?);
    let top_view = |simulation: &Simulation<Pga>| traced(simulation, BASE_CENTRE).iter().map(|p| (p.x, p.y)).collect();
    let bound = |degrees: f64| vec![(0.0, degrees), (10.0, degrees)];
    figure(
        &folder.join("heavy_top.png"),
        "Heavy top: solid cone (1 kg, h = r = 1 m) spinning at 20 rad/s, tip pinned, PGA",
        &[
            Panel::new(
                Labels::new("Centre of the base, seen from above", "world x (m)", "world y (m)"),
                vec![
                    Series::line("3a: from rest (cusps)", top_view(cusp)),
                    Series::line("3b: steady precession", top_view(steady)),
                ],
            )
            .equal_aspect(),
            Panel::new(
                Labels::new("Tilt of the axis from the vertical", "time t (s)", "θ (degrees)"),
                vec![
                    Series::line("3a", tilt(cusp)),
                    Series::line("3b", tilt(steady)),
                    Series::line("analytic θmax (3a)", bound(HEAVY_TOP_VALUES.theta_max.to_degrees())),
                ],
            ),
        ],
    )?;
    println!("wrote {}", folder.display());
    Ok(())
}
