//! The force elements added to the mechanism: the robot's URDF damping and torques, then the file's springs, couples,
//! joint torques, joint damping and PD controllers, each joint found by name among the robot's and the file's, and
//! every value checked as it is added.

use std::sync::Arc;

use dynamics::mechanism::force_elements::{ForceElement, JointState, OfTime};
use dynamics::{Algebra, BodyId, JointId, JointKind, Mechanism, Reference};
use nalgebra::{DVector, Isometry3, Vector3};

use super::assembly::{Assembly, FileJoint, Places};
use crate::check::elements::element_name;
use crate::check::robot::LoadedRobot;
use crate::check::scene::CheckedScene;
use crate::check::values::{bounded, finite, non_negative};
use crate::error::{invalid, SceneFileError};
use crate::syntax::elements::{PdSpec, SpringSpec, TimeValue};
use crate::syntax::robot::JointDynamicsName;

/// Adds the force elements: the robot's URDF damping and torques, then the file's springs, couples, joint torques,
/// joint damping and PD controllers.
pub(crate) fn add_elements<A: Algebra>(assembly: &mut Assembly<A>) -> Result<(), SceneFileError> {
    let scene = assembly.scene;
    let Assembly {
        mechanism,
        places,
        file_joints,
        ..
    } = assembly;
    let places: &Places<A> = places;
    let mut elements = Elements {
        scene,
        mechanism,
        places,
        joints: Joints {
            robot: (scene.robot.as_ref().map(|robot| &robot.loaded)).zip(places.robot.as_ref()),
            file: file_joints,
        },
        taken: Vec::new(),
    };
    elements.add_robot_elements()?;
    for (k, spring) in scene.springs.iter().enumerate() {
        elements.add_spring(k, spring)?;
    }
    for (k, couple) in scene.couples.iter().enumerate() {
        let name = element_name(&couple.name, || format!("couple {}", k + 1), &mut elements.taken)?;
        let what = format!("couple {name}");
        let ends = elements.ends(&what, &couple.between)?;
        let moment = finite(&format!("{what}: moment"), couple.moment)?;
        let moment = if ends.swapped { -moment } else { moment };
        let element = ForceElement::couple(name, ends.first.0, ends.second.0, OfTime::Constant(moment));
        elements.mechanism.add_force_element(element)?;
    }
    for torque in &scene.joint_torques {
        let name = element_name(
            &torque.name,
            || format!("torque on {}", torque.joint),
            &mut elements.taken,
        )?;
        let what = format!("joint_torque {name}");
        let id = elements.joints.find(&format!("{what}: joint"), &torque.joint, true)?;
        let force = match torque.torque.checked(&format!("{what}: torque"))? {
            TimeValue::Constant(value) => OfTime::Constant(value),
            sine => OfTime::Function(Arc::new(move |t| sine.at(t))),
        };
        elements
            .mechanism
            .add_force_element(ForceElement::joint_force(name, id, force))?;
    }
    for damping in &scene.joint_dampings {
        let name = element_name(
            &damping.name,
            || format!("damping on {}", damping.joint),
            &mut elements.taken,
        )?;
        let what = format!("joint_damping {name}");
        let id = elements.joints.find(&format!("{what}: joint"), &damping.joint, false)?;
        let coefficient = non_negative(&format!("{what}: damping"), damping.damping)?;
        let element = ForceElement::joint_damping(name, id, coefficient)?;
        elements.mechanism.add_force_element(element)?;
    }
    for (k, pd) in scene.pds.iter().enumerate() {
        elements.add_pd(k, pd)?;
    }
    Ok(())
}

/// The mechanism's force elements being added, and the names already taken.
struct Elements<'a, A: Algebra> {
    scene: &'a CheckedScene,
    mechanism: &'a mut Mechanism<A>,
    places: &'a Places<A>,
    joints: Joints<'a, A>,
    taken: Vec<String>,
}

/// An element's two ends, each with its frame there: the first on a body, the second on a body or the world.
struct Ends {
    first: (BodyId, Isometry3<f64>),
    second: (Reference, Isometry3<f64>),
    /// Whether the file wrote them the other way round (the world first).
    swapped: bool,
}

impl<A: Algebra> Elements<'_, A> {
    /// The URDF's joint damping (with `joint_dynamics = "urdf"`) and the `[robot]`'s constant torques.
    fn add_robot_elements(&mut self) -> Result<(), SceneFileError> {
        let Some((robot, built)) = self.joints.robot else {
            return Ok(());
        };
        if robot.spec.joint_dynamics == JointDynamicsName::Urdf {
            for urdf_joint in robot.model.joints.iter().filter(|j| j.damping > 0.0) {
                let id = built.joint(&urdf_joint.name).expect("a moving joint");
                let name = element_name(&None, || format!("{} damping (URDF)", urdf_joint.name), &mut self.taken)?;
                let element = ForceElement::joint_damping(name, id, urdf_joint.damping)?;
                self.mechanism.add_force_element(element)?;
            }
        }
        for (name, value) in &robot.spec.torque {
            let what = format!("robot.torque.{name}");
            let id = self.joints.find("robot.torque", name, true)?;
            let value = bounded(&what, *value)?;
            let element = element_name(&None, || format!("torque on {name}"), &mut self.taken)?;
            let element = ForceElement::joint_force(element, id, OfTime::Constant(value));
            self.mechanism.add_force_element(element)?;
        }
        Ok(())
    }

    /// A spring-damper between the points of its two ends.
    fn add_spring(&mut self, k: usize, spring: &SpringSpec) -> Result<(), SceneFileError> {
        let name = element_name(&spring.name, || format!("spring {}", k + 1), &mut self.taken)?;
        let what = format!("spring {name}");
        let Ends {
            first: (first, first_frame),
            second: (second, second_frame),
            swapped,
        } = self.ends(&what, &spring.between)?;
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
        let at = |frame: Isometry3<f64>, point: Vector3<f64>| frame.transform_point(&point.into()).coords;
        let element = ForceElement::spring_damper(
            name,
            (first, at(first_frame, a)),
            (second, at(second_frame, b)),
            stiffness,
            damping,
            rest,
        )?;
        self.mechanism.add_force_element(element)?;
        Ok(())
    }

    /// A PD controller on one-coordinate joints, with the bias forces added if it compensates gravity.
    fn add_pd(&mut self, k: usize, pd: &PdSpec) -> Result<(), SceneFileError> {
        let name = element_name(&pd.name, || format!("pd {}", k + 1), &mut self.taken)?;
        let what = format!("pd {name}");
        let kp = non_negative(&format!("{what}: kp"), pd.kp)?;
        let kd = non_negative(&format!("{what}: kd"), pd.kd)?;
        if pd.target.is_empty() {
            return Err(invalid(
                format!("{what}: target"),
                "names no joint: write target = { joint = value, … }",
            ));
        }
        let space = self.mechanism.joint_space()?;
        let mut targets = Vec::with_capacity(pd.target.len());
        for (joint_name, value) in &pd.target {
            let id = self.joints.find(&format!("{what}: target"), joint_name, true)?;
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
        self.mechanism
            .add_force_element(ForceElement::controller(name, Arc::new(law)))?;
        Ok(())
    }

    /// The two ends of the element `what` between `between`, swapped if the first is the world.
    fn ends(&self, what: &str, between: &[String; 2]) -> Result<Ends, SceneFileError> {
        let robot = self.scene.robot.as_ref().map(|robot| &robot.loaded);
        let end = |name: &str| {
            let end = (self.scene.layout).end(robot, &format!("{what}: between"), name)?;
            self.places.place(&end)
        };
        let (first, second) = (end(&between[0])?, end(&between[1])?);
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
        let (first, second, swapped) = match (first, second) {
            ((Reference::Body(body), frame), second) => ((body, frame), second, false),
            (world, (Reference::Body(body), frame)) => ((body, frame), world, true),
            (_, _) => unreachable!("the two ends are not both the world"),
        };
        Ok(Ends { first, second, swapped })
    }
}

/// The joints force elements name: the robot's (its URDF and the robot built) and the file's.
struct Joints<'a, A: Algebra> {
    robot: Option<(&'a LoadedRobot, &'a urdf_import::Robot<A>)>,
    file: &'a [FileJoint],
}

impl<A: Algebra> Joints<'_, A> {
    /// The joint `name`, with coordinates a force can act on; `single`: one coordinate (a torque, a PD target). Errors
    /// under `what`.
    fn find(&self, what: &str, name: &str, single: bool) -> Result<JointId, SceneFileError> {
        if let Some((robot, built)) = self.robot {
            if robot.has_joint(name) {
                if single {
                    robot.single_coordinate_joint(what, name)?;
                } else {
                    robot.joint_index(what, name)?;
                }
                return built
                    .joint(name)
                    .ok_or_else(|| invalid(what, format!("joint `{name}` has no coordinate")));
            }
        }
        let Some(joint) = self.file.iter().find(|j| j.name == name) else {
            let mut known: Vec<&str> = self
                .robot
                .map(|(robot, _)| robot.model.joints.iter().map(|j| j.name.as_str()).collect())
                .unwrap_or_default();
            known.extend(self.file.iter().map(|j| j.name.as_str()));
            return Err(invalid(
                what,
                format!(
                    "no joint named `{name}` (the joints: {})",
                    if known.is_empty() {
                        "none".to_owned()
                    } else {
                        known.join(", ")
                    }
                ),
            ));
        };
        match (joint.model, joint.driven) {
            (Some(JointKind::Weld), _) => Err(invalid(
                what,
                format!("joint `{name}` is a fixed joint: it has no coordinates"),
            )),
            (Some(kind), false) => {
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
                Ok(joint.id)
            }
            (Some(_), true) => Err(invalid(
                what,
                format!("joint `{name}` is driven: its motion is prescribed, so a force on it does nothing"),
            )),
            (None, _) => Err(invalid(
                what,
                format!(
                    "joint `{name}` is a constraint without coordinates (it is not a body's first joint of a kind \
                     with coordinates)"
                ),
            )),
        }
    }
}
