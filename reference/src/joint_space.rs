//! Joint-space dynamics of kinematic trees by the textbook recursive algorithms, in spatial-vector algebra
//! (R. Featherstone, *Rigid Body Dynamics Algorithms*, Springer 2008, cited as RBDA): Plücker transforms (§2.8),
//! spatial cross products (§2.9), rigid-body spatial inertia (§2.13, eq. 2.63), joint models (ch. 4), the
//! recursive Newton–Euler algorithm (RNEA, §5.3) and the composite-rigid-body algorithm (CRBA, §6.2). Used as an
//! independent yardstick for another simulator's joint-space quantities: M(q), h(q, v) = C(q, v) v + g(q),
//! inverse and forward dynamics, energies and body velocities.
//!
//! Conventions:
//! * Spatial vectors are RBDA's, angular part first: a motion vector is (ω, v_O) with v_O the velocity of the
//!   body-fixed point at the coordinate origin O, a force vector is (n_O, f). Each body's quantities are
//!   expressed in its own body frame.
//! * Body frame of body i: X_world←i = X_world←parent · placement · J(q_i), with J a rotation about the joint
//!   axis by q (revolute), a translation q · axis (prismatic), the identity (fixed), or the pose (p, r) of the
//!   free joint's coordinates.
//! * **Free joint** (Pinocchio's free-flyer convention): q = (p_x, p_y, p_z, q_w, q_x, q_y, q_z), the position
//!   and unit quaternion of the body frame in the joint frame (`placement`, usually the identity, so: in the
//!   world for a free root); v = (v, ω) with v the velocity of the body-frame origin and ω the angular
//!   velocity, both in the body's own axes (linear part first, unlike RBDA's spatial vectors); the
//!   acceleration is the time derivative of those six body-frame components (the body's spatial acceleration
//!   in its own frame, not the classical acceleration of the origin); τ = (f, n) is the force and the torque
//!   about the body-frame origin, in body axes. [`Tree::configuration_rate`] maps v to q̇.
//! * Gravity is the `gravity` vector of the [`Tree`] (m/s², e.g. (0, 0, −9.81)); the potential energy is
//!   −Σ m_i g · c_i, zero at z = 0 for gravity along −z.
//! * SI units throughout: m, kg, kg m², s, rad, N, N m.
//!
//! ```
//! use nalgebra::{DVector, Isometry3, Matrix3, Vector3};
//! use reference::joint_space::{Tree, TreeBody, TreeJoint};
//!
//! // A point mass of 2 kg on a massless rod of 0.5 m hinged about world x: M = m d², h = m g d sin θ.
//! let tree = Tree {
//!     bodies: vec![TreeBody {
//!         parent: None,
//!         placement: Isometry3::identity(),
//!         joint: TreeJoint::Revolute(Vector3::x_axis()),
//!         mass: 2.0,
//!         centre_of_mass: Vector3::new(0.0, 0.0, -0.5),
//!         inertia: Matrix3::zeros(),
//!     }],
//!     gravity: Vector3::new(0.0, 0.0, -9.81),
//! };
//! let q = DVector::from_element(1, 0.3);
//! let m = tree.mass_matrix(&q)?;
//! let h = tree.bias(&q, &DVector::zeros(1))?;
//! assert!((m[(0, 0)] - 0.5).abs() < 1e-15);
//! assert!((h[0] - 2.0 * 9.81 * 0.5 * 0.3_f64.sin()).abs() < 1e-14);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use nalgebra::{
    DMatrix, DVector, Isometry3, Matrix3, Matrix6, Point3, Quaternion, Translation3, Unit, UnitQuaternion, Vector3,
    Vector6,
};
use thiserror::Error;

/// How far a free joint's quaternion may be from unit norm before it is rejected; within it, it is normalised.
/// Loose enough for an integrator's intermediate stages (norm off by O(h²)), tight enough to catch a missing or
/// garbage quaternion.
pub const QUATERNION_NORM_TOLERANCE: f64 = 1e-3;

/// How far a joint axis (`Unit`, which can be built unchecked) may be from unit norm.
const AXIS_NORM_TOLERANCE: f64 = 1e-9;

/// Relative asymmetry allowed in a body's inertia tensor; its symmetric part is used.
const INERTIA_SYMMETRY_TOLERANCE: f64 = 1e-9;

/// A malformed tree or input vector.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum JointSpaceError {
    /// A body's parent is not an earlier body (the bodies must be in topological order).
    #[error("body {body}: parent {parent} is not an earlier body (bodies must be listed parents first)")]
    ParentOrder {
        /// Index of the body.
        body: usize,
        /// Its parent index as given.
        parent: usize,
    },
    /// A body's data is invalid (non-finite, negative mass, asymmetric inertia, non-unit axis).
    #[error("body {body}: {reason}")]
    InvalidBody {
        /// Index of the body.
        body: usize,
        /// What is wrong.
        reason: String,
    },
    /// The gravity vector is not finite.
    #[error("the gravity vector is not finite")]
    NonFiniteGravity,
    /// An input vector has the wrong length.
    #[error("{vector} has {found} entries, the tree needs {expected}")]
    Length {
        /// Which input (`q`, `v`, `a`, `tau`).
        vector: &'static str,
        /// nq or nv of the tree.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// An input vector has a NaN or infinite entry.
    #[error("{vector}[{index}] is not finite")]
    NonFiniteInput {
        /// Which input (`q`, `v`, `a`, `tau`).
        vector: &'static str,
        /// Index of the first bad entry.
        index: usize,
    },
    /// A free joint's quaternion is too far from unit norm.
    #[error("body {body}: the free joint's quaternion has norm {norm}, not 1 (within {QUATERNION_NORM_TOLERANCE})")]
    QuaternionNorm {
        /// Index of the body.
        body: usize,
        /// The norm of the four given numbers.
        norm: f64,
    },
    /// The joint-space inertia matrix is not positive definite (massless leaves, degenerate inertias), so the
    /// forward dynamics has no unique solution.
    #[error("the joint-space inertia matrix is not positive definite")]
    NotPositiveDefinite,
}

/// A joint between a body and its parent (or the world). Axes are in the joint frame (`placement`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TreeJoint {
    /// Rotation by q (rad) about the axis, right-handed. nq = nv = 1.
    Revolute(Unit<Vector3<f64>>),
    /// Translation by q (m) along the axis. nq = nv = 1.
    Prismatic(Unit<Vector3<f64>>),
    /// Rigid attachment. nq = nv = 0.
    Fixed,
    /// Six degrees of freedom, Pinocchio's free-flyer convention (module documentation). nq = 7, nv = 6.
    Free,
}

impl TreeJoint {
    /// Number of position coordinates (1, 1, 0, 7).
    pub fn nq(&self) -> usize {
        match self {
            TreeJoint::Revolute(_) | TreeJoint::Prismatic(_) => 1,
            TreeJoint::Fixed => 0,
            TreeJoint::Free => 7,
        }
    }

    /// Number of velocity coordinates (1, 1, 0, 6).
    pub fn nv(&self) -> usize {
        match self {
            TreeJoint::Revolute(_) | TreeJoint::Prismatic(_) => 1,
            TreeJoint::Fixed => 0,
            TreeJoint::Free => 6,
        }
    }
}

/// One body of a [`Tree`] and the joint to its parent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TreeBody {
    /// Index of the parent body, which must be smaller than this body's; `None`: attached to the world.
    pub parent: Option<usize>,
    /// The joint frame in the parent body's frame (or the world's), which is the body frame at q = 0.
    pub placement: Isometry3<f64>,
    /// The joint to the parent.
    pub joint: TreeJoint,
    /// Mass (kg), ≥ 0.
    pub mass: f64,
    /// Centre of mass in the body frame (m).
    pub centre_of_mass: Vector3<f64>,
    /// Inertia tensor about the centre of mass, body axes (kg m²), symmetric.
    pub inertia: Matrix3<f64>,
}

/// A kinematic tree with a fixed base (the world): plain data, constructed by the caller.
#[derive(Debug, Clone, PartialEq)]
pub struct Tree {
    /// The bodies in topological order: a parent's index is smaller than its children's.
    pub bodies: Vec<TreeBody>,
    /// Gravitational acceleration in the world frame (m/s²).
    pub gravity: Vector3<f64>,
}

/// A body's velocity in world axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyVelocity {
    /// Angular velocity (rad/s).
    pub angular: Vector3<f64>,
    /// Velocity of the centre of mass (m/s).
    pub centre_of_mass: Vector3<f64>,
}

/// A body's kinematic data at one configuration.
struct Link {
    parent: Option<usize>,
    /// ⁱX_λ(i): the Plücker motion transform from the parent's (or the world's) coordinates to this body's.
    from_parent: Matrix6<f64>,
    /// X_world←i.
    pose: Isometry3<f64>,
    /// Columns of the motion subspace S_i, body coordinates (constant in them for every joint here).
    subspace: Vec<Vector6<f64>>,
    /// Index of this joint's first velocity coordinate.
    offset: usize,
    /// Spatial inertia about the body-frame origin, body coordinates.
    inertia: Matrix6<f64>,
}

/// The cross-product matrix a×, a× b = a × b.
fn skew(a: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

/// A spatial vector (angular part, linear part).
fn spatial(angular: &Vector3<f64>, linear: &Vector3<f64>) -> Vector6<f64> {
    Vector6::new(angular.x, angular.y, angular.z, linear.x, linear.y, linear.z)
}

/// A 6×6 matrix from its 3×3 blocks [a b; c d].
fn blocks(a: &Matrix3<f64>, b: &Matrix3<f64>, c: &Matrix3<f64>, d: &Matrix3<f64>) -> Matrix6<f64> {
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(a);
    m.fixed_view_mut::<3, 3>(0, 3).copy_from(b);
    m.fixed_view_mut::<3, 3>(3, 0).copy_from(c);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(d);
    m
}

/// RBDA §2.8: the motion transform ᴮX_A = [E 0; −E r× E] from frame A to frame B, where E rotates A coordinates
/// into B coordinates and r is B's origin in A coordinates. `a_from_b` is the pose of B in A (R, p): E = Rᵀ, r = p.
/// Force vectors go back from B to A with its transpose, ᴬX*_B = (ᴮX_A)ᵀ.
fn motion_transform(a_from_b: &Isometry3<f64>) -> Matrix6<f64> {
    let e = a_from_b.rotation.to_rotation_matrix().into_inner().transpose();
    let r = a_from_b.translation.vector;
    blocks(&e, &Matrix3::zeros(), &(-e * skew(&r)), &e)
}

/// RBDA §2.9: the motion cross product v× = [ω× 0; v_O× ω×].
fn motion_cross(v: &Vector6<f64>) -> Matrix6<f64> {
    let w = skew(&v.fixed_rows::<3>(0).into_owned());
    let u = skew(&v.fixed_rows::<3>(3).into_owned());
    blocks(&w, &Matrix3::zeros(), &u, &w)
}

/// RBDA §2.9: the force cross product v×* = −(v×)ᵀ = [ω× v_O×; 0 ω×].
fn force_cross(v: &Vector6<f64>) -> Matrix6<f64> {
    -motion_cross(v).transpose()
}

/// RBDA eq. 2.63: the spatial inertia about the origin of a body of mass m, centre of mass c and inertia I_c
/// about it, [I_c + m c× c×ᵀ, m c×; m c×ᵀ, m 1].
fn spatial_inertia(mass: f64, centre: &Vector3<f64>, inertia: &Matrix3<f64>) -> Matrix6<f64> {
    let c = skew(centre);
    blocks(
        &(inertia + mass * c * c.transpose()),
        &(mass * c),
        &(mass * c.transpose()),
        &(mass * Matrix3::identity()),
    )
}

/// Checks an input vector's length and finiteness.
fn check_input(vector: &'static str, x: &DVector<f64>, expected: usize) -> Result<(), JointSpaceError> {
    if x.len() != expected {
        return Err(JointSpaceError::Length {
            vector,
            expected,
            found: x.len(),
        });
    }
    match x.iter().position(|value| !value.is_finite()) {
        Some(index) => Err(JointSpaceError::NonFiniteInput { vector, index }),
        None => Ok(()),
    }
}

impl TreeBody {
    /// The body's checks (the parent order is the tree's).
    fn validate(&self, index: usize) -> Result<(), JointSpaceError> {
        let invalid = |reason: String| Err(JointSpaceError::InvalidBody { body: index, reason });
        let placement_finite = self.placement.translation.vector.iter().all(|x| x.is_finite())
            && self.placement.rotation.coords.iter().all(|x| x.is_finite());
        if !placement_finite {
            return invalid("the placement is not finite".into());
        }
        if (self.placement.rotation.coords.norm() - 1.0).abs() > AXIS_NORM_TOLERANCE {
            return invalid("the placement's rotation is not a unit quaternion".into());
        }
        if let TreeJoint::Revolute(axis) | TreeJoint::Prismatic(axis) = &self.joint {
            let norm = axis.norm();
            if !norm.is_finite() || (norm - 1.0).abs() > AXIS_NORM_TOLERANCE {
                return invalid(format!("the joint axis has norm {norm}, not 1"));
            }
        }
        if !self.mass.is_finite() || self.mass < 0.0 {
            return invalid(format!("mass {} is not finite and ≥ 0", self.mass));
        }
        if !self.centre_of_mass.iter().all(|x| x.is_finite()) {
            return invalid("the centre of mass is not finite".into());
        }
        if !self.inertia.iter().all(|x| x.is_finite()) {
            return invalid("the inertia tensor is not finite".into());
        }
        let asymmetry = (self.inertia - self.inertia.transpose()).norm();
        if asymmetry > INERTIA_SYMMETRY_TOLERANCE * self.inertia.norm().max(f64::MIN_POSITIVE) {
            return invalid(format!("the inertia tensor is not symmetric (‖I − Iᵀ‖ = {asymmetry})"));
        }
        Ok(())
    }

    /// J(q) for this joint's coordinates, with a free joint's quaternion normalised.
    fn joint_transform(&self, index: usize, q: &[f64]) -> Result<Isometry3<f64>, JointSpaceError> {
        Ok(match &self.joint {
            TreeJoint::Revolute(axis) => {
                Isometry3::from_parts(Translation3::identity(), UnitQuaternion::from_axis_angle(axis, q[0]))
            }
            TreeJoint::Prismatic(axis) => {
                Isometry3::from_parts(Translation3::from(axis.into_inner() * q[0]), UnitQuaternion::identity())
            }
            TreeJoint::Fixed => Isometry3::identity(),
            TreeJoint::Free => {
                let quaternion = Quaternion::new(q[3], q[4], q[5], q[6]);
                let norm = quaternion.norm();
                if (norm - 1.0).abs() > QUATERNION_NORM_TOLERANCE {
                    return Err(JointSpaceError::QuaternionNorm { body: index, norm });
                }
                Isometry3::from_parts(
                    Translation3::new(q[0], q[1], q[2]),
                    UnitQuaternion::new_normalize(quaternion),
                )
            }
        })
    }

    /// RBDA ch. 4: the columns of the motion subspace S, body coordinates. Revolute: (a, 0);
    /// prismatic: (0, a); free, with Pinocchio's (v, ω) ordering: S = [0 1; 1 0].
    fn subspace(&self) -> Vec<Vector6<f64>> {
        let zero = Vector3::zeros();
        match &self.joint {
            TreeJoint::Revolute(axis) => vec![spatial(axis, &zero)],
            TreeJoint::Prismatic(axis) => vec![spatial(&zero, axis)],
            TreeJoint::Fixed => Vec::new(),
            TreeJoint::Free => {
                let linear = (0..3).map(|k| spatial(&zero, &Vector3::ith(k, 1.0)));
                let angular = (0..3).map(|k| spatial(&Vector3::ith(k, 1.0), &zero));
                linear.chain(angular).collect()
            }
        }
    }
}

impl Tree {
    /// Number of position coordinates.
    pub fn nq(&self) -> usize {
        self.bodies.iter().map(|body| body.joint.nq()).sum()
    }

    /// Number of velocity coordinates (degrees of freedom).
    pub fn nv(&self) -> usize {
        self.bodies.iter().map(|body| body.joint.nv()).sum()
    }

    /// The configuration q = 0 with identity quaternions for the free joints (every body frame at its placement).
    pub fn neutral_configuration(&self) -> DVector<f64> {
        let mut q = DVector::zeros(self.nq());
        let mut offset = 0;
        for body in &self.bodies {
            if body.joint == TreeJoint::Free {
                q[offset + 3] = 1.0;
            }
            offset += body.joint.nq();
        }
        q
    }

    /// Checks the tree: parents before children, finite data, masses ≥ 0, symmetric inertias, unit axes.
    pub fn validate(&self) -> Result<(), JointSpaceError> {
        if !self.gravity.iter().all(|x| x.is_finite()) {
            return Err(JointSpaceError::NonFiniteGravity);
        }
        for (index, body) in self.bodies.iter().enumerate() {
            if let Some(parent) = body.parent {
                if parent >= index {
                    return Err(JointSpaceError::ParentOrder { body: index, parent });
                }
            }
            body.validate(index)?;
        }
        Ok(())
    }

    /// Forward kinematics: every body's transforms, subspaces and inertias at q.
    fn links(&self, q: &DVector<f64>) -> Result<Vec<Link>, JointSpaceError> {
        self.validate()?;
        check_input("q", q, self.nq())?;
        let mut links: Vec<Link> = Vec::with_capacity(self.bodies.len());
        let (mut q_offset, mut v_offset) = (0, 0);
        for (index, body) in self.bodies.iter().enumerate() {
            let nq = body.joint.nq();
            let parent_from_body =
                body.placement * body.joint_transform(index, &q.as_slice()[q_offset..q_offset + nq])?;
            let parent_pose = body
                .parent
                .map_or_else(Isometry3::identity, |parent| links[parent].pose);
            let symmetric_inertia = 0.5 * (body.inertia + body.inertia.transpose());
            links.push(Link {
                parent: body.parent,
                from_parent: motion_transform(&parent_from_body),
                pose: parent_pose * parent_from_body,
                subspace: body.subspace(),
                offset: v_offset,
                inertia: spatial_inertia(body.mass, &body.centre_of_mass, &symmetric_inertia),
            });
            q_offset += nq;
            v_offset += body.joint.nv();
        }
        Ok(links)
    }

    /// The joint velocity v_J = S q̇ of a link.
    fn joint_motion(link: &Link, v: &DVector<f64>) -> Vector6<f64> {
        link.subspace
            .iter()
            .enumerate()
            .fold(Vector6::zeros(), |sum, (k, column)| sum + column * v[link.offset + k])
    }

    /// RBDA §5.3: v_i = ⁱX_λ v_λ + S_i q̇_i with v_0 = 0 (body coordinates).
    fn spatial_velocities(links: &[Link], v: &DVector<f64>) -> Vec<Vector6<f64>> {
        let mut velocities: Vec<Vector6<f64>> = Vec::with_capacity(links.len());
        for link in links {
            let parent_velocity = link.parent.map_or_else(Vector6::zeros, |parent| velocities[parent]);
            velocities.push(link.from_parent * parent_velocity + Self::joint_motion(link, v));
        }
        velocities
    }

    /// RBDA §5.3, the recursive Newton–Euler algorithm with the base acceleration a_0 = −a_g
    /// (a_g = (0, g)) standing in for gravity: outwards v_i = ⁱX_λ v_λ + S q̇, a_i = ⁱX_λ a_λ + S q̈ + v_i × S q̇
    /// (c_J = 0: S is constant in body coordinates), f_i = I_i a_i + v_i ×* I_i v_i; inwards τ_i = S_iᵀ f_i,
    /// f_λ += ⁱX_λᵀ f_i.
    fn recursive_newton_euler(&self, links: &[Link], v: &DVector<f64>, a: Option<&DVector<f64>>) -> DVector<f64> {
        let base_acceleration = spatial(&Vector3::zeros(), &(-self.gravity));
        let velocities = Self::spatial_velocities(links, v);
        let mut forces: Vec<Vector6<f64>> = Vec::with_capacity(links.len());
        let mut accelerations: Vec<Vector6<f64>> = Vec::with_capacity(links.len());
        for (link, velocity) in links.iter().zip(&velocities) {
            let parent_acceleration = link.parent.map_or(base_acceleration, |parent| accelerations[parent]);
            let joint_acceleration = a.map_or_else(Vector6::zeros, |a| Self::joint_motion(link, a));
            let acceleration = link.from_parent * parent_acceleration
                + joint_acceleration
                + motion_cross(velocity) * Self::joint_motion(link, v);
            accelerations.push(acceleration);
            forces.push(link.inertia * acceleration + force_cross(velocity) * link.inertia * velocity);
        }
        let mut tau = DVector::zeros(v.len());
        for (index, link) in links.iter().enumerate().rev() {
            for (k, column) in link.subspace.iter().enumerate() {
                tau[link.offset + k] = column.dot(&forces[index]);
            }
            if let Some(parent) = link.parent {
                let transmitted = link.from_parent.transpose() * forces[index];
                forces[parent] += transmitted;
            }
        }
        tau
    }

    /// Every body frame in the world, X_world←i = X_world←parent · placement · J(q_i).
    pub fn positions(&self, q: &DVector<f64>) -> Result<Vec<Isometry3<f64>>, JointSpaceError> {
        Ok(self.links(q)?.iter().map(|link| link.pose).collect())
    }

    /// q̇ from v: v itself for revolute and prismatic joints; for a free joint ṗ = R v and
    /// ṙ = ½ r ⊗ (0, ω) (quaternion r = (w, x, y, z) of rotation R, v and ω in body axes).
    pub fn configuration_rate(&self, q: &DVector<f64>, v: &DVector<f64>) -> Result<DVector<f64>, JointSpaceError> {
        self.validate()?;
        check_input("q", q, self.nq())?;
        check_input("v", v, self.nv())?;
        let mut rate = DVector::zeros(self.nq());
        let (mut q_offset, mut v_offset) = (0, 0);
        for (index, body) in self.bodies.iter().enumerate() {
            match body.joint {
                TreeJoint::Revolute(_) | TreeJoint::Prismatic(_) => rate[q_offset] = v[v_offset],
                TreeJoint::Fixed => {}
                TreeJoint::Free => {
                    let pose = body.joint_transform(index, &q.as_slice()[q_offset..q_offset + 7])?;
                    let linear = pose.rotation * Vector3::new(v[v_offset], v[v_offset + 1], v[v_offset + 2]);
                    let omega = Quaternion::from_imag(Vector3::new(v[v_offset + 3], v[v_offset + 4], v[v_offset + 5]));
                    let spin = pose.rotation.into_inner() * omega * 0.5;
                    rate.rows_mut(q_offset, 3).copy_from(&linear);
                    rate[q_offset + 3] = spin.w;
                    rate[q_offset + 4] = spin.i;
                    rate[q_offset + 5] = spin.j;
                    rate[q_offset + 6] = spin.k;
                }
            }
            q_offset += body.joint.nq();
            v_offset += body.joint.nv();
        }
        Ok(rate)
    }

    /// RBDA §6.2, the composite-rigid-body algorithm: composite inertias I^c_λ += ⁱX_λᵀ I^c_i ⁱX_λ inwards,
    /// then H_ii = S_iᵀ I^c_i S_i and, walking F = I^c_i S_i to the root by F ← ʲX_λ(j)ᵀ F,
    /// H_ij = H_jiᵀ = Fᵀ S_j. Exactly symmetric by construction.
    pub fn mass_matrix(&self, q: &DVector<f64>) -> Result<DMatrix<f64>, JointSpaceError> {
        let links = self.links(q)?;
        let mut composite: Vec<Matrix6<f64>> = links.iter().map(|link| link.inertia).collect();
        for (index, link) in links.iter().enumerate().rev() {
            if let Some(parent) = link.parent {
                let contribution = link.from_parent.transpose() * composite[index] * link.from_parent;
                composite[parent] += contribution;
            }
        }
        let mut m = DMatrix::zeros(self.nv(), self.nv());
        for (index, link) in links.iter().enumerate() {
            for (k, column) in link.subspace.iter().enumerate() {
                let row = link.offset + k;
                let mut force = composite[index] * column;
                for (l, other) in link.subspace.iter().enumerate().take(k + 1) {
                    let value = other.dot(&force);
                    m[(link.offset + l, row)] = value;
                    m[(row, link.offset + l)] = value;
                }
                let mut j = index;
                while let Some(parent) = links[j].parent {
                    force = links[j].from_parent.transpose() * force;
                    j = parent;
                    for (l, other) in links[j].subspace.iter().enumerate() {
                        let value = other.dot(&force);
                        m[(row, links[j].offset + l)] = value;
                        m[(links[j].offset + l, row)] = value;
                    }
                }
            }
        }
        Ok(m)
    }

    /// h(q, v) = C(q, v) v + g(q): the RNEA with q̈ = 0, gravity included (RBDA §5.3).
    pub fn bias(&self, q: &DVector<f64>, v: &DVector<f64>) -> Result<DVector<f64>, JointSpaceError> {
        let links = self.links(q)?;
        check_input("v", v, self.nv())?;
        Ok(self.recursive_newton_euler(&links, v, None))
    }

    /// τ = M(q) q̈ + h(q, v) by the RNEA (RBDA §5.3).
    pub fn inverse_dynamics(
        &self,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
    ) -> Result<DVector<f64>, JointSpaceError> {
        let links = self.links(q)?;
        check_input("v", v, self.nv())?;
        check_input("a", a, self.nv())?;
        Ok(self.recursive_newton_euler(&links, v, Some(a)))
    }

    /// q̈ = M⁻¹ (τ − h) (M by the CRBA, RBDA §6.2; h by the RNEA, §5.3), solved by Cholesky; an error if M is not
    /// positive definite.
    pub fn forward_dynamics(
        &self,
        q: &DVector<f64>,
        v: &DVector<f64>,
        tau: &DVector<f64>,
    ) -> Result<DVector<f64>, JointSpaceError> {
        check_input("tau", tau, self.nv())?;
        let m = self.mass_matrix(q)?;
        let h = self.bias(q, v)?;
        let cholesky = m.cholesky().ok_or(JointSpaceError::NotPositiveDefinite)?;
        Ok(cholesky.solve(&(tau - h)))
    }

    /// T = ½ Σ v_iᵀ I_i v_i over the bodies' spatial velocities (RBDA §2.13), which equals ½ q̇ᵀ M q̇.
    pub fn kinetic_energy(&self, q: &DVector<f64>, v: &DVector<f64>) -> Result<f64, JointSpaceError> {
        let links = self.links(q)?;
        check_input("v", v, self.nv())?;
        let velocities = Self::spatial_velocities(&links, v);
        Ok(links
            .iter()
            .zip(&velocities)
            .map(|(link, velocity)| 0.5 * velocity.dot(&(link.inertia * velocity)))
            .sum())
    }

    /// V = −Σ m_i g · c_i with c_i the world centre of mass: zero at z = 0 for gravity along −z.
    pub fn potential_energy(&self, q: &DVector<f64>) -> Result<f64, JointSpaceError> {
        let links = self.links(q)?;
        Ok(links
            .iter()
            .zip(&self.bodies)
            .map(|(link, body)| {
                -body.mass
                    * self
                        .gravity
                        .dot(&(link.pose * Point3::from(body.centre_of_mass)).coords)
            })
            .sum())
    }

    /// Every body's angular velocity and centre-of-mass velocity in world axes, for comparison with a
    /// maximal-coordinate simulator: ω = R ω_B, ċ = R (v_O + ω_B × c) from the body-frame spatial velocity
    /// (ω_B, v_O).
    pub fn body_velocities(&self, q: &DVector<f64>, v: &DVector<f64>) -> Result<Vec<BodyVelocity>, JointSpaceError> {
        let links = self.links(q)?;
        check_input("v", v, self.nv())?;
        let velocities = Self::spatial_velocities(&links, v);
        Ok(links
            .iter()
            .zip(&velocities)
            .zip(&self.bodies)
            .map(|((link, velocity), body)| {
                let omega = velocity.fixed_rows::<3>(0).into_owned();
                let origin = velocity.fixed_rows::<3>(3).into_owned();
                BodyVelocity {
                    angular: link.pose.rotation * omega,
                    centre_of_mass: link.pose.rotation * (origin + omega.cross(&body.centre_of_mass)),
                }
            })
            .collect())
    }
}
