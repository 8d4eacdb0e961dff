//! The joint-limit scenes of the report (docs/limits.md): the pendulum meets its bound at the time the elliptic
//! integrals give and stays on it; the double pendulum's elbow bounces at half its speed and never passes ±0.3 rad;
//! both algebras alike.

use dynamics::limits::LimitChange;
use dynamics::{simulate, Algebra, Method, Schedule, Simulation, State, Tolerance};
use scenarios::limits::LimitScene;

fn run<A: Algebra>(scene: LimitScene) -> (Simulation<A>, Vec<f64>) {
    let (system, start) = scene.build::<A>().unwrap();
    let schedule = Schedule::adaptive(Tolerance::new(1e-12, 1e-12).unwrap(), scene.duration(), 0.01).unwrap();
    let run = simulate(&system, &start, Method::Dop853Body, &schedule).unwrap();
    let coordinate = (0..run.body(0).len())
        .map(|k| {
            let states: Vec<State<A>> = (0..run.bodies.len())
                .map(|i| run.body(i)[k].state(dynamics::Dynamics::body(&system, i)))
                .collect();
            system.joint_positions(&states, None).unwrap()[scene.limited_coordinate()]
        })
        .collect();
    (run, coordinate)
}

fn the_scenes_do_what_the_report_says<A: Algebra>() {
    let (pendulum, q) = run::<A>(LimitScene::StoppingPendulum);
    let exact = LimitScene::StoppingPendulum.exact_first_impact().unwrap().unwrap();
    let first = &pendulum.transitions[0];
    assert!((first.t - exact).abs() < 1e-12, "{} vs {exact} s", first.t);
    assert_eq!(pendulum.transitions.len(), 1);
    let bound = LimitScene::StoppingPendulum.limit().upper();
    for (q, sample) in q.iter().zip(pendulum.body(0)) {
        assert!(*q <= bound + 1e-12);
        if sample.t > exact {
            assert!((q - bound).abs() < 1e-12, "at {} s: {q} rad", sample.t);
        }
    }
    let (double, elbow) = run::<A>(LimitScene::BouncingDoublePendulum);
    assert!(elbow.iter().all(|q| q.abs() <= 0.3 + 1e-12));
    let bounces: Vec<_> = (double.transitions.iter())
        .filter_map(|t| match t.change {
            LimitChange::Bounced {
                speed_before,
                speed_after,
                ..
            } => Some((speed_before, speed_after)),
            _ => None,
        })
        .collect();
    assert!(bounces.len() >= 5, "{:?}", double.transitions);
    for (before, after) in bounces {
        assert!((after - 0.5 * before).abs() < 1e-12 * before);
    }
}

for_both_algebras!(the_scenes_do_what_the_report_says);
