//! The articulated solve (docs/mechanisms.md §M7): when every joint of a mechanism is a joint model
//! ([`crate::joint_models`]) and the joints form a tree, the bodies' accelerations follow from the articulated-body
//! recursion in the joints' motion subspaces — one column per degree of freedom, where the constraint-space solve
//! of §M4 carries one row per constrained one (a revolute joint: 1 against 5).
//!
//! Everything is expressed in world axes about one reference point o (the first root's centre of mass at this
//! evaluation), so no quantity is moved between body frames: a body's spatial inertia about o is its inertia map
//! in world axes, the articulated inertias of children simply add to their parents', and a joint's motion subspace
//! is a set of screws (lines through the joint origin, or directions) in world coordinates. Velocities are
//! `V = (ω; v_o)` (v_o the velocity of the body point at o), forces `F = (n_o; f)` (moment about o), the two paired
//! by the power `V·F`: the (ω; v), (τ; f) coordinates of §M1 with the moments taken about o.

use nalgebra::{DMatrix, DVector, Matrix3, Matrix6, Vector3, Vector6};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::eigen::least_norm_by_blocks;
use crate::joint_models::{JointAxis, JointModel, Motion, Side};
use crate::mechanism::joint_rows::{BodyKinematics, Joint};
use crate::mechanism::parts::MechanismBody;
use crate::mechanism::spatial::{angular, force_cross, join, linear, motion_cross, spatial_body, Inertia6};

/// The tree of a mechanism whose joints are all joint models: bodies parents first, each with its parent joint.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Articulation {
    /// Bodies in topological order (parents before children).
    pub order: Vec<usize>,
    /// Per body: the joint holding it to its parent, if any (a root otherwise: free in the world).
    pub parent_joint: Vec<Option<usize>>,
    /// Per body: its parent body (None for a root or a joint to the world).
    pub parent_body: Vec<Option<usize>>,
}

impl Articulation {
    /// The tree of joints `(child, parent, is_model)`, if every joint is a joint model, no body is the child of two
    /// joints and no chain of parents closes on itself.
    pub(crate) fn new(bodies: usize, joints: &[(usize, Option<usize>, bool)]) -> Option<Self> {
        let mut parent_joint = vec![None; bodies];
        let mut parent_body = vec![None; bodies];
        for (j, &(child, parent, is_model)) in joints.iter().enumerate() {
            if !is_model || parent_joint[child].is_some() {
                return None;
            }
            parent_joint[child] = Some(j);
            parent_body[child] = parent;
        }
        // Children before parents is impossible to satisfy on a cycle: order by depth from the roots.
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); bodies];
        let mut roots = Vec::new();
        for (body, parent) in parent_body.iter().enumerate() {
            match parent {
                Some(p) => children[*p].push(body),
                None => roots.push(body),
            }
        }
        let mut order = Vec::with_capacity(bodies);
        let mut next = 0;
        order.extend(roots);
        while next < order.len() {
            let body = order[next];
            order.extend(children[body].iter().copied());
            next += 1;
        }
        (order.len() == bodies).then_some(Articulation {
            order,
            parent_joint,
            parent_body,
        })
    }
}

/// One body at one evaluation.
#[derive(Clone, Copy, Debug)]
struct BodyTerms {
    /// Its articulated inertia (first its spatial inertia about o).
    inertia: Inertia6,
    /// A root's inverse articulated inertia, kept when rows couple: each row's response needs it.
    compliance: Matrix6<f64>,
    /// Its articulated bias force (first `V ×* I V − F_ext`).
    bias: Vector6<f64>,
    velocity: Vector6<f64>,
    acceleration: Vector6<f64>,
    /// `c − o`.
    offset: Vector3<f64>,
}

/// One joint at one evaluation.
#[derive(Clone, Copy, Debug)]
struct JointTerms {
    /// The free columns (the motion subspace S, world, about o); a driven joint's column is prescribed, not free.
    free: usize,
    columns: [Vector6<f64>; 6],
    /// `c`: the child's acceleration with the joint's rates held, relative to the parent's (`Ṡ q̇`), plus a driven
    /// joint's prescribed `S q̈`.
    bias_acceleration: Vector6<f64>,
    /// `U = I^A S`, `D⁻¹ = (Sᵀ U)⁻¹` (row-major, free × free) and `u = −Sᵀ p^A`.
    weighted: [Vector6<f64>; 6],
    inverse: [f64; 36],
    force: [f64; 6],
    /// The joint accelerations q̈ of the free columns.
    rates: [f64; 6],
    /// A driven joint's prescribed q̈ (its one column is not free).
    prescribed: f64,
}

impl Default for JointTerms {
    fn default() -> Self {
        JointTerms {
            free: 0,
            columns: [Vector6::zeros(); 6],
            bias_acceleration: Vector6::zeros(),
            weighted: [Vector6::zeros(); 6],
            inverse: [0.0; 36],
            force: [0.0; 6],
            rates: [0.0; 6],
            prescribed: 0.0,
        }
    }
}

/// A row of the articulated solve: an acceleration held at zero by a multiplier (docs/limits.md "Hold").
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Row {
    /// `q̈_follower = multiplier · q̈_leader` on one-coordinate joints, by their indices: the acceleration level of a
    /// coupling `q_f = m q_l + offset` (a URDF mimic), or with multiplier 0 of a joint held at a limit's bound
    /// (`q̈ = 0`). Its unit multiplier is a generalised force, +1 on the follower and −m on the leader.
    Joints {
        follower: usize,
        leader: usize,
        multiplier: f64,
    },
    /// `d · a = 0` for a contact held (docs/contacts.md): the rate along the world direction `direction` of the
    /// relative velocity w = v_body(p) − v_other(p) at the touching point p (`lever`: p − o, world), the other body the
    /// world where there is none. Its unit multiplier is the force `force` (world) through p on `body`, and its
    /// opposite on `other`: the direction itself, or a sliding contact's `n − μ ŝ` (docs/contacts.md "Friction").
    /// `moving` is ṗ, the velocity of the touching point as the contact moves, and `extra` the rate the direction's
    /// own turning adds, `ḋ · w` (docs/contacts.md "Between bodies"); both are filled in at each evaluation.
    Point {
        body: usize,
        other: Option<usize>,
        lever: Vector3<f64>,
        moving: Vector3<f64>,
        direction: Vector3<f64>,
        force: Vector3<f64>,
        extra: f64,
    },
}

/// Singular values of a gram matrix with point rows below this, relative to its largest diagonal entry, belong to
/// contacts that repeat others: the least-norm multipliers share the load among them.
pub(super) const REPEATED_ROW: f64 = 1e-12;

impl Row {
    /// A point row's rate from the bodies' spatial accelerations about o, `accelerations(b)`: `d · (a_o + α × l)` of
    /// `body` less the other's, with (`velocities` given: the solve's right-hand side, not a response to a unit force)
    /// the velocity products `ω × ṗ` of each and `extra`. A material point's acceleration is `a_o + α × l + ω × v_p`;
    /// a touching point that moves at ṗ sees the relative velocity change at `a_o + α × l + ω × ṗ` on each body
    /// (docs/contacts.md "Between bodies").
    fn point_rate(
        &self,
        accelerations: &dyn Fn(usize) -> Vector6<f64>,
        velocities: Option<&dyn Fn(usize) -> Vector6<f64>>,
    ) -> f64 {
        let Row::Point {
            body,
            other,
            lever,
            moving,
            direction,
            extra,
            ..
        } = *self
        else {
            return 0.0;
        };
        let side = |b: usize| {
            let a = accelerations(b);
            let mut point = linear(&a) + angular(&a).cross(&lever);
            if let Some(v) = velocities {
                point += angular(&v(b)).cross(&moving);
            }
            point
        };
        let mut relative = side(body);
        if let Some(other) = other {
            relative -= side(other);
        }
        direction.dot(&relative) + if velocities.is_some() { extra } else { 0.0 }
    }
}

/// The articulated solve's scratch, sized once per run.
#[derive(Clone, Debug)]
pub(crate) struct ArticulatedScratch {
    /// The reference point o of the last solve.
    origin: Vector3<f64>,
    /// Whether the last solve added couplings' forces (then the joints' rates of the forward pass are not final).
    coupled: bool,
    bodies: Vec<BodyTerms>,
    joints: Vec<JointTerms>,
    /// Per row: every body's acceleration under its unit multiplier, and every joint's first rate.
    responses: Vec<Vec<Vector6<f64>>>,
    response_rates: Vec<Vec<f64>>,
    /// A response pass's bias forces and joint force terms.
    response_bias: Vec<Vector6<f64>>,
    response_force: Vec<f64>,
    /// The rows' multipliers of the last solve: the generalised force (N m or N) each joint row put on its follower,
    /// the force (N) each point row put through its point.
    multipliers: Vec<f64>,
}

impl ArticulatedScratch {
    /// Scratch for `bodies` bodies, `joints` joints and up to `rows` joint-space rows.
    pub(crate) fn new(bodies: usize, joints: usize, rows: usize) -> Self {
        let body = BodyTerms {
            inertia: Inertia6::ZERO,
            compliance: Matrix6::zeros(),
            bias: Vector6::zeros(),
            velocity: Vector6::zeros(),
            acceleration: Vector6::zeros(),
            offset: Vector3::zeros(),
        };
        ArticulatedScratch {
            origin: Vector3::zeros(),
            coupled: false,
            bodies: vec![body; bodies],
            joints: vec![JointTerms::default(); joints],
            responses: vec![vec![Vector6::zeros(); bodies]; rows],
            response_rates: vec![vec![0.0; joints]; rows],
            response_bias: vec![Vector6::zeros(); bodies],
            response_force: vec![0.0; joints],
            multipliers: Vec::with_capacity(rows),
        }
    }
}

/// The world screw `(d; r × d)` of a turn about the line through `r` (from o) along d, or `(0; d)` of a slide.
#[inline]
pub(crate) fn axis_column(axis: &JointAxis, rotation: &Matrix3<f64>, through: &Vector3<f64>) -> Vector6<f64> {
    let d = rotation * axis.direction;
    match axis.motion {
        Motion::Rotation => join(d, through.cross(&d)),
        Motion::Translation => join(Vector3::zeros(), d),
    }
}

/// The rate of one velocity coordinate in the relative motion `relative = V_child − V_parent` (world, about o):
/// a turn's rate is its direction's share of the relative angular velocity, a slide's its share of the relative
/// velocity of the child joint origin (at `through` from o). The directions of one kind are orthonormal for every
/// joint kind, so these are exact on the joint.
#[inline]
pub(crate) fn axis_rate(column: &Vector6<f64>, motion: Motion, relative: &Vector6<f64>, through: &Vector3<f64>) -> f64 {
    match motion {
        Motion::Rotation => angular(column).dot(&angular(relative)),
        Motion::Translation => {
            let at_joint = linear(relative) + angular(relative).cross(through);
            linear(column).dot(&at_joint)
        }
    }
}

/// The world position of a joint's child origin, relative to o.
#[inline]
pub(crate) fn joint_origin<A: Algebra>(
    model: &JointModel,
    child: &crate::constraints::Kinematics<A>,
    origin: &Vector3<f64>,
) -> Vector3<f64> {
    child.frame.position + child.frame.rotation * model.child_frame().translation.vector - origin
}

/// Inverts the symmetric positive definite `n × n` matrix in `m` (row-major, stride 6) in place by Cholesky;
/// false if it is not positive definite.
#[inline]
fn invert_positive_definite(m: &mut [f64; 36], n: usize) -> bool {
    if n == 1 {
        let d = m[0];
        m[0] = 1.0 / d;
        return d > 0.0;
    }
    // L Lᵀ = M, then M⁻¹ = L⁻ᵀ L⁻¹.
    let mut l = [0.0; 36];
    for i in 0..n {
        for j in 0..=i {
            let mut sum = m[i * 6 + j];
            for k in 0..j {
                sum -= l[i * 6 + k] * l[j * 6 + k];
            }
            if i == j {
                if sum <= 0.0 || !sum.is_finite() {
                    return false;
                }
                l[i * 6 + i] = sum.sqrt();
            } else {
                l[i * 6 + j] = sum / l[j * 6 + j];
            }
        }
    }
    let mut inverse_l = [0.0; 36];
    for i in 0..n {
        inverse_l[i * 6 + i] = 1.0 / l[i * 6 + i];
        for j in 0..i {
            let mut sum = 0.0;
            for k in j..i {
                sum -= l[i * 6 + k] * inverse_l[k * 6 + j];
            }
            inverse_l[i * 6 + j] = sum / l[i * 6 + i];
        }
    }
    for i in 0..n {
        for j in 0..=i {
            let value: f64 = (i..n).map(|k| inverse_l[k * 6 + i] * inverse_l[k * 6 + j]).sum();
            m[i * 6 + j] = value;
            m[j * 6 + i] = value;
        }
    }
    true
}

impl ArticulatedScratch {
    /// The last solve's responses: column k every body's spatial acceleration (stacked) under row k's unit multiplier.
    /// A combination of multipliers this maps to zero moves nothing: a load that the rows balance among themselves.
    /// (Padded with zero rows to at least as many rows as columns, so that its SVD gives every right singular
    /// vector.)
    pub fn responses(&self) -> DMatrix<f64> {
        let rows = self.multipliers.len();
        let bodies = self.bodies.len();
        DMatrix::from_fn((6 * bodies).max(rows), rows, |i, k| {
            if i < 6 * bodies {
                self.responses[k][i / 6][i % 6]
            } else {
                0.0
            }
        })
    }

    /// The joint-space rows' multipliers of the last solve, in the rows' order.
    pub fn multipliers(&self) -> &[f64] {
        &self.multipliers
    }

    /// The reference point o of the last solve.
    pub fn origin(&self) -> Vector3<f64> {
        self.origin
    }

    /// A body's spatial acceleration at the last solve (world axes, about o).
    pub fn acceleration(&self, body: usize) -> &Vector6<f64> {
        &self.bodies[body].acceleration
    }

    /// Joint j's accelerations q̈ at the last solve (between child and parent bodies), the shares `Sᵀ` of
    /// `a_c − a_p − c` (exact: the directions of one kind are orthonormal), plus a driven joint's prescribed q̈.
    pub fn joint_accelerations(
        &self,
        j: usize,
        child: usize,
        parent: Option<usize>,
        axes: &[JointAxis],
        through: &Vector3<f64>,
        out: &mut [f64],
    ) {
        let terms = &self.joints[j];
        if !self.coupled && terms.free == axes.len() {
            // The forward pass's q̈ = D⁻¹(u − Uᵀa'), exact as they are.
            out.copy_from_slice(&terms.rates[..axes.len()]);
            return;
        }
        let parent = parent.map_or_else(Vector6::zeros, |p| self.bodies[p].acceleration);
        let relative = self.bodies[child].acceleration - parent - terms.bias_acceleration;
        for (k, (axis, value)) in axes.iter().zip(out.iter_mut()).enumerate() {
            *value = axis_rate(&terms.columns[k], axis.motion, &relative, through);
        }
        if terms.free == 0 && !axes.is_empty() {
            out[0] += terms.prescribed;
        }
    }
}

/// A child's articulated inertia and bias projected through its joint (Featherstone's articulated-body step):
/// `U = I^A S`, `D = Sᵀ U`, `u = −Sᵀ p^A` into the joint's terms, and the bias the parent receives,
/// `p^a = p^A + I^a c + U D⁻¹ u = p^A + I^A c + U D⁻¹ (u − Uᵀ c)` (the inertia it receives, `I^A − U D⁻¹ Uᵀ`, is
/// added by the caller). `None` if D is not positive definite.
#[inline]
fn project(terms: &mut JointTerms, child: &BodyTerms) -> Option<Vector6<f64>> {
    let c = terms.bias_acceleration;
    let mut passed = child.bias + child.inertia.apply(&c);
    let n = terms.free;
    if n == 1 {
        // One degree of freedom, the common case: scalars throughout.
        let column = terms.columns[0];
        let weighted = child.inertia.apply(&column);
        let d = column.dot(&weighted);
        // D > 0 for every body with mass and inertia; NaN fails too.
        if d.is_nan() || d <= 0.0 {
            return None;
        }
        let inverse = 1.0 / d;
        let force = -column.dot(&child.bias);
        passed += weighted * (inverse * (force - weighted.dot(&c)));
        terms.weighted[0] = weighted;
        terms.inverse[0] = inverse;
        terms.force[0] = force;
        return Some(passed);
    }
    for k in 0..n {
        terms.weighted[k] = child.inertia.apply(&terms.columns[k]);
        terms.force[k] = -terms.columns[k].dot(&child.bias);
        for l in 0..=k {
            let value = terms.columns[l].dot(&terms.weighted[k]);
            terms.inverse[k * 6 + l] = value;
            terms.inverse[l * 6 + k] = value;
        }
    }
    if !invert_positive_definite(&mut terms.inverse, n) {
        return None;
    }
    for k in 0..n {
        let share: f64 = (0..n)
            .map(|l| terms.inverse[k * 6 + l] * (terms.force[l] - terms.weighted[l].dot(&c)))
            .sum();
        passed += terms.weighted[k] * share;
    }
    Some(passed)
}

/// A child's acceleration from `a' = a_parent + c` (given): `q̈ = D⁻¹(u − Uᵀa')`, stored in the joint's rates, and
/// `a = a' + S q̈`; `force` is u.
#[inline]
fn joint_acceleration(terms: &mut JointTerms, mut a: Vector6<f64>, force: &[f64; 6]) -> Vector6<f64> {
    let n = terms.free;
    if n == 1 {
        let rate = terms.inverse[0] * (force[0] - terms.weighted[0].dot(&a));
        terms.rates[0] = rate;
        return a + terms.columns[0] * rate;
    }
    let mut rhs = [0.0; 6];
    for (k, value) in rhs.iter_mut().enumerate().take(n) {
        *value = force[k] - terms.weighted[k].dot(&a);
    }
    for k in 0..n {
        let rate: f64 = (0..n).map(|l| terms.inverse[k * 6 + l] * rhs[l]).sum();
        terms.rates[k] = rate;
        a += terms.columns[k] * rate;
    }
    a
}

impl Articulation {
    /// Adds the rows' forces: each row's unit multiplier (a generalised force on its joints, or a unit force through
    /// its point) moves every body by a response, found by the articulated passes with that force alone (no velocity
    /// terms, the same articulated inertias); the multipliers λ solve `G λ = −ρ` with ρ the rows' accelerations of the
    /// solve so far and G the responses' (`C M⁻¹ Cᵀ`, symmetric), and each body's acceleration gains `Σ λ a⁽ᵏ⁾`.
    /// Joint rows are independent (G positive definite, Cholesky); contacts may repeat each other (a block resting
    /// on four corners: four rows of rank 3), so with point rows λ is G's least-squares, least-norm solution.
    fn couple(&self, rows: &[Row], scratch: &mut ArticulatedScratch) -> Result<(), ()> {
        let r = rows.len();
        for (k, row) in rows.iter().enumerate() {
            scratch.response_force.iter_mut().for_each(|f| *f = 0.0);
            scratch.response_bias.iter_mut().for_each(|b| *b = Vector6::zeros());
            match *row {
                Row::Joints {
                    follower,
                    leader,
                    multiplier,
                } => {
                    scratch.response_force[follower] = 1.0;
                    scratch.response_force[leader] -= multiplier;
                }
                // The bias is the velocity terms less the applied wrench: the force on the body, its opposite on
                // the other.
                Row::Point {
                    body,
                    other,
                    lever,
                    force,
                    ..
                } => {
                    let wrench = join(lever.cross(&force), force);
                    scratch.response_bias[body] = -wrench;
                    if let Some(other) = other {
                        scratch.response_bias[other] = wrench;
                    }
                }
            }
            for &body in self.order.iter().rev() {
                let Some(j) = self.parent_joint[body] else {
                    continue;
                };
                let terms = &mut scratch.joints[j];
                let bias = scratch.response_bias[body];
                let n = terms.free;
                for k in 0..n {
                    let applied = if k == 0 { scratch.response_force[j] } else { 0.0 };
                    terms.force[k] = applied - terms.columns[k].dot(&bias);
                }
                // p^a = p + U D⁻¹ u: no bias acceleration in a response.
                let mut passed = bias;
                for k in 0..n {
                    let share: f64 = (0..n).map(|l| terms.inverse[k * 6 + l] * terms.force[l]).sum();
                    passed += terms.weighted[k] * share;
                }
                if let Some(parent) = self.parent_body[body] {
                    scratch.response_bias[parent] += passed;
                }
            }
            for &body in &self.order {
                let acceleration = match self.parent_joint[body] {
                    None => -(scratch.bodies[body].compliance * scratch.response_bias[body]),
                    Some(j) => {
                        let parent = self.parent_body[body].map_or_else(Vector6::zeros, |p| scratch.responses[k][p]);
                        let terms = &mut scratch.joints[j];
                        let saved = terms.rates;
                        let force = terms.force;
                        let a = joint_acceleration(terms, parent, &force);
                        // A driven joint's rate is prescribed: no response.
                        scratch.response_rates[k][j] = if terms.free > 0 { terms.rates[0] } else { 0.0 };
                        terms.rates = saved;
                        a
                    }
                };
                scratch.responses[k][body] = acceleration;
            }
        }
        let mut gram = DMatrix::zeros(r, r);
        let mut rhs = DVector::zeros(r);
        for (i, row) in rows.iter().enumerate() {
            // Row i's acceleration from joint accelerations `rates` or, for a point, the bodies' spatial accelerations.
            let joint_rate = |rates: &dyn Fn(usize) -> f64| match *row {
                Row::Joints {
                    follower,
                    leader,
                    multiplier,
                } => rates(follower) - multiplier * rates(leader),
                Row::Point { .. } => 0.0,
            };
            let point = matches!(row, Row::Point { .. });
            rhs[i] = -if point {
                row.point_rate(
                    &|b| scratch.bodies[b].acceleration,
                    Some(&|b| scratch.bodies[b].velocity),
                )
            } else {
                joint_rate(&|j| {
                    let terms = &scratch.joints[j];
                    if terms.free > 0 {
                        terms.rates[0]
                    } else {
                        terms.prescribed
                    }
                })
            };
            for k in 0..r {
                gram[(i, k)] = if point {
                    row.point_rate(&|b| scratch.responses[k][b], None)
                } else {
                    joint_rate(&|j| scratch.response_rates[k][j])
                };
            }
        }
        let lambda = if rows.iter().all(|row| matches!(row, Row::Joints { .. })) {
            gram.cholesky().ok_or(())?.solve(&rhs)
        } else {
            // Not symmetric where sliding friction tilts a row's force from its direction.
            let largest = gram.diagonal().amax();
            let tilted = |block: &[usize]| {
                (block.iter()).any(|&k| matches!(rows[k], Row::Point { direction, force, .. } if force != direction))
            };
            least_norm_by_blocks(&gram, &rhs, REPEATED_ROW * largest, tilted)
        };
        if !lambda.iter().all(|x| x.is_finite()) {
            return Err(());
        }
        scratch.multipliers.clear();
        scratch.multipliers.extend(lambda.iter());
        for (k, response) in scratch.responses.iter().take(r).enumerate() {
            for (body, terms) in scratch.bodies.iter_mut().enumerate() {
                terms.acceleration += response[body] * lambda[k];
            }
        }
        Ok(())
    }

    /// The reference point o of an evaluation: the first root's centre of mass.
    pub fn origin<A: Algebra>(&self, bodies: &[BodyKinematics<A>]) -> Vector3<f64> {
        self.order
            .first()
            .map_or_else(Vector3::zeros, |&b| bodies[b].kinematics.frame.position)
    }

    /// Every body's acceleration (in `scratch`) and, if asked, its reaction (the joints' wrench on it) in its own
    /// frame, as wrench coordinates `(τ; f)`, from the bodies' kinematics and their external wrenches (body frames,
    /// moments about the centre of mass), by the articulated-body recursion (docs/mechanisms.md §M7). `t` times the
    /// drives. Fails with the body whose articulated inertia is not positive definite.
    #[allow(clippy::too_many_arguments)]
    pub fn solve<A: Algebra>(
        &self,
        t: f64,
        joints: &[Joint<A>],
        masses: &[MechanismBody<A>],
        bodies: &[BodyKinematics<A>],
        external: &[ScrewCoordinates],
        rows: &[Row],
        scratch: &mut ArticulatedScratch,
        reactions: Option<&mut [[f64; 6]]>,
    ) -> Result<(), usize> {
        let origin = self.origin(bodies);
        scratch.origin = origin;
        for (i, terms) in scratch.bodies.iter_mut().enumerate() {
            let kinematics = &bodies[i].kinematics;
            let spatial = spatial_body(&masses[i].body, kinematics, &origin);
            let rotation = kinematics.frame.rotation.matrix();
            let force = rotation * external[i].l;
            let moment = rotation * external[i].t + spatial.offset.cross(&force);
            terms.inertia = spatial.inertia;
            terms.bias = force_cross(&spatial.velocity, &spatial.momentum) - join(moment, force);
            terms.velocity = spatial.velocity;
            terms.offset = spatial.offset;
        }
        for (j, joint) in joints.iter().enumerate() {
            let model = joint
                .model
                .as_ref()
                .expect("an articulated mechanism's joints are joint models");
            let child = &bodies[joint.body].kinematics;
            let through = joint_origin(model, child, &origin);
            let parent_velocity = joint
                .reference
                .map_or_else(Vector6::zeros, |p| scratch.bodies[p].velocity);
            let child_velocity = scratch.bodies[joint.body].velocity;
            let terms = &mut scratch.joints[j];
            // Ṡq̇ summed over the columns: those fixed in the child turn with it (V_c × S), those fixed in the parent
            // with the parent (V_p × S); on the joint Σ S q̇ = V_c − V_p, so the child's share is V_c × (V_c − V_p)
            // = V_p × V_c less the parent-side columns' V_c × S q̇.
            let mut bias = motion_cross(&parent_velocity, &child_velocity);
            let axes = model.axes();
            for (k, axis) in axes.iter().enumerate() {
                let rotation = match axis.side {
                    Side::Child => child.frame.rotation.matrix(),
                    Side::Parent => match joint.reference {
                        Some(p) => bodies[p].kinematics.frame.rotation.matrix(),
                        None => &Matrix3::identity(),
                    },
                };
                let column = axis_column(axis, rotation, &through);
                if axis.side == Side::Parent {
                    let relative = child_velocity - parent_velocity;
                    let rate = axis_rate(&column, axis.motion, &relative, &through);
                    bias += motion_cross(&(parent_velocity - child_velocity), &column) * rate;
                }
                terms.columns[k] = column;
            }
            terms.free = axes.len();
            terms.prescribed = 0.0;
            if let Some(drive) = model.drive_at(t) {
                bias += terms.columns[0] * drive.acceleration;
                terms.free = 0;
                terms.prescribed = drive.acceleration;
            }
            terms.bias_acceleration = bias;
        }
        // Children before parents: each child's articulated inertia and bias, projected through its joint, join
        // its parent's (Featherstone's articulated-body recursion, in world axes so nothing is transformed):
        // I^a = I^A − U D⁻¹ Uᵀ and p^a = p^A + I^a c + U D⁻¹ u = p^A + I^A c + U D⁻¹ (u − Uᵀ c).
        for &body in self.order.iter().rev() {
            let Some(j) = self.parent_joint[body] else {
                continue;
            };
            let terms = &mut scratch.joints[j];
            let (child, parent) = match self.parent_body[body] {
                Some(p) => {
                    let [child, parent] = scratch
                        .bodies
                        .get_disjoint_mut([body, p])
                        .expect("a body is not its parent");
                    (&*child, Some(parent))
                }
                None => (&scratch.bodies[body], None),
            };
            let passed = project(terms, child).ok_or(body)?;
            if let Some(parent) = parent {
                parent.inertia.add(&child.inertia);
                parent.bias += passed;
                let n = terms.free;
                if n == 1 {
                    parent.inertia.subtract_outer(&terms.weighted[0], terms.inverse[0]);
                } else {
                    for k in 0..n {
                        for l in 0..n {
                            parent.inertia.subtract_symmetric(
                                &terms.weighted[k],
                                &terms.weighted[l],
                                terms.inverse[k * 6 + l],
                            );
                        }
                    }
                }
            }
        }
        // Parents before children: the accelerations.
        for &body in &self.order {
            let acceleration = match self.parent_joint[body] {
                // A free root: `I^A a = −p^A`, an error if its articulated inertia is not positive definite.
                None => {
                    let terms = &mut scratch.bodies[body];
                    let factor = terms.inertia.matrix().cholesky().ok_or(body)?;
                    if !rows.is_empty() {
                        terms.compliance = factor.inverse();
                    }
                    -factor.solve(&terms.bias)
                }
                Some(j) => {
                    let parent = self.parent_body[body].map_or_else(Vector6::zeros, |p| scratch.bodies[p].acceleration);
                    let terms = &mut scratch.joints[j];
                    let force = terms.force;
                    joint_acceleration(terms, parent + terms.bias_acceleration, &force)
                }
            };
            scratch.bodies[body].acceleration = acceleration;
        }
        scratch.coupled = !rows.is_empty();
        scratch.multipliers.clear();
        if scratch.coupled {
            self.couple(rows, scratch).map_err(|_| self.order[0])?;
        }
        let Some(reactions) = reactions else {
            return Ok(());
        };
        for (i, out) in reactions.iter_mut().enumerate() {
            let terms = &scratch.bodies[i];
            let kinematics = &bodies[i].kinematics;
            let rotation = kinematics.frame.rotation.matrix();
            let (omega_rate, origin_acceleration) = (angular(&terms.acceleration), linear(&terms.acceleration));
            // The centre of mass: v_c = v_o + ω × r, so a_c = a_o + ω̇ × r + ω × v_c (o fixed, c moving).
            let omega = kinematics.angular_velocity;
            let centre =
                origin_acceleration + omega_rate.cross(&terms.offset) + omega.cross(&kinematics.linear_velocity);
            let body = &masses[i].body;
            let moments = body.moments();
            let omega_body = rotation.tr_mul(&omega);
            let omega_rate_body = rotation.tr_mul(&omega_rate);
            // Euler's and Newton's equations in the body frame: W = (I ω̇ + ω × I ω; m Rᵀ a_c).
            let moment =
                moments.component_mul(&omega_rate_body) + omega_body.cross(&moments.component_mul(&omega_body));
            let force = rotation.tr_mul(&centre) * body.mass();
            let applied = &external[i];
            *out = [
                moment.x - applied.t.x,
                moment.y - applied.t.y,
                moment.z - applied.t.z,
                force.x - applied.l.x,
                force.y - applied.l.y,
                force.z - applied.l.z,
            ];
        }
        Ok(())
    }
}
