//! The single-body constrained solver became the N = 1 case of `Mechanism` (docs/mechanisms.md §M6). This test
//! runs every single-body scene configuration — scene × algebra × formulation × stabilisation × method — and
//! compares the end state with the one the former single-body solver computed (`data/`, with its commit).
//!
//! The two solve the same equations by different linear algebra (stacked rows with a kinetic-metric truncated
//! pseudo-inverse, against per-joint reduced rows and the joint-space factorisation), so they agree to
//! round-off amplified by the dynamics over 2 s, not bit for bit.

use dynamics::constraints::Stabilisation;
use dynamics::{simulate, Algebra, Cga, Method, Pga, Schedule};
use reference::SceneId;
use scenarios::{build, Formulation, SceneAlgebra};

struct Expected {
    scene: String,
    algebra: String,
    formulation: String,
    stabilisation: String,
    method: String,
    initial: Vec<f64>,
    end: Vec<f64>,
}

fn expected() -> Vec<Expected> {
    include_str!("../data/single_body_before_mechanisms.csv")
        .lines()
        .filter(|line| !line.starts_with('#'))
        .skip(1)
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            let numbers: Vec<f64> = fields[5..].iter().map(|x| x.parse().unwrap()).collect();
            Expected {
                scene: fields[0].to_owned(),
                algebra: fields[1].to_owned(),
                formulation: fields[2].to_owned(),
                stabilisation: fields[3].to_owned(),
                method: fields[4].to_owned(),
                initial: numbers[..14].to_vec(),
                end: numbers[14..].to_vec(),
            }
        })
        .collect()
}

fn coordinates<A: Algebra>(state: &dynamics::State<A>) -> Vec<f64> {
    let m = A::motor_coordinates(state.motor);
    let p = A::screw_coordinates(state.momentum_about_origin());
    vec![
        m.scalar,
        m.l.x,
        m.l.y,
        m.l.z,
        m.t.x,
        m.t.y,
        m.t.z,
        m.pseudoscalar,
        p.l.x,
        p.l.y,
        p.l.z,
        p.t.x,
        p.t.y,
        p.t.z,
    ]
}

/// The recorded end state a run is compared with: its own, except for CGA point pins (the ball joint of the tops,
/// the point of the pendulum's hinge) under Baumgarte. Since the null-basis migration CGA pins the flat point
/// `up(x) ∧ n∞`, whose rows are those of PGA's point, where the recording pinned the round point `up(x)` (five
/// coefficients reduced to rank 3). On the manifold the two agree; Baumgarte feeds back the residual off it, which
/// the two define differently, so the former CGA run ends 6.4e-9 from the new one on the top (RK4), and the new
/// CGA run follows PGA's recording instead (to 7e-15 on that case).
fn recorded_end<'a>(case: &'a Expected, expected: &'a [Expected]) -> &'a [f64] {
    let point_pin = case.scene.starts_with("2 ") || case.scene.starts_with("3");
    if case.algebra == Cga::NAME && case.formulation == "pinning" && case.stabilisation == "baumgarte" && point_pin {
        let pga = expected.iter().find(|c| {
            c.algebra == Pga::NAME
                && (&c.scene, &c.formulation, &c.stabilisation, &c.method)
                    == (&case.scene, &case.formulation, &case.stabilisation, &case.method)
        });
        return &pga.expect("every CGA case has its PGA twin").end;
    }
    &case.end
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// Runs the configurations of one algebra; returns the largest differences of the initial (projected) states
/// and of the end states, per scene label.
fn compare<A: SceneAlgebra>(expected: &[Expected]) -> Vec<(String, f64, f64)> {
    let mut results = Vec::new();
    for case in expected.iter().filter(|c| c.algebra == A::NAME) {
        let id = SceneId::ALL
            .into_iter()
            .find(|id| id.label().replace(',', ";") == case.scene)
            .unwrap();
        let formulation = match case.formulation.as_str() {
            "virtual power" => Formulation::VirtualPower,
            _ => Formulation::Pinning,
        };
        let stabilisation = match case.stabilisation.as_str() {
            "projection" => Stabilisation::PROJECTION,
            "baumgarte" => Stabilisation::Baumgarte {
                alpha: 10.0,
                beta: 10.0,
            },
            _ => Stabilisation::None,
        };
        let method = Method::ALL.into_iter().find(|m| m.name() == case.method).unwrap();
        let scene = build::<A>(id, formulation, stabilisation).unwrap();
        let schedule = Schedule::new(1e-3, 2.0).unwrap();
        let run = simulate(&scene.system, &[scene.initial], method, &schedule).unwrap();
        let initial = largest_difference(&coordinates(&scene.initial), &case.initial);
        let end = largest_difference(&coordinates(&run.final_state[0]), recorded_end(case, expected));
        results.push((
            format!(
                "{} {} {} {} {}",
                case.scene, case.algebra, case.formulation, case.stabilisation, case.method
            ),
            initial,
            end,
        ));
    }
    results
}

fn check<A: SceneAlgebra>() {
    let expected = expected();
    let results = compare::<A>(&expected);
    assert!(!results.is_empty());
    for (label, initial, end) in &results {
        println!("{label}: initial {initial:.1e}, end {end:.1e}");
    }
    // Measured: initial states within 2.2e-16, end states within 6.4e-12, except the rod end on a sphere with
    // projection and the fourth-order methods, within 2.6e-11: there the projection differs from the former
    // solver's by design (it leaves residuals below 1e-14 m and 1e-12 m/s alone and may share one
    // factorisation between its position and velocity solves, docs/mechanisms.md §M5), a 1e-12 difference per
    // step that 2 s of this scene's dynamics amplify. The Lie-group methods on the hinge and the tops mostly
    // agree within 1e-13.
    //
    // One case changed by design after the recording: the torque-free cuboid with RKMK4-body, whose steps now
    // end on the conserved world momentum (`integrate::end_of_body_step`). That projection changes the
    // trajectory by its local error, 2.0e-9 after 2 s (RKMK6-body's, sixth order, by 7.6e-14); it is held to
    // the recorded state within 1e-8, and to the reference trajectory by `scene1_free_body.rs`.
    //
    // A second changed with the null basis: the CGA rod end on a circle by pinning with Baumgarte. Its incidence
    // `P ∧ C` has five coefficients of rank 2, now taken on the null basis' blades: a different linear combination of
    // the same conditions, equivalent on the manifold, but the rank-2 truncation and Baumgarte's feedback act on
    // them off it. Measured 1.8e-10 (RK4), 3.9e-10 (RKMK4), 5.2e-11 (RKMK4-body), 3.1e-13 (RKMK6-body) from the
    // recording; with projection, which keeps the run on the manifold, the same case agrees to round-off.
    //
    // A third changed when states came to hold the momentum about the centre of mass (docs/dynamics.md, "Momentum
    // about the centre of mass"). RK4 and RKMK4 now step `(R, Ω_c)`, the same motion written in other coordinates,
    // so they differ from the recording by their truncation error: at most 9.2e-7 (the rod end on a sphere with
    // RKMK4), 2.9e-8 on the tops, 4e-9 on the circle, 9e-10 on the cuboid and the pendulum. The position projection
    // now keeps each body's momentum about its centre, not about the world origin, as it moves the body onto the
    // joints: the rod end on a sphere with RKMK4-body and projection moves by 2.1e-8, the circle by 5.3e-11.
    for (label, initial, end) in results {
        assert!(initial < 1e-15, "{label}: initial state differs by {initial:e}");
        let body_method = label.ends_with("RKMK4-body");
        let bound = if label.ends_with(" RK4") || label.ends_with(" RKMK4") {
            2e-6
        } else if body_method && label.starts_with("4 rod end on sphere") {
            5e-8
        } else if body_method && label.starts_with("1 cuboid") {
            1e-8
        } else if label.starts_with("4 rod end on circle") {
            1e-9
        } else {
            3e-11
        };
        assert!(end < bound, "{label}: end state differs by {end:e}");
    }
}

#[test]
fn pga_single_bodies_are_reproduced() {
    check::<Pga>();
}

#[test]
fn cga_single_bodies_are_reproduced() {
    check::<Cga>();
}
