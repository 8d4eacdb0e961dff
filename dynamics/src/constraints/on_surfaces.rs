//! A body point held on a surface (rank 1) or on the curve where two surfaces meet (rank 2), by pinning
//! (`docs/surfaces.md` §6): the incidence `F(a) = X(a) · Q` of the embedded point with each surface is pinned to
//! zero, and its rows are its derivatives along the motion. The virtual-power form of the same constraint,
//! [`crate::constraints::VirtualPower::point_on_surface`], shares the surfaces and the checks made here.
//!
//! With a the point in the reference frame, ȧ its velocity and ω the angular velocity (reference frame):
//!
//! ```text
//! e = F(a)
//! ė = ∇F · ȧ                        body covector (p_b × g_b; g_b), g_b = Rᵀ∇F
//! ë = ∇F · ä + ȧ · H ȧ              bias ∇F · (ω × ȧ) + ȧ · H ȧ
//! ```

use arrayvec::ArrayVec;
use nalgebra::Vector3;

use crate::algebra::Algebra;
use crate::constraints::kinematics::Kinematics;
use crate::constraints::rows::{ConstraintRow, RowBuffer};
use crate::constraints::{Constraint, ConstraintError};
use crate::surfaces::Surface;

/// The sine of the angle between two surfaces' normals below which they count as tangent: the curve's two rows
/// have lost rank (`docs/surfaces.md` §5).
pub const TANGENT: f64 = 1e-6;

/// One surface at the held point a moving at ȧ: `F`, `∇F`, `|∇F|` and `H ȧ`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SurfaceAt {
    pub value: f64,
    pub gradient: Vector3<f64>,
    pub length: f64,
    pub bending: Vector3<f64>,
}

/// Calls `row` with each surface at the reference-frame point `a` moving at `a_rate`, checked: an error naming the
/// constraint at a singular point of a surface (no normal) or where the two surfaces of a curve are tangent.
#[inline(always)]
pub(crate) fn each_surface_at(
    name: &str,
    surfaces: &[Surface],
    (a, a_rate): (&Vector3<f64>, &Vector3<f64>),
    mut row: impl FnMut(SurfaceAt),
) -> Result<(), ConstraintError> {
    let mut first_normal: Option<Vector3<f64>> = None;
    for surface in surfaces {
        let (value, gradient, bending) = surface.terms(a, a_rate);
        let length = gradient.norm();
        if surface.is_singular(length) {
            return Err(no_normal(name, a, length));
        }
        if surfaces.len() == 2 {
            let normal = gradient / length;
            match first_normal {
                None => first_normal = Some(normal),
                Some(first) => {
                    let sine = normal.cross(&first).norm();
                    if sine.is_nan() || sine <= TANGENT {
                        return Err(tangent(name, a, sine));
                    }
                }
            }
        }
        row(SurfaceAt {
            value,
            gradient,
            length,
            bending,
        });
    }
    Ok(())
}

#[cold]
fn no_normal(name: &str, a: &Vector3<f64>, length: f64) -> ConstraintError {
    ConstraintError::Singular {
        name: name.to_owned(),
        reason: format!("the surface has no normal at {a:?} (a singular point, gradient {length:e})"),
    }
}

#[cold]
fn tangent(name: &str, a: &Vector3<f64>, sine: f64) -> ConstraintError {
    ConstraintError::Singular {
        name: name.to_owned(),
        reason: format!(
            "the two surfaces are tangent at {a:?} (normals at sine {sine:e}): the curve's rows have rank 1"
        ),
    }
}

/// Checks the body point of a constraint called `name`: finite and within [`crate::state::LARGEST_COORDINATE`].
pub(crate) fn check_held_point(name: &str, body_point: &Vector3<f64>) -> Result<(), ConstraintError> {
    let largest = crate::state::LARGEST_COORDINATE;
    if !body_point.iter().all(|x| x.is_finite() && x.abs() <= largest) {
        return Err(ConstraintError::InvalidParameter {
            name: name.to_owned(),
            reason: format!("the body point {body_point:?} must be finite and within {largest:e} m"),
        });
    }
    Ok(())
}

/// A body point pinned to one surface or to the curve of two (see the module docs).
#[derive(Clone, Debug)]
pub struct SurfacePin {
    name: String,
    body_point: Vector3<f64>,
    surfaces: ArrayVec<Surface, 2>,
}

impl SurfacePin {
    /// The body point `body_point` (body coordinates, m) stays on `surface` (reference frame). Rank 1.
    ///
    /// A bead on a torus of radii 1 and 0.25 m: on its outer equator and moving along it, both residuals vanish.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, SurfacePin};
    /// use dynamics::surfaces::Surface;
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ring = Surface::torus(Vector3::zeros(), Vector3::z(), 1.0, 0.25)?;
    /// let on_ring = SurfacePin::point_on_surface("bead", Vector3::zeros(), ring)?;
    /// assert_eq!((Constraint::<Pga>::rank(&on_ring), Constraint::<Pga>::row_count(&on_ring)), (1, 1));
    /// let bead = Body::sphere(0.1, 0.01)?;
    /// let system = Mechanism::<Pga>::single(bead).with_constraint(on_ring)?;
    /// let at = Vector3::new(1.25, 0.0, 0.0); // m
    /// let state = State::new(&bead, at, &UnitQuaternion::identity(), Vector3::zeros(), Vector3::y()); // 1 m/s along y
    /// let on = system.violation(0.0, &[state])?;
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn point_on_surface(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        surface: Surface,
    ) -> Result<Self, ConstraintError> {
        Self::new(name.into(), body_point, &[surface])
    }

    /// The body point stays on the curve where `surfaces` meet: an ellipse as an ellipsoid cut by a plane, a circle
    /// of a torus cut by a plane or a cylinder. Rank 2. Where the surfaces are tangent the rows lose rank, an error
    /// naming the constraint.
    ///
    /// The top circle of a torus of radii 1 and 0.25 m, as the torus cut by the plane z = 0.25 m (where they are
    /// tangent: the torus's top) is refused; cut by the cylinder of radius 1 m it is the same circle, and holds.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, SurfacePin};
    /// use dynamics::surfaces::Surface;
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{Isometry3, UnitQuaternion, Vector2, Vector3};
    ///
    /// let ring = Surface::torus(Vector3::zeros(), Vector3::z(), 1.0, 0.25)?;
    /// let can = Surface::elliptic_cylinder(Vector2::new(1.0, 1.0), &Isometry3::identity())?;
    /// let top = SurfacePin::point_on_curve("top circle", Vector3::zeros(), [ring, can])?;
    /// let bead = Body::sphere(0.1, 0.01)?;
    /// let system = Mechanism::<Pga>::single(bead).with_constraint(top)?;
    /// let still = UnitQuaternion::identity();
    /// let state = State::new(&bead, Vector3::new(0.0, 1.0, 0.25), &still, Vector3::zeros(), Vector3::x());
    /// assert!(system.violation(0.0, &[state])?.position < 1e-15);
    /// let lid = Surface::plane(Vector3::z(), 0.25)?;
    /// let tangent = SurfacePin::point_on_curve("lid", Vector3::zeros(), [ring, lid])?;
    /// let touching = Mechanism::<Pga>::single(bead).with_constraint(tangent)?;
    /// assert!(touching.violation(0.0, &[state]).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn point_on_curve(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        surfaces: [Surface; 2],
    ) -> Result<Self, ConstraintError> {
        Self::new(name.into(), body_point, &surfaces)
    }

    fn new(name: String, body_point: Vector3<f64>, surfaces: &[Surface]) -> Result<Self, ConstraintError> {
        check_held_point(&name, &body_point)?;
        Ok(SurfacePin {
            name,
            body_point,
            surfaces: surfaces.iter().copied().collect(),
        })
    }
}

impl<A: Algebra> Constraint<A> for SurfacePin {
    fn name(&self) -> &str {
        &self.name
    }

    fn rank(&self) -> usize {
        self.surfaces.len()
    }

    fn row_count(&self) -> usize {
        self.surfaces.len()
    }

    fn has_position_residual(&self) -> bool {
        true
    }

    fn uses_motor(&self) -> bool {
        false
    }

    fn rows(&self, kinematics: &Kinematics<A>, rows: &mut RowBuffer) -> Result<(), ConstraintError> {
        let a = kinematics.world_point(&self.body_point);
        let a_rate = kinematics.world_point_velocity(&self.body_point);
        let turning = kinematics.angular_velocity.cross(&a_rate);
        each_surface_at(&self.name, &self.surfaces, (&a, &a_rate), |at| {
            let g_body = kinematics.frame.rotation.inverse_transform_vector(&at.gradient);
            let moment = self.body_point.cross(&g_body);
            rows.push(ConstraintRow {
                jacobian: [moment.x, moment.y, moment.z, g_body.x, g_body.y, g_body.z],
                velocity_residual: at.gradient.dot(&a_rate),
                bias: at.gradient.dot(&turning) + a_rate.dot(&at.bending),
                position_residual: Some(at.value),
            });
        })
    }
}
