//! Two layouts, one list of bodies and joints ([`Layout`]): a single `[body]` with its `[initial]` state, `[[forces]]`
//! and `[[constraints]]` to the world; or named `[[body]]` entries, each with its `initial` state and `forces`, and
//! `[[joint]]` entries `between = ["body", "other body", "world" or a robot link]`, with or without a `[robot]`. Every
//! name is resolved first (`Names`), then every body's and joint's values are checked.

use dynamics::limits::JointLimit;
use dynamics::Body;

use super::bodies::{BodyForce, InitialState};
use super::geometry::{relative_pose, HeldGeometry, JointGeometry};
use super::robot::LoadedRobot;
use crate::error::{invalid, SceneFileError};
use crate::names::FormulationName;
use crate::syntax::bodies::{Bodies, BodySpec, ForceSpec, InitialSpec, NamedBody};
use crate::syntax::elements::DriveSpec;
use crate::syntax::file::SceneFile;
use crate::syntax::joints::{Geometry, JointSpec, LimitSpec};

/// A body of the scene, whichever layout it came from, checked.
#[derive(Clone, Debug)]
pub struct LayoutBody {
    /// Its name: the `[[body]]` entry's, or "body" for the single `[body]`.
    pub name: String,
    /// Its mass properties.
    pub body: Body,
    /// Its state at t = 0, as the file gives it.
    pub initial: InitialState,
    /// Whether the file gives it (an `initial` table); otherwise its joint places it.
    pub initial_given: bool,
    /// Its external forces.
    pub forces: Vec<BodyForce>,
}

/// What a joint holds its body to, or where a force element's end is.
#[derive(Clone, Debug, PartialEq)]
pub enum End {
    /// The world.
    World,
    /// A body of the file, by its index in [`Layout::bodies`].
    Body(usize),
    /// A link of the robot, by name.
    Link(String),
}

/// A joint of the scene, checked.
#[derive(Clone, Debug)]
pub struct LayoutJoint {
    /// Its name in messages: the `[[joint]]` entry's, or "1 (hinge)" for the first of `[[constraints]]`.
    pub name: String,
    /// The body it holds, by its index in [`Layout::bodies`].
    pub body: usize,
    /// What it holds the body to.
    pub reference: End,
    /// By pinning or by virtual power.
    pub formulation: FormulationName,
    /// What it is: "hinge", "point on sphere", ….
    pub kind: &'static str,
    /// What it holds, the reference side in the reference's frame.
    pub geometry: HeldGeometry,
    /// A `[[joint]]` entry (a joint model where it can be), not a `[[constraints]]` one.
    pub entry: bool,
    /// The prescribed coordinate of a hinge or prismatic joint.
    pub drive: Option<DriveSpec>,
    /// The range of a hinge's or prismatic joint's coordinate.
    pub limit: Option<JointLimit>,
}

/// The scene's bodies and joints.
#[derive(Clone, Debug)]
pub struct Layout {
    /// In file order.
    pub bodies: Vec<LayoutBody>,
    /// In file order.
    pub joints: Vec<LayoutJoint>,
    /// Whether the bodies are named `[[body]]` entries (else the single `[body]`, named "body").
    pub named: bool,
}

impl Layout {
    /// Per joint: its geometry (reference-side values in the reference's frame), its body and its reference, to
    /// measure violations with.
    ///
    /// A fixed joint without a given pose holds its body where the file starts it (before the projection onto the
    /// joints). Joints to a robot link are placed by the system
    /// ([`SceneSystem::joint_violation`](crate::SceneSystem::joint_violation)), not here: they are an error.
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
                let start = || {
                    let reference = reference.map(|r| self.bodies[r].initial.pose());
                    relative_pose(&self.bodies[j.body].initial.pose(), reference.as_ref())
                };
                Ok((j.geometry.at_start(start), j.body, reference))
            })
            .collect()
    }

    /// Where the end `name` of a force element or contact is: a body of the file, a robot link, or the world; an error
    /// under `what` listing them.
    pub(crate) fn end(&self, robot: Option<&LoadedRobot>, what: &str, name: &str) -> Result<End, SceneFileError> {
        let bodies: Vec<&str> = self.bodies.iter().map(|b| b.name.as_str()).collect();
        end_of(&bodies, robot, what, name)
    }
}

/// The name of the world in `between`.
const WORLD: &str = "world";

/// A body with its name resolved, its values not yet checked.
struct BodyEntry<'f> {
    name: String,
    spec: BodySpec,
    initial: Option<&'f InitialSpec>,
    forces: &'f [ForceSpec],
}

/// A joint with its names resolved, its values not yet checked.
struct JointEntry<'f> {
    name: String,
    body: usize,
    reference: End,
    formulation: FormulationName,
    geometry: &'f Geometry,
    entry: bool,
    drive: Option<DriveSpec>,
    limit: Option<LimitSpec>,
}

/// The bodies and joints of a file, from either layout, with every name resolved and none of their values checked.
pub(crate) struct Names<'f> {
    bodies: Vec<BodyEntry<'f>>,
    joints: Vec<JointEntry<'f>>,
    named: bool,
}

impl<'f> Names<'f> {
    /// The bodies and joints of `file`, with those of `robot`'s links the file's joints refer to.
    pub(crate) fn resolve(file: &'f SceneFile, robot: Option<&LoadedRobot>) -> Result<Names<'f>, SceneFileError> {
        match &file.body {
            Some(Bodies::One(spec)) => {
                if robot.is_some() {
                    return Err(invalid(
                        "body",
                        "with a [robot], write the scene's other bodies as [[body]] entries with a `name`",
                    ));
                }
                if !file.joint.is_empty() {
                    return Err(invalid(
                        "joint",
                        "[[joint]] entries join named bodies: write the bodies as [[body]] entries with a `name`",
                    ));
                }
                let joints = (file.constraints.iter().enumerate())
                    .map(|(index, c)| JointEntry {
                        name: format!("{} ({})", index + 1, c.geometry.kind()),
                        body: 0,
                        reference: End::World,
                        formulation: c.formulation,
                        geometry: &c.geometry,
                        entry: false,
                        drive: None,
                        limit: None,
                    })
                    .collect();
                let body = BodyEntry {
                    name: "body".to_owned(),
                    spec: spec.clone(),
                    initial: file.initial.as_ref(),
                    forces: &file.forces,
                };
                Ok(Names {
                    bodies: vec![body],
                    joints,
                    named: false,
                })
            }
            Some(Bodies::Named(entries)) => Names::named(file, entries, robot),
            None => match robot {
                Some(_) => Names::named(file, &[], robot),
                None => Err(invalid(
                    "body",
                    "a scene needs a [body] table, [[body]] entries or a [robot]",
                )),
            },
        }
    }

    /// Named `[[body]]` entries (none with a robot alone) and their joints, which may refer to the robot's links.
    fn named(
        file: &'f SceneFile,
        entries: &'f [NamedBody],
        robot: Option<&LoadedRobot>,
    ) -> Result<Names<'f>, SceneFileError> {
        if file.initial.is_some() || !file.forces.is_empty() || !file.constraints.is_empty() {
            return Err(invalid(
                "initial, forces, constraints",
                "with [[body]] entries or a [robot], give each body its `initial` state and `forces` in its entry, \
                 and the joints as [[joint]] entries",
            ));
        }
        if entries.is_empty() && robot.is_none() {
            return Err(invalid("body", "needs at least one entry"));
        }
        let mut bodies: Vec<BodyEntry> = Vec::with_capacity(entries.len());
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
            bodies.push(BodyEntry {
                name: name.clone(),
                spec: BodySpec {
                    mass: entry.mass,
                    shape: entry.shape.clone(),
                    principal_moments: entry.principal_moments,
                    collision: entry.collision.clone(),
                },
                initial: entry.initial.as_ref(),
                forces: &entry.forces,
            });
        }
        let names: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
        let mut joints: Vec<JointEntry> = Vec::with_capacity(file.joint.len());
        for spec in &file.joint {
            if joints.iter().any(|j| j.name == spec.name) {
                return Err(invalid(format!("joint {}", spec.name), "two joints have this name"));
            }
            joints.push(JointEntry::named(spec, &names, robot)?);
        }
        Ok(Names {
            bodies,
            joints,
            named: true,
        })
    }

    /// How many bodies the file has.
    pub(crate) fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// How many joints the file has.
    pub(crate) fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// The bodies' and joints' values checked, in file order; a drive over a run of `duration` s.
    pub(crate) fn checked(self, duration: f64) -> Result<Layout, SceneFileError> {
        let named = self.named;
        let bodies = (self.bodies.into_iter())
            .map(|entry| entry.checked(named))
            .collect::<Result<_, _>>()?;
        let joints = (self.joints.into_iter())
            .map(|entry| entry.checked(duration))
            .collect::<Result<_, _>>()?;
        Ok(Layout { bodies, joints, named })
    }
}

impl BodyEntry<'_> {
    /// The body checked, its errors naming it in front if the bodies are `named`.
    fn checked(self, named: bool) -> Result<LayoutBody, SceneFileError> {
        let in_entry = |error| about_body(named, &self.name, error);
        let body = self.spec.body().map_err(in_entry)?;
        let forces = (self.forces.iter().enumerate())
            .map(|(index, force)| force.checked(index + 1).map_err(in_entry))
            .collect::<Result<_, _>>()?;
        let prefix = if named {
            format!("body {}: ", self.name)
        } else {
            String::new()
        };
        let initial = self.initial.cloned().unwrap_or_default().checked(&prefix)?;
        Ok(LayoutBody {
            name: self.name,
            body,
            initial,
            initial_given: self.initial.is_some(),
            forces,
        })
    }
}

impl<'f> JointEntry<'f> {
    /// A `[[joint]]` entry, its names resolved among `bodies` and the robot's links.
    fn named(
        spec: &'f JointSpec,
        bodies: &[&str],
        robot: Option<&LoadedRobot>,
    ) -> Result<JointEntry<'f>, SceneFileError> {
        let name = &spec.name;
        if name.is_empty() {
            return Err(invalid("joint \"\"", "a joint needs a non-empty name"));
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
        let body = match end_of(bodies, robot, &what, held)? {
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
        let reference = end_of(bodies, robot, &what, reference)?;
        if reference == End::Body(body) {
            return Err(invalid(what, format!("joins {held} to itself")));
        }
        Ok(JointEntry {
            name: name.clone(),
            body,
            reference,
            formulation: spec.formulation,
            geometry: &spec.geometry,
            entry: true,
            drive: spec.drive,
            limit: spec.limit,
        })
    }

    /// The joint's geometry, drive (over a run of `duration` s) and limit checked.
    fn checked(self, duration: f64) -> Result<LayoutJoint, SceneFileError> {
        let name = &self.name;
        let geometry = self.geometry.checked(name)?;
        let drive = (self.drive)
            .map(|d| d.checked(&format!("joint {name}: drive"), duration))
            .transpose()?;
        let limit = (self.limit)
            .map(|l| l.limit(&format!("joint {name}: limit")))
            .transpose()?;
        Ok(LayoutJoint {
            kind: self.geometry.kind(),
            geometry,
            drive,
            limit,
            name: self.name,
            body: self.body,
            reference: self.reference,
            formulation: self.formulation,
            entry: self.entry,
        })
    }
}

/// The end `name`: one of `bodies`, a link of `robot`, or the world; an error under `what` listing them.
fn end_of(bodies: &[&str], robot: Option<&LoadedRobot>, what: &str, name: &str) -> Result<End, SceneFileError> {
    if name == WORLD {
        return Ok(End::World);
    }
    if let Some(index) = bodies.iter().position(|b| *b == name) {
        return Ok(End::Body(index));
    }
    if robot.is_some_and(|r| r.links().any(|link| link == name)) {
        return Ok(End::Link(name.to_owned()));
    }
    let links = robot.map_or(String::new(), |r| {
        format!("; or a link of the robot: {}", r.links().collect::<Vec<_>>().join(", "))
    });
    Err(invalid(
        what,
        format!(
            "no body named {name:?} (the bodies: {}; or \"world\"{links})",
            if bodies.is_empty() {
                "none".to_owned()
            } else {
                bodies.join(", ")
            }
        ),
    ))
}

/// An error about the body `name`'s entry, with the body's name in front if the bodies are `named` (the single
/// `[body]`'s keys are the file's own).
fn about_body(named: bool, name: &str, error: SceneFileError) -> SceneFileError {
    if !named {
        return error;
    }
    match error {
        SceneFileError::Invalid { what, reason } => SceneFileError::Invalid {
            what: format!("body {name}: {what}"),
            reason,
        },
        SceneFileError::Body(e) => SceneFileError::Invalid {
            what: format!("body {name}"),
            reason: e.to_string(),
        },
        other => other,
    }
}
