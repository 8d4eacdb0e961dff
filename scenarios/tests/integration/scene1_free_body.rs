//! Scene 1 (docs/scenes.md): the free Dzhanibekov cuboid, T = 10 s, with every integrator in both algebras,
//! against the analytic flip instants, the reference trajectory and end state, and the invariants of a free
//! body; the two algebras against each other; and each method's order of convergence.
//!
//! Bounds are the values measured at dt = 1e-3 (printed with `-- --nocapture`; quoted next to each bound)
//! times a margin: 2–3 where the error is the method's truncation error (the same to three digits in both
//! algebras and unchanged by reordering the arithmetic), 10 where it is round-off amplified by the flips,
//! which moves with any change in the order of the generated arithmetic (one such change of the code
//! generator moved a round-off-dominated error by 4×: `thrown_under_gravity`, RKMK4-body, 1.4e-8 → 5.3e-8).

use crate::common;

use common::{cuboid, trajectory};
use dynamics::simulate::{Sample, Simulation};
use dynamics::{simulate, Algebra, Cga, Integrator, Method, Pga, Schedule, SplittingMethod, State};
use nalgebra::Vector3;
use reference::scenes::CUBOID_VALUES;
use reference::{flip_time_error, flip_times, trajectory_errors, SceneId, Trajectory};

const DT: f64 = 1e-3;

/// Upper bounds on the errors of one integrator at dt = 1e-3 (measured values in the comments).
struct Bounds {
    /// max |t_flip − t_analytic| over the four flips (s).
    flip: f64,
    /// Orientation error at T = 10 s and its maximum over the run (rad).
    end_orientation: f64,
    max_orientation: f64,
    /// Maximum centre-of-mass error against the reference (m).
    max_position: f64,
    /// Angular velocity error at T against the end state printed in docs/scenes.md (rad/s).
    end_angular_velocity: f64,
    /// max |E − E₀| / E₀ over the samples.
    energy: f64,
    /// Whether the momentum Ω_c the state holds stays bitwise constant (dΩ_c/dt = 0 is integrated exactly).
    exact_momentum: bool,
    /// Largest change of a classical world momentum coordinate (p, L about the origin) over the samples.
    momentum: f64,
    /// Largest distance of the centre of mass from the line c₀ + v₀t (m).
    line: f64,
}

/// RK4 and RKMK4 differ little: both carry the momentum about the centre of mass in world axes, so R's rotation
/// error feeds into Ḃ = M⁻¹[Ω_b] (see `Method::Rkmk4Body`). That momentum stays bitwise constant; the classical
/// angular momentum about the origin read from the samples adds `c × p`, so it changes as the centre leaves its
/// straight line (by the line error times |p| = 2.3 kg m/s). (While the state held the momentum about the origin,
/// the centre's error entered Ḃ too: RK4 then measured flip 1.69e-8 s, orientation 2.27e-8 at the end and
/// 8.04e-8 at most, position 1.22e-9 m.)
const RK4: Bounds = Bounds {
    flip: 6e-8,                   // 2.57e-8 s
    end_orientation: 7e-8,        // 3.07e-8 rad
    max_orientation: 3e-7,        // 1.22e-7 rad
    max_position: 8e-10,          // 3.16e-10 m
    end_angular_velocity: 3.5e-7, // 1.46e-7 rad/s
    energy: 1e-10,                // 4.42e-11
    exact_momentum: true,
    momentum: 5e-11, // 1.97e-11
    line: 8e-10,     // 3.16e-10 m
};

const RKMK4: Bounds = Bounds {
    flip: 1e-7,                   // 4.03e-8 s
    end_orientation: 1.2e-7,      // 4.85e-8 rad
    max_orientation: 5e-7,        // 1.92e-7 rad
    max_position: 1.2e-9,         // 4.89e-10 m
    end_angular_velocity: 5.5e-7, // 2.31e-7 rad/s
    energy: 1.5e-10,              // 6.07e-11
    exact_momentum: true,
    momentum: 6e-10, // 2.51e-10
    line: 1.2e-9,    // 4.89e-10 m
};

/// The body-frame momentum decouples the flips from R's error: 200× more accurate in orientation than RK4. The
/// steps end on the kept momentum seen from the body (`integrate::end_of_body_step`), through the step's rotation
/// alone since states hold the momentum about the centre of mass, so the straight line and the classical momentum
/// (its `c × p` follows the line) hold to 2.2e-9. (While states held the momentum about the origin, the position
/// error entered that view: the line held to 4.7e-8, the orientation to 2.4e-10 at the end and 3.8e-10 at most, and
/// CGA's sandwiches added their ½|x|² round-off to 1.8e-9 rad; both algebras now agree to the digits shown.)
const RKMK4_BODY: Bounds = Bounds {
    flip: 1e-9,                 // 2.87e-10 s
    end_orientation: 5e-10,     // 1.33e-10 rad
    max_orientation: 1.5e-9,    // 5.27e-10 rad
    max_position: 6e-9,         // 2.22e-9 m
    end_angular_velocity: 2e-9, // 4.69e-10 rad/s
    energy: 3e-14,              // 8.57e-15
    exact_momentum: false,
    momentum: 3e-9, // 1.13e-9
    line: 6e-9,     // 2.22e-9 m
};

/// Every sub-step is an exact flow that keeps Ω, and the translation is exact: the centre of mass stays on
/// its line to round-off (1.5e-13 m). The energy error is the splitting's, bounded (2nd order).
const STRANG: Bounds = Bounds {
    flip: 2e-5,                 // 7.74e-6 s
    end_orientation: 1.5e-5,    // 6.81e-6 rad
    max_orientation: 8e-5,      // 3.72e-5 rad
    max_position: 1e-12,        // 3.2e-13 m
    end_angular_velocity: 8e-5, // 3.51e-5 rad/s
    energy: 3e-6,               // 1.21e-6
    exact_momentum: true,
    momentum: 1e-12,
    line: 1e-12,
};

const YOSHIDA4: Bounds = Bounds {
    flip: 2e-8,                 // 7.53e-9 s
    end_orientation: 1.5e-8,    // 6.86e-9 rad
    max_orientation: 8e-8,      // 3.51e-8 rad
    max_position: 1.5e-12,      // 4.3e-13 m
    end_angular_velocity: 8e-8, // 3.15e-8 rad/s
    energy: 2.5e-10,            // 1.01e-10
    exact_momentum: true,
    momentum: 1e-12,
    line: 1.5e-12,
};

fn run<A: Algebra>(integrator: Integrator, initial: State<A>, duration: f64, dt: f64) -> Simulation<A> {
    let scene = cuboid::<A>();
    let schedule = Schedule::new(dt, duration).expect("dt divides 0.01 and the duration");
    simulate(&scene.system, &[initial], integrator, &schedule).expect("scene 1 runs")
}

/// World momentum (p, L about the origin) from a sample, classically: p = m v, L = R I Rᵀ ω + c ⨯ p.
fn classical_momentum(sample: &Sample, mass: f64, moments: &Vector3<f64>) -> [Vector3<f64>; 2] {
    let p = mass * sample.velocity;
    let body_omega = sample.orientation.inverse() * sample.angular_velocity;
    let spin = sample.orientation * moments.component_mul(&body_omega);
    [p, spin + sample.position.cross(&p)]
}

fn max_over(samples: &[Sample], error: impl Fn(&Sample) -> f64) -> f64 {
    samples.iter().map(error).fold(0.0, f64::max)
}

fn check<A: Algebra>(integrator: Integrator, bounds: &Bounds) {
    let scene = cuboid::<A>();
    let simulation = run::<A>(integrator, scene.initial, scene.scene.duration, DT);
    let samples = simulation.body(0);
    let simulated = trajectory(&simulation);
    let reference = SceneId::Cuboid
        .reference_trajectory()
        .expect("embedded reference parses");
    let errors = trajectory_errors(&reference, &simulated).expect("same 0.01 s grid");
    let flips = flip_times(&simulated, &scene.scene.principal_moments);
    let flip = flip_time_error(&flips, &CUBOID_VALUES.flip_instants).expect("four flips in 10 s");
    let published = SceneId::Cuboid.published_end_state();
    let end_angular_velocity = (simulated.last().angular_velocity - published.angular_velocity).norm();

    let e0 = scene.scene.initial_energy;
    let energy = max_over(samples, |s| (s.energy - e0).abs() / e0);
    let [p0, l0] = classical_momentum(&samples[0], scene.body.mass(), &scene.body.moments());
    let momentum = max_over(samples, |s| {
        let [p, l] = classical_momentum(s, scene.body.mass(), &scene.body.moments());
        (p - p0).amax().max((l - l0).amax())
    });
    let line = max_over(samples, |s| {
        (s.position - (scene.scene.initial_com + s.t * scene.scene.initial_com_velocity)).norm()
    });

    println!(
        "{} {}: flip {flip:.2e} s, orientation end {:.2e} max {:.2e} rad, position max {:.2e} m, \
         ω end {end_angular_velocity:.2e} rad/s, energy {energy:.2e}, momentum {momentum:.2e}, line {line:.2e} m",
        A::NAME,
        integrator.name(),
        errors.end_orientation,
        errors.max_orientation,
        errors.max_position,
    );
    assert!(flip < bounds.flip, "flip-time error {flip:.2e}");
    assert!(errors.end_orientation < bounds.end_orientation, "{errors:?}");
    assert!(errors.max_orientation < bounds.max_orientation, "{errors:?}");
    assert!(errors.max_position < bounds.max_position, "{errors:?}");
    assert!(
        end_angular_velocity < bounds.end_angular_velocity,
        "{end_angular_velocity:.2e}"
    );
    assert!(energy < bounds.energy, "energy error {energy:.2e}");
    assert!(momentum < bounds.momentum, "momentum change {momentum:.2e}");
    assert!(line < bounds.line, "distance from the straight line {line:.2e}");
    if bounds.exact_momentum {
        assert_eq!(
            simulation.final_state[0].central_momentum,
            scene.initial.central_momentum
        );
    }
}

fn rk4<A: Algebra>() {
    check::<A>(Integrator::General(Method::Rk4), &RK4);
}

fn rkmk4<A: Algebra>() {
    check::<A>(Integrator::General(Method::Rkmk4), &RKMK4);
}

fn rkmk4_body<A: Algebra>() {
    check::<A>(Integrator::General(Method::Rkmk4Body), &RKMK4_BODY);
}

fn strang<A: Algebra>() {
    check::<A>(Integrator::Splitting(SplittingMethod::Strang), &STRANG);
}

fn yoshida4<A: Algebra>() {
    check::<A>(Integrator::Splitting(SplittingMethod::Yoshida4), &YOSHIDA4);
}

/// Each method converges at its order: over the first 2 s (one flip), halving dt from 5e-3 to 2.5e-3
/// divides the maximum orientation error by 2^order. Measured exponents (PGA): RK4 4.01, RKMK4 3.98,
/// RKMK4-body 4.07, Strang 3.99 → 2.00, Yoshida4 4.00; the errors (≥ 3e-9 rad) are far above the reference
/// floor (1e-11 rad). RKMK6-body is at that floor by dt = 5e-3, so it halves dt from 1e-2 instead (its
/// largest step on the 0.01 s sample grid), where its errors are still well above the floor.
///
/// An exponent below the order fails, and so does one far above it. RKMK6-body converges a little faster than
/// order 6 on this torque-free body: since its steps end on the conserved world momentum (`integrate`'s
/// `end_of_body_step`) the h⁶ term of the orientation error nearly cancels, and the exponent is 6.53, 6.47 and
/// 6.54 for dt 1e-2 → 5e-3 → 3.3e-3 → 2.5e-3 (6.0 before that projection); hence the asymmetric bounds.
fn convergence_orders<A: Algebra>() {
    let scene = cuboid::<A>();
    let reference = SceneId::Cuboid
        .reference_trajectory()
        .expect("embedded reference parses");
    let horizon = 2.0;
    let samples = (horizon / reference::scenes::SAMPLE_INTERVAL).round() as usize + 1;
    let reference = Trajectory::new(reference.samples()[..samples].to_vec()).expect("a prefix of the reference");
    // RKMK8-body is below the reference's floor already at dt = 1e-2 (3.3e-13 rad; 3.2e-14 at 5e-3, PGA and
    // CGA), the largest step on the sample grid: its order is observed on the heavy top instead
    // (`constraint_scenes.rs`).
    for integrator in Integrator::ALL.into_iter().filter(|i| i.order() <= 6) {
        let error = |dt: f64| {
            let run = run::<A>(integrator, scene.initial, horizon, dt);
            trajectory_errors(&reference, &trajectory(&run))
                .expect("same grid")
                .max_orientation
        };
        let coarse = if integrator.order() > 4 { 1e-2 } else { 5e-3 };
        let observed = (error(coarse) / error(0.5 * coarse)).log2();
        println!("{} {}: observed order {observed:.3}", A::NAME, integrator.name());
        let order = integrator.order() as f64;
        assert!(
            observed > order - 0.15 && observed < order + 0.6,
            "{}: order {observed:.3}, expected {}",
            integrator.name(),
            integrator.order()
        );
    }
}

/// CGA on the null basis keeps motors and screws in the subalgebra {1, lᵢ, tᵢ, Π}, whose products are PGA's
/// (`hard_cases.rs`, `cga_far_from_the_origin`), so over scene 1 (the centre of mass travels to (10, 5, 0)) the two
/// algebras take the same steps: measured, every integrator's positions are identical and its orientations agree
/// to 1.1e-16–1.6e-16 rad, the resolution of the angle between two unit quaternions.
#[test]
fn algebras_agree_on_scene_1() {
    for integrator in Integrator::ALL {
        let (pga, cga) = (cuboid::<Pga>(), cuboid::<Cga>());
        let pga = run::<Pga>(integrator, pga.initial, pga.scene.duration, DT);
        let cga = run::<Cga>(integrator, cga.initial, cga.scene.duration, DT);
        let (mut orientation, mut position) = (0.0f64, 0.0f64);
        for (p, c) in pga.body(0).iter().zip(cga.body(0)) {
            orientation = orientation.max(p.orientation.angle_to(&c.orientation));
            position = position.max((p.position - c.position).norm());
        }
        println!(
            "{}: CGA − PGA orientation {orientation:.2e} rad, position {position:.2e} m",
            integrator.name()
        );
        assert!(orientation < 1e-15, "{}: {orientation:.2e}", integrator.name());
        assert!(position < 1e-15, "{}: {position:.2e}", integrator.name());
    }
}

/// With the centre of mass held at the origin (v₀ = 0) CGA's ½|x|² terms vanish and both algebras do the
/// same arithmetic: measured agreement 1.2e-16 rad for every method.
#[test]
fn algebras_agree_at_the_origin() {
    for integrator in Integrator::ALL {
        let (pga, cga) = (cuboid::<Pga>(), cuboid::<Cga>());
        let at_origin =
            |scene: &reference::SceneParameters| (scene.initial_orientation, scene.initial_body_angular_velocity);
        let (rotation, omega) = at_origin(&pga.scene);
        let pga_initial = State::<Pga>::new(&pga.body, Vector3::zeros(), &rotation, omega, Vector3::zeros());
        let cga_initial = State::<Cga>::new(&cga.body, Vector3::zeros(), &rotation, omega, Vector3::zeros());
        let pga = run::<Pga>(integrator, pga_initial, 10.0, DT);
        let cga = run::<Cga>(integrator, cga_initial, 10.0, DT);
        let orientation = pga
            .body(0)
            .iter()
            .zip(cga.body(0))
            .map(|(p, c)| p.orientation.angle_to(&c.orientation))
            .fold(0.0, f64::max);
        println!(
            "{} at the origin: CGA − PGA orientation {orientation:.2e} rad",
            integrator.name()
        );
        assert!(orientation < 1e-15, "{}: {orientation:.2e}", integrator.name());
    }
}

/// Scene 1 thrown under gravity (9.81 m/s² along −e3): gravity exerts no torque about the centre of mass,
/// so the orientation must follow the scene-1 reference while the centre of mass falls on the parabola
/// `c₀ + v₀t − ½gt²e₃` (490 m in 10 s) and the total energy is conserved. Every method runs with the force,
/// RKMK4-body also through the generic [`dynamics::step`] path.
///
/// Measured (orientation rad, distance from the parabola m, energy error / E₀), PGA and CGA alike to the digits
/// shown: RK4 1.2e-7, 1.4e-8, 3.2e-9; RKMK4 1.9e-7, 2.4e-8, 5.5e-9; RKMK4-body 2.5e-10, 1.5e-6, 2.0e-9 (the generic
/// path the same); RKMK6-body 4.0e-11, 5.0e-11, 2.3e-11; RKMK8-body 1.3e-10, 4.2e-11, 2.2e-11; DP5(4)-body 6.3e-11,
/// 5.2e-10, 2.3e-10; DOP853-body 2.3e-10, 3.4e-11, 1.9e-11; Strang 3.7e-5, 3.4e-11, 1.2e-6; Yoshida4 3.5e-8,
/// 1.3e-10, 1.4e-10. The orientations are those without gravity: the state holds the momentum about the centre of
/// mass, on which gravity exerts no torque, so nothing of the 490 m fall reaches the spin. (While states held the
/// momentum about the origin, Ḃ read the angular momentum about the centre as L_origin − c × p, so the centre's
/// error δc of RK4 and RKMK4 became an angular momentum error δc × p with |p| up to 98 kg m/s: RK4 ended 1.0e-3 rad
/// off and RKMK4 5.3e-4; the body methods 4e-9 to 2e-8 rad, CGA's sandwiches ½|x|² more.) RKMK4-body's parabola is its
/// linear momentum integrated by RK4 in the turning body frame. Margins: 2–3 on the truncation errors, 10 on those
/// set by round-off (the orientations of the methods of order 5 and more, the splittings' parabolas, the energies of
/// the higher orders).
fn thrown_under_gravity<A: Algebra>() {
    let bounds: [(f64, f64, f64); Integrator::ALL.len()] = [
        (3e-7, 4e-8, 8e-9),
        (5e-7, 6e-8, 1.5e-8),
        (2.5e-9, 4e-6, 5e-9),
        (4e-10, 1.5e-10, 2.5e-10),
        (1.3e-9, 1.2e-10, 2.2e-10),
        (6e-10, 1.5e-9, 7e-10),
        (2.3e-9, 1e-10, 1.9e-10),
        (8e-5, 3.4e-10, 3e-6),
        (1e-7, 1.3e-9, 4e-10),
    ];
    let generic_bounds = bounds[2];
    let scene = cuboid::<A>();
    let system = scene.system.clone().with_force(dynamics::Force::gravity());
    let schedule = Schedule::new(DT, scene.scene.duration).expect("1e-3 divides 0.01 and 10 s");
    let reference = SceneId::Cuboid
        .reference_trajectory()
        .expect("embedded reference parses");
    let check = |name: &str, run: Simulation<A>, (orientation, parabola, energy): (f64, f64, f64)| {
        let e0 = run.body(0)[0].energy;
        let (mut worst_orientation, mut worst_parabola, mut worst_energy) = (0.0f64, 0.0f64, 0.0f64);
        for (sample, expected) in run.body(0).iter().zip(reference.samples()) {
            let fall = Vector3::new(
                0.0,
                0.0,
                -0.5 * dynamics::forces::STANDARD_GRAVITY * sample.t * sample.t,
            );
            worst_orientation = worst_orientation.max(sample.orientation.angle_to(&expected.orientation));
            worst_parabola = worst_parabola.max((sample.position - (expected.position + fall)).norm());
            worst_energy = worst_energy.max((sample.energy - e0).abs() / e0);
        }
        println!(
            "{} {name} under gravity: orientation {worst_orientation:.2e} rad, parabola {worst_parabola:.2e} m, \
             energy {worst_energy:.2e}",
            A::NAME
        );
        assert!(worst_orientation < orientation, "{name}: {worst_orientation:.2e}");
        assert!(worst_parabola < parabola, "{name}: {worst_parabola:.2e}");
        assert!(worst_energy < energy, "{name}: {worst_energy:.2e}");
    };
    for (integrator, bound) in Integrator::ALL.into_iter().zip(bounds) {
        let run = simulate(&system, &[scene.initial], integrator, &schedule).expect("the throw runs");
        check(integrator.name(), run, bound);
    }
    // The same body as a one-body mechanism (the general evaluation every mechanism takes).
    let mechanism = dynamics::Mechanism::single(system.body)
        .with_force(dynamics::Force::gravity())
        .unwrap();
    let generic = simulate(&mechanism, &[scene.initial], Method::Rkmk4Body, &schedule).expect("the throw runs");
    check("RKMK4-body (one-body mechanism)", generic, generic_bounds);
}

for_both_algebras!(
    rk4,
    rkmk4,
    rkmk4_body,
    strang,
    yoshida4,
    convergence_orders,
    thrown_under_gravity
);
