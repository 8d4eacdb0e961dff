//! A chain of 16 links joined by ball joints (docs/scenes.md's M3), its top end at the world origin, released at
//! rest straight and horizontal. Simulated in PGA with the reactions of all 16 joints solved together (cost
//! linear in the number of links); prints the energy drift and the joint violation; writes `chain.png`: the
//! chain seen from the side at a few instants as it falls and whips.
//!
//! ```sh
//! cargo run --release --example chain [output folder, default out/examples]
//! ```

mod output;

use dynamics::constraints::Stabilisation;
use dynamics::{simulate, Method, Pga, Schedule};
use nalgebra::Vector3;
use reference::multibody::CHAIN;
use report::plot::{figure, Labels, Panel, Series};
use scenarios::mechanism_measures::measure;
use scenarios::{build_mechanism, Formulation, MechanismId};

const LINKS: usize = 16;

fn main() -> output::Result<()> {
    let folder = output::output_folder()?;
    let id = MechanismId::Chain(LINKS);
    let scene = build_mechanism::<Pga>(id, Formulation::VirtualPower, Stabilisation::PROJECTION)?;
    let schedule = Schedule::with_sample_interval(1e-3, 2.0, 0.01)?;
    let run = simulate(&scene.system, &scene.initial, Method::Rkmk6Body, &schedule)?;
    let m = measure(id, &run.bodies)?;
    println!(
        "{LINKS} links over 2 s: joints held to {:.1e} m, energy drift {:.1e} J (the chain trades about {:.0} J \
         between potential and kinetic energy); {:.1} µs per step",
        m.violation,
        m.energy_drift,
        CHAIN.link.mass * 9.81 * (LINKS as f64 * CHAIN.link.extents.z).powi(2) / (2.0 * CHAIN.link.extents.z),
        run.time_per_step().as_secs_f64() * 1e6
    );
    assert!(m.violation < 1e-12 && m.energy_drift < 1e-6, "{m:?}");

    // Each link as the segment between its ends, the chain as the polyline through them, seen along x.
    let half = CHAIN.half_length();
    let series: Vec<Series> = [0.0, 0.3, 0.6, 0.9, 1.2]
        .iter()
        .map(|&t| {
            let k = (t / 0.01_f64).round() as usize;
            let mut points = vec![(0.0, 0.0)];
            for body in &run.bodies {
                let s = &body[k];
                let end = s.position + s.orientation * Vector3::new(0.0, 0.0, -half);
                points.push((end.y, end.z));
            }
            Series {
                markers: true,
                ..Series::line(format!("t = {t:.1} s"), points)
            }
        })
        .collect();
    figure(
        &folder.join("chain.png"),
        "16-link chain released from horizontal (M3), PGA, RKMK6-body",
        &[Panel::new(Labels::new("Seen along x", "world y (m)", "world z (m)"), series).equal_aspect()],
    )?;
    println!("wrote {}", folder.join("chain.png").display());
    Ok(())
}
