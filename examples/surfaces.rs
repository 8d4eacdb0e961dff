//! Body points on quadrics and tori (docs/surfaces.md), from Rust: a bead on a tilted torus (pinned to its DCGA
//! incidence), a rod whose end slides on a turned ellipsoid (a QCGA quadric, by virtual power), and a pendulum whose
//! end rides an elliptic cylinder carried by a turntable driven at 1.5 rad/s (a joint between the two bodies). Each
//! runs in PGA with DOP853-body at tolerance 1e-12 and projection; prints how far each point strayed from its
//! surface (by the surface's classical equation) and the energy drift; writes `surfaces.png`: the bead's path seen
//! along the torus axis, the rod's end and the rod itself seen along the ellipsoid's turning axis, and the pendulum's
//! end in the world and on the turntable.
//!
//! ```sh
//! cargo run --release --example surfaces [output folder, default out/examples]
//! ```

mod output;

use dynamics::constraints::{SurfacePin, VirtualPower};
use dynamics::joint_models::{JointKind, JointModel};
use dynamics::surfaces::Surface;
use dynamics::{simulate, Body, Force, Mechanism, Method, Pga, Reference, Schedule, State, Tolerance};
use nalgebra::{Isometry3, UnitQuaternion, Vector2, Vector3};
use report::plot::{figure, Labels, Panel, Series};

/// DOP853-body at tolerance 1e-12, sampled every 0.01 s.
fn schedule(duration: f64) -> output::Result<Schedule> {
    Ok(Schedule::adaptive(Tolerance::new(1e-12, 1e-12)?, duration, 0.01)?)
}

/// Points of a closed curve `angle ↦ (x, y)`.
fn closed(curve: impl Fn(f64) -> (f64, f64)) -> Vec<(f64, f64)> {
    (0..=200)
        .map(|k| curve(k as f64 * std::f64::consts::TAU / 200.0))
        .collect()
}

fn main() -> output::Result<()> {
    let folder = output::output_folder()?;
    let mut panels = Vec::new();

    // A bead on a torus of radii 1 and 0.3 m tilted 16.7° from the vertical.
    let (centre, axis, major, minor) = (Vector3::new(0.0, 0.0, 1.0), Vector3::new(0.3, 0.0, 1.0), 1.0, 0.3);
    let torus = Surface::torus(centre, axis, major, minor)?;
    let bead = Body::sphere(0.2, 0.02)?;
    let system = Mechanism::<Pga>::single(bead)
        .with_force(Force::gravity())?
        .with_constraint(SurfacePin::point_on_surface("bead", Vector3::zeros(), torus)?)?;
    let start = State::new(
        &bead,
        Vector3::new(1.190287161857, 0.368691212106, 0.819765066149),
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::new(-0.832066296735, 2.308668448278, 0.637373944677),
    );
    let run = simulate(&system, &[start], Method::Dop853Body, &schedule(5.0)?)?;
    let turn = UnitQuaternion::rotation_between(&Vector3::z(), &axis).ok_or("a turn to the axis")?;
    let local: Vec<Vector3<f64>> = run
        .body(0)
        .iter()
        .map(|s| turn.inverse() * (s.position - centre))
        .collect();
    let off = local
        .iter()
        .map(|y| (((y.xy().norm() - major).powi(2) + y.z * y.z).sqrt() - minor).abs())
        .fold(0.0, f64::max);
    let drift = (run.body(0).last().ok_or("samples")?.energy - run.body(0)[0].energy).abs();
    println!("bead on a torus: at most {off:.1e} m off the torus over 5 s, energy drift {drift:.1e} J");
    panels.push(
        Panel::new(
            Labels::new("A bead on a tilted torus, along its axis", "torus x (m)", "torus y (m)"),
            vec![
                Series::line("the bead (5 s)", local.iter().map(|y| (y.x, y.y)).collect()),
                Series {
                    reference: true,
                    ..Series::line(
                        "outer equator",
                        closed(|a| ((major + minor) * a.cos(), (major + minor) * a.sin())),
                    )
                },
                Series {
                    dashed: true,
                    ..Series::line(
                        "inner equator",
                        closed(|a| ((major - minor) * a.cos(), (major - minor) * a.sin())),
                    )
                },
            ],
        )
        .equal_aspect(),
    );

    // A rod of 0.8 m whose lower end slides on an ellipsoid of radii 1.2, 0.8, 0.5 m turned 15° about y.
    let tilt = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 15f64.to_radians());
    let radii = Vector3::new(1.2, 0.8, 0.5);
    let ellipsoid = Surface::ellipsoid(radii, &Isometry3::from_parts(Vector3::zeros().into(), tilt))?;
    let rod = Body::rod(1.0, 0.8, 1e-4)?;
    let end = Vector3::new(0.0, 0.0, -0.4);
    let system = Mechanism::<Pga>::single(rod)
        .with_force(Force::gravity())?
        .with_constraint(VirtualPower::point_on_surface("end", end, ellipsoid)?)?;
    let lean = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 25f64.to_radians());
    let top = tilt * Vector3::new(0.0, 0.0, 0.5);
    let start = State::new(&rod, top - lean * end, &lean, Vector3::zeros(), Vector3::zeros());
    let run = simulate(&system, &[start], Method::Dop853Body, &schedule(2.0)?)?;
    let ends: Vec<Vector3<f64>> = run.body(0).iter().map(|s| s.position + s.orientation * end).collect();
    let off = ends
        .iter()
        .map(|x| {
            let y = tilt.inverse() * x;
            let gradient = 2.0 * y.component_div(&radii.component_mul(&radii));
            (y.component_div(&radii).norm_squared() - 1.0).abs() / gradient.norm()
        })
        .fold(0.0, f64::max);
    let drift = (run.body(0).last().ok_or("samples")?.energy - run.body(0)[0].energy).abs();
    println!("rod end on an ellipsoid: at most {off:.1e} m off it over 2 s, energy drift {drift:.1e} J");
    let outline = closed(|a| {
        let p = tilt * Vector3::new(radii.x * a.cos(), 0.0, radii.z * a.sin());
        (p.x, p.z)
    });
    let mut series = vec![
        Series::line("the rod's end (2 s)", ends.iter().map(|p| (p.x, p.z)).collect()),
        Series {
            reference: true,
            ..Series::line("the ellipsoid's outline", outline)
        },
    ];
    for k in [0, 60, 120, 180] {
        let s = &run.body(0)[k];
        let (a, b) = (s.position + s.orientation * end, s.position - s.orientation * end);
        series.push(Series {
            markers: true,
            ..Series::line(format!("rod at t = {:.1} s", s.t), vec![(a.x, a.z), (b.x, b.z)])
        });
    }
    panels.push(
        Panel::new(
            Labels::new("A rod's end on an ellipsoid, along y", "world x (m)", "world z (m)"),
            series,
        )
        .equal_aspect(),
    );

    // A pendulum hung from (0, 0, 1.2) whose end rides the cylinder of radii 0.5, 0.3 m about the turntable's (0.2, 0, 0).
    let mut system = Mechanism::<Pga>::new();
    let table_body = Body::cuboid(2.0, Vector3::new(1.2, 1.2, 0.05))?;
    let table = system.add_body("turntable", table_body)?;
    let spin = 1.5;
    let drive = move |t: f64| dynamics::constraints::PathPoint {
        value: spin * t,
        rate: spin,
        acceleration: 0.0,
    };
    let axle = JointModel::new(
        "axle",
        JointKind::Revolute { axis: Vector3::z() },
        Isometry3::identity(),
        Isometry3::identity(),
    )?
    .driven(drive)?;
    system.connect(table, Reference::World, axle)?;
    let pendulum_body = Body::rod(0.5, 1.0, 1e-4)?;
    let pendulum = system.add_body("pendulum", pendulum_body)?;
    system.add_force(pendulum, Force::gravity())?;
    let (top_point, end) = (Vector3::new(0.0, 0.0, 0.5), Vector3::new(0.0, 0.0, -0.5));
    let pivot = Vector3::new(0.0, 0.0, 1.2);
    system.add_joint(
        pendulum,
        Reference::World,
        VirtualPower::ball_joint("pivot", top_point, pivot),
    )?;
    let cylinder = Surface::elliptic_cylinder(Vector2::new(0.5, 0.3), &Isometry3::translation(0.2, 0.0, 0.0))?;
    system.add_joint(pendulum, table, SurfacePin::point_on_surface("rider", end, cylinder)?)?;
    let hang = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -44.42700400080571f64.to_radians());
    let omega = Vector3::new(0.0, 0.0, 0.8);
    let centre = pivot - hang * top_point;
    let start = [
        State::from_world_twist(
            &table_body,
            Vector3::zeros(),
            &UnitQuaternion::identity(),
            Vector3::z() * spin,
            Vector3::zeros(),
        ),
        State::from_world_twist(&pendulum_body, centre, &hang, omega, omega.cross(&(centre - pivot))),
    ];
    let run = simulate(&system, &start, Method::Dop853Body, &schedule(4.0)?)?;
    let (mut world, mut on_table) = (Vec::new(), Vec::new());
    let mut off: f64 = 0.0;
    for (table, rider) in run.body(0).iter().zip(run.body(1)) {
        let p = rider.position + rider.orientation * end;
        let y = table.orientation.inverse() * (p - table.position);
        let value = ((y.x - 0.2) / 0.5).powi(2) + (y.y / 0.3).powi(2) - 1.0;
        off = off.max(value.abs() / (2.0 * Vector2::new((y.x - 0.2) / 0.25, y.y / 0.09)).norm());
        world.push((p.x, p.y));
        on_table.push((y.x, y.y));
    }
    println!("pendulum on a carried cylinder: its end at most {off:.1e} m off the cylinder over 4 s");
    panels.push(
        Panel::new(
            Labels::new(
                "A pendulum's end on a cylinder carried by a turntable, from above",
                "x (m)",
                "y (m)",
            ),
            vec![
                Series::line("the end in the world (4 s)", world),
                Series {
                    thick: true,
                    ..Series::line("the end on the turntable", on_table)
                },
                Series {
                    reference: true,
                    ..Series::line(
                        "the cylinder, on the turntable",
                        closed(|a| (0.2 + 0.5 * a.cos(), 0.3 * a.sin())),
                    )
                },
            ],
        )
        .equal_aspect(),
    );

    let path = folder.join("surfaces.png");
    figure(
        &path,
        "Body points on quadrics and tori: PGA, DOP853-body at tolerance 1e-12",
        &panels,
    )?;
    println!("wrote {}", path.display());
    Ok(())
}
