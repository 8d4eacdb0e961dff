//! The four-bar linkage (docs/scenes.md's M2): crank, coupler and rocker hinged to each other and to two ground
//! pivots, a closed loop whose four hinges write 20 conditions of rank 17. Simulated by the mechanism solver in
//! PGA (the loop closes through a rank-revealing Schur complement); prints the loop violation, the crank's
//! revolution period against the exact 0.7906242901366745 s and the end angles' error; writes `four_bar.png`:
//! the coupler curve (the path of a point on the coupler, the classic picture of a four-bar) with the linkage
//! drawn at a few instants.
//!
//! ```sh
//! cargo run --release --example four_bar [output folder, default out/examples]
//! ```

mod output;

use dynamics::constraints::Stabilisation;
use dynamics::{simulate, Method, Pga, Schedule};
use nalgebra::Vector3;
use reference::multibody::FOUR_BAR;
use report::plot::{figure, Labels, Panel, Series};
use scenarios::mechanism_measures::measure;
use scenarios::{build_mechanism, Formulation, MechanismId};

fn main() -> output::Result<()> {
    let folder = output::output_folder()?;
    let scene = build_mechanism::<Pga>(
        MechanismId::FourBar,
        Formulation::VirtualPower,
        Stabilisation::PROJECTION,
    )?;
    // Sampled every step, so the revolution times are interpolated to O(dt⁴).
    let schedule = Schedule::with_sample_interval(2e-3, FOUR_BAR.duration, 2e-3)?;
    let run = simulate(&scene.system, &scene.initial, Method::Rkmk6Body, &schedule)?;
    let m = measure(MechanismId::FourBar, &run.bodies)?;
    let four_bar = m.four_bar.ok_or("the four-bar's features")?;
    println!(
        "loop held to {:.1e} m; {} crank revolutions, each within {:.1e} (relative) of {} s; end angles within {:.1e} \
         rad and the coupler within {:.1e} m of the reference",
        m.violation,
        four_bar.revolutions,
        four_bar.period_error,
        FOUR_BAR.revolution_period,
        four_bar.angle_error,
        four_bar.coupler_error
    );
    assert!(m.violation < 1e-12 && four_bar.period_error < 1e-9 && four_bar.coupler_error < 1e-9);

    // The coupler point: 0.3 m off the coupler's middle, across it (body x), which traces a closed curve.
    let [l1, l2, l3] = FOUR_BAR.lengths;
    let coupler_point = Vector3::new(0.3, 0.0, 0.0);
    let one_turn = (FOUR_BAR.revolution_period / schedule.dt()).round() as usize + 1;
    let curve: Vec<(f64, f64)> = run.body(1)[..one_turn]
        .iter()
        .map(|s| s.position + s.orientation * coupler_point)
        .map(|p| (p.x, p.z))
        .collect();
    let mut series = vec![Series::line("coupler point (one crank turn)", curve)];
    // The linkage at four instants: ground A → B → C → ground D, and the coupler's triangle to its point.
    let quarter = one_turn / 4;
    for k in [0, quarter, 2 * quarter, 3 * quarter] {
        let at = |body: usize, z: f64| {
            let s = &run.body(body)[k];
            let p = s.position + s.orientation * Vector3::new(0.0, 0.0, z);
            (p.x, p.z)
        };
        let point = {
            let s = &run.body(1)[k];
            let p = s.position + s.orientation * coupler_point;
            (p.x, p.z)
        };
        let (b, c) = (at(0, l1 / 2.0), at(2, l3 / 2.0));
        series.push(Series {
            markers: true,
            ..Series::line(
                format!("t = {:.2} s", run.body(0)[k].t),
                vec![at(0, -l1 / 2.0), b, c, at(2, -l3 / 2.0), c, point, b],
            )
        });
        debug_assert!((at(1, -l2 / 2.0).0 - b.0).abs() < 1e-9);
    }
    figure(
        &folder.join("four_bar.png"),
        "Four-bar linkage (docs/scenes.md M2): the coupler curve, PGA, RKMK6-body at dt = 2e-3 s",
        &[Panel::new(
            Labels::new("Seen along the hinge axes (y)", "world x (m)", "world z (m)"),
            series,
        )
        .equal_aspect()],
    )?;
    println!("wrote {}", folder.join("four_bar.png").display());
    Ok(())
}
