//! The contact scenes of the report (docs/contacts.md): the cube dropped flat lands on four corners together at the
//! free-fall time, bounces straight up and comes to rest flat; the tumbling cube ends resting on a face; no corner goes
//! below the floor; both algebras alike.

use dynamics::limits::LimitChange;
use dynamics::{simulate, Algebra, Method, Schedule, Simulation, Tolerance};
use scenarios::contacts::ContactScene;

fn run<A: Algebra>(scene: ContactScene) -> Simulation<A> {
    let (system, start) = scene.build::<A>().unwrap();
    let schedule = Schedule::adaptive(Tolerance::new(1e-12, 1e-12).unwrap(), scene.duration(), 0.01).unwrap();
    simulate(&system, &start, Method::Dop853Body, &schedule).unwrap()
}

fn the_scenes_do_what_the_report_says<A: Algebra>() {
    let flat = run::<A>(ContactScene::FlatDrop);
    let exact = ContactScene::FlatDrop.exact_first_impact().unwrap();
    for transition in &flat.transitions[..4] {
        assert!((transition.t - exact).abs() < 1e-12, "{} vs {exact} s", transition.t);
    }
    // Bounces of four corners at once, until they rest together.
    assert_eq!(flat.transitions.len() % 4, 0);
    let last = &flat.transitions[flat.transitions.len() - 4..];
    assert!(
        last.iter().all(|t| matches!(t.change, LimitChange::Held { .. })),
        "{last:?}"
    );
    for run in [&flat, &run::<A>(ContactScene::TumblingCube)] {
        for sample in run.body(0) {
            let lowest = (ContactScene::corners().iter())
                .map(|c| (sample.position + sample.orientation * c).z)
                .fold(f64::INFINITY, f64::min);
            assert!(lowest > -1e-12, "{lowest:e} m at {} s", sample.t);
        }
        let end = run.body(0).last().unwrap();
        assert!(
            (end.position.z - 0.1).abs() < 1e-12,
            "resting on a face: {} m",
            end.position.z
        );
        assert!(end.velocity.z.abs() < 1e-12 && end.angular_velocity.xy().norm() < 1e-12);
    }
}

for_both_algebras!(the_scenes_do_what_the_report_says);
