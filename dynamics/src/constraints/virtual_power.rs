//! Constraints by virtual power (`docs/theory.md` §6): a set of constraint wrenches `T_k(t)` (world frame, bivectors)
//! spanning the reactions the constraint can exert. With `T_bk = ~R T_k R`:
//!
//! * velocity condition `P_k = ⟨Ḃ ∧ T_bk⟩_Π = s_k` (`s_k = 0` unless the constraint moves, see below);
//! * acceleration condition `⟨B̈ ∧ T_bk⟩_Π + ⟨Ḃ ∧ (Ḃ × T_bk + ~R Ṫ_k R)⟩_Π = ṡ_k`.
//!
//! So each wrench is one row with Jacobian `a = (τ; f)` of `T_bk` and bias `⟨Ḃ ∧ ~RṪ_kR⟩_Π − ṡ_k`: the term
//! `⟨Ḃ ∧ (Ḃ × T_bk)⟩_Π` vanishes identically because the Π-pairing is invariant under the commutator
//! (`⟨X ∧ (Z×Y)⟩_Π = −⟨(Z×X) ∧ Y⟩_Π`, and `Ḃ × Ḃ = 0`), and `⟨Ḃ ∧ ~RṪR⟩_Π = ⟨Ḃ_w ∧ Ṫ⟩_Π` is evaluated in
//! the world frame. The reaction is `F = Σλ_k T_bk` (d'Alembert, E6), which is exactly the kinetic-metric
//! solution of the reaction solve ([`crate::mechanism`]) for these rows.
//!
//! The wrenches are all *dual* lines `force_line(f, a) = f I₃ − (a∧f) I₃ N` — bivectors in both algebras —
//! never the OPNS line `A∧V∧n∞` itself (E4). The catalogue (`virtual_power_joints`) places the forces at the constrained body point A
//! (world position a) and the couples along directions that follow the body, so that each row's power is
//! exactly the rate of a position residual e (on the manifold these are the static wrenches of theory §6):
//! projection and Baumgarte's β term then apply to virtual power as well (theory §10 notes that the bare method has
//! no position-level residual; [`VirtualPower::from_wrenches`] has none).
//!
//! A moving constraint does work: its velocity condition is `P = s` with the prescribed power s of the driven
//! motion — `(c − a)·ċ` for the sphere with centre c(t), `f·ṗ` for a force f at a pivot moving along p(t), the
//! path's relative velocity for a motor joint (theory §14.1).

use std::sync::Arc;

use arrayvec::ArrayVec;
use nalgebra::Vector3;

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::kinematics::Kinematics;
use crate::constraints::on_surfaces::each_surface_at;
use crate::constraints::paths::{MotorPath, Path, PathPoint};
use crate::constraints::rows::{ConstraintRow, RowBuffer};
use crate::constraints::{Constraint, ConstraintError};
use crate::convert::direction_and_length;
use crate::exponential::log;
use crate::forces::{couple, force_line};
use crate::surfaces::Surface;

/// One constraint wrench at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstraintWrench<A: Algebra> {
    /// `T_k`, world frame.
    pub wrench: A::Screw,
    /// `Ṫ_k`, its total time derivative along the motion, world frame.
    pub rate: A::Screw,
    /// `s_k`: the velocity condition is `⟨Ḃ ∧ T_bk⟩_Π = s_k`.
    pub prescribed_power: f64,
    /// `ṡ_k`.
    pub prescribed_power_rate: f64,
    /// A position residual whose rate is `⟨Ḃ ∧ T_bk⟩_Π − s_k`, if there is one.
    pub position_residual: Option<f64>,
}

/// A user constraint wrench at one time (theory §6, §14.1): `T(t)` and `Ṫ(t)` in the reference frame (the world,
/// or the reference body's frame for a joint), independent of the state, and the power `s(t)` the constrained
/// motion must put through it: zero for a fixed constraint, the prescribed power of a driven one (a moving
/// pivot's forces `f` have power `f·ṗ`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WrenchPoint<A: Algebra> {
    /// `T`, reference frame.
    pub wrench: A::Screw,
    /// `Ṫ`, its time derivative, reference frame.
    pub rate: A::Screw,
    /// `s`: the velocity condition is `⟨Ḃ ∧ T_b⟩_Π = s`.
    pub power: f64,
    /// `ṡ`.
    pub power_rate: f64,
}

impl<A: Algebra> WrenchPoint<A> {
    /// A fixed wrench: no rate, no prescribed power.
    ///
    /// A constraint wrench's row is its power: a unit force along z through the centre of mass against a body
    /// rising at 2 m/s gives the velocity residual 2 W (the condition is zero power).
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, Kinematics, RowBuffer, VirtualPower, WrenchPoint};
    /// use dynamics::{forces::force_line, motor, Algebra, Pga, ScrewCoordinates};
    /// use nalgebra::Vector3;
    ///
    /// let vertical = WrenchPoint::<Pga>::fixed(force_line::<Pga>(Vector3::z(), Vector3::zeros())); // 1 N
    /// assert_eq!((vertical.power, vertical.power_rate), (0.0, 0.0));
    /// let level = VirtualPower::from_wrenches("level", [move |_t: f64| vertical]);
    /// let rising = Pga::screw(ScrewCoordinates { l: Vector3::zeros(), t: Vector3::new(1.0, 0.0, 2.0) }); // m/s
    /// let mut rows = RowBuffer::new();
    /// level.rows(&Kinematics::new(0.0, motor::identity::<Pga>(), rising), &mut rows)?;
    /// assert_eq!(rows.rows()[0].velocity_residual, 2.0); // W
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn fixed(wrench: A::Screw) -> Self {
        let zero = A::screw(ScrewCoordinates::default());
        WrenchPoint {
            wrench,
            rate: zero,
            power: 0.0,
            power_rate: 0.0,
        }
    }
}

/// A user wrench as a function of time: a closure `Fn(f64) -> WrenchPoint<A>`, or an `Arc` of one (a list of
/// different closures is a `Vec<Arc<dyn WrenchPath<A>>>`).
pub trait WrenchPath<A: Algebra>: Send + Sync {
    /// The wrench, its rate and the prescribed power at time `t` (s).
    fn at(&self, t: f64) -> WrenchPoint<A>;
}

impl<A: Algebra, F: Fn(f64) -> WrenchPoint<A> + Send + Sync> WrenchPath<A> for F {
    fn at(&self, t: f64) -> WrenchPoint<A> {
        self(t)
    }
}

impl<A: Algebra, P: WrenchPath<A> + ?Sized> WrenchPath<A> for Arc<P> {
    fn at(&self, t: f64) -> WrenchPoint<A> {
        (**self).at(t)
    }
}

/// A body direction whose world (reference-frame) image d must stay normal to the world direction `normal`:
/// residual `normal·d`, whose rate `normal·(ω⨯d) = ω·(d⨯normal)` is the power of the couple `d⨯normal`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Alignment {
    pub(super) body_direction: Vector3<f64>,
    pub(super) normal: Vector3<f64>,
}

// The point joints are the common case: boxing them would add an indirection to every evaluation.
#[allow(clippy::large_enum_variant)]
#[derive(Clone)]
pub(super) enum Wrenches<A: Algebra> {
    /// Forces along the world directions `forces` at the body point, with residuals `f·(a − p(t))` (a moving
    /// point p prescribes the power `f·ṗ`), and couples for the alignments: ball (3 forces), hinge (3 forces, 2
    /// alignments), cylindrical (2 + 2), prismatic (2 + 3), planar (1 + 2), point on plane (1), point on line (2).
    Point {
        body_point: Vector3<f64>,
        point: Arc<dyn Path<Vector3<f64>>>,
        forces: ArrayVec<Vector3<f64>, 3>,
        /// Whether the forces are the world axes x, y, z (ball joints, hinges), whose rows are read off the
        /// rotation rather than computed (`point_rows`).
        along_axes: bool,
        /// The point, when its path is fixed (read once rather than asked of the path at every evaluation).
        fixed: Option<Vector3<f64>>,
        alignments: ArrayVec<Alignment, 3>,
    },
    /// One force from the body point towards the centre; residual ½(ρ² − |a − c|²).
    Sphere {
        body_point: Vector3<f64>,
        centre: Arc<dyn Path<Vector3<f64>>>,
        radius: f64,
    },
    /// Unit forces along the normals of one surface or two (a curve) through the body point; residuals F/|∇F|.
    Surfaces {
        body_point: Vector3<f64>,
        surfaces: ArrayVec<Surface, 2>,
    },
    /// The six unit wrenches of the body frame, with the prescribed relative velocity of a motor path.
    Motor(Arc<dyn MotorPath<A>>),
    /// User wrenches, no position residual.
    Custom(Vec<Arc<dyn WrenchPath<A>>>),
}

/// A constraint by virtual power (see the module docs).
#[derive(Clone)]
pub struct VirtualPower<A: Algebra> {
    pub(super) name: String,
    pub(super) wrenches: Wrenches<A>,
}

impl<A: Algebra> std::fmt::Debug for VirtualPower<A> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VirtualPower")
            .field("name", &self.name)
            .field("rank", &self.rank())
            .finish_non_exhaustive()
    }
}

/// `v`'s direction, or an error naming the constraint `name` and `what` `v` is.
pub(crate) fn unit(name: &str, what: &str, v: Vector3<f64>) -> Result<Vector3<f64>, ConstraintError> {
    direction_and_length(v)
        .map(|(unit, _)| unit)
        .ok_or_else(|| ConstraintError::InvalidParameter {
            name: name.to_owned(),
            reason: format!("{what} {v:?} has no direction"),
        })
}

/// Two unit vectors completing `axis` (unit) to a right-handed orthonormal frame.
pub(crate) fn normals_to(axis: Vector3<f64>) -> [Vector3<f64>; 2] {
    // Cross with the coordinate axis least aligned with `axis`, for a well-conditioned first normal.
    let least = axis.iamin();
    let first = axis.cross(&Vector3::ith(least, 1.0)).normalize();
    [first, axis.cross(&first)]
}

/// The coordinate axes e₁, e₂, e₃: the forces of a ball joint.
pub(super) fn coordinate_axes() -> ArrayVec<Vector3<f64>, 3> {
    (0..3).map(|k| Vector3::ith(k, 1.0)).collect()
}

impl<A: Algebra> VirtualPower<A> {
    /// The general form of theory §6: user wrenches `T_k(t)` with their derivatives and prescribed powers, static in
    /// the body's state. Rank = the number of wrenches (they must be independent). No position residual.
    ///
    /// A body held by one vertical force line through its centre of mass: the reaction cancels its weight, so at
    /// rest it does not accelerate. Such a constraint has no position residual, so its mechanism is not stabilised
    /// by projection (the default).
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower, WrenchPoint};
    /// use dynamics::{forces::force_line, Algebra, Body, Force, Mechanism, Pga, Stabilisation, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let vertical = WrenchPoint::<Pga>::fixed(force_line::<Pga>(Vector3::z(), Vector3::zeros()));
    /// let held = VirtualPower::from_wrenches("held up", [move |_t: f64| vertical]);
    /// assert_eq!((held.rank(), held.has_position_residual()), (1, false));
    /// let ball = Body::sphere(2.0, 0.1)?;
    /// let unstabilised = Mechanism::single(ball).with_stabilisation(Stabilisation::None)?;
    /// let system = unstabilised.with_force(Force::gravity())?.with_constraint(held)?;
    /// let still = UnitQuaternion::identity();
    /// let at_rest = State::new(&ball, Vector3::zeros(), &still, Vector3::zeros(), Vector3::zeros());
    /// let rate = Pga::screw_coordinates(system.rates_at(0.0, &[at_rest])?[0].momentum_rate);
    /// assert!(rate.l.norm() < 1e-12 && rate.t.norm() < 1e-12); // N, N m
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_wrenches<W: WrenchPath<A> + 'static>(
        name: impl Into<String>,
        wrenches: impl IntoIterator<Item = W>,
    ) -> Self {
        VirtualPower {
            name: name.into(),
            wrenches: Wrenches::Custom(
                wrenches
                    .into_iter()
                    .map(|wrench| Arc::new(wrench) as Arc<dyn WrenchPath<A>>)
                    .collect(),
            ),
        }
    }

    /// The constraint wrenches at this state, in row order.
    pub fn wrenches(
        &self,
        kinematics: &Kinematics<A>,
        mut emit: impl FnMut(ConstraintWrench<A>),
    ) -> Result<(), ConstraintError> {
        match &self.wrenches {
            Wrenches::Point {
                body_point,
                point,
                forces,
                alignments,
                ..
            } => {
                let a = kinematics.world_point(body_point);
                let velocity = kinematics.world_point_velocity(body_point);
                let p = point.at(kinematics.t);
                let offset = a - p.value;
                for force in forces {
                    emit(ConstraintWrench {
                        wrench: force_line::<A>(*force, a),
                        // d/dt (f, a⨯f) with f constant.
                        rate: couple::<A>(velocity.cross(force)),
                        prescribed_power: force.dot(&p.rate),
                        prescribed_power_rate: force.dot(&p.acceleration),
                        position_residual: Some(force.dot(&offset)),
                    });
                }
                for alignment in alignments {
                    let d = kinematics.world_direction(&alignment.body_direction);
                    let d_rate = kinematics.angular_velocity.cross(&d);
                    emit(ConstraintWrench {
                        wrench: couple::<A>(d.cross(&alignment.normal)),
                        rate: couple::<A>(d_rate.cross(&alignment.normal)),
                        prescribed_power: 0.0,
                        prescribed_power_rate: 0.0,
                        position_residual: Some(alignment.normal.dot(&d)),
                    });
                }
            }
            Wrenches::Sphere {
                body_point,
                centre,
                radius,
            } => {
                let a = kinematics.world_point(body_point);
                let a_rate = kinematics.world_point_velocity(body_point);
                let PathPoint {
                    value: c,
                    rate: c_rate,
                    acceleration: c_acceleration,
                } = centre.at(kinematics.t);
                let inward = c - a;
                // T = force_line(c − a, a) = (c − a; a⨯c), the dual line (A∧up(c)∧n∞)I₅ of theory §6 (E4);
                // e = ½(ρ² − |a − c|²) has rate (c − a)·ȧ − (c − a)·ċ = P − s.
                emit(ConstraintWrench {
                    wrench: force_line::<A>(inward, a),
                    rate: A::screw(ScrewCoordinates {
                        l: c_rate - a_rate,
                        t: a_rate.cross(&c) + a.cross(&c_rate),
                    }),
                    prescribed_power: inward.dot(&c_rate),
                    prescribed_power_rate: (c_rate - a_rate).dot(&c_rate) + inward.dot(&c_acceleration),
                    position_residual: Some(0.5 * (radius * radius - inward.norm_squared())),
                });
            }
            Wrenches::Surfaces { body_point, surfaces } => {
                let a = kinematics.world_point(body_point);
                let a_rate = kinematics.world_point_velocity(body_point);
                each_surface_at(&self.name, surfaces, (&a, &a_rate), |at| {
                    // n = ∇F/|∇F| has rate ṅ = (I − n nᵀ) H ȧ / |∇F|; the force line (n; a × n) has rate
                    // (ṅ; ȧ × n + a × ṅ), and F/|∇F| has rate n · ȧ where F = 0 (docs/surfaces.md §6).
                    let normal = at.gradient / at.length;
                    let normal_rate = (at.bending - normal * normal.dot(&at.bending)) / at.length;
                    emit(ConstraintWrench {
                        wrench: force_line::<A>(normal, a),
                        rate: A::screw(ScrewCoordinates {
                            l: normal_rate,
                            t: a_rate.cross(&normal) + a.cross(&normal_rate),
                        }),
                        prescribed_power: 0.0,
                        prescribed_power_rate: 0.0,
                        position_residual: Some(at.value / at.length),
                    });
                })?;
            }
            Wrenches::Motor(path) => {
                let prescribed = path.at(kinematics.t);
                let error = A::screw_coordinates(log::<A>(A::compose(A::reverse(prescribed.motor), kinematics.motor)));
                let (xi, xi_rate) = (
                    A::screw_coordinates(prescribed.velocity),
                    A::screw_coordinates(prescribed.acceleration),
                );
                // Unit wrench k of the body frame, in (τ; f) order: couples about the body axes, then forces along
                // them through the body origin; its world view R T_b ~R has rate R(T_b × Ḃ)~R.
                for k in 0..6 {
                    let mut unit = ScrewCoordinates::default();
                    let (power, power_rate, residual) = if k < 3 {
                        unit.t[k] = 1.0;
                        (xi.l[k], xi_rate.l[k], -2.0 * error.l[k])
                    } else {
                        unit.l[k - 3] = 1.0;
                        (xi.t[k - 3], xi_rate.t[k - 3], -2.0 * error.t[k - 3])
                    };
                    let body = A::screw(unit);
                    emit(ConstraintWrench {
                        wrench: kinematics.to_world(body),
                        rate: kinematics.to_world(A::commutator(body, kinematics.body_velocity)),
                        prescribed_power: power,
                        prescribed_power_rate: power_rate,
                        position_residual: Some(residual),
                    });
                }
            }
            Wrenches::Custom(wrenches) => {
                for wrench in wrenches {
                    let point = wrench.at(kinematics.t);
                    emit(ConstraintWrench {
                        wrench: point.wrench,
                        rate: point.rate,
                        prescribed_power: point.power,
                        prescribed_power_rate: point.power_rate,
                        position_residual: None,
                    });
                }
            }
        }
        Ok(())
    }
}

impl<A: Algebra> Constraint<A> for VirtualPower<A> {
    fn name(&self) -> &str {
        &self.name
    }

    fn rank(&self) -> usize {
        self.row_count()
    }

    fn row_count(&self) -> usize {
        match &self.wrenches {
            Wrenches::Point { forces, alignments, .. } => forces.len() + alignments.len(),
            Wrenches::Sphere { .. } => 1,
            Wrenches::Surfaces { surfaces, .. } => surfaces.len(),
            Wrenches::Motor(_) => 6,
            Wrenches::Custom(wrenches) => wrenches.len(),
        }
    }

    fn has_position_residual(&self) -> bool {
        !matches!(self.wrenches, Wrenches::Custom(_))
    }

    /// Only a motor joint compares motors; the others read the frame and velocities.
    fn uses_motor(&self) -> bool {
        matches!(self.wrenches, Wrenches::Motor(_))
    }

    fn rows(&self, kinematics: &Kinematics<A>, rows: &mut RowBuffer) -> Result<(), ConstraintError> {
        if let Wrenches::Point {
            body_point,
            point,
            forces,
            along_axes,
            fixed,
            alignments,
        } = &self.wrenches
        {
            let p = match fixed {
                Some(value) => PathPoint::at_rest(*value),
                None => point.at(kinematics.t),
            };
            point_rows(kinematics, body_point, &p, (forces, *along_axes), alignments, rows);
            return Ok(());
        }
        self.wrenches(kinematics, |w| rows.push(wrench_row(kinematics, &w)))
    }
}

/// The row of a world constraint wrench: its body-frame covector, the velocity residual `⟨Ḃ ∧ T⟩_Π − s` and the
/// bias `⟨Ḃ_w ∧ Ṫ⟩_Π − ṡ`.
fn wrench_row<A: Algebra>(kinematics: &Kinematics<A>, w: &ConstraintWrench<A>) -> ConstraintRow {
    let body = kinematics.to_body_coordinates(&A::screw_coordinates(w.wrench));
    // Wrench coordinates (τ; f) pair with velocity coordinates (ω; v) to the power (theory §3).
    let jacobian = [body.t.x, body.t.y, body.t.z, body.l.x, body.l.y, body.l.z];
    let power: f64 = jacobian
        .iter()
        .zip(kinematics.velocity.iter())
        .map(|(a, x)| a * x)
        .sum();
    ConstraintRow {
        jacobian,
        velocity_residual: power - w.prescribed_power,
        bias: A::wedge_pi(kinematics.world_velocity, w.rate) - w.prescribed_power_rate,
        position_residual: w.position_residual,
    }
}

/// The rows of the point wrenches ([`VirtualPower::wrenches`], `Wrenches::Point`) written directly in the body
/// frame — the same numbers as moving each world wrench to the body, at a fraction of the cost (these joints are
/// the hot path of every mechanism). With `Q` the body's rotation, `a = c + Q p_b` the joint point, `ȧ` its
/// velocity and ω the angular velocity (world):
/// * a force f through a is the wrench `(f; a⨯f)`; in the body frame `(Qᵀf; p_b⨯Qᵀf)`, i.e. the covector
///   `(τ; f) = (p_b⨯f_b; f_b)`. Its rate is the couple `ȧ⨯f`, whose power with the twist is `ω·(ȧ⨯f) = f·(ω⨯ȧ)`:
///   the bias. Residual `f·(a − p)`, prescribed power `f·ṗ`, its rate `f·p̈`.
/// * a couple `d⨯n` (body direction d, reference normal n) is `(d_b⨯n_b; 0)` in the body frame; its rate is the
///   couple `ḋ⨯n` with `ḋ = ω⨯d`, bias `ω·(ḋ⨯n)`. Residual `n·d`.
///
/// Forces along the world axes (`along_axes`: ball joints and hinges) are read off the rotation, `f_b = Qᵀe_k`
/// being row k of Q, and `f·y` being y's k-th coordinate: the same numbers as the general products, without them.
fn point_rows<A: Algebra>(
    kinematics: &Kinematics<A>,
    body_point: &Vector3<f64>,
    p: &PathPoint<Vector3<f64>>,
    (forces, along_axes): (&[Vector3<f64>], bool),
    alignments: &[Alignment],
    rows: &mut RowBuffer,
) {
    let rotation = &kinematics.frame.rotation;
    let x = &kinematics.velocity;
    let omega = kinematics.angular_velocity;
    let a = kinematics.world_point(body_point);
    let a_rate = kinematics.world_point_velocity(body_point);
    let offset = a - p.value;
    let turning = omega.cross(&a_rate);
    let power = |jacobian: &[f64; 6]| -> f64 { jacobian.iter().zip(x.iter()).map(|(j, x)| j * x).sum() };
    let force_row = |f: Vector3<f64>, rate: f64, bias: f64, residual: f64| -> ConstraintRow {
        let moment = body_point.cross(&f);
        let jacobian = [moment.x, moment.y, moment.z, f.x, f.y, f.z];
        ConstraintRow {
            velocity_residual: power(&jacobian) - rate,
            bias,
            position_residual: Some(residual),
            jacobian,
        }
    };
    if along_axes {
        let q = rotation.matrix();
        for k in 0..3 {
            let f = Vector3::new(q[(k, 0)], q[(k, 1)], q[(k, 2)]);
            rows.push(force_row(f, p.rate[k], turning[k] - p.acceleration[k], offset[k]));
        }
    } else {
        for force in forces {
            let f = rotation.inverse_transform_vector(force);
            let bias = force.dot(&turning) - force.dot(&p.acceleration);
            rows.push(force_row(f, force.dot(&p.rate), bias, force.dot(&offset)));
        }
    }
    for alignment in alignments {
        let d = kinematics.world_direction(&alignment.body_direction);
        let moment = alignment
            .body_direction
            .cross(&rotation.inverse_transform_vector(&alignment.normal));
        let jacobian = [moment.x, moment.y, moment.z, 0.0, 0.0, 0.0];
        rows.push(ConstraintRow {
            velocity_residual: power(&jacobian),
            bias: omega.dot(&omega.cross(&d).cross(&alignment.normal)),
            position_residual: Some(alignment.normal.dot(&d)),
            jacobian,
        });
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::UnitQuaternion;

    use super::*;
    use crate::{motor, Cga, Pga};

    /// The body-frame rows of point wrenches equal the world wrenches moved to the body, for a ball joint on a
    /// moving pivot, a hinge and a prismatic joint at random poses and velocities, in both algebras.
    fn point_rows_are_the_moved_wrenches<A: Algebra>() {
        let mut uniform = crate::test_random::uniform(0x2545_f491_4f6c_dd1d_u64);
        let mut next = || uniform() * 4.0 - 2.0;
        let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
        let pivot = |t: f64| PathPoint {
            value: Vector3::new(t.sin(), 0.5, -t),
            rate: Vector3::new(t.cos(), 0.0, -1.0),
            acceleration: Vector3::new(-t.sin(), 0.0, 0.0),
        };
        let joints: [VirtualPower<A>; 3] = [
            VirtualPower::driven_ball_joint("ball", Vector3::new(0.1, -0.2, 0.4), pivot),
            VirtualPower::hinge(
                "hinge",
                (Vector3::new(0.0, 0.3, 0.1), y),
                (Vector3::new(1.0, 0.0, 0.2), x + z),
            )
            .unwrap(),
            VirtualPower::prismatic("slider", (Vector3::zeros(), x, z), (Vector3::new(0.2, 0.1, 0.0), y, z)).unwrap(),
        ];
        for _ in 0..50 {
            let mut vector = || Vector3::new(next(), next(), next());
            let motor = motor::from_pose::<A>(vector(), &UnitQuaternion::from_scaled_axis(vector()));
            let velocity = A::screw(ScrewCoordinates {
                l: vector(),
                t: vector(),
            });
            let kinematics = Kinematics::<A>::new(next(), motor, velocity);
            for joint in &joints {
                let mut fast = RowBuffer::new();
                joint.rows(&kinematics, &mut fast).unwrap();
                let mut moved = Vec::new();
                joint
                    .wrenches(&kinematics, |w| moved.push(wrench_row(&kinematics, &w)))
                    .unwrap();
                assert_eq!(fast.rows().len(), moved.len());
                for (a, b) in fast.rows().iter().zip(&moved) {
                    let difference = a
                        .jacobian
                        .iter()
                        .zip(&b.jacobian)
                        .map(|(p, q)| (p - q).abs())
                        .fold(0.0, f64::max)
                        + (a.velocity_residual - b.velocity_residual).abs()
                        + (a.bias - b.bias).abs()
                        + (a.position_residual.unwrap() - b.position_residual.unwrap()).abs();
                    assert!(difference < 1e-13, "{}: {a:?} vs {b:?}", joint.name);
                }
            }
        }
    }

    #[test]
    fn point_rows_are_the_moved_wrenches_in_both_algebras() {
        point_rows_are_the_moved_wrenches::<Pga>();
        point_rows_are_the_moved_wrenches::<Cga>();
    }
}
