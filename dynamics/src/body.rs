//! Rigid bodies: mass and principal moments of inertia about the centre of mass. The body frame has
//! its origin at the centre of mass and its axes along the principal axes (`docs/theory.md` §2, E10a). A body given
//! as a full inertia tensor in some other frame (a CAD part's) is diagonalised into that form, keeping where
//! the principal frame sits ([`Body::from_inertia_tensor`]).

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// The largest mass (kg) or principal moment (kg m²) a body may have: the weight `m g`, the momenta and energies
/// multiply these by positions and velocities, and a mass of 1e308 kg overflowed its weight to infinity (then
/// reported as a joint's "non-finite residual"). Far beyond any physical body.
pub const MAX_MASS_PROPERTY: f64 = 1e50;

/// The smallest mass (kg) or principal moment (kg m²) a body may have, [`MAX_MASS_PROPERTY`]'s reciprocal: the
/// dynamics divides by both, and a subnormal mass (1e-310 kg) has an infinite reciprocal. Far below any physical
/// body.
pub const MIN_MASS_PROPERTY: f64 = 1e-50;

/// Why a body's parameters are not physical.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BodyError {
    /// The mass (held, in kg) is not finite or lies outside [`MIN_MASS_PROPERTY`] … [`MAX_MASS_PROPERTY`].
    #[error(
        "mass must be positive, finite, at least {MIN_MASS_PROPERTY:e} and at most {MAX_MASS_PROPERTY:e}, got {0:?}"
    )]
    Mass(f64),
    /// A principal moment (all three held, in kg m²) is not finite or lies outside [`MIN_MASS_PROPERTY`] …
    /// [`MAX_MASS_PROPERTY`].
    #[error(
        "principal moments must be positive, finite, at least {MIN_MASS_PROPERTY:e} and at most {MAX_MASS_PROPERTY:e}, got {0:?}"
    )]
    Moments([f64; 3]),
    /// The principal moments (held, in kg m²) violate `Iᵢ ≤ Iⱼ + Iₖ`, which every mass distribution satisfies.
    #[error("principal moments {0:?} violate the triangle inequality (each at most the sum of the others)")]
    Triangle([f64; 3]),
    /// A shape constructor's dimensions (all of them held, in m; the rod's include its axial moment) are not
    /// positive and finite.
    #[error("shape dimensions must be positive and finite, got {0:?}")]
    Dimensions(Vec<f64>),
    /// An inertia tensor that is not finite or not symmetric (`Iᵢⱼ = Iⱼᵢ` up to round-off).
    #[error("an inertia tensor must be finite and symmetric, got {0:?}")]
    Tensor([[f64; 3]; 3]),
    /// The point the inertia tensor is given about, or the centre of mass, is not finite (that point held).
    #[error("the point the inertia is given about and the centre of mass must be finite, got {0:?}")]
    Point([f64; 3]),
}

/// Where a body's principal frame sits in the frame its inertia tensor was given in ([`Body::from_inertia_tensor`]):
/// the centre of mass, and the rotation from the principal axes (the body frame of the dynamics) to that frame's
/// axes. A part placed in the world with pose `(position, rotation)` of its own frame has its body frame at
/// [`PrincipalFrame::body_pose`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipalFrame {
    /// The centre of mass, in the frame the inertia tensor was given in (m).
    pub centre_of_mass: Vector3<f64>,
    /// The rotation taking the principal axes (body frame) to the axes of the frame the tensor was given in.
    pub rotation: UnitQuaternion<f64>,
}

impl PrincipalFrame {
    /// The centre of mass and the body-frame orientation (principal axes → world) of a part whose own frame is at
    /// `position` with orientation `rotation` in the world: the pose a [`crate::State`] constructor takes.
    pub fn body_pose(
        &self,
        position: Vector3<f64>,
        rotation: &UnitQuaternion<f64>,
    ) -> (Vector3<f64>, UnitQuaternion<f64>) {
        (position + rotation * self.centre_of_mass, rotation * self.rotation)
    }
}

/// Mass and principal moments (about the centre of mass, along the body axes). The fields are private so
/// that every `Body` went through [`Body::new`]'s checks: a negative mass or moments that no mass distribution
/// has would otherwise simulate without a word. A struct literal does not compile (E0451, private fields):
///
/// ```compile_fail,E0451
/// let _ = dynamics::Body { mass: -1.0, moments: nalgebra::Vector3::new(-1.0, 2.0, 3.0) };
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body {
    mass: f64,
    moments: Vector3<f64>,
}

/// A mass or moment a body may have: within [`MIN_MASS_PROPERTY`] … [`MAX_MASS_PROPERTY`] (NaN fails).
fn physical(value: f64) -> bool {
    (MIN_MASS_PROPERTY..=MAX_MASS_PROPERTY).contains(&value)
}

fn positive(values: &[f64]) -> Result<(), BodyError> {
    if values.iter().all(|v| v.is_finite() && *v > 0.0) {
        Ok(())
    } else {
        Err(BodyError::Dimensions(values.to_vec()))
    }
}

impl Body {
    /// A body with these principal moments, checked to be physical.
    ///
    /// ```
    /// use dynamics::{Body, BodyError};
    /// use nalgebra::Vector3;
    ///
    /// let plate = Body::new(2.0, Vector3::new(0.1, 0.2, 0.3))?; // 2 kg; kg m², a thin plate: I₃ = I₁ + I₂
    /// assert_eq!((plate.mass(), plate.moments().z), (2.0, 0.3));
    /// // No mass distribution has one moment above the sum of the other two.
    /// let impossible = Body::new(1.0, Vector3::new(0.1, 0.1, 0.3));
    /// assert_eq!(impossible, Err(BodyError::Triangle([0.1, 0.1, 0.3])));
    /// assert!(matches!(Body::new(-1.0, Vector3::repeat(0.1)), Err(BodyError::Mass(_))));
    /// # Ok::<(), BodyError>(())
    /// ```
    pub fn new(mass: f64, moments: Vector3<f64>) -> Result<Body, BodyError> {
        if !physical(mass) {
            return Err(BodyError::Mass(mass));
        }
        let m = [moments.x, moments.y, moments.z];
        if !m.iter().all(|&v| physical(v)) {
            return Err(BodyError::Moments(m));
        }
        // Any mass distribution has Iᵢ ≤ Iⱼ + Iₖ; allow round-off in the equality (thin plates).
        let total = m[0] + m[1] + m[2];
        if m.iter().any(|&v| v > (total - v) * (1.0 + 1e-12)) {
            return Err(BodyError::Triangle(m));
        }
        Ok(Body { mass, moments })
    }

    /// A body from its full inertia tensor `inertia` (kg m², any frame) about the point `about`, and its centre
    /// of mass, both in that frame. The parallel-axis theorem moves the tensor to the centre of mass,
    /// `I_c = I_about − m(|d|²𝟙 − d dᵀ)` with `d = centre_of_mass − about`; its eigenvectors are the principal
    /// axes (made right-handed) and its eigenvalues the moments, checked like [`Body::new`]'s.
    ///
    /// ```
    /// use dynamics::Body;
    /// use nalgebra::{Matrix3, Vector3};
    ///
    /// // A 2 kg rod 1 m long along x, its inertia given about its end at the origin: m l²/3 across.
    /// let end = Matrix3::from_diagonal(&Vector3::new(1e-4, 2.0 / 3.0, 2.0 / 3.0));
    /// let (rod, frame) = Body::from_inertia_tensor(2.0, end, Vector3::zeros(), Vector3::new(0.5, 0.0, 0.0))?;
    /// let mut moments: Vec<f64> = rod.moments().iter().copied().collect();
    /// moments.sort_by(f64::total_cmp);
    /// assert!((moments[2] - 2.0 / 12.0).abs() < 1e-15); // m l²/12 about the centre
    /// assert_eq!(frame.centre_of_mass, Vector3::new(0.5, 0.0, 0.0));
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn from_inertia_tensor(
        mass: f64,
        inertia: Matrix3<f64>,
        about: Vector3<f64>,
        centre_of_mass: Vector3<f64>,
    ) -> Result<(Body, PrincipalFrame), BodyError> {
        let as_rows = |m: &Matrix3<f64>| std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]));
        let largest = inertia.amax();
        let asymmetry = (inertia - inertia.transpose()).amax();
        if !largest.is_finite() || asymmetry > 1e-12 * largest {
            return Err(BodyError::Tensor(as_rows(&inertia)));
        }
        for point in [about, centre_of_mass] {
            if !point.iter().all(|x| x.is_finite()) {
                return Err(BodyError::Point([point.x, point.y, point.z]));
            }
        }
        if !physical(mass) {
            return Err(BodyError::Mass(mass));
        }
        let d = centre_of_mass - about;
        let central =
            (inertia + inertia.transpose()) * 0.5 - (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * mass;
        // Jacobi rotations rather than nalgebra's `SymmetricEigen`, whose eigenvectors can miss the tensor by 5e-9
        // relative when two moments are close (0.08981 and 0.08991 kg m²; nalgebra issue #1109): the body must
        // keep the inertia it was given (`scenarios/tests/integration/joint_space.rs`).
        let mut eigenvectors = central;
        let mut values = [0.0; 3];
        let mut work = [0.0; 9];
        crate::eigen::symmetric_eigen(eigenvectors.as_mut_slice(), &mut values, &mut work, 3);
        let eigenvalues = Vector3::from(values);
        if eigenvectors.determinant() < 0.0 {
            eigenvectors.column_mut(2).neg_mut();
        }
        let body = Body::new(mass, eigenvalues)?;
        let rotation = UnitQuaternion::from_matrix(&eigenvectors);
        Ok((
            body,
            PrincipalFrame {
                centre_of_mass,
                rotation,
            },
        ))
    }

    /// A solid cylinder of this radius and length, axis along body z: axial moment `m r²/2`, transverse
    /// `m(3r² + h²)/12`.
    ///
    /// ```
    /// use dynamics::Body;
    ///
    /// let (m, r, h) = (3.0, 0.2, 1.0); // kg, m, m
    /// let can = Body::cylinder(m, r, h)?;
    /// assert!((can.moments().z - m * r * r / 2.0).abs() < 1e-15); // kg m², about the axis
    /// assert!((can.moments().x - m * (3.0 * r * r + h * h) / 12.0).abs() < 1e-15); // across, through the centre
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn cylinder(mass: f64, radius: f64, length: f64) -> Result<Body, BodyError> {
        positive(&[radius, length])?;
        let transverse = mass * (3.0 * radius * radius + length * length) / 12.0;
        Body::new(mass, Vector3::new(transverse, transverse, 0.5 * mass * radius * radius))
    }

    /// A solid cuboid with side lengths `extents` along the body axes:
    /// `I = m/12 (b² + c², a² + c², a² + b²)` (theory §11).
    ///
    /// ```
    /// use dynamics::Body;
    /// use nalgebra::Vector3;
    ///
    /// let brick = Body::cuboid(1.2, Vector3::new(0.1, 0.2, 0.3))?; // kg; sides in m
    /// let expected = 1.2 / 12.0 * Vector3::<f64>::new(0.04 + 0.09, 0.01 + 0.09, 0.01 + 0.04); // kg m²
    /// assert!((brick.moments() - expected).norm() < 1e-15);
    /// assert!(Body::cuboid(1.0, Vector3::new(0.1, 0.0, 0.3)).is_err()); // a side of zero
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn cuboid(mass: f64, extents: Vector3<f64>) -> Result<Body, BodyError> {
        positive(&[extents.x, extents.y, extents.z])?;
        let s = extents.component_mul(&extents);
        Body::new(mass, mass / 12.0 * Vector3::new(s.y + s.z, s.x + s.z, s.x + s.y))
    }

    /// A thin rod of this length along the body z axis, with the given (small) axial moment, which a
    /// thin rod needs for a non-singular inertia map (the scenes use 1e-3).
    ///
    /// ```
    /// use dynamics::Body;
    ///
    /// let rod = Body::rod(2.0, 1.5, 1e-3)?; // 2 kg, 1.5 m along body z
    /// assert!((rod.moments().x - 2.0 * 1.5 * 1.5 / 12.0).abs() < 1e-15); // m l²/12 (kg m²)
    /// assert_eq!(rod.moments().z, 1e-3); // the axial moment as given
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn rod(mass: f64, length: f64, axial_moment: f64) -> Result<Body, BodyError> {
        positive(&[length, axial_moment])?;
        let transverse = mass * length * length / 12.0;
        Body::new(mass, Vector3::new(transverse, transverse, axial_moment))
    }

    /// A solid cone of this height and base radius, axis along body z: transverse moment about the
    /// centre of mass `m(3h²/80 + 3r²/20)`, axial `3mr²/10`. The centre of mass is on the axis at
    /// `3h/4` from the tip, so the tip is at body `(0, 0, −3h/4)`.
    ///
    /// ```
    /// use dynamics::Body;
    ///
    /// let (m, h, r) = (0.5, 0.4, 0.1); // kg, m, m
    /// let top = Body::solid_cone(m, h, r)?;
    /// assert!((top.moments().z - 0.3 * m * r * r).abs() < 1e-15); // 3mr²/10 about the axis (kg m²)
    /// // About the tip, 3h/4 from the centre of mass (parallel axes): 3m(h²/5 + r²/20).
    /// let about_tip = top.moments().x + m * (0.75 * h).powi(2);
    /// assert!((about_tip - 3.0 * m * (h * h / 5.0 + r * r / 20.0)).abs() < 1e-15);
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn solid_cone(mass: f64, height: f64, radius: f64) -> Result<Body, BodyError> {
        positive(&[height, radius])?;
        let transverse = mass * (3.0 / 80.0 * height * height + 3.0 / 20.0 * radius * radius);
        Body::new(mass, Vector3::new(transverse, transverse, 0.3 * mass * radius * radius))
    }

    /// A solid sphere: `I = 2mr²/5` about every axis.
    ///
    /// ```
    /// use dynamics::Body;
    /// use nalgebra::Vector3;
    ///
    /// let ball = Body::sphere(5.0, 0.1)?; // 5 kg, radius 0.1 m
    /// assert!((ball.moments() - Vector3::repeat(0.02)).norm() < 1e-15); // 2mr²/5 (kg m²) about every axis
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn sphere(mass: f64, radius: f64) -> Result<Body, BodyError> {
        positive(&[radius])?;
        Body::new(mass, Vector3::repeat(0.4 * mass * radius * radius))
    }

    /// The mass (kg).
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// The principal moments of inertia about the centre of mass, along the body axes (kg m²).
    pub fn moments(&self) -> Vector3<f64> {
        self.moments
    }

    /// The smallest radius of gyration, √(I_min / m) (m): the size of the body as its rotation sees it.
    pub fn smallest_gyration_radius(&self) -> f64 {
        (self.moments().min() / self.mass()).sqrt()
    }

    /// `H = diag(I₁, I₂, I₃, m, m, m)`: the inertia in velocity coordinates `(ω; v)` (theory §3–§4).
    pub fn kinetic_metric(&self) -> nalgebra::Matrix6<f64> {
        let m = self.mass;
        nalgebra::Matrix6::from_diagonal(&nalgebra::Vector6::new(
            self.moments.x,
            self.moments.y,
            self.moments.z,
            m,
            m,
            m,
        ))
    }
}
