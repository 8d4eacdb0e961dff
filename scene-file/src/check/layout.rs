//! Two layouts, one list of bodies and joints ([`Layout`]): a single `[body]` with its `[initial]` state, `[[forces]]`
//! and `[[constraints]]` to the world; or named `[[body]]` entries, each with its `initial` state and `forces`, and
//! `[[joint]]` entries `between = ["body", "other body", "world" or a robot link]`, with or without a `[robot]`; every name
//! resolved.

use super::geometry::{relative_pose, JointGeometry, Pose};
use super::robot::LoadedRobot;
use super::values::finite;
use crate::error::{invalid, SceneFileError};
use crate::names::FormulationName;
use crate::syntax::bodies::{Bodies, BodySpec, ForceSpec, InitialSpec, NamedBody};
use crate::syntax::elements::DriveSpec;
use crate::syntax::file::SceneFile;
use crate::syntax::joints::{Geometry, LimitSpec};

/// A body of the scene, whichever layout it came from.
#[derive(Clone, Debug)]
pub struct LayoutBody {
    pub name: String,
    pub spec: BodySpec,
    /// Its state at t = 0, as the file gives it.
    pub initial: InitialSpec,
    /// Whether the file gives it (an `initial` table); otherwise its joint places it.
    pub initial_given: bool,
    pub forces: Vec<ForceSpec>,
}

/// What a joint holds its body to, or where a force element's end is.
#[derive(Clone, Debug, PartialEq)]
pub enum End {
    World,
    /// A body of the file, by its index in [`Layout::bodies`].
    Body(usize),
    /// A link of the robot, by name.
    Link(String),
}

/// A joint of the scene: its name in messages, its body (by index) and reference.
#[derive(Clone, Debug)]
pub struct LayoutJoint {
    pub name: String,
    pub body: usize,
    pub reference: End,
    pub formulation: FormulationName,
    pub geometry: Geometry,
    /// A `[[joint]]` entry (a joint model where it can be), not a `[[constraints]]` one.
    pub entry: bool,
    pub drive: Option<DriveSpec>,
    pub limit: Option<LimitSpec>,
}

/// The scene's bodies and joints.
#[derive(Clone, Debug)]
pub struct Layout {
    /// In file order.
    pub bodies: Vec<LayoutBody>,
    pub joints: Vec<LayoutJoint>,
    /// Whether the bodies are named `[[body]]` entries (else the single `[body]`, named "body").
    pub named: bool,
}

impl Layout {
    /// Per joint: its checked geometry (reference-side values in the reference's frame), its body and its
    /// reference, to measure violations with.
    ///
    /// A fixed joint without a given pose holds its body where the file starts it (before the projection onto the
    /// joints). Joints to a robot link are placed by the system ([`SceneSystem::joint_violation`](crate::SceneSystem::joint_violation)), not here: they are
    /// an error.
    pub fn joint_geometries(&self) -> Result<Vec<JointGeometry>, SceneFileError> {
        self.joints
            .iter()
            .map(|j| {
                let reference = match &j.reference {
                    End::World => None,
                    End::Body(index) => Some(*index),
                    End::Link(link) => {
                        return Err(invalid(
                            format!("joint {}: between", j.name),
                            format!(
                                "its reference is the robot link {link}, which only the built system places (see \
                                 SceneSystem::joint_violation)"
                            ),
                        ))
                    }
                };
                let start = if j.geometry.needs_start() {
                    let body = self.initial_pose(j.body)?;
                    let reference = reference.map(|r| self.initial_pose(r)).transpose()?;
                    Some(relative_pose(&body, reference.as_ref()))
                } else {
                    None
                };
                Ok((j.geometry.checked(&j.name, start)?, j.body, reference))
            })
            .collect()
    }

    /// Body `index`'s pose as the file starts it.
    fn initial_pose(&self, index: usize) -> Result<Pose, SceneFileError> {
        let body = &self.bodies[index];
        let prefix = prefix(self, &body.name);
        let position = finite(&format!("{prefix}initial.position"), body.initial.position)?;
        let orientation = body
            .initial
            .orientation
            .rotation()
            .map_err(|e| named(self, &body.name, e))?;
        Ok((position, orientation))
    }
}

/// The name of the world in `between`.
const WORLD: &str = "world";

impl SceneFile {
    /// The bodies and joints, from either layout, with every name resolved.
    pub fn layout(&self) -> Result<Layout, SceneFileError> {
        let robot = self.robot()?;
        match &self.body {
            Some(Bodies::One(spec)) => {
                if robot.is_some() {
                    return Err(invalid(
                        "body",
                        "with a [robot], write the scene's other bodies as [[body]] entries with a `name`",
                    ));
                }
                if !self.joint.is_empty() {
                    return Err(invalid(
                        "joint",
                        "[[joint]] entries join named bodies: write the bodies as [[body]] entries with a `name`",
                    ));
                }
                let joints = self
                    .constraints
                    .iter()
                    .enumerate()
                    .map(|(index, c)| LayoutJoint {
                        name: format!("{} ({})", index + 1, c.geometry.kind()),
                        body: 0,
                        reference: End::World,
                        formulation: c.formulation,
                        geometry: c.geometry.clone(),
                        entry: false,
                        drive: None,
                        limit: None,
                    })
                    .collect();
                Ok(Layout {
                    bodies: vec![LayoutBody {
                        name: "body".to_owned(),
                        spec: spec.clone(),
                        initial: self.initial.clone().unwrap_or_default(),
                        initial_given: self.initial.is_some(),
                        forces: self.forces.clone(),
                    }],
                    joints,
                    named: false,
                })
            }
            Some(Bodies::Named(entries)) => self.named_layout(entries, robot.map(|(_, loaded)| loaded)),
            None => match robot {
                Some((_, loaded)) => self.named_layout(&[], Some(loaded)),
                None => Err(invalid(
                    "body",
                    "a scene needs a [body] table, [[body]] entries or a [robot]",
                )),
            },
        }
    }

    /// The layout of named `[[body]]` entries (none with a robot alone), their joints and the robot's links.
    fn named_layout(&self, entries: &[NamedBody], robot: Option<&LoadedRobot>) -> Result<Layout, SceneFileError> {
        if self.initial.is_some() || !self.forces.is_empty() || !self.constraints.is_empty() {
            return Err(invalid(
                "initial, forces, constraints",
                "with [[body]] entries or a [robot], give each body its `initial` state and `forces` in its entry, \
                 and the joints as [[joint]] entries",
            ));
        }
        if entries.is_empty() && robot.is_none() {
            return Err(invalid("body", "needs at least one entry"));
        }
        let mut bodies: Vec<LayoutBody> = Vec::with_capacity(entries.len());
        for entry in entries {
            let name = &entry.name;
            let valid = !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
            if !valid {
                return Err(invalid(
                    format!("body {name:?}"),
                    "a name is letters, digits, `_` and `-` (it heads the CSV columns)",
                ));
            }
            if name == WORLD || bodies.iter().any(|b| &b.name == name) {
                return Err(invalid(
                    format!("body {name}"),
                    if name == WORLD {
                        "\"world\" is the name of the world".to_owned()
                    } else {
                        "two bodies have this name".to_owned()
                    },
                ));
            }
            if robot.is_some_and(|r| r.links().any(|link| link == name)) {
                return Err(invalid(
                    format!("body {name}"),
                    "the robot has a link of this name (its bodies are named after their links)",
                ));
            }
            bodies.push(LayoutBody {
                name: name.clone(),
                spec: BodySpec {
                    mass: entry.mass,
                    shape: entry.shape.clone(),
                    principal_moments: entry.principal_moments,
                },
                initial: entry.initial.clone().unwrap_or_default(),
                initial_given: entry.initial.is_some(),
                forces: entry.forces.clone(),
            });
        }
        let mut joints: Vec<LayoutJoint> = Vec::with_capacity(self.joint.len());
        for spec in &self.joint {
            let name = &spec.name;
            if name.is_empty() {
                return Err(invalid("joint \"\"", "a joint needs a non-empty name"));
            }
            if joints.iter().any(|j| &j.name == name) {
                return Err(invalid(format!("joint {name}"), "two joints have this name"));
            }
            if robot.is_some_and(|r| r.has_joint(name)) {
                return Err(invalid(format!("joint {name}"), "the robot has a joint of this name"));
            }
            let [held, reference] = &spec.between;
            let what = format!("joint {name}: between");
            if held == WORLD {
                return Err(invalid(
                    what,
                    "the first is the held body, not the world (write [\"body\", \"world\"])",
                ));
            }
            let body = match end_of(&bodies, robot, &what, held)? {
                End::Body(index) => index,
                _ => {
                    return Err(invalid(
                        what,
                        format!(
                            "the first is the held body, a [[body]] entry; the robot link {held} can be the \
                             reference (the second) only"
                        ),
                    ))
                }
            };
            let reference = end_of(&bodies, robot, &what, reference)?;
            if reference == End::Body(body) {
                return Err(invalid(what, format!("joins {held} to itself")));
            }
            joints.push(LayoutJoint {
                name: name.clone(),
                body,
                reference,
                formulation: spec.formulation,
                geometry: spec.geometry.clone(),
                entry: true,
                drive: spec.drive,
                limit: spec.limit,
            });
        }
        Ok(Layout {
            bodies,
            joints,
            named: true,
        })
    }

    /// Where the end `name` of a force element is: a body of the file, a robot link, or the world.
    pub(crate) fn end(&self, layout: &Layout, what: &str, name: &str) -> Result<End, SceneFileError> {
        end_of(
            &layout.bodies,
            self.robot()?.map(|(_, loaded)| loaded),
            &format!("{what}: between"),
            name,
        )
    }
}

/// The end `name`: a body of `bodies`, a link of `robot`, or the world; an error under `what` listing them.
pub(crate) fn end_of(
    bodies: &[LayoutBody],
    robot: Option<&LoadedRobot>,
    what: &str,
    name: &str,
) -> Result<End, SceneFileError> {
    if name == WORLD {
        return Ok(End::World);
    }
    if let Some(index) = bodies.iter().position(|b| b.name == name) {
        return Ok(End::Body(index));
    }
    if robot.is_some_and(|r| r.links().any(|link| link == name)) {
        return Ok(End::Link(name.to_owned()));
    }
    let known: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
    let links = robot.map_or(String::new(), |r| {
        format!("; or a link of the robot: {}", r.links().collect::<Vec<_>>().join(", "))
    });
    Err(invalid(
        what,
        format!(
            "no body named {name:?} (the bodies: {}; or \"world\"{links})",
            if known.is_empty() {
                "none".to_owned()
            } else {
                known.join(", ")
            }
        ),
    ))
}

/// How a body is named in messages: nothing for the single-body layout (its fields are top-level), else
/// "body NAME: ".
pub(crate) fn prefix(layout: &Layout, name: &str) -> String {
    if !layout.named {
        String::new()
    } else {
        format!("body {name}: ")
    }
}

/// An error about a body's entry, with the body's name in front.
pub(crate) fn named(layout: &Layout, name: &str, error: SceneFileError) -> SceneFileError {
    let prefix = prefix(layout, name);
    if prefix.is_empty() {
        return error;
    }
    match error {
        SceneFileError::Invalid { what, reason } => SceneFileError::Invalid {
            what: format!("{prefix}{what}"),
            reason,
        },
        SceneFileError::Body(e) => SceneFileError::Invalid {
            what: format!("body {name}"),
            reason: e.to_string(),
        },
        other => other,
    }
}
