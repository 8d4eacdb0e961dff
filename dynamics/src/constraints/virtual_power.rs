//! Constraints by virtual power (SPEC §6): a set of constraint wrenches `T_k(t)` (world frame, bivectors)
//! spanning the reactions the constraint can exert. With `T_bk = ~R T_k R`:
//!
//! * velocity condition `P_k = ⟨Ḃ ∧ T_bk⟩_Π = s_k` (`s_k = 0` unless the constraint moves, see below);
//! * acceleration condition `⟨B̈ ∧ T_bk⟩_Π + ⟨Ḃ ∧ (Ḃ × T_bk + ~R Ṫ_k R)⟩_Π = ṡ_k`.
//!
//! So each wrench is one row with Jacobian `a = (τ; f)` of `T_bk` and bias `⟨Ḃ ∧ ~RṪ_kR⟩_Π − ṡ_k`: the term
//! `⟨Ḃ ∧ (Ḃ × T_bk)⟩_Π` vanishes identically because the Π-pairing is invariant under the commutator
//! (`⟨X ∧ (Z×Y)⟩_Π = −⟨(Z×X) ∧ Y⟩_Π`, and `Ḃ × Ḃ = 0`), and `⟨Ḃ ∧ ~RṪR⟩_Π = ⟨Ḃ_w ∧ Ṫ⟩_Π` is evaluated in
//! the world frame. The reaction is `F = Σλ_k T_bk` (d'Alembert, E6), which is exactly the kinetic-metric
//! solution of [`crate::constraints::solve`] for these rows.
//!
//! The wrenches are all *dual* lines `force_line(f, a) = f I₃ − (a∧f) I₃ N` — bivectors in both algebras —
//! never the OPNS line `A∧V∧n∞` itself (E4). The catalogue places the forces at the constrained body point A
//! (world position a) and the couples along directions that follow the body, so that each row's power is
//! exactly the rate of a position residual e (on the manifold these are the SPEC's wrenches): projection and
//! Baumgarte's β term then apply to virtual power as well (SPEC §10 notes that the bare method has no
//! position-level residual; [`VirtualPower::from_wrenches`] has none).
//!
//! A moving constraint (the sphere with centre c(t)) does work: its velocity condition is `P = s` with the
//! prescribed power `s = (c − a)·ċ`.

use std::sync::Arc;

use nalgebra::Vector3;

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::kinematics::Kinematics;
use crate::constraints::paths::{Fixed, FunctionPath, Path, PathPoint};
use crate::constraints::rows::{ConstraintRow, RowBuffer};
use crate::constraints::{Composite, Constraint, ConstraintError};
use crate::forces::{couple, force_line};

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

/// A user wrench `t ↦ (T(t), Ṫ(t))` (world frame, independent of the state).
pub type WrenchPath<A> = Arc<dyn Fn(f64) -> (<A as Algebra>::Screw, <A as Algebra>::Screw) + Send + Sync>;

#[derive(Clone)]
enum Wrenches<A: Algebra> {
    /// Forces along e₁, e₂, e₃ at the body point; residual a − p(t). A moving pivot prescribes the power
    /// `ṗₖ` of force k (the body point must move with it).
    Ball {
        body_point: Vector3<f64>,
        pivot: Arc<dyn Path<Vector3<f64>>>,
    },
    /// The ball joint's three forces, or (`axial_force: false`) only the two normal to the axis, plus two
    /// couples normal to the axis.
    Axis {
        body_point: Vector3<f64>,
        world_point: Vector3<f64>,
        body_axis: Vector3<f64>,
        normals: [Vector3<f64>; 2],
        axial_force: bool,
    },
    /// One force along the plane normal at the body point; residual n·a − δ.
    Plane {
        body_point: Vector3<f64>,
        normal: Vector3<f64>,
        offset: f64,
    },
    /// One force from the body point towards the centre; residual ½(ρ² − |a − c|²).
    Sphere {
        body_point: Vector3<f64>,
        centre: Arc<dyn Path<Vector3<f64>>>,
        radius: f64,
    },
    /// User wrenches, no position residual.
    Custom(Vec<WrenchPath<A>>),
}

/// A constraint by virtual power (see the module docs).
#[derive(Clone)]
pub struct VirtualPower<A: Algebra> {
    name: String,
    wrenches: Wrenches<A>,
}

impl<A: Algebra> std::fmt::Debug for VirtualPower<A> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VirtualPower")
            .field("name", &self.name)
            .field("rank", &self.rank())
            .finish_non_exhaustive()
    }
}

fn unit(name: &str, what: &str, v: Vector3<f64>) -> Result<Vector3<f64>, ConstraintError> {
    v.try_normalize(0.0)
        .filter(|u| u.iter().all(|c| c.is_finite()))
        .ok_or_else(|| ConstraintError::InvalidParameter {
            name: name.to_owned(),
            reason: format!("{what} {v:?} has no direction"),
        })
}

/// Two unit vectors completing `axis` (unit) to a right-handed orthonormal frame.
fn normals_to(axis: Vector3<f64>) -> [Vector3<f64>; 2] {
    // Cross with the coordinate axis least aligned with `axis`, for a well-conditioned first normal.
    let least = axis.iamin();
    let first = axis.cross(&Vector3::ith(least, 1.0)).normalize();
    [first, axis.cross(&first)]
}

impl<A: Algebra> VirtualPower<A> {
    /// Ball joint: the body point `body_point` (body coordinates) stays at `world_point`. Rank 3.
    pub fn ball_joint(name: impl Into<String>, body_point: Vector3<f64>, world_point: Vector3<f64>) -> Self {
        VirtualPower {
            name: name.into(),
            wrenches: Wrenches::Ball {
                body_point,
                pivot: Arc::new(Fixed(world_point)),
            },
        }
    }

    /// A driven ball joint: the body point stays at a pivot moving along `pivot(t)` (value, velocity,
    /// acceleration, world or reference frame). The pivot's motion does work: force k's velocity condition is
    /// `⟨Ḃ ∧ T_bk⟩_Π = ṗₖ`, the prescribed power of the driven motion (SPEC §14.1). Rank 3.
    pub fn driven_ball_joint<F>(name: impl Into<String>, body_point: Vector3<f64>, pivot: F) -> Self
    where
        F: Fn(f64) -> PathPoint<Vector3<f64>> + Send + Sync + 'static,
    {
        VirtualPower {
            name: name.into(),
            wrenches: Wrenches::Ball {
                body_point,
                pivot: Arc::new(FunctionPath(pivot)),
            },
        }
    }

    /// Hinge: a ball joint at the point plus two couples normal to the axis, so the body turns only about
    /// the world axis through `world_point`; `body_axis` is the axis in body coordinates. Rank 5.
    pub fn hinge(
        name: impl Into<String>,
        (body_point, body_axis): (Vector3<f64>, Vector3<f64>),
        (world_point, world_axis): (Vector3<f64>, Vector3<f64>),
    ) -> Result<Self, ConstraintError> {
        Self::axis_joint(name.into(), (body_point, body_axis), (world_point, world_axis), true)
    }

    /// Cylindrical joint: two forces normal to the axis at the body point plus two couples normal to the axis,
    /// so the body slides along and turns about the world axis. Rank 4.
    pub fn cylindrical(
        name: impl Into<String>,
        (body_point, body_axis): (Vector3<f64>, Vector3<f64>),
        (world_point, world_axis): (Vector3<f64>, Vector3<f64>),
    ) -> Result<Self, ConstraintError> {
        Self::axis_joint(name.into(), (body_point, body_axis), (world_point, world_axis), false)
    }

    fn axis_joint(
        name: String,
        (body_point, body_axis): (Vector3<f64>, Vector3<f64>),
        (world_point, world_axis): (Vector3<f64>, Vector3<f64>),
        axial_force: bool,
    ) -> Result<Self, ConstraintError> {
        let body_axis = unit(&name, "body axis", body_axis)?;
        let world_axis = unit(&name, "world axis", world_axis)?;
        Ok(VirtualPower {
            name,
            wrenches: Wrenches::Axis {
                body_point,
                world_point,
                body_axis,
                normals: normals_to(world_axis),
                axial_force,
            },
        })
    }

    /// The body point stays on the world plane `{x : normal·x = offset}`. Rank 1.
    pub fn point_on_plane(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        (normal, offset): (Vector3<f64>, f64),
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        let length = normal.norm();
        let normal = unit(&name, "plane normal", normal)?;
        Ok(VirtualPower {
            name,
            wrenches: Wrenches::Plane {
                body_point,
                normal,
                offset: offset / length,
            },
        })
    }

    /// The body point stays on the sphere `|a − centre| = radius`. Rank 1.
    pub fn point_on_sphere(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        centre: Vector3<f64>,
        radius: f64,
    ) -> Result<Self, ConstraintError> {
        Self::point_on_moving_sphere(name, body_point, Arc::new(Fixed(centre)), radius)
    }

    /// The body point stays on a sphere whose centre follows `centre` (value, velocity, acceleration). Rank 1.
    pub fn point_on_moving_sphere(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        centre: Arc<dyn Path<Vector3<f64>>>,
        radius: f64,
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        if !(radius.is_finite() && radius > 0.0) {
            return Err(ConstraintError::InvalidParameter {
                name,
                reason: format!("sphere radius {radius} is not positive"),
            });
        }
        Ok(VirtualPower {
            name,
            wrenches: Wrenches::Sphere {
                body_point,
                centre,
                radius,
            },
        })
    }

    /// The body point stays on the circle of `radius` about `centre` in the plane with `normal`: a sphere plus
    /// a plane through its centre (SPEC §6). Rank 2.
    pub fn point_on_circle(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        (centre, radius, normal): (Vector3<f64>, f64, Vector3<f64>),
    ) -> Result<Composite<A>, ConstraintError> {
        let name = name.into();
        let sphere = Self::point_on_sphere(format!("{name}: sphere"), body_point, centre, radius)?;
        let plane = Self::point_on_plane(format!("{name}: plane"), body_point, (normal, normal.dot(&centre)))?;
        Ok(Composite::new(name, vec![Arc::new(sphere), Arc::new(plane)], 2))
    }

    /// The SPEC's general form: user wrenches `T_k(t)` with their derivatives, static in the body's state.
    /// Rank = the number of wrenches (they must be independent). No position residual.
    pub fn from_wrenches(name: impl Into<String>, wrenches: Vec<WrenchPath<A>>) -> Self {
        VirtualPower {
            name: name.into(),
            wrenches: Wrenches::Custom(wrenches),
        }
    }

    /// The constraint wrenches at this state, in row order.
    pub fn wrenches(&self, kinematics: &Kinematics<A>, mut emit: impl FnMut(ConstraintWrench<A>)) {
        let force_at = |force: Vector3<f64>, point: Vector3<f64>, point_velocity: Vector3<f64>, residual| {
            ConstraintWrench {
                wrench: force_line::<A>(force, point),
                // d/dt (f, a⨯f) with f constant.
                rate: couple::<A>(point_velocity.cross(&force)),
                prescribed_power: 0.0,
                prescribed_power_rate: 0.0,
                position_residual: Some(residual),
            }
        };
        match &self.wrenches {
            Wrenches::Ball { body_point, pivot } => {
                let a = kinematics.world_point(body_point);
                let velocity = kinematics.world_point_velocity(body_point);
                let p = pivot.at(kinematics.t);
                for k in 0..3 {
                    let direction = Vector3::ith(k, 1.0);
                    emit(ConstraintWrench {
                        prescribed_power: p.rate[k],
                        prescribed_power_rate: p.acceleration[k],
                        ..force_at(direction, a, velocity, a[k] - p.value[k])
                    });
                }
            }
            Wrenches::Axis {
                body_point,
                world_point,
                body_axis,
                normals,
                axial_force,
            } => {
                let a = kinematics.world_point(body_point);
                let velocity = kinematics.world_point_velocity(body_point);
                if *axial_force {
                    for k in 0..3 {
                        let direction = Vector3::ith(k, 1.0);
                        emit(force_at(direction, a, velocity, a[k] - world_point[k]));
                    }
                } else {
                    for normal in normals {
                        emit(force_at(*normal, a, velocity, normal.dot(&(a - world_point))));
                    }
                }
                // The world image b of the body axis should stay along the world axis: residuals wⱼ·b for the
                // two world normals wⱼ. Their rates wⱼ·(ω⨯b) = ω·(b⨯wⱼ) are the powers of the couples b⨯wⱼ
                // (= the SPEC's couples normal to the axis when b is on the axis).
                let b = kinematics.world_direction(body_axis);
                let b_rate = kinematics.angular_velocity.cross(&b);
                for normal in normals {
                    emit(ConstraintWrench {
                        wrench: couple::<A>(b.cross(normal)),
                        rate: couple::<A>(b_rate.cross(normal)),
                        prescribed_power: 0.0,
                        prescribed_power_rate: 0.0,
                        position_residual: Some(normal.dot(&b)),
                    });
                }
            }
            Wrenches::Plane {
                body_point,
                normal,
                offset,
            } => {
                let a = kinematics.world_point(body_point);
                let velocity = kinematics.world_point_velocity(body_point);
                emit(force_at(*normal, a, velocity, normal.dot(&a) - offset));
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
                // T = force_line(c − a, a) = (c − a; a⨯c), the SPEC's (A∧up(c)∧n∞)I₅; e = ½(ρ² − |a − c|²) has
                // rate (c − a)·ȧ − (c − a)·ċ = P − s.
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
            Wrenches::Custom(wrenches) => {
                for wrench in wrenches {
                    let (wrench, rate) = wrench(kinematics.t);
                    emit(ConstraintWrench {
                        wrench,
                        rate,
                        prescribed_power: 0.0,
                        prescribed_power_rate: 0.0,
                        position_residual: None,
                    });
                }
            }
        }
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
            Wrenches::Ball { .. } => 3,
            Wrenches::Axis { axial_force, .. } => {
                if *axial_force {
                    5
                } else {
                    4
                }
            }
            Wrenches::Plane { .. } | Wrenches::Sphere { .. } => 1,
            Wrenches::Custom(wrenches) => wrenches.len(),
        }
    }

    fn has_position_residual(&self) -> bool {
        !matches!(self.wrenches, Wrenches::Custom(_))
    }

    fn rows(&self, kinematics: &Kinematics<A>, rows: &mut RowBuffer) -> Result<(), ConstraintError> {
        self.wrenches(kinematics, |w| {
            let body = kinematics.to_body_coordinates(&A::screw_coordinates(w.wrench));
            // Wrench coordinates (τ; f) pair with velocity coordinates (ω; v) to the power (SPEC §3).
            let jacobian = [body.t.x, body.t.y, body.t.z, body.l.x, body.l.y, body.l.z];
            let power: f64 = jacobian
                .iter()
                .zip(kinematics.velocity.iter())
                .map(|(a, x)| a * x)
                .sum();
            rows.push(ConstraintRow {
                jacobian,
                velocity_residual: power - w.prescribed_power,
                bias: A::wedge_pi(kinematics.world_velocity, w.rate) - w.prescribed_power_rate,
                position_residual: w.position_residual,
            });
        });
        Ok(())
    }
}
