//! One joint: a constraint between a body and its reference (the world or another body), evaluated in the
//! relative kinematics of the two (docs/mechanisms.md §M2).
//!
//! Every constraint of [`crate::constraints`] is written for one body against a fixed "world". Between two
//! moving bodies, body b against its reference body a, the same constraint holds with a's frame as the world:
//! the relative motor `M = ~R_a R_b` (b's frame → a's frame) and the relative body velocity
//! `Ḃ_rel = Ḃ_b − ~M Ḃ_a M` (b relative to a, in b's frame) give the constraint's rows unchanged, each a
//! covector `a` with `ė = a·x_rel`. Two things change:
//!
//! * the rate of the relative velocity has an extra term, `dḂ_rel/dt = B̈_b − ~M B̈_a M − Ḃ_b × (~M Ḃ_a M)`, so
//!   each row's bias gains `−a·(Ḃ_b × Ḃ_a')` (with `Ḃ_a' = ~M Ḃ_a M`);
//! * `x_rel = x_b − Ad x_a`, so the row acts on body b as `a` (in b's frame) and on body a as `−Adᵀa`: the
//!   same wrench, expressed in a's frame, with the opposite sign — Newton's third law, and by d'Alembert the
//!   joint's reaction on b is `Σλa`, on a the opposite.
//!
//! With the world as reference, `M = R_b` and `Ḃ_a = 0`: the single-body constraint exactly (`docs/theory.md` §6–§9).

use std::fmt;
use std::sync::Arc;

use arrayvec::ArrayVec;

use nalgebra::Vector3;

use crate::algebra::{Algebra, MotorCoordinates, ScrewCoordinates};
use crate::constraints::{Constraint, ConstraintError, Kinematics, RowBuffer, Stabilisation, MAX_ROWS};
use crate::joint_models::JointModel;
use crate::mechanism::reduce::{reduce, Reduced, RIGHT_HAND_SIDES};
use crate::mechanism::solve::{dot6, SolverSettings};
use crate::motor::ScrewFrame;

/// What the joints' rows are evaluated for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Rows {
    /// The equations of motion: the acceleration condition, stabilised, reduced.
    Dynamics,
    /// The projection onto the joint manifold: position and velocity conditions, reduced.
    Projection,
    /// A violation query: the residuals alone, not reduced (they exist where the rows lose rank).
    Residuals,
}

/// A joint of a mechanism: its constraint, the body it holds and the reference it holds it to.
#[derive(Clone)]
pub(crate) struct Joint<A: Algebra> {
    pub constraint: Arc<dyn Constraint<A>>,
    pub body: usize,
    /// None: the world.
    pub reference: Option<usize>,
    /// A supplied reaction basis (wrenches in the reference frame, theory §7.1 method 2).
    pub reaction_basis: Option<Vec<A::Screw>>,
    /// The constraint's [`Constraint::uses_motor`] and [`Constraint::rank`], asked once.
    pub uses_motor: bool,
    pub rank: usize,
    /// The joint model, for a joint added by `Mechanism::connect`.
    pub model: Option<JointModel>,
}

impl<A: Algebra> fmt::Debug for Joint<A> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Joint")
            .field("name", &self.constraint.name())
            .field("rank", &self.rank)
            .field("body", &self.body)
            .field("reference", &self.reference)
            .finish()
    }
}

/// One body at one evaluation: its kinematics and free acceleration.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BodyKinematics<A: Algebra> {
    pub kinematics: Kinematics<A>,
    /// `f = H⁻¹(Ḃ × Ω_b + S_b)` in velocity coordinates `(ω̇; v̇)`: the body's acceleration without reactions
    /// (zero when only positions and velocities are needed).
    pub free_acceleration: [f64; 6],
}

/// A joint's reduced rows at one evaluation.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct JointRows {
    /// Rows in the body's frame, values: the acceleration condition, −e, −ė.
    pub reduced: Reduced,
    /// The same rows acting on the reference body, in its frame (`−Adᵀa`); unused for the world.
    pub reference_rows: [[f64; 6]; 6],
    /// The largest |e| and |ė| over the raw rows (for the violation).
    pub position_residual: f64,
    pub velocity_residual: f64,
    /// Whether every row has a position residual.
    pub has_position: bool,
    /// The size of the terms summed into the acceleration conditions: their round-off is this times ε.
    pub acceleration_scale: f64,
}

impl JointRows {
    /// The reactions `Σ λ_k a_k` of multipliers λ on the body and on the reference (wrench coordinates, each in
    /// its own frame).
    pub fn reactions(&self, lambda: &[f64]) -> ([f64; 6], [f64; 6]) {
        let (mut body, mut reference) = ([0.0; 6], [0.0; 6]);
        for ((row, reference_row), &l) in self.reduced.rows.iter().zip(&self.reference_rows).zip(lambda) {
            for (((b, r), a), c) in body.iter_mut().zip(reference.iter_mut()).zip(row).zip(reference_row) {
                *b += a * l;
                *r += c * l;
            }
        }
        (body, reference)
    }
}

/// Wrench (covector) coordinates `(τ; f)` of screw coordinates `(l = f, t = τ)` and back (theory §3: a wrench's
/// force is its l-part, its moment its t-part, and `(τ; f)` pairs with the velocity `(ω; v)` to the power).
#[inline]
pub(crate) fn wrench_coordinates(c: &ScrewCoordinates) -> [f64; 6] {
    [c.t.x, c.t.y, c.t.z, c.l.x, c.l.y, c.l.z]
}

#[inline]
pub(crate) fn wrench_screw(y: &[f64; 6]) -> ScrewCoordinates {
    ScrewCoordinates {
        l: Vector3::new(y[3], y[4], y[5]),
        t: Vector3::new(y[0], y[1], y[2]),
    }
}

/// Velocity coordinates `(ω; v)` of screw coordinates `(l = ω, t = v)`.
#[inline]
fn velocity_vector(c: &ScrewCoordinates) -> [f64; 6] {
    [c.l.x, c.l.y, c.l.z, c.t.x, c.t.y, c.t.z]
}

/// Screw coordinates `(l = ω, t = v)` of velocity coordinates `(ω; v)`.
#[inline]
pub(crate) fn velocity_screw(x: &[f64; 6]) -> ScrewCoordinates {
    ScrewCoordinates {
        l: Vector3::new(x[0], x[1], x[2]),
        t: Vector3::new(x[3], x[4], x[5]),
    }
}

/// What an evaluation of the joint needs besides the bodies.
pub(crate) struct JointContext<'a> {
    pub t: f64,
    pub stabilisation: Stabilisation,
    pub settings: &'a SolverSettings,
    /// The bodies' inverse inertias `H⁻¹` (diagonal, velocity coordinates).
    pub inverse_metric: &'a [[f64; 6]],
    /// Whether the mechanism has loop joints (whose consistency check needs every joint's round-off scale).
    pub loops: bool,
    /// What the rows are for: the acceleration condition is wanted only for the dynamics (the projection
    /// needs only e and ė), and a violation query wants the residuals alone, not reduced, so that a joint where
    /// its rows lose rank (a point at the centre of its sphere) still reports them.
    pub purpose: Rows,
}

impl<A: Algebra> Joint<A> {
    pub fn name(&self) -> &str {
        self.constraint.name()
    }

    /// The joint's reduced rows at the bodies' kinematics, into `out`; `raw` is scratch for the raw rows.
    pub fn evaluate(
        &self,
        context: &JointContext<'_>,
        bodies: &[BodyKinematics<A>],
        raw: &mut RowBuffer,
        out: &mut JointRows,
    ) -> Result<(), ConstraintError> {
        let body = &bodies[self.body];
        // The kinematics of the body relative to its reference; for a body reference also the relative frame,
        // the correction −a·(Ḃ_b × Ḃ_a') as a velocity vector c, and the reference's free acceleration seen from b.
        let relative;
        let (kinematics, frame, correction, reference_acceleration) = match self.reference {
            None => (&body.kinematics, None, [0.0; 6], [0.0; 6]),
            Some(r) => {
                let reference = &bodies[r];
                // The relative motor only for constraints that read it (the rest get NaN, see `uses_motor`).
                let motor = if self.uses_motor {
                    A::compose(reference.kinematics.reverse, body.kinematics.motor)
                } else {
                    A::motor(MotorCoordinates {
                        scalar: f64::NAN,
                        l: Vector3::repeat(f64::NAN),
                        t: Vector3::repeat(f64::NAN),
                        pseudoscalar: f64::NAN,
                    })
                };
                let frame = ScrewFrame::relative(&reference.kinematics.frame, &body.kinematics.frame);
                let reference_velocity = frame.to_body(&A::screw_coordinates(reference.kinematics.body_velocity));
                let relative_velocity = body.kinematics.body_velocity - A::screw(reference_velocity);
                relative = Kinematics::with_frame(context.t, motor, frame, relative_velocity);
                let (correction, acceleration) = if context.purpose == Rows::Dynamics {
                    (
                        velocity_vector(&A::screw_coordinates(A::commutator(
                            body.kinematics.body_velocity,
                            A::screw(reference_velocity),
                        ))),
                        velocity_vector(&frame.to_body(&velocity_screw(&reference.free_acceleration))),
                    )
                } else {
                    ([0.0; 6], [0.0; 6])
                };
                (&relative, Some(frame), correction, acceleration)
            }
        };

        raw.clear();
        self.constraint.rows(kinematics, raw)?;
        if raw.requested() > MAX_ROWS {
            return Err(ConstraintError::TooManyRows {
                name: self.name().to_owned(),
                rows: raw.requested(),
                capacity: MAX_ROWS,
            });
        }
        if !raw.rows().iter().all(|row| row.is_finite()) {
            return Err(ConstraintError::NonFinite {
                name: self.name().to_owned(),
                t: context.t,
            });
        }

        // Per raw row: β = −b − a·(Δf − c) − feedback for the acceleration condition (Δf = f_b − Ad f_a), −e, −ė.
        let relative_acceleration: [f64; 6] =
            std::array::from_fn(|k| body.free_acceleration[k] - reference_acceleration[k] - correction[k]);
        let mut rhs: ArrayVec<[f64; RIGHT_HAND_SIDES], MAX_ROWS> = ArrayVec::new();
        out.position_residual = 0.0;
        out.velocity_residual = 0.0;
        out.has_position = true;
        for row in raw.rows() {
            let mut acceleration = 0.0;
            if context.purpose == Rows::Dynamics {
                let drift = dot6(&row.jacobian, &relative_acceleration);
                acceleration = -drift - row.bias - context.stabilisation.feedback(row);
            }
            let e = row.position_residual.unwrap_or(0.0);
            out.has_position &= row.position_residual.is_some();
            rhs.push([acceleration, -e, -row.velocity_residual]);
            out.position_residual = out.position_residual.max(e.abs());
            out.velocity_residual = out.velocity_residual.max(row.velocity_residual.abs());
        }

        if context.purpose == Rows::Residuals {
            return Ok(());
        }
        let rank = self.rank;
        let basis: Option<ArrayVec<[f64; 6], 6>> = self.reaction_basis.as_ref().map(|wrenches| {
            wrenches
                .iter()
                .take(6)
                .map(|w| wrench_coordinates(&kinematics.frame.to_body(&A::screw_coordinates(*w))))
                .collect()
        });
        reduce(
            raw.rows(),
            &rhs,
            rank,
            &context.inverse_metric[self.body],
            basis.as_deref(),
            context.settings.rank_tolerance,
            &mut out.reduced,
        )
        .map_err(|deficiency| ConstraintError::RankDeficient {
            names: self.name().to_owned(),
            rank,
            singular_value: deficiency.singular_value,
            largest: deficiency.largest,
        })?;
        // The round-off scale of the acceleration conditions, for the consistency checks: a joint's own (whose rows
        // the reduction may not reproduce) and the loops'. Rows a tree joint uses as they are leave no residual.
        out.acceleration_scale = 0.0;
        if context.purpose == Rows::Dynamics && (context.loops || !out.reduced.direct) {
            // Bounds within a small factor (the checks only compare with 1e-10 of them): the drift sums
            // a·(f_b, f_a', c) term by term, at most |a|₁ times their largest coordinate; the bias is a sum of
            // velocity products like Ḃ×(Ḃ×V), about |ω_rel| times the velocity terms |aₖxₖ| ≤ |a|₁|x|∞ — it can
            // cancel to round-off of those (a slider turning with its base), so its own size is no measure of
            // its error.
            let acceleration_size = (0..6)
                .map(|k| body.free_acceleration[k].abs() + reference_acceleration[k].abs() + correction[k].abs())
                .fold(0.0, f64::max);
            let velocity = &kinematics.velocity;
            let term_size = acceleration_size + velocity.fixed_rows::<3>(0).norm() * velocity.amax();
            let scale_squared: f64 = raw
                .rows()
                .iter()
                .map(|row| {
                    let a = row.jacobian.map(f64::abs);
                    let row_size = (a[0] + a[1]) + (a[2] + a[3]) + (a[4] + a[5]);
                    let feedback = context.stabilisation.feedback(row);
                    (row_size * term_size + row.bias.abs() + feedback.abs()).powi(2)
                })
                .sum();
            out.acceleration_scale = scale_squared.sqrt();
        }
        if context.purpose == Rows::Dynamics {
            let consistency = crate::mechanism::solve::Consistency::Check {
                scale: out.acceleration_scale,
            };
            if consistency.violated(out.reduced.residual_squared, out.reduced.rhs_squared, context.settings) {
                return Err(ConstraintError::Inconsistent {
                    names: self.name().to_owned(),
                    relative_residual: (out.reduced.residual_squared / out.reduced.rhs_squared).sqrt(),
                });
            }
        }
        if let Some(frame) = frame {
            for (reference_row, row) in out.reference_rows.iter_mut().zip(&out.reduced.rows[..out.reduced.rank]) {
                let moved = frame.to_world(&wrench_screw(row));
                *reference_row = wrench_coordinates(&moved).map(|x| -x);
            }
        }
        Ok(())
    }
}
