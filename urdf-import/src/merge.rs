//! Stage 3: links joined by `fixed` joints (and joints frozen by [`MasslessSubtrees::Freeze`]) become one rigid
//! body, with exactly merged mass properties, and the remaining joints are placed in their bodies' frames.
//!
//! The output, [`RobotModel`], is everything a builder needs: bodies with their mass, centre and full inertia
//! tensor in one frame each, and moving joints with their frame, axis, limits and mimic in those frames.
//!
//! [`MasslessSubtrees::Freeze`]: crate::MasslessSubtrees::Freeze

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use nalgebra::{Isometry3, Matrix3, Unit, Vector3};

use crate::parse::{Collision, JointKind, Limit};
use crate::validate::{principal_axes, MimicMode, Repair, Validated};

/// A link's place in its rigid body.
#[derive(Clone, Debug, PartialEq)]
pub struct LinkPlacement {
    /// The link's name.
    pub name: String,
    /// The link frame in the body's reference-link frame (identity for the reference link itself).
    pub pose: Isometry3<f64>,
    /// The `<link>` element's line.
    pub line: u32,
}

/// A rigid body: a group of links joined by fixed (or frozen) joints.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidBody {
    /// The name of its reference link, the link of the group closest to the root.
    pub name: String,
    /// Every link of the group, the reference link first, then the others depth first in file order.
    pub links: Vec<LinkPlacement>,
    /// Total mass (kg).
    pub mass: f64,
    /// The centre of mass in the reference-link frame (m); the reference link's origin when the mass is zero.
    pub centre_of_mass: Vector3<f64>,
    /// The full symmetric inertia tensor about the centre of mass, in the reference-link axes (kg m²).
    pub inertia: Matrix3<f64>,
}

impl RigidBody {
    /// The principal moments about the centre of mass, ascending (kg m²); `None` if the tensor is not finite.
    pub fn principal_moments(&self) -> Option<[f64; 3]> {
        principal_axes(&self.inertia).map(|(moments, _)| moments)
    }
}

/// A `<mimic>`: `q = multiplier q_target + offset`.
#[derive(Clone, Debug, PartialEq)]
pub struct Mimic {
    /// The mimicked joint's name as written.
    pub joint: String,
    /// Its index in [`RobotModel::joints`]. Always `Some` with [`MimicMode::Constraint`] unless the target was
    /// frozen (its coordinate is then the constant 0, and this joint's the constant `offset`; noted in the
    /// warnings). With [`MimicMode::Independent`], `None` when the target is undefined or not a moving joint.
    pub index: Option<usize>,
    /// Multiplier (default 1).
    pub multiplier: f64,
    /// Offset (rad or m, default 0).
    pub offset: f64,
}

/// A joint with coordinates: not fixed, not frozen.
#[derive(Clone, Debug, PartialEq)]
pub struct MovingJoint {
    /// Its name.
    pub name: String,
    /// Revolute, continuous, prismatic, floating or planar (never fixed).
    pub kind: JointKind,
    /// The index of the parent body in [`RobotModel::bodies`].
    pub parent: usize,
    /// The index of the child body; its reference link is this joint's child link.
    pub child: usize,
    /// The parent link's name (a link of the parent body).
    pub parent_link: String,
    /// The joint frame, which is the child link frame at q = 0, in the parent body's reference-link frame.
    pub origin: Isometry3<f64>,
    /// The unit axis in the joint frame (the plane normal of a planar joint; x for a floating joint, unused).
    pub axis: Unit<Vector3<f64>>,
    /// The `<limit>`, if any.
    pub limit: Option<Limit>,
    /// Viscous damping (N m s/rad or N s/m).
    pub damping: f64,
    /// Coulomb friction (N m or N).
    pub friction: f64,
    /// The `<mimic>`, if any.
    pub mimic: Option<Mimic>,
    /// The `<joint>` element's line.
    pub line: u32,
}

impl MovingJoint {
    /// The `<limit>`'s position range of a revolute or prismatic joint, a missing side infinite; `None` without a
    /// bound, and for the other kinds (the URDF specification ignores a continuous joint's limits).
    pub fn position_range(&self) -> Option<(f64, f64)> {
        let limit = self.limit?;
        if !matches!(self.kind, JointKind::Revolute | JointKind::Prismatic)
            || (limit.lower.is_none() && limit.upper.is_none())
        {
            return None;
        }
        Some((
            limit.lower.unwrap_or(f64::NEG_INFINITY),
            limit.upper.unwrap_or(f64::INFINITY),
        ))
    }
}

/// A moving joint frozen by [`crate::MasslessSubtrees::Freeze`]: treated as fixed, its subtree merged into the
/// parent body.
#[derive(Clone, Debug, PartialEq)]
pub struct FrozenJoint {
    /// Its name.
    pub name: String,
    /// Its type as written.
    pub kind: JointKind,
    /// The coordinate it is frozen at (0: the child link at the joint's `<origin>`).
    pub position: f64,
    /// The body its child link was merged into.
    pub body: usize,
    /// The `<joint>` element's line.
    pub line: u32,
}

/// An imported robot: rigid bodies and the joints that move them, ready for a builder.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotModel {
    /// The robot's name.
    pub name: String,
    /// Rigid bodies: groups of links joined by fixed joints. Index 0 holds the root link; every other body is
    /// the child of exactly one moving joint and comes after its parent body (root first, then in the file
    /// order of the joints that carry them, a parent always before its children).
    pub bodies: Vec<RigidBody>,
    /// The moving (non-fixed, non-frozen) joints in URDF file order.
    pub joints: Vec<MovingJoint>,
    /// The joints frozen by [`crate::MasslessSubtrees::Freeze`], in file order.
    pub frozen_joints: Vec<FrozenJoint>,
    /// Every change the opt-in repairs made, in the order made.
    pub repairs: Vec<Repair>,
    /// Notes that are not errors (an unnamed robot, dangling independent mimics, a massless root, ...).
    pub warnings: Vec<String>,
    /// How many links were merged away into another link's body (links − bodies).
    pub merged_links: usize,
    /// How the builder should treat [`MovingJoint::mimic`]: couple the coordinates, or leave them independent.
    pub mimic: MimicMode,
    /// The root body has zero mass or a singular inertia, so it can only be fixed to the world (a floating base
    /// needs an invertible inertia). The builder decides which the root is.
    pub root_fixed_only: bool,
    /// Top-level elements ignored (visual-only, simulator-specific, ...), by tag, with their counts.
    pub ignored: Vec<(String, usize)>,
    /// Every link's `<collision>` elements, by link name (in the link's frame), file order.
    pub collisions: Vec<(String, Collision)>,
}

impl RobotModel {
    /// The moving joints of each kind, as (kind, count) in the order revolute, continuous, prismatic, floating,
    /// planar, kinds with no joint left out.
    pub fn joint_counts(&self) -> Vec<(JointKind, usize)> {
        [
            JointKind::Revolute,
            JointKind::Continuous,
            JointKind::Prismatic,
            JointKind::Floating,
            JointKind::Planar,
        ]
        .into_iter()
        .map(|k| (k, self.joints.iter().filter(|j| j.kind == k).count()))
        .filter(|&(_, n)| n > 0)
        .collect()
    }
}

/// Mass, first moment and second moment accumulated over a body's links; finished into the centre and the
/// central inertia at the end, so the merge is exact up to one rounding per term.
struct MassSum {
    parts: Vec<(f64, Vector3<f64>, Matrix3<f64>)>,
}

impl MassSum {
    /// A link's inertial: mass `m` at centre `c` (reference-link frame) with the tensor `I` about `c` in axes
    /// rotated by `R` from the reference-link axes: contributes `R I Rᵀ` about `c`.
    fn add(&mut self, mass: f64, centre: Vector3<f64>, rotated_inertia: Matrix3<f64>) {
        self.parts.push((mass, centre, rotated_inertia));
    }

    /// Total mass, centre of mass (the origin when massless) and the tensor about the centre by the parallel-axis
    /// theorem `Σ R I Rᵀ + m (|d|² 𝟙 − d dᵀ)`, `d` each part's centre relative to the common one.
    fn finish(&self) -> (f64, Vector3<f64>, Matrix3<f64>) {
        // Folded from +0: `Iterator::sum` starts at -0.0, which a massless body would report as "-0 kg".
        let mass = self.parts.iter().fold(0.0, |acc, p| acc + p.0);
        // Averaged as offsets from the heaviest part's centre: a one-link body keeps its centre bit for bit (m c / m
        // need not round to c), and the offsets are smaller than the positions, so the sum rounds less.
        let anchor = self
            .parts
            .iter()
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .map_or(Vector3::zeros(), |p| p.1);
        let centre = if mass > 0.0 {
            anchor
                + self
                    .parts
                    .iter()
                    .fold(Vector3::zeros(), |acc, (m, c, _)| acc + (c - anchor) * *m)
                    / mass
        } else {
            Vector3::zeros()
        };
        let inertia = self.parts.iter().fold(Matrix3::zeros(), |acc, (m, c, i)| {
            let d = c - centre;
            acc + i + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * *m
        });
        (mass, centre, inertia.symmetric_part())
    }
}

/// Merges a validated model into rigid bodies (stage 3). The body checks come after, in
/// [`crate::bodies::check_bodies`].
pub fn merge(validated: Validated) -> RobotModel {
    let Validated {
        raw,
        root,
        child_joints,
        joint_links,
        frozen,
        mimic_target,
        options,
        repairs,
        mut warnings,
        ..
    } = validated;
    let moving = |j: usize| raw.joints[j].kind != JointKind::Fixed && !frozen[j];

    let mut body_of = vec![usize::MAX; raw.links.len()];
    let mut pose_in_body = vec![Isometry3::identity(); raw.links.len()];
    let mut bodies = Vec::new();
    let mut frozen_joints = Vec::new();
    // Moving joints whose parent body exists, smallest file index first.
    let mut ready: BinaryHeap<Reverse<usize>> = BinaryHeap::new();
    let mut next_reference = Some(root);
    while let Some(reference) = next_reference {
        let b = bodies.len();
        let mut links = Vec::new();
        let mut sum = MassSum { parts: Vec::new() };
        let mut stack = vec![reference];
        while let Some(l) = stack.pop() {
            body_of[l] = b;
            let link = &raw.links[l];
            let pose = pose_in_body[l];
            links.push(LinkPlacement {
                name: link.name.clone(),
                pose,
                line: link.line,
            });
            if let Some(inertial) = &link.inertial {
                let frame = pose * inertial.origin;
                let rotation = frame.rotation.to_rotation_matrix();
                let rotated = rotation.matrix() * inertial.inertia * rotation.matrix().transpose();
                sum.add(inertial.mass, frame.translation.vector, rotated);
            }
            for &j in child_joints[l].iter().rev() {
                if moving(j) {
                    ready.push(Reverse(j));
                } else {
                    let child = joint_links[j].1;
                    pose_in_body[child] = pose * raw.joints[j].origin;
                    stack.push(child);
                }
            }
        }
        let (mass, centre_of_mass, inertia) = sum.finish();
        bodies.push(RigidBody {
            name: raw.links[reference].name.clone(),
            links,
            mass,
            centre_of_mass,
            inertia,
        });
        next_reference = ready.pop().map(|Reverse(j)| joint_links[j].1);
    }

    let mut moving_index = vec![None; raw.joints.len()];
    for (j, index) in moving_index.iter_mut().enumerate() {
        if moving(j) {
            *index = Some(j);
        }
    }
    let mut count = 0;
    for index in moving_index.iter_mut().flatten() {
        *index = count;
        count += 1;
    }

    let mut joints = Vec::with_capacity(count);
    for (j, joint) in raw.joints.iter().enumerate() {
        let (parent, child) = joint_links[j];
        if frozen[j] {
            frozen_joints.push(FrozenJoint {
                name: joint.name.clone(),
                kind: joint.kind,
                position: 0.0,
                body: body_of[child],
                line: joint.line,
            });
        }
        if !moving(j) {
            continue;
        }
        let mimic = joint.mimic.as_ref().map(|m| {
            let index = mimic_target[j].and_then(|t| moving_index[t]);
            if let (Some(t), None, MimicMode::Constraint) = (mimic_target[j], index, options.mimic) {
                warnings.push(format!(
                    "joint `{}` (line {}) mimics joint `{}`, which was frozen at 0: its coordinate is the constant {}",
                    joint.name, m.line, raw.joints[t].name, m.offset
                ));
            }
            Mimic {
                joint: m.joint.clone(),
                index,
                multiplier: m.multiplier,
                offset: m.offset,
            }
        });
        // Scaled by its largest component first, so that neither 1e-300 nor 1e300 under- or overflows the norm.
        let largest = joint.axis.amax();
        let axis = if largest > 0.0 && largest.is_finite() {
            Unit::new_normalize(joint.axis / largest)
        } else {
            Vector3::x_axis() // a floating joint's axis, unused; validation refused zero axes on the others
        };
        joints.push(MovingJoint {
            name: joint.name.clone(),
            kind: joint.kind,
            parent: body_of[parent],
            child: body_of[child],
            parent_link: joint.parent.clone(),
            origin: pose_in_body[parent] * joint.origin,
            axis,
            limit: joint.limit.map(|(limit, _)| limit),
            damping: joint.damping,
            friction: joint.friction,
            mimic,
            line: joint.line,
        });
    }

    RobotModel {
        name: raw.name,
        merged_links: raw.links.len() - bodies.len(),
        bodies,
        joints,
        frozen_joints,
        repairs,
        warnings,
        mimic: options.mimic,
        root_fixed_only: false,
        ignored: raw.ignored,
        collisions: (raw.links.iter())
            .flat_map(|link| link.collisions.iter().map(|c| (link.name.clone(), c.clone())))
            .collect(),
    }
}
