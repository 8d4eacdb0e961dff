//! A system ready to run in one algebra ([`SceneSystem`]): the mechanism (the robot's bodies and joints first, then the
//! file's), its initial state projected onto the joints, and what the run measures; and running it.

use dynamics::integrate::Integrator;
use dynamics::simulate::{simulate, Schedule, Simulation, SimulationError};
use dynamics::{Algebra, Correction, Dynamics, FreeBody, Mechanism, State, Stepper};
use nalgebra::{Isometry3, Translation3, Vector3};

use super::assembly::Assembly;
use super::constraints::RoundPins;
use super::contacts::{add_contacts, check_contact_start};
use super::elements::add_elements;
use super::pairs::{add_pair_contacts, deepest_overlap, ShapePair};
use super::robot::{RobotColumns, RobotJoint};
use crate::check::bodies::Pose;
use crate::check::geometry::{joint_violations, JointGeometry};
use crate::check::scene::CheckedScene;
use crate::error::{invalid, SceneFileError};

/// A system ready to run in one algebra: the mechanism (the robot's bodies and joints first, then the file's), its
/// initial state (one per body) on the joints, and what the run measures.
pub struct SceneSystem<A: Algebra> {
    mechanism: Mechanism<A>,
    /// The single body of a free-body scene, where every integrator (splittings included) applies.
    free_body: Option<FreeBody<A>>,
    initial: Vec<State<A>>,
    /// Every body's name, in the mechanism's order.
    names: Vec<String>,
    /// The file's joints: their geometry (reference side in the reference body's frame, or the world's), body and
    /// reference, by mechanism index.
    geometries: Vec<JointGeometry>,
    /// The robot's moving joints: model, child, parent (mechanism indices) and where the coordinates start.
    robot_joints: Vec<RobotJoint>,
    /// The joints CSV's columns, with a robot.
    robot_columns: Option<RobotColumns>,
    /// How far putting the file's start on the joints moved each body.
    start_correction: Correction,
    /// The `[[collision]]` pairs' shapes, for [`SceneSystem::deepest_overlap`].
    shape_pairs: Vec<ShapePair>,
}

impl<A: Algebra> SceneSystem<A> {
    /// The mechanism.
    pub fn mechanism(&self) -> &Mechanism<A> {
        &self.mechanism
    }

    /// The initial state, one per body, on the joints.
    pub fn initial(&self) -> &[State<A>] {
        &self.initial
    }

    /// Every body's name, in the mechanism's order (the robot's bodies, named after their links, first).
    pub fn body_names(&self) -> &[String] {
        &self.names
    }

    /// How far putting the file's start on the joints moved each body.
    pub fn start_correction(&self) -> &Correction {
        &self.start_correction
    }

    /// The `[[collision]]` pair of shapes that go deepest into each other with the bodies at `states` (mechanism
    /// order): its description ("`pair`: `body` `shape` and `body` `shape`") and the depth (m), from parry3d's contact
    /// query, independent of the contacts; `None` where no two shapes of a pair overlap. The contacts keep the
    /// features they watch apart; this sees shapes that meet elsewhere (a sphere past the face it is held on,
    /// docs/contacts.md "Between bodies"), to within parry3d's tolerance for polytopes (some 1e-8 m).
    pub fn deepest_overlap(&self, states: &[State<A>]) -> Option<(String, f64)> {
        (states.len() == self.names.len())
            .then(|| deepest_overlap(&self.shape_pairs, states))
            .flatten()
    }

    /// The headers of the joints CSV between `t` and `energy`, with a robot.
    pub fn joint_columns(&self) -> Option<&[String]> {
        self.robot_columns.as_ref().map(|c| c.headers.as_slice())
    }

    /// The joints CSV's values between `t` and `energy` at the mechanism's joint positions `q`.
    pub fn joint_row(&self, q: &[f64]) -> Option<Vec<f64>> {
        self.robot_columns.as_ref().map(|c| c.row(q))
    }

    /// The largest joint violation with the bodies at `poses` (mechanism order): the file's joints measured as
    /// [`CheckedGeometry::violation`](crate::CheckedGeometry::violation) (m), the robot's by how far each child is
    /// from where its joint's coordinates put it relative to its parent (the joint origin's distance, m, and the turn's angle, rad). `q`: the joint
    /// positions at these poses, if known.
    pub fn joint_violation(&self, poses: &[Pose], q: Option<&[f64]>) -> f64 {
        let files = joint_violations(&self.geometries, poses).fold(0.0, f64::max);
        if self.robot_joints.is_empty() {
            return files;
        }
        let read;
        let q = match q {
            Some(q) => q,
            None => {
                let states: Vec<State<A>> = poses
                    .iter()
                    .enumerate()
                    .map(|(i, (position, orientation))| {
                        State::new(
                            self.mechanism.body(i),
                            *position,
                            orientation,
                            Vector3::zeros(),
                            Vector3::zeros(),
                        )
                    })
                    .collect();
                match self.mechanism.joint_positions(&states, None) {
                    Ok(q) => {
                        read = q;
                        &read
                    }
                    Err(_) => return f64::NAN,
                }
            }
        };
        let isometry =
            |(position, orientation): &Pose| Isometry3::from_parts(Translation3::from(*position), *orientation);
        let robot = self
            .robot_joints
            .iter()
            .map(|(model, child, parent, offset)| {
                let parent = parent.map_or(Isometry3::identity(), |p| isometry(&poses[p]));
                let relative = parent.inverse() * isometry(&poses[*child]);
                let actual = model.parent_frame().inverse() * relative * model.child_frame();
                let count = model.kind().position_count();
                match model.joint_pose(&q[*offset..*offset + count]) {
                    Ok(placed) => (actual.translation.vector - placed.translation.vector)
                        .norm()
                        .max(actual.rotation.angle_to(&placed.rotation)),
                    Err(_) => f64::NAN,
                }
            })
            .fold(0.0, f64::max);
        files.max(robot)
    }

    /// Runs the system with `integrator` on `schedule`: a free-body scene as a free body, otherwise the mechanism.
    pub fn run(&self, integrator: Integrator, schedule: &Schedule) -> Result<Simulation<A>, SceneFileError> {
        let failed = |error: SimulationError| SceneFileError::Run {
            algebra: A::NAME,
            message: error.to_string(),
        };
        match &self.free_body {
            Some(free_body) => simulate(free_body, &self.initial, integrator, schedule).map_err(failed),
            None => simulate(&self.mechanism, &self.initial, integrator, schedule).map_err(failed),
        }
    }
}

/// The system of `scene` in algebra `A`, its initial state projected onto the joints; an error if the joints cannot
/// all hold there, their reactions cannot be solved for, or the integrator cannot step it.
pub(crate) fn build<A: RoundPins>(scene: &CheckedScene) -> Result<SceneSystem<A>, SceneFileError> {
    let mut assembly = Assembly::<A>::new(scene)?;
    assembly.add_joints()?;
    assembly.mechanism.set_stabilisation(scene.stabilisation)?;
    add_elements(&mut assembly)?;
    add_contacts(&mut assembly)?;
    let (initial, start_correction) = start(&assembly)?;
    // The pairs' features are chosen where the start is, on the joints (a body a joint places has its pose only now).
    let shape_pairs = add_pair_contacts(&mut assembly, &initial)?;
    let Assembly {
        mechanism,
        places,
        geometries,
        ..
    } = assembly;
    // A rank-deficient or inconsistent reaction solve fails here, with the joints' names.
    mechanism.rates_at(0.0, &initial)?;
    let (robot_columns, robot_joints) = match (&places.robot, &scene.robot) {
        (Some(built), Some(robot)) => (
            Some(robot.loaded.columns(built, &mechanism)?),
            robot.loaded.joint_models(built, &mechanism)?,
        ),
        _ => (None, Vec::new()),
    };
    // An integrator stepping in joint coordinates needs every joint a joint model, in a tree: refused here, naming
    // the integrator, rather than when the run starts.
    let integrator = Integrator::from(scene.integrator);
    if matches!(integrator, Integrator::Joint(_)) {
        Stepper::new(&mechanism, integrator).map_err(|e| invalid("integrator", e.to_string()))?;
    }
    let free_body = scene.free_body.then(|| {
        let only = &scene.layout.bodies[0];
        (only.forces.iter()).fold(FreeBody::new(only.body), |free, force| free.with_force(force.force()))
    });
    Ok(SceneSystem {
        names: mechanism.body_names().map(str::to_owned).collect(),
        mechanism,
        free_body,
        initial,
        start_correction,
        geometries,
        robot_joints,
        robot_columns,
        shape_pairs,
    })
}

/// The start on the joints (theory §10) and how far putting it there moved each body: joints that cannot hold together
/// are an error naming them, and a start that breaks them by more than the file allows, puts a driven joint off its
/// path, a limited one outside its limit or a contact point below its plane is refused.
fn start<A: Algebra>(assembly: &Assembly<A>) -> Result<(Vec<State<A>>, Correction), SceneFileError> {
    let Assembly { scene, mechanism, .. } = assembly;
    let mut initial = assembly.states.clone();
    let correction = mechanism.project(0.0, &mut initial)?;
    // Bodies on a joint model are placed by their joint, from the coordinates their state gives; the others' states
    // are where the file puts them.
    let held_as_given: Vec<bool> = (assembly.parent_of.iter().enumerate())
        .map(|(index, parent)| {
            let given = |name: &str| (scene.layout.bodies.iter()).any(|body| body.initial_given && body.name == name);
            parent.is_none() && mechanism.body_names().nth(index).is_some_and(given)
        })
        .collect();
    check_start_correction(scene.max_start_correction, &correction, mechanism, &held_as_given)?;
    if !assembly.driven.is_empty() {
        // The driven joints start on their paths (the projection by joint coordinates leaves them where they are).
        let mut q = mechanism.joint_positions(&initial, None)?;
        let mut v = mechanism.joint_velocities(&initial)?;
        let space = mechanism.joint_space()?;
        for (id, drive) in &assembly.driven {
            if let Some(group) = space.groups().iter().find(|g| g.joint() == Some(*id)) {
                let at = drive.at(0.0);
                q[group.position_offset()] = at.value;
                v[group.velocity_offset()] = at.rate;
            }
        }
        initial = mechanism.states_from_joints(&q, &v)?;
        mechanism.project(0.0, &mut initial)?;
    }
    if !assembly.limited.is_empty() {
        // A start outside a limit, by the joint's coordinate as the start gives it.
        let q = mechanism.joint_positions(&initial, None)?;
        let space = mechanism.joint_space()?;
        for (name, limit) in &assembly.limited {
            let group = space.group(name).expect("a limited joint is a joint model");
            let at = q[group.position_offset()];
            if limit.gap(at) < -dynamics::simulate::AT_BOUND {
                return Err(invalid(
                    format!("joint {name}: limit"),
                    format!(
                        "the start puts the joint at {at:?}, outside [{:?}, {:?}]",
                        limit.lower(),
                        limit.upper()
                    ),
                ));
            }
        }
    }
    check_contact_start(scene, mechanism, &initial)?;
    Ok((initial, correction))
}

/// Refuses a start that the projection onto the joints moved by more than `limit` (m and rad), naming the body: of the
/// bodies `checked` by index, those whose initial state the file gives and no joint model places.
fn check_start_correction<A: Algebra>(
    limit: f64,
    correction: &Correction,
    mechanism: &Mechanism<A>,
    checked: &[bool],
) -> Result<(), SceneFileError> {
    let names: Vec<&str> = mechanism.body_names().collect();
    let largest = (correction.moved.iter().zip(&correction.turned).enumerate())
        .filter(|(body, _)| checked.get(*body).copied().unwrap_or(false))
        .map(|(body, (moved, turned))| (body, moved.max(*turned)))
        .max_by(|a, b| a.1.total_cmp(&b.1));
    match largest {
        Some((body, largest)) if largest > limit => Err(invalid(
            "max_start_correction",
            format!(
                "the start breaks the joints: putting it on them moves body `{}` by {:.3e} m and turns it by \
                 {:.3e} rad, more than max_start_correction = {limit} (m and rad); correct its initial state or \
                 raise max_start_correction",
                names[body], correction.moved[body], correction.turned[body],
            ),
        )),
        _ => Ok(()),
    }
}
