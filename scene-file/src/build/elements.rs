//! The force elements added to the mechanism: the robot's URDF damping and torques, then the file's springs, couples,
//! joint torques, joint damping and PD controllers, each joint found by name.

use std::sync::Arc;

use dynamics::force_elements::{ForceElement, JointState, OfTime};
use dynamics::{JointId, JointKind, Mechanism, Reference};
use nalgebra::DVector;

use super::constraints::FileAlgebra;
use super::system::Place;
use crate::check::elements::element_name;
use crate::check::layout::Layout;
use crate::check::values::{bounded, finite, non_negative};
use crate::error::{invalid, SceneFileError};
use crate::syntax::elements::TimeValue;
use crate::syntax::file::SceneFile;
use crate::syntax::robot::JointDynamicsName;

impl SceneFile {
    /// Adds the force elements: the robot's URDF damping and torques, then the file's springs, couples, joint torques,
    /// joint damping and PD controllers.
    pub(crate) fn add_elements<A: FileAlgebra>(
        &self,
        layout: &Layout,
        system: &mut Mechanism<A>,
        place: &Place<'_>,
        robot: Option<&urdf_import::Robot<A>>,
        file_joints: &[(String, JointId, Option<JointKind>, bool)],
    ) -> Result<(), SceneFileError> {
        let mut taken: Vec<String> = Vec::new();
        let loaded = self.robot()?;
        // A joint by name: its id; `single`: one coordinate (a torque, a PD target).
        let joint = |what: &str, name: &str, single: bool| -> Result<JointId, SceneFileError> {
            if let (Some((_, loaded)), Some(robot)) = (loaded, robot) {
                if loaded.has_joint(name) {
                    if single {
                        loaded.single_coordinate_joint(what, name)?;
                    } else {
                        loaded.joint_index(what, name)?;
                    }
                    return robot
                        .joint(name)
                        .ok_or_else(|| invalid(what, format!("joint `{name}` has no coordinate")));
                }
            }
            match file_joints.iter().find(|(n, ..)| n == name) {
                Some((_, _, Some(JointKind::Weld), _)) => Err(invalid(
                    what,
                    format!("joint `{name}` is a fixed joint: it has no coordinates"),
                )),
                Some((_, id, Some(kind), false)) => {
                    if single && kind.velocity_count() != 1 {
                        return Err(invalid(
                            what,
                            format!(
                                "joint `{name}` is a {} joint, with {} coordinates; a torque or a PD target needs a \
                                 hinge or prismatic joint",
                                kind.name(),
                                kind.velocity_count()
                            ),
                        ));
                    }
                    Ok(*id)
                }
                Some((_, _, Some(_), true)) => Err(invalid(
                    what,
                    format!("joint `{name}` is driven: its motion is prescribed, so a force on it does nothing"),
                )),
                Some((_, _, None, _)) => Err(invalid(
                    what,
                    format!(
                        "joint `{name}` is a constraint without coordinates (it is not a body's first joint of a \
                         kind with coordinates)"
                    ),
                )),
                None => {
                    let mut known: Vec<&str> = loaded
                        .map(|(_, l)| l.model.joints.iter().map(|j| j.name.as_str()).collect())
                        .unwrap_or_default();
                    known.extend(file_joints.iter().map(|(n, ..)| n.as_str()));
                    Err(invalid(
                        what,
                        format!(
                            "no joint named `{name}` (the joints: {})",
                            if known.is_empty() {
                                "none".to_owned()
                            } else {
                                known.join(", ")
                            }
                        ),
                    ))
                }
            }
        };
        if let (Some((spec, loaded)), Some(robot)) = (loaded, robot) {
            if spec.joint_dynamics == JointDynamicsName::Urdf {
                for urdf_joint in loaded.model.joints.iter().filter(|j| j.damping > 0.0) {
                    let id = robot.joint(&urdf_joint.name).expect("a moving joint");
                    let name = element_name(&None, || format!("{} damping (URDF)", urdf_joint.name), &mut taken)?;
                    system.add_force_element(ForceElement::joint_damping(name, id, urdf_joint.damping)?)?;
                }
            }
            for (name, value) in &spec.torque {
                let what = format!("robot.torque.{name}");
                let id = joint("robot.torque", name, true)?;
                let value = bounded(&what, *value)?;
                let element = element_name(&None, || format!("torque on {name}"), &mut taken)?;
                system.add_force_element(ForceElement::joint_force(element, id, OfTime::Constant(value)))?;
            }
        }
        // Two ends of an element: the first a body (swapped if it is the world), and whether they were swapped.
        let ends = |what: &str, between: &[String; 2]| -> Result<_, SceneFileError> {
            let first = self.end(layout, what, &between[0])?;
            let second = self.end(layout, what, &between[1])?;
            let (first, second) = (place(&first)?, place(&second)?);
            let same = match (first.0, second.0) {
                (Reference::World, Reference::World) => true,
                (Reference::Body(a), Reference::Body(b)) => a == b,
                _ => false,
            };
            if same {
                return Err(invalid(
                    format!("{what}: between"),
                    format!(
                        "{} and {} are on the same body (or both on the world): the element would act on nothing",
                        between[0], between[1]
                    ),
                ));
            }
            Ok(match first.0 {
                Reference::World => (second, first, true),
                Reference::Body(_) => (first, second, false),
            })
        };
        let body_of = |reference: Reference| match reference {
            Reference::Body(body) => body,
            Reference::World => unreachable!("the first end is a body"),
        };
        for (k, spring) in self.spring.iter().enumerate() {
            let name = element_name(&spring.name, || format!("spring {}", k + 1), &mut taken)?;
            let what = format!("spring {name}");
            let ((first, first_frame), (second, second_frame), swapped) = ends(&what, &spring.between)?;
            let [mut a, mut b] = spring.points;
            if swapped {
                std::mem::swap(&mut a, &mut b);
            }
            let (a, b) = (
                finite(&format!("{what}: points"), a)?,
                finite(&format!("{what}: points"), b)?,
            );
            let stiffness = non_negative(&format!("{what}: stiffness"), spring.stiffness)?;
            let damping = non_negative(&format!("{what}: damping"), spring.damping)?;
            let rest = non_negative(&format!("{what}: rest_length"), spring.rest_length)?;
            let element = ForceElement::spring_damper(
                name,
                (body_of(first), first_frame.transform_point(&a.into()).coords),
                (second, second_frame.transform_point(&b.into()).coords),
                stiffness,
                damping,
                rest,
            )?;
            system.add_force_element(element)?;
        }
        for (k, couple) in self.couple.iter().enumerate() {
            let name = element_name(&couple.name, || format!("couple {}", k + 1), &mut taken)?;
            let what = format!("couple {name}");
            let ((first, _), (second, _), swapped) = ends(&what, &couple.between)?;
            let moment = finite(&format!("{what}: moment"), couple.moment)?;
            let moment = if swapped { -moment } else { moment };
            system.add_force_element(ForceElement::couple(
                name,
                body_of(first),
                second,
                OfTime::Constant(moment),
            ))?;
        }
        for torque in &self.joint_torque {
            let name = element_name(&torque.name, || format!("torque on {}", torque.joint), &mut taken)?;
            let what = format!("joint_torque {name}");
            let id = joint(&format!("{what}: joint"), &torque.joint, true)?;
            let value = torque.torque.checked(&format!("{what}: torque"))?;
            let force = match value {
                TimeValue::Constant(value) => OfTime::Constant(value),
                sine => OfTime::Function(Arc::new(move |t| sine.at(t))),
            };
            system.add_force_element(ForceElement::joint_force(name, id, force))?;
        }
        for damping in &self.joint_damping {
            let name = element_name(&damping.name, || format!("damping on {}", damping.joint), &mut taken)?;
            let what = format!("joint_damping {name}");
            let id = joint(&format!("{what}: joint"), &damping.joint, false)?;
            let coefficient = non_negative(&format!("{what}: damping"), damping.damping)?;
            system.add_force_element(ForceElement::joint_damping(name, id, coefficient)?)?;
        }
        for (k, pd) in self.pd.iter().enumerate() {
            let name = element_name(&pd.name, || format!("pd {}", k + 1), &mut taken)?;
            let what = format!("pd {name}");
            let kp = non_negative(&format!("{what}: kp"), pd.kp)?;
            let kd = non_negative(&format!("{what}: kd"), pd.kd)?;
            if pd.target.is_empty() {
                return Err(invalid(
                    format!("{what}: target"),
                    "names no joint: write target = { joint = value, … }",
                ));
            }
            let space = system.joint_space()?;
            let mut targets = Vec::with_capacity(pd.target.len());
            for (joint_name, value) in &pd.target {
                let id = joint(&format!("{what}: target"), joint_name, true)?;
                let value = bounded(&format!("{what}: target.{joint_name}"), *value)?;
                let group = space.groups().iter().find(|g| g.joint() == Some(id)).ok_or_else(|| {
                    invalid(
                        format!("{what}: target"),
                        format!("joint `{joint_name}` has no coordinate"),
                    )
                })?;
                let turns = matches!(group.model().kind(), JointKind::Revolute { .. });
                targets.push((group.position_offset(), group.velocity_offset(), value, turns));
            }
            let compensate = pd.gravity_compensation;
            let law = move |state: &JointState<'_, A>| {
                let n = state.velocities.len();
                let bias = if compensate {
                    match state.bias_forces() {
                        Ok(h) => Some(h),
                        Err(_) => return DVector::from_element(n, f64::NAN),
                    }
                } else {
                    None
                };
                let mut tau = DVector::zeros(n);
                for &(p, v, target, turns) in &targets {
                    let mut error = target - state.positions[p];
                    if turns {
                        // Angles are read in (−π, π]: the error is taken the short way round.
                        error -= std::f64::consts::TAU * (error / std::f64::consts::TAU).round();
                    }
                    tau[v] = kp * error - kd * state.velocities[v] + bias.as_ref().map_or(0.0, |h| h[v]);
                }
                tau
            };
            system.add_force_element(ForceElement::controller(name, Arc::new(law)))?;
        }
        Ok(())
    }
}
