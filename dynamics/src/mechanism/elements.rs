//! A mechanism's force elements at one evaluation (docs/mechanisms.md §M8): each element's world wrench on its
//! two bodies, moved into their body frames, its non-conservative power, and the potential of the conservative
//! ones.

use nalgebra::{DMatrix, DVector, Vector3};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::{ConstraintError, Kinematics};
use crate::joint_models::{JointModel, Motion, Side};
use crate::mechanism::error::MechanismError;
use crate::mechanism::force_elements::{ElementKind, ForceElement, JointSpaceQueries, JointState};
use crate::mechanism::model::Mechanism;
use crate::state::State;

/// A wrench in world screw coordinates: `l` the force, `t` its moment about the world origin.
fn force_at(force: Vector3<f64>, point: Vector3<f64>) -> ScrewCoordinates {
    ScrewCoordinates {
        l: force,
        t: point.cross(&force),
    }
}

fn couple(moment: Vector3<f64>) -> ScrewCoordinates {
    ScrewCoordinates {
        l: Vector3::zeros(),
        t: moment,
    }
}

/// The power of a world wrench on a body moving with world kinematics `k`: `f·v_o + m_o·ω`, with v_o the velocity
/// of the body point at the world origin.
fn power<A: Algebra>(wrench: &ScrewCoordinates, k: &Kinematics<A>) -> f64 {
    let twist = A::screw_coordinates(k.world_velocity);
    wrench.l.dot(&twist.t) + wrench.t.dot(&twist.l)
}

/// The world wrench of generalised forces `forces` on a joint's coordinates, acting on the child (the parent takes
/// the opposite): a couple τ d about each turn's direction d, a force τ d through the child joint origin x along
/// each slide's. Its power is `Σ τ q̇`.
fn joint_wrench<A: Algebra>(
    model: &JointModel,
    child: &Kinematics<A>,
    parent: Option<&Kinematics<A>>,
    forces: &[f64],
) -> ScrewCoordinates {
    let x = child.world_point(&model.child_frame().translation.vector);
    let (mut moment, mut force) = (Vector3::zeros(), Vector3::zeros());
    for (axis, tau) in model.axes().iter().zip(forces) {
        let d = match (axis.side, parent) {
            (Side::Child, _) => child.world_direction(&axis.direction),
            (Side::Parent, Some(p)) => p.world_direction(&axis.direction),
            (Side::Parent, None) => axis.direction,
        };
        match axis.motion {
            Motion::Rotation => moment += d * *tau,
            Motion::Translation => force += d * *tau,
        }
    }
    ScrewCoordinates {
        l: force,
        t: moment + x.cross(&force),
    }
}

/// A joint's rates from its two bodies' world kinematics, read at the child joint origin (as
/// [`Mechanism::joint_velocities`]).
fn joint_rates<A: Algebra>(model: &JointModel, child: &Kinematics<A>, parent: Option<&Kinematics<A>>, out: &mut [f64]) {
    let x = child.world_point(&model.child_frame().translation.vector);
    let velocity_at = |k: &Kinematics<A>| k.linear_velocity + k.angular_velocity.cross(&(x - k.frame.position));
    let (parent_angular, parent_at) = parent.map_or((Vector3::zeros(), Vector3::zeros()), |p| {
        (p.angular_velocity, velocity_at(p))
    });
    let (angular, at) = (child.angular_velocity - parent_angular, velocity_at(child) - parent_at);
    for (axis, rate) in model.axes().iter().zip(out.iter_mut()) {
        let d = match (axis.side, parent) {
            (Side::Child, _) => child.world_direction(&axis.direction),
            (Side::Parent, Some(p)) => p.world_direction(&axis.direction),
            (Side::Parent, None) => axis.direction,
        };
        *rate = match axis.motion {
            Motion::Rotation => d.dot(&angular),
            Motion::Translation => d.dot(&at),
        };
    }
}

/// A body's state from its kinematics (the world momentum of its body velocity).
fn state_of<A: Algebra>(body: &crate::body::Body, k: &Kinematics<A>) -> State<A> {
    State {
        motor: k.motor,
        central_momentum: crate::motor::central_from_body::<A>(k.motor, body.momentum::<A>(k.body_velocity)),
    }
}

impl<A: Algebra> Mechanism<A> {
    /// Adds a force element (a spring-damper, a couple, a joint actuator or damper, a controller, a user wrench
    /// between bodies; `force_elements`). Refused, naming the element: bodies or joints that are not the
    /// mechanism's, an element between a body and itself, a joint force on a joint that is not a one-coordinate joint
    /// model, joint damping on a joint that is not a joint model, a controller on a mechanism without joint
    /// coordinates.
    pub fn add_force_element(&mut self, element: ForceElement<A>) -> Result<(), MechanismError> {
        let refuse = |reason: String| -> Result<(), MechanismError> {
            Err(ConstraintError::InvalidParameter {
                name: element.name.clone(),
                reason,
            }
            .into())
        };
        if element.name.is_empty() {
            return Err(MechanismError::EmptyName("force element"));
        }
        let bodies = self.bodies.len();
        let pair = match &element.kind {
            ElementKind::SpringDamper { first, second, .. } => Some((first.0, second.0)),
            ElementKind::Couple { first, second, .. } | ElementKind::Between { first, second, .. } => {
                Some((*first, *second))
            }
            _ => None,
        };
        if let Some((first, second)) = pair {
            for body in std::iter::once(first).chain(second) {
                if body >= bodies {
                    return Err(MechanismError::UnknownBody(body));
                }
            }
            if second == Some(first) {
                return refuse(format!("acts between body {} and itself", self.bodies[first].name));
            }
        }
        match &element.kind {
            ElementKind::JointForce { joint, .. } | ElementKind::JointDamping { joint, .. } => {
                let Some(entry) = self.joints.get(*joint) else {
                    return Err(MechanismError::UnknownJoint(*joint));
                };
                match &entry.model {
                    None => {
                        return refuse(format!(
                            "joint {} is not a joint model (Mechanism::connect)",
                            entry.name()
                        ))
                    }
                    Some(model) => {
                        let dof = model.kind().velocity_count();
                        if matches!(element.kind, ElementKind::JointForce { .. }) && dof != 1 {
                            return refuse(format!(
                                "a joint force needs a one-coordinate joint; {} has {dof} (use a controller)",
                                entry.name()
                            ));
                        }
                    }
                }
            }
            ElementKind::Controller(_) => {
                self.joint_space()?;
            }
            _ => {}
        }
        self.elements.push(element);
        Ok(())
    }

    /// The force elements, in the order added.
    pub fn force_elements(&self) -> &[ForceElement<A>] {
        &self.elements
    }

    /// Adds every force element's wrench on each body (body frame, moments about its centre of mass) into
    /// `external` and returns their non-conservative power (W); `actuators` includes the joint forces and
    /// controllers. `kinematics(i)` is body i's.
    #[inline]
    pub(crate) fn apply_elements<'k>(
        &self,
        t: f64,
        kinematics: &(impl Fn(usize) -> &'k Kinematics<A> + ?Sized),
        external: &mut [ScrewCoordinates],
        actuators: bool,
    ) -> Result<f64, ConstraintError>
    where
        A: 'k,
    {
        let mut total = 0.0;
        let mut add = |body: usize, world: &ScrewCoordinates, sign: f64| {
            let k = kinematics(body);
            let local = k.to_body_coordinates(world);
            external[body] = external[body]
                + ScrewCoordinates {
                    l: local.l * sign,
                    t: local.t * sign,
                };
        };
        for element in &self.elements {
            if !actuators && element.is_actuator() {
                continue;
            }
            let fail = |what: &str| ConstraintError::InvalidParameter {
                name: element.name.clone(),
                reason: format!("{what} at t = {t}"),
            };
            match &element.kind {
                ElementKind::SpringDamper {
                    first,
                    second,
                    stiffness,
                    damping,
                    rest_length,
                } => {
                    let a_kinematics = kinematics(first.0);
                    let (a, va) = (
                        a_kinematics.world_point(&first.1),
                        a_kinematics.world_point_velocity(&first.1),
                    );
                    let (b, vb) = match second.0 {
                        Some(body) => {
                            let k = kinematics(body);
                            (k.world_point(&second.1), k.world_point_velocity(&second.1))
                        }
                        None => (second.1, Vector3::zeros()),
                    };
                    let d = b - a;
                    let length = d.norm();
                    if length == 0.0 {
                        if *rest_length > 0.0 || *damping > 0.0 {
                            return Err(fail("the spring's two points meet, so its line of action is undefined"));
                        }
                        continue;
                    }
                    let direction = d / length;
                    let rate = direction.dot(&(vb - va));
                    let tension = stiffness * (length - rest_length) + damping * rate;
                    let pull = direction * tension;
                    add(first.0, &force_at(pull, a), 1.0);
                    if let Some(body) = second.0 {
                        add(body, &force_at(pull, b), -1.0);
                    }
                    total -= damping * rate * rate;
                }
                ElementKind::Couple { first, second, moment } => {
                    let m = moment.at(t);
                    if !m.iter().all(|x| x.is_finite()) {
                        return Err(fail("the couple is not finite"));
                    }
                    let w = couple(m);
                    add(*first, &w, 1.0);
                    total += m.dot(&kinematics(*first).angular_velocity);
                    if let Some(body) = second {
                        add(*body, &w, -1.0);
                        total -= m.dot(&kinematics(*body).angular_velocity);
                    }
                }
                ElementKind::JointForce { joint, force } => {
                    let tau = force.at(t);
                    if !tau.is_finite() {
                        return Err(fail("the joint force is not finite"));
                    }
                    total += self.apply_joint(*joint, &[tau], kinematics, &mut add);
                }
                ElementKind::JointDamping { joint, coefficient } => {
                    let entry = &self.joints[*joint];
                    let model = entry.model.as_ref().expect("checked when added");
                    let mut rates = [0.0; 7];
                    let n = model.kind().velocity_count();
                    joint_rates(
                        model,
                        kinematics(entry.body),
                        entry.reference.map(kinematics),
                        &mut rates[..n],
                    );
                    let forces: Vec<f64> = rates[..n].iter().map(|r| -coefficient * r).collect();
                    total += self.apply_joint(*joint, &forces, kinematics, &mut add);
                }
                ElementKind::Controller(law) => {
                    total += self.apply_controller(t, &element.name, law, kinematics, &mut add)?;
                }
                ElementKind::Between { first, second, wrench } => {
                    let a = state_of(&self.bodies[*first].body, kinematics(*first));
                    let b = second.map(|body| state_of(&self.bodies[body].body, kinematics(body)));
                    let w = A::screw_coordinates(wrench(t, &a, b.as_ref()));
                    if !w.l.iter().chain(w.t.iter()).all(|x| x.is_finite()) {
                        return Err(fail("the wrench is not finite"));
                    }
                    add(*first, &w, 1.0);
                    total += power(&w, kinematics(*first));
                    if let Some(body) = second {
                        add(*body, &w, -1.0);
                        total -= power(&w, kinematics(*body));
                    }
                }
            }
        }
        Ok(total)
    }

    /// Applies generalised forces to joint `joint`'s coordinates: `+W` on the child, `−W` on the parent; returns
    /// their power `Σ τ q̇`.
    #[inline]
    fn apply_joint<'k>(
        &self,
        joint: usize,
        forces: &[f64],
        kinematics: &(impl Fn(usize) -> &'k Kinematics<A> + ?Sized),
        add: &mut impl FnMut(usize, &ScrewCoordinates, f64),
    ) -> f64
    where
        A: 'k,
    {
        let entry = &self.joints[joint];
        let model = entry.model.as_ref().expect("checked when added");
        let (child, parent) = (kinematics(entry.body), entry.reference.map(kinematics));
        let w = joint_wrench(model, child, parent, forces);
        add(entry.body, &w, 1.0);
        if let Some(p) = entry.reference {
            add(p, &w, -1.0);
        }
        let mut rates = [0.0; 7];
        let n = forces.len();
        joint_rates(model, child, parent, &mut rates[..n]);
        forces.iter().zip(&rates).map(|(f, r)| f * r).sum()
    }

    /// A controller's generalised forces on every coordinate group, from the joint-space state at the bodies'
    /// kinematics; returns their power.
    #[inline]
    fn apply_controller<'k>(
        &self,
        t: f64,
        name: &str,
        law: &crate::force_elements::ControlLaw<A>,
        kinematics: &(impl Fn(usize) -> &'k Kinematics<A> + ?Sized),
        add: &mut impl FnMut(usize, &ScrewCoordinates, f64),
    ) -> Result<f64, ConstraintError>
    where
        A: 'k,
    {
        let fail = |reason: String| ConstraintError::InvalidParameter {
            name: name.to_owned(),
            reason,
        };
        let states: Vec<State<A>> = (0..self.bodies.len())
            .map(|i| state_of(&self.bodies[i].body, kinematics(i)))
            .collect();
        let space = self.joint_space().map_err(|e| fail(e.to_string()))?;
        let positions = self.joint_positions(&states, None).map_err(|e| fail(e.to_string()))?;
        let velocities = self.joint_velocities(&states).map_err(|e| fail(e.to_string()))?;
        let forces: DVector<f64> = law(&JointState {
            t,
            positions: &positions,
            velocities: &velocities,
            states: &states,
            mechanism: self,
        });
        if forces.len() != space.velocity_count() {
            return Err(fail(format!(
                "the control law returned {} forces, the joint space has {} velocity coordinates",
                forces.len(),
                space.velocity_count()
            )));
        }
        if !forces.iter().all(|f| f.is_finite()) {
            return Err(fail(format!(
                "the control law returned forces that are not finite at t = {t}"
            )));
        }
        let mut total = 0.0;
        for group in space.groups() {
            let range = group.velocity_offset()..group.velocity_offset() + group.model().kind().velocity_count();
            let tau = &forces.as_slice()[range.clone()];
            if tau.iter().all(|f| *f == 0.0) {
                continue;
            }
            let body = group.body().index();
            let parent = match group.joint() {
                Some(j) => self.joints[j.index()].reference,
                None => None,
            };
            let (child, parent_kinematics) = (kinematics(body), parent.map(kinematics));
            let w = joint_wrench(group.model(), child, parent_kinematics, tau);
            add(body, &w, 1.0);
            if let Some(p) = parent {
                add(p, &w, -1.0);
            }
            total += tau.iter().zip(&velocities[range]).map(|(f, v)| f * v).sum::<f64>();
        }
        Ok(total)
    }

    /// The potential energy of the conservative force elements (the springs' `½ k (l − l₀)²`) at `states`.
    pub(crate) fn elements_potential(&self, states: &[State<A>]) -> f64 {
        let point = |body: usize, p: &Vector3<f64>| states[body].world_point(*p);
        self.elements
            .iter()
            .map(|element| match &element.kind {
                ElementKind::SpringDamper {
                    first,
                    second,
                    stiffness,
                    rest_length,
                    ..
                } => {
                    let a = point(first.0, &first.1);
                    let b = second.0.map_or(second.1, |body| point(body, &second.1));
                    0.5 * stiffness * ((b - a).norm() - rest_length).powi(2)
                }
                _ => 0.0,
            })
            .sum()
    }
}

impl<A: Algebra> JointSpaceQueries<A> for Mechanism<A> {
    fn mass_matrix(&self, states: &[State<A>]) -> Result<DMatrix<f64>, MechanismError> {
        Mechanism::mass_matrix(self, states)
    }

    fn bias_forces(&self, t: f64, states: &[State<A>]) -> Result<DVector<f64>, MechanismError> {
        Mechanism::bias_forces(self, t, states)
    }
}
