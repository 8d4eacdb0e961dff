//! The stages of the general methods on the motor group (`docs/theory.md` §5, §10): RK4 on `(R, Ω)` as vectors, and
//! the Runge–Kutta–Munthe-Kaas methods that move each motor only by exponentials of screws, with the momentum in the
//! world frame or in the body frame; the per-body buffers they share.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::ConstraintError;
use crate::exponential::exp;
use crate::integrate::error::{StepError, MAX_TURN_PER_STEP};
use crate::integrate::tableaux::{Tableau, DOP853_EXTENDED_STAGES};
use crate::motion::{BodyRates, Dynamics, Rates};
use crate::motor::{self, body_from_central, central_from_body};
use crate::state::State;

/// The per-body buffers of a step, sized once for the system.
pub(super) struct Buffers<A: Algebra> {
    /// The state being advanced (copied back into the caller's slice only if the step succeeds).
    pub(super) next: Vec<State<A>>,
    /// A stage's states (world-momentum methods).
    pub(super) stage: Vec<State<A>>,
    pub(super) rates: Vec<Rates<A>>,
    pub(super) body_rates: Vec<BodyRates<A>>,
    /// A stage's motors and body momenta (body-momentum methods).
    pub(super) motors: Vec<A::Motor>,
    pub(super) momenta: Vec<A::Screw>,
    /// The body momenta and the motors at the start of the step (the dense output starts from them).
    pub(super) start_momenta: Vec<A::Screw>,
    pub(super) start_motors: Vec<A::Motor>,
    /// A stage's Lie-algebra offsets σ (the stage motors are `R₀ exp(σ)`).
    pub(super) sigmas: Vec<A::Screw>,
    /// Per stage and body, stage-major: `(dR/dt, dΩ/dt)` (RK4), or the Lie-algebra slopes σ-increments and
    /// momentum slopes (RKMK).
    pub(super) derivatives: Vec<Derivative<A>>,
    pub(super) slopes: Vec<A::Screw>,
    pub(super) momentum_slopes: Vec<A::Screw>,
    /// Per stage: the system's non-conservative power ([`Dynamics::power`]), which the method's weights integrate
    /// into the step's work, exactly as an extra state `ẇ = P` integrated by the same method.
    pub(super) powers: Vec<f64>,
}

impl<A: Algebra> Buffers<A> {
    pub(super) fn new(bodies: usize) -> Self {
        let zero_screw = A::screw(ScrewCoordinates::default());
        let zero_motor = A::motor(Default::default());
        let state = State {
            motor: zero_motor,
            central_momentum: zero_screw,
        };
        let stages = DOP853_EXTENDED_STAGES;
        Buffers {
            next: vec![state; bodies],
            stage: vec![state; bodies],
            rates: vec![
                Rates {
                    body_velocity: zero_screw,
                    momentum_rate: zero_screw,
                };
                bodies
            ],
            body_rates: vec![
                BodyRates {
                    body_velocity: zero_screw,
                    body_wrench: zero_screw,
                };
                bodies
            ],
            motors: vec![zero_motor; bodies],
            momenta: vec![zero_screw; bodies],
            start_momenta: vec![zero_screw; bodies],
            start_motors: vec![zero_motor; bodies],
            sigmas: vec![zero_screw; bodies],
            derivatives: vec![
                Derivative {
                    motor: zero_motor,
                    momentum: zero_screw,
                };
                4 * bodies
            ],
            slopes: vec![zero_screw; stages * bodies],
            momentum_slopes: vec![zero_screw; stages * bodies],
            powers: vec![0.0; stages],
        }
    }
}

/// Refuses a step in which a body turns by more than [`MAX_TURN_PER_STEP`]: `start_slopes` are the first
/// stage's `−½ dt Ḃ` of every body (every method stores them), whose angular part has length `½ |ω| dt`.
pub(super) fn check_turn<A: Algebra>(start_slopes: &[A::Screw], t: f64, dt: f64) -> Result<(), StepError> {
    for (body, slope) in start_slopes.iter().enumerate() {
        let turn = 2.0 * A::screw_coordinates(*slope).l.norm();
        // Written so that a NaN turn passes to the finiteness check, which names it.
        if turn > MAX_TURN_PER_STEP {
            return Err(StepError::StepTooLarge {
                t,
                dt,
                body,
                turn,
                angular_speed: turn / dt,
            });
        }
    }
    Ok(())
}

/// The time derivative `(dR/dt, dΩ_c/dt)` of `(R, Ω_c)` of one body at one state ([`Rates::momentum_rate`]).
#[derive(Clone, Copy)]
pub(super) struct Derivative<A: Algebra> {
    pub(super) motor: A::Motor,
    pub(super) momentum: A::Screw,
}

/// `(dR/dt, dΩ_c/dt)` of every body at `states`, into `out`.
pub(super) fn derivatives<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    t: f64,
    states: &[State<A>],
    rates: &mut [Rates<A>],
    out: &mut [Derivative<A>],
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    dynamics.rates(t, states, rates, workspace)?;
    for ((slope, rate), state) in out.iter_mut().zip(rates.iter()).zip(states) {
        *slope = Derivative {
            motor: rate.motor_rate(state.motor),
            momentum: rate.momentum_rate,
        };
    }
    Ok(())
}

/// `stage = y + h·k` for every body.
pub(super) fn advance<A: Algebra>(stage: &mut [State<A>], y: &[State<A>], slopes: &[Derivative<A>], h: f64) {
    for ((stage, state), slope) in stage.iter_mut().zip(y).zip(slopes) {
        *stage = State {
            motor: state.motor + slope.motor * h,
            central_momentum: state.central_momentum + slope.momentum * h,
        };
    }
}

/// Classic RK4 on every body's (R, Ω) as vectors.
pub(super) fn rk4<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    t: f64,
    y: &mut [State<A>],
    dt: f64,
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let n = y.len();
    let half = 0.5 * dt;
    let Buffers {
        stage,
        rates,
        derivatives: k,
        ..
    } = buffers;
    let (k1, rest) = k.split_at_mut(n);
    let (k2, rest) = rest.split_at_mut(n);
    let (k3, k4) = rest.split_at_mut(n);
    let powers = &mut buffers.powers;
    derivatives(dynamics, t, y, rates, k1, workspace)?;
    powers[0] = dynamics.power(workspace);
    for (slope, rate) in buffers.slopes.iter_mut().zip(rates.iter()) {
        *slope = rate.body_velocity * (-0.5 * dt);
    }
    advance(stage, y, k1, half);
    derivatives(dynamics, t + half, stage, rates, k2, workspace)?;
    powers[1] = dynamics.power(workspace);
    advance(stage, y, k2, half);
    derivatives(dynamics, t + half, stage, rates, k3, workspace)?;
    powers[2] = dynamics.power(workspace);
    advance(stage, y, k3, dt);
    derivatives(dynamics, t + dt, stage, rates, k4, workspace)?;
    powers[3] = dynamics.power(workspace);
    let sixth = dt / 6.0;
    for (i, state) in y.iter_mut().enumerate() {
        *state = State {
            motor: state.motor + (k1[i].motor + k2[i].motor * 2.0 + k3[i].motor * 2.0 + k4[i].motor) * sixth,
            central_momentum: state.central_momentum
                + (k1[i].momentum + k2[i].momentum * 2.0 + k3[i].momentum * 2.0 + k4[i].momentum) * sixth,
        };
    }
    Ok(())
}

/// The Lie bracket `[X, Y] = XY − YX`, twice the commutator product of theory §1.1.
#[inline]
pub(super) fn bracket<A: Algebra>(x: A::Screw, y: A::Screw) -> A::Screw {
    A::commutator(x, y) * 2.0
}

/// RKMK4 for `dR/dt = R ξ` with `ξ = −½Ḃ` (theory §3) and `dΩ/dt = W`, body by body.
///
/// With `R = R₀ exp(σ)`, σ obeys `dσ/dt = dexp⁻¹_{−σ}(ξ) = ξ + ½[σ, ξ] + …` (`[X, Y] = XY − YX`, twice the
/// commutator product of theory §1.1). Classic RK4 on σ, with `dexp⁻¹` truncated to the terms that matter at
/// order 4, leaves two commutators (Munthe-Kaas' RKMK4, here for the right action `R ξ`, which flips the sign
/// of the odd terms relative to the usual left-action form):
///
/// ```text
/// kᵢ = h ξ(Rᵢ, Ωᵢ)      R₂ = R₀ exp(½k₁)   R₃ = R₀ exp(½k₂ + ⅛[k₁, k₂])   R₄ = R₀ exp(k₃)
/// R₁ = R₀ exp(⅙(k₁ + 2k₂ + 2k₃ + k₄) + ¹⁄₁₂[k₁, k₄])
/// ```
///
/// Ω lives in a vector space, where the commutators vanish and the stages are classic RK4's.
pub(super) fn rkmk4<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    t: f64,
    y: &mut [State<A>],
    dt: f64,
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let n = y.len();
    let half = 0.5 * dt;
    // Stage s: rates at `stage`, then kₛ = −½hḂ and the momentum rate, stored at [s n + i].
    let evaluate = |s: usize, at: f64, buffers: &mut Buffers<A>, workspace: &mut D::Workspace, first: bool| {
        let Buffers {
            stage,
            rates,
            slopes,
            momentum_slopes,
            powers,
            ..
        } = buffers;
        dynamics.rates(at, if first { &*y } else { &*stage }, rates, workspace)?;
        powers[s] = dynamics.power(workspace);
        for (i, rate) in rates.iter().enumerate() {
            slopes[s * n + i] = rate.body_velocity * (-0.5 * dt);
            momentum_slopes[s * n + i] = rate.momentum_rate;
        }
        Ok::<(), ConstraintError>(())
    };
    // The stage `R₀ exp(σ)`, `Ω₀ + h dΩ` from the σ buffer and momentum slope s.
    let set_stage = |buffers: &mut Buffers<A>, s: usize, h: f64| {
        let slopes = &buffers.momentum_slopes[s * n..(s + 1) * n];
        for (((stage, start), &sigma), &slope) in
            buffers.stage.iter_mut().zip(y.iter()).zip(&buffers.sigmas).zip(slopes)
        {
            *stage = State {
                motor: A::compose(start.motor, exp::<A>(sigma)),
                central_momentum: start.central_momentum + slope * h,
            };
        }
    };
    evaluate(0, t, buffers, workspace, true)?;
    for i in 0..n {
        buffers.sigmas[i] = buffers.slopes[i] * 0.5;
    }
    set_stage(buffers, 0, half);
    evaluate(1, t + half, buffers, workspace, false)?;
    for i in 0..n {
        let (k1, k2) = (buffers.slopes[i], buffers.slopes[n + i]);
        buffers.sigmas[i] = k2 * 0.5 + bracket::<A>(k1, k2) * 0.125;
    }
    set_stage(buffers, 1, half);
    evaluate(2, t + half, buffers, workspace, false)?;
    for i in 0..n {
        buffers.sigmas[i] = buffers.slopes[2 * n + i];
    }
    set_stage(buffers, 2, dt);
    evaluate(3, t + dt, buffers, workspace, false)?;
    let (k, m) = (&buffers.slopes, &buffers.momentum_slopes);
    for (i, state) in y.iter_mut().enumerate() {
        let (k1, k2, k3, k4) = (k[i], k[n + i], k[2 * n + i], k[3 * n + i]);
        let sigma = (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (1.0 / 6.0) + bracket::<A>(k1, k4) * (1.0 / 12.0);
        let momentum_rate = m[i] + m[n + i] * 2.0 + m[2 * n + i] * 2.0 + m[3 * n + i];
        *state = State {
            motor: A::compose(state.motor, exp::<A>(sigma)),
            central_momentum: state.central_momentum + momentum_rate * (dt / 6.0),
        };
    }
    Ok(())
}

/// One stage of a body-momentum method: the body rates at the stage motors `R₀ exp(σᵢ)` (σ from
/// `buffers.sigmas`; the start motors for the first stage, and for systems whose rates do not depend on the
/// motors, which skips an exponential and a motor product per body) and the body momenta `buffers.momenta`;
/// stores `k = −½hḂ` and `dΩ_b/dt = Ḃ × Ω_b + W_b` (theory §5) of body i at `[s n + i]`.
pub(super) fn body_stage<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    (s, at, dt): (usize, f64, f64),
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let n = buffers.motors.len();
    let skip_motors = s == 0 || !dynamics.rates_depend_on_motors();
    for ((motor, &start), &sigma) in buffers
        .motors
        .iter_mut()
        .zip(&buffers.start_motors)
        .zip(&buffers.sigmas)
    {
        *motor = if skip_motors {
            start
        } else {
            A::compose(start, exp::<A>(sigma))
        };
    }
    dynamics.body_rates(
        at,
        &buffers.motors,
        &buffers.momenta,
        &mut buffers.body_rates,
        workspace,
    )?;
    buffers.powers[s] = dynamics.power(workspace);
    for (i, (rates, &momentum)) in buffers.body_rates.iter().zip(&buffers.momenta).enumerate() {
        let velocity = rates.body_velocity;
        buffers.slopes[s * n + i] = velocity * (-0.5 * dt);
        buffers.momentum_slopes[s * n + i] = A::commutator(velocity, momentum) + rates.body_wrench;
    }
    Ok(())
}

/// [`Method::Rkmk4Body`]: the RKMK4 stages of [`rkmk4`] for every R, classic RK4 stages for the body momenta
/// `Ω_b`, with `dΩ_b/dt = Ḃ × Ω_b + W_b` (theory §5). The stages' R are exact motors, so any system can be
/// handed the state `(R, Ω_c)` with Ω_c the body momentum turned to world axes.
///
/// The state carries the momentum about the centre of mass in world axes, so every step turns it to the body frame
/// and back, through the rotation of the motor's map on screw coordinates ([`crate::motor::ScrewFrame`]), with no
/// translation: the round trip's round-off does not grow with the distance from the origin, as it did while the
/// state held the momentum about the origin (scene 1 1e4 m out: RKMK4-body 1.2e-7 rad, against 2.4e-10 at the
/// origin; `scenarios/tests/integration/hard_cases.rs`). That map is the sandwich divided by
/// `⟨R~R⟩₀`, which [`crate::motor::normalise`] leaves about 1.3e-16 above 1 on average: an undivided sandwich
/// would grow the momentum by ~5e-16 per round trip, a systematic energy drift (5e-11 relative after 1e5
/// steps, measured on scene 1). In CGA the map also avoids the sandwiches' `½|x|²` round-off: at 100 m the
/// orientation error of this method on scene 1 fell from 4.7e-6 to 2.1e-9 rad, and at 1e4 m from total loss
/// to 1.6e-4 rad (`scenarios/tests/integration/hard_cases.rs`).
pub(super) fn rkmk4_body_momentum<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    t: f64,
    y: &mut [State<A>],
    dt: f64,
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let n = y.len();
    let half = 0.5 * dt;
    let conserving = dynamics.conserves_world_momenta();
    for ((start, motor), state) in (buffers.start_momenta.iter_mut())
        .zip(&mut buffers.start_motors)
        .zip(y.iter())
    {
        *start = body_from_central::<A>(state.motor, state.central_momentum);
        *motor = state.motor;
    }
    // Stage s + 1 starts from momentum slope s over h, with σ from `sigma(k₁, k₂, k₃)` of body i.
    let prepare = |buffers: &mut Buffers<A>, s: usize, h: f64, sigma: fn(&[A::Screw], usize, usize) -> A::Screw| {
        for i in 0..n {
            buffers.momenta[i] = buffers.start_momenta[i] + buffers.momentum_slopes[s * n + i] * h;
            buffers.sigmas[i] = sigma(&buffers.slopes, n, i);
        }
    };
    buffers.momenta.copy_from_slice(&buffers.start_momenta);
    body_stage(dynamics, (0, t, dt), buffers, workspace)?;
    prepare(buffers, 0, half, |k, _, i| k[i] * 0.5);
    body_stage(dynamics, (1, t + half, dt), buffers, workspace)?;
    prepare(buffers, 1, half, |k, n, i| {
        k[n + i] * 0.5 + bracket::<A>(k[i], k[n + i]) * 0.125
    });
    body_stage(dynamics, (2, t + half, dt), buffers, workspace)?;
    prepare(buffers, 2, dt, |k, n, i| k[2 * n + i]);
    body_stage(dynamics, (3, t + dt, dt), buffers, workspace)?;

    let (k, m) = (&buffers.slopes, &buffers.momentum_slopes);
    for (i, state) in y.iter_mut().enumerate() {
        let (k1, k2, k3, k4) = (k[i], k[n + i], k[2 * n + i], k[3 * n + i]);
        let sigma = (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (1.0 / 6.0) + bracket::<A>(k1, k4) * (1.0 / 12.0);
        let motor = A::compose(state.motor, exp::<A>(sigma));
        let momentum =
            buffers.start_momenta[i] + (m[i] + m[n + i] * 2.0 + m[2 * n + i] * 2.0 + m[3 * n + i]) * (dt / 6.0);
        *state = end_of_body_step(conserving, state, motor, momentum);
    }
    Ok(())
}

/// `dexp⁻¹_{−σ}(k) = k + ½[σ, k] + ¹⁄₁₂[σ, [σ, k]] − ¹⁄₇₂₀ ad⁴_σ k + ¹⁄₃₀₂₄₀ ad⁶_σ k − …` (the Bernoulli numbers
/// Bₙ/n!, with the odd terms' sign flipped for the right action, see [`rkmk4`]), truncated for a method of
/// `order`: with σ = O(h) the term ad^n_σ k is O(hⁿ⁺¹), so the terms n ≤ order − 1 are kept (the odd ones
/// beyond n = 1 vanish).
pub(super) fn dexp_inverse<A: Algebra>(sigma: A::Screw, k: A::Screw, order: u32) -> A::Screw {
    let bracket = |x: A::Screw, y: A::Screw| A::commutator(x, y) * 2.0;
    let first = bracket(sigma, k);
    let second = bracket(sigma, first);
    let mut result = k + first * 0.5 + second * (1.0 / 12.0);
    if order > 4 {
        let fourth = bracket(sigma, bracket(sigma, second));
        result = result + fourth * (-1.0 / 720.0);
        if order > 6 {
            let sixth = bracket(sigma, bracket(sigma, fourth));
            result = result + sixth * (1.0 / 30240.0);
        }
    }
    result
}

/// A body-momentum Runge–Kutta–Munthe-Kaas step ([`Method::Rkmk6Body`]) on any explicit tableau, body by body
/// ([`rkmk_stage`]). The step ends at `R₀ exp(Σ bᵢKᵢ)` with its body momentum turned to world axes; the stages stay in
/// `buffers` for an embedded pair's error estimate and continuous extension.
pub(super) fn rkmk_body_momentum<A: Algebra, D: Dynamics<A> + ?Sized, const S: usize>(
    tableau: &Tableau<S>,
    dynamics: &D,
    t: f64,
    y: &mut [State<A>],
    dt: f64,
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let conserving = dynamics.conserves_world_momenta();
    for ((start, motor), state) in buffers
        .start_momenta
        .iter_mut()
        .zip(&mut buffers.start_motors)
        .zip(y.iter())
    {
        *start = body_from_central::<A>(state.motor, state.central_momentum);
        *motor = state.motor;
    }
    for s in 0..S {
        let at = (s, t + tableau.c[s] * dt, dt);
        rkmk_stage(dynamics, at, &tableau.a[s], tableau.order, buffers, workspace)?;
    }
    for (b, state) in y.iter_mut().enumerate() {
        let (sigma, momentum) = weighted_slopes(buffers, &tableau.b, b, (dt, buffers.start_momenta[b]));
        let motor = A::compose(state.motor, exp::<A>(sigma));
        *state = end_of_body_step(conserving, state, motor, momentum);
    }
    Ok(())
}

/// Stage `s` at time `at` of a body-momentum RKMK step of `order`, with coefficients `row` on the earlier stages:
/// it evaluates the rates at `R₀ exp(σₛ)`, `σₛ = Σⱼ aₛⱼ Kⱼ`, and turns `kₛ = −½hḂₛ` into `Kₛ = dexp⁻¹_{−σₛ}(kₛ)`
/// (see [`rkmk4`] for the right-action form); the body momentum `Ω_b` takes the classic stages of
/// `dΩ_b/dt = Ḃ × Ω_b + W_b` (theory §5).
pub(super) fn rkmk_stage<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    (s, at, dt): (usize, f64, f64),
    row: &[f64],
    order: u32,
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let n = buffers.motors.len();
    for b in 0..n {
        // The high-order tableaux are sparse: `weighted_slopes` skips a zero coefficient.
        (buffers.sigmas[b], buffers.momenta[b]) =
            weighted_slopes(buffers, &row[..s], b, (dt, buffers.start_momenta[b]));
    }
    body_stage(dynamics, (s, at, dt), buffers, workspace)?;
    if s > 0 {
        for b in 0..n {
            let slope = &mut buffers.slopes[s * n + b];
            *slope = dexp_inverse::<A>(buffers.sigmas[b], *slope, order);
        }
    }
    Ok(())
}

/// `(Σ wₛKₛ, m₀ + h Σ wₛ dΩ_b/dtₛ)` of body `b` from the stages in `buffers` (zero weights skipped).
pub(super) fn weighted_slopes<A: Algebra>(
    buffers: &Buffers<A>,
    weights: &[f64],
    b: usize,
    (dt, start_momentum): (f64, A::Screw),
) -> (A::Screw, A::Screw) {
    let n = buffers.start_momenta.len();
    let zero = A::screw(ScrewCoordinates::default());
    (0..weights.len())
        .filter(|&s| weights[s] != 0.0)
        .fold((zero, start_momentum), |(sigma, m), s| {
            (
                sigma + buffers.slopes[s * n + b] * weights[s],
                m + buffers.momentum_slopes[s * n + b] * (weights[s] * dt),
            )
        })
}

/// The state at the end of a body-momentum step from `start`: the step's motor with the step's body momentum `Ω_b`
/// turned to world axes.
///
/// Unless the world momentum is a constant of the motion (`conserving`: no force, no joint). The stages integrate
/// Euler's equations for `Ω_b`, which keep `R Ω_b ~R` only to the truncation error, so a torque-free body's world
/// momentum would wander (7e-9 relative over 10⁶ steps at dt = 1e-3, flipping about its middle axis). Then the end
/// state is projected onto that invariant (Hairer, Lubich & Wanner, *Geometric Numerical Integration*, §IV.4): the
/// momentum is kept exactly (the state's, about the centre of mass, is as constant as the world one), and the motor
/// turned about the centre of mass by the shortest arc that makes the kept angular momentum, seen from the body, point
/// along the step's (the `t` part of momentum coordinates, `Iω`). That keeps what the body-frame methods are for: the
/// direction of the body's angular momentum, which sets its angular velocity, comes from Euler's equations, not from
/// the motor's error. The turn about that axis stays the step's own, and the body's linear momentum is the world one
/// seen from the body. The correction is the size of the local error, so the method's order is kept. The kept momentum
/// is seen from the body by the step's rotation alone: while the state held the momentum about the origin, it was seen
/// through the step's position error too, which cost scene 1 up to 20× its accuracy at a given tolerance.
pub(super) fn end_of_body_step<A: Algebra>(
    conserving: bool,
    start: &State<A>,
    motor: A::Motor,
    body_momentum: A::Screw,
) -> State<A> {
    if !conserving {
        return State {
            motor,
            central_momentum: central_from_body::<A>(motor, body_momentum),
        };
    }
    // With no force the momentum about the moving centre of mass is as constant as the one about the origin.
    let seen = A::screw_coordinates(body_from_central::<A>(motor, start.central_momentum)).t;
    let stepped = A::screw_coordinates(body_momentum).t;
    // The body frame turned by Q sees the world momentum as Q⁻¹ applied to what the step's frame sees: Q takes the
    // stepped direction to the seen one.
    let turn = motor::from_pose::<A>(Vector3::zeros(), &shortest_arc(&stepped, &seen));
    State {
        motor: A::compose(motor, turn),
        central_momentum: start.central_momentum,
    }
}

/// The rotation by the smallest angle taking the direction of `from` to that of `to`: the quaternion
/// `(1 + u·v, u⨯v)` of the unit vectors, normalised, which is exact for the tiny angles met here (nalgebra's
/// `rotation_between`, an arccosine of u·v, resolves only 1.5e-8 rad). The identity where a vector vanishes or
/// the two are more than 90° apart (not a correction of a step's error).
pub(super) fn shortest_arc(from: &Vector3<f64>, to: &Vector3<f64>) -> UnitQuaternion<f64> {
    let (Some(from), Some(to)) = (from.try_normalize(0.0), to.try_normalize(0.0)) else {
        return UnitQuaternion::identity();
    };
    let cosine = 1.0 + from.dot(&to);
    if cosine.is_nan() || cosine <= 1.0 {
        return UnitQuaternion::identity();
    }
    let axis = from.cross(&to);
    UnitQuaternion::new_normalize(Quaternion::new(cosine, axis.x, axis.y, axis.z))
}
