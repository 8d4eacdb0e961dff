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
    // The first surface's normal and the point's distance from it (to first order, |F| / |∇F|).
    let mut first: Option<(Vector3<f64>, f64)> = None;
    for surface in surfaces {
        let (value, gradient, bending) = surface.terms(a, a_rate);
        let length = gradient.norm();
        if surface.is_singular(length) {
            return Err(no_normal(name, a, length));
        }
        if surfaces.len() == 2 {
            let normal = gradient / length;
            let distance = value.abs() / length;
            match first {
                None => first = Some((normal, distance)),
                Some((first, first_distance)) => {
                    let sine = normal.cross(&first).norm();
                    if sine.is_nan() || sine <= TANGENT {
                        return Err(tangent(name, a, sine, [first_distance, distance]));
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
fn tangent(name: &str, a: &Vector3<f64>, sine: f64, distances: [f64; 2]) -> ConstraintError {
    // Off both surfaces by more than round-off, parallel normals say the point is where the surfaces are nearest, not
    // on a curve they share.
    let reason = if distances[0].max(distances[1]) > 1e-9 * a.amax().max(1.0) {
        format!(
            "the point at {a:?} is {:e} m and {:e} m from the two surfaces, whose normals are parallel there (sine \
             {sine:e}): the surfaces do not meet near it, and may not meet at all",
            distances[0], distances[1]
        )
    } else {
        format!("the two surfaces are tangent at {a:?} (normals at sine {sine:e}): the curve's rows have rank 1")
    };
    ConstraintError::Singular {
        name: name.to_owned(),
        reason,
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

/// A sphere or a plane, recognised from a quadric's coefficients (within round-off), for [`check_curve`].
#[derive(Clone, Copy, Debug)]
enum Round {
    /// Centre and radius.
    Sphere(Vector3<f64>, f64),
    /// Unit normal n and offset d of `n · x = d`.
    Plane(Vector3<f64>, f64),
}

impl Round {
    fn of(surface: &Surface) -> Option<Round> {
        let [a, b, c, d, e, f, g, h, i, j] = surface.coefficients()?;
        let linear = Vector3::new(g, h, i);
        let second = [a, b, c, d, e, f].iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if second == 0.0 {
            let length = linear.norm();
            return (length > 0.0).then(|| Round::Plane(linear / length, -j / length));
        }
        let round = 1e-12 * second;
        if (a - b).abs() > round || (a - c).abs() > round || d.abs().max(e.abs()).max(f.abs()) > round {
            return None;
        }
        let centre = -linear / (2.0 * a);
        let squared = centre.norm_squared() - j / a;
        (squared > 0.0).then(|| Round::Sphere(centre, squared.sqrt()))
    }
}

/// An error naming the constraint `name` unless two spheres or planes among `surfaces` meet in a curve: disjoint,
/// touching at one point, or one and the same, they have none to hold a point on (other surfaces are checked where
/// the point is, [`each_surface_at`]).
pub(crate) fn check_curve(name: &str, surfaces: &[Surface]) -> Result<(), ConstraintError> {
    let [first, second] = surfaces else {
        return Ok(());
    };
    let (Some(first), Some(second)) = (Round::of(first), Round::of(second)) else {
        return Ok(());
    };
    let refuse = |reason: String| {
        Err(ConstraintError::InvalidParameter {
            name: name.to_owned(),
            reason: format!("the two surfaces have no curve in common: {reason}"),
        })
    };
    // Distances within this of each other count as equal: touching, or one surface.
    let near = |scale: f64| 1e-12 * scale.max(1.0);
    match (first, second) {
        (Round::Sphere(c1, r1), Round::Sphere(c2, r2)) => {
            let apart = (c1 - c2).norm();
            let round = near(c1.amax().max(c2.amax()).max(r1).max(r2));
            let (outer, inner) = (r1 + r2, (r1 - r2).abs());
            if apart < round && inner < round {
                refuse(format!("they are one sphere (centre {}, radius {r1})", point(&c1)))
            } else if apart > outer + round || apart < inner - round {
                refuse(format!(
                    "the spheres (centres {} and {}, radii {r1} and {r2}) do not meet: their centres are {apart} m \
                     apart",
                    point(&c1),
                    point(&c2)
                ))
            } else if apart >= outer - round || apart <= inner + round {
                refuse(format!(
                    "the spheres (centres {} and {}, radii {r1} and {r2}) touch at one point",
                    point(&c1),
                    point(&c2)
                ))
            } else {
                Ok(())
            }
        }
        (Round::Sphere(centre, radius), Round::Plane(normal, offset))
        | (Round::Plane(normal, offset), Round::Sphere(centre, radius)) => {
            let height = (normal.dot(&centre) - offset).abs();
            let round = near(centre.amax().max(radius).max(offset.abs()));
            if height > radius + round {
                refuse(format!(
                    "the sphere (centre {}, radius {radius}) is {} m from the plane",
                    point(&centre),
                    height - radius
                ))
            } else if height >= radius - round {
                refuse(format!(
                    "the plane touches the sphere (centre {}, radius {radius}) at one point",
                    point(&centre)
                ))
            } else {
                Ok(())
            }
        }
        (Round::Plane(n1, d1), Round::Plane(n2, d2)) => {
            if n1.cross(&n2).norm() > TANGENT {
                return Ok(());
            }
            let gap = (d1 - n1.dot(&n2) * d2).abs();
            if gap > near(d1.abs().max(d2.abs())) {
                refuse(format!("the planes are parallel, {gap} m apart"))
            } else {
                refuse("they are one plane".to_owned())
            }
        }
    }
}

/// A point as `[x, y, z]`, a zero without its sign.
fn point(x: &Vector3<f64>) -> String {
    format!("{:?}", x.map(|c| c + 0.0).as_slice())
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
    /// naming the constraint; two spheres or planes that have no curve in common (disjoint, touching at a point, or
    /// one surface) are refused here.
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
    /// let ball = Surface::ellipsoid(Vector3::repeat(1.0), &Isometry3::identity())?;
    /// let far = Surface::ellipsoid(Vector3::repeat(1.0), &Isometry3::translation(3.0, 0.0, 0.0))?;
    /// let apart = SurfacePin::point_on_curve("apart", Vector3::zeros(), [ball, far]);
    /// assert!(apart.unwrap_err().to_string().contains("do not meet")); // two unit spheres 3 m apart
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
        check_curve(&name, surfaces)?;
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
