//! Stage 2: the checks that messy real files need, and the opt-in repairs ([`ImportOptions`]).
//!
//! [`validate`] runs before merging: names, the tree, joint axes and limits, mimics, and each link's inertia.
//! The bodies' checks run after [`crate::merge`], in [`crate::bodies`], with the same options and round-off.
//!
//! By default every check is an error; each repair is opt-in, changes exactly what its doc comment says, and is
//! listed in [`crate::RobotModel::repairs`].

use std::collections::HashMap;
use std::fmt;

use nalgebra::{Matrix3, SymmetricEigen, Vector3};

use crate::error::{ImportError, Moments};
use crate::parse::{JointKind, RawLink, RawMimic, RawModel};

/// Relative round-off allowed in the inertia checks, measured against [`inertia_scale`]: a principal moment above
/// `-ROUND_OFF × scale` is not negative, `I₃ ≤ I₁ + I₂ + ROUND_OFF × scale` satisfies the triangle inequality, and a
/// moment at most `ROUND_OFF × scale` is zero (singular) for [`crate::bodies::check_bodies`]. CAD exports round tensors
/// to 6–9 digits, and an eigen-solve of a singular tensor returns ±1e-22 rather than 0.
pub const ROUND_OFF: f64 = 1e-9;

/// The scale (kg m²) round-off in an inertia is measured against: the sum of the principal moments' magnitudes
/// plus the mass times 1 m² (the moment of that mass at a robot's size). The mass term is what lets a tensor of
/// pure noise, such as `ixz="2.40741e-35"` and zeros on iCub's 1.34 kg head, read as the zero tensor (a point
/// mass) it stands for instead of as an indefinite one; it allows 1e-9 kg m² per kg, the moment of the mass at
/// 30 µm.
pub fn inertia_scale(moments: &[f64; 3], mass: f64) -> f64 {
    moments.iter().map(|m| m.abs()).sum::<f64>() + mass.abs() * 1.0
}

/// What to do with a moving joint whose whole child subtree has no mass.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum MasslessSubtrees {
    /// An error ([`ImportError::SingularBody`] with `massless_subtree: true`).
    #[default]
    Error,
    /// The joint is treated as fixed at coordinate 0: its child subtree (every link below it) is merged into the
    /// parent's body as a massless part, changing no mass, centre or inertia (except for the inertia of links
    /// written with mass 0 and a non-zero tensor, which is added as written). Every such joint is listed in
    /// [`RobotModel::frozen_joints`](crate::RobotModel::frozen_joints) and as [`Repair::JointFrozen`], so a
    /// builder can still report its coordinate as the constant 0. Nested massless joints are all frozen.
    Freeze,
}

/// How `<mimic>` tags are treated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum MimicMode {
    /// Each mimic is a constraint `q = multiplier q_target + offset` for the builder to enforce; it is validated:
    /// the target must exist, not be the joint itself, not mimic another joint, and both joints must have a single
    /// coordinate (revolute, continuous, prismatic).
    #[default]
    Constraint,
    /// Mimics are recorded ([`Mimic`](crate::Mimic)) but checked for syntax only: every joint keeps its own
    /// coordinate, so a mimic naming a joint that does not exist is harmless and only noted in
    /// [`RobotModel::warnings`](crate::RobotModel::warnings).
    Independent,
}

/// Import options. `Default` repairs nothing: every check is an error.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct ImportOptions {
    /// Moving joints whose whole child subtree is massless: an error, or frozen (see [`MasslessSubtrees`]).
    pub massless_subtrees: MasslessSubtrees,
    /// Lower bound on the mass (kg) of each body carried by a moving joint (as MuJoCo's `boundmass`): a smaller
    /// mass, zero included, is raised to it. The centre of mass stays where it was (a body of zero mass has its
    /// centre at its reference link's origin) and the inertia tensor is unchanged. The root body is never changed
    /// (it may be fixed to the world; see [`RobotModel::root_fixed_only`](crate::RobotModel::root_fixed_only)).
    /// Each change is a [`Repair::MassRaised`].
    pub bound_mass: Option<f64>,
    /// Lower bound on each principal moment (kg m²) of each body carried by a moving joint (as MuJoCo's
    /// `boundinertia`): every principal moment below it is raised to it, and the tensor rebuilt from the same
    /// principal axes (`V diag(λ) Vᵀ`); the mass and centre are unchanged. Raising the smaller moments keeps the
    /// triangle inequality of a valid tensor. The root body is never changed. Each change is a
    /// [`Repair::InertiaRaised`].
    pub bound_inertia: Option<f64>,
    /// Replace each link inertia that has a negative principal moment or breaks the triangle inequality by the
    /// nearest valid one, keeping its principal axes: negative moments are raised to 0, then if the largest moment
    /// still exceeds the sum of the two others, both smaller moments are raised by the same amount
    /// `(I₃ − I₁ − I₂)/2`, so that `I₃ = I₁ + I₂` (a thin plate) and the largest moment, the one the link's shape
    /// mostly fixes, is kept. Mass and centre unchanged. Each change is a [`Repair::InertiaBalanced`].
    pub balance_inertia: bool,
    /// How `<mimic>` tags are treated (see [`MimicMode`]).
    pub mimic: MimicMode,
}

impl ImportOptions {
    /// Every repair on: massless subtrees frozen, inertias balanced, mimics independent, and the mass and
    /// principal moments of each moving body bounded below by `bound_mass` (kg) and `bound_inertia` (kg m²).
    pub fn repair_all(bound_mass: f64, bound_inertia: f64) -> ImportOptions {
        ImportOptions {
            massless_subtrees: MasslessSubtrees::Freeze,
            bound_mass: Some(bound_mass),
            bound_inertia: Some(bound_inertia),
            balance_inertia: true,
            mimic: MimicMode::Independent,
        }
    }

    pub(crate) fn check(&self) -> Result<(), ImportError> {
        for (option, value) in [("bound_mass", self.bound_mass), ("bound_inertia", self.bound_inertia)] {
            if let Some(value) = value {
                if !(value.is_finite() && value > 0.0) {
                    return Err(ImportError::Option { option, value });
                }
            }
        }
        Ok(())
    }
}

/// One change an opt-in repair made to the file's model.
#[derive(Clone, Debug, PartialEq)]
pub enum Repair {
    /// `balance_inertia`: a link's principal moments (ascending, kg m²) replaced.
    InertiaBalanced {
        /// The link.
        link: String,
        /// Its `<inertia>` line.
        line: u32,
        /// The moments as written.
        old: [f64; 3],
        /// The moments used.
        new: [f64; 3],
    },
    /// `MasslessSubtrees::Freeze`: a moving joint treated as fixed at coordinate 0.
    JointFrozen {
        /// The joint.
        joint: String,
        /// Its type as written.
        kind: JointKind,
        /// Its line.
        line: u32,
    },
    /// `bound_mass`: a body's mass (kg) raised.
    MassRaised {
        /// The body (its reference link's name).
        body: String,
        /// The merged mass.
        old: f64,
        /// The bound.
        new: f64,
    },
    /// `bound_inertia`: a body's principal moments (ascending, kg m²) raised.
    InertiaRaised {
        /// The body (its reference link's name).
        body: String,
        /// The merged moments.
        old: [f64; 3],
        /// The moments used.
        new: [f64; 3],
    },
}

impl fmt::Display for Repair {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Repair::InertiaBalanced { link, line, old, new } => write!(
                f,
                "link `{link}` (line {line}): principal moments {} -> {} kg m² (balanced)",
                Moments(old),
                Moments(new)
            ),
            Repair::JointFrozen { joint, kind, line } => {
                write!(
                    f,
                    "{kind} joint `{joint}` (line {line}) frozen at 0: its subtree is massless"
                )
            }
            Repair::MassRaised { body, old, new } => write!(f, "body `{body}`: mass {old:e} -> {new:e} kg"),
            Repair::InertiaRaised { body, old, new } => write!(
                f,
                "body `{body}`: principal moments {} -> {} kg m²",
                Moments(old),
                Moments(new)
            ),
        }
    }
}

/// A [`RawModel`] that passed [`validate`]: a single tree, with the inertia repairs applied and the joints to
/// freeze marked. The input of [`crate::merge::merge`].
#[derive(Clone, Debug, PartialEq)]
pub struct Validated {
    /// The model, with balanced inertias written back into the links.
    pub raw: RawModel,
    /// The root link's index.
    pub root: usize,
    /// Per link, the index of the joint whose child it is (`None` for the root).
    pub parent_joint: Vec<Option<usize>>,
    /// Per link, the indices of the joints whose parent it is, in file order.
    pub child_joints: Vec<Vec<usize>>,
    /// Per joint, the indices of its parent and child links.
    pub joint_links: Vec<(usize, usize)>,
    /// Per joint: moving but frozen by [`MasslessSubtrees::Freeze`].
    pub frozen: Vec<bool>,
    /// Per joint, the index of its mimic's target when that joint exists.
    pub mimic_target: Vec<Option<usize>>,
    /// The options the import runs with.
    pub options: ImportOptions,
    /// The repairs made so far.
    pub repairs: Vec<Repair>,
    /// Notes that are not errors.
    pub warnings: Vec<String>,
}

/// Principal moments in ascending order, and the principal axes as the matching columns (a rotation or a
/// reflection; only `V diag(λ) Vᵀ` is formed from it). `None` when the tensor or its moments are not finite.
pub fn principal_axes(inertia: &Matrix3<f64>) -> Option<([f64; 3], Matrix3<f64>)> {
    if !inertia.iter().all(|v| v.is_finite()) {
        return None;
    }
    let eigen = SymmetricEigen::new(inertia.symmetric_part());
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
    let moments = order.map(|i| eigen.eigenvalues[i]);
    let axes = Matrix3::from_columns(&order.map(|i| eigen.eigenvectors.column(i).into_owned()));
    moments.iter().all(|m| m.is_finite()).then_some((moments, axes))
}

/// `V diag(λ) Vᵀ`, made exactly symmetric.
pub(crate) fn rebuild(axes: &Matrix3<f64>, moments: [f64; 3]) -> Matrix3<f64> {
    (axes * Matrix3::from_diagonal(&Vector3::from(moments)) * axes.transpose()).symmetric_part()
}

/// Checks a parsed model (stage 2, before merging) and applies the link-level repairs the options ask for. The
/// steps run in this order, and the first error found is the one returned: names, the tree, joint axes and limits,
/// mimics, link inertias, massless subtrees.
pub fn validate(mut raw: RawModel, options: &ImportOptions) -> Result<Validated, ImportError> {
    options.check()?;
    let mut warnings = std::mem::take(&mut raw.warnings);
    let mut repairs = Vec::new();
    let (link_index, joint_index) = name_indices(&raw)?;
    let tree = tree(&raw, &link_index)?;
    check_axes_and_limits(&raw)?;
    let mimic_target = mimic_targets(&raw, &joint_index, options.mimic, &mut warnings)?;
    check_link_inertias(&mut raw.links, options.balance_inertia, &mut repairs, &mut warnings)?;
    let frozen = match options.massless_subtrees {
        MasslessSubtrees::Freeze => freeze_massless_subtrees(&raw, &tree, &mut repairs),
        MasslessSubtrees::Error => vec![false; raw.joints.len()],
    };
    let Tree {
        root,
        parent_joint,
        child_joints,
        joint_links,
    } = tree;
    Ok(Validated {
        raw,
        root,
        parent_joint,
        child_joints,
        joint_links,
        frozen,
        mimic_target,
        options: *options,
        repairs,
        warnings,
    })
}

/// Indices of links or joints by name.
type NameIndex<'a> = HashMap<&'a str, usize>;

/// The index of each link and of each joint by name; an error for a name defined twice.
fn name_indices(raw: &RawModel) -> Result<(NameIndex<'_>, NameIndex<'_>), ImportError> {
    let mut link_index: NameIndex = HashMap::with_capacity(raw.links.len());
    for (i, link) in raw.links.iter().enumerate() {
        if let Some(&first) = link_index.get(link.name.as_str()) {
            return Err(ImportError::DuplicateLink {
                name: link.name.clone(),
                first_line: raw.links[first].line,
                line: link.line,
            });
        }
        link_index.insert(&link.name, i);
    }
    let mut joint_index: NameIndex = HashMap::with_capacity(raw.joints.len());
    for (i, joint) in raw.joints.iter().enumerate() {
        if let Some(&first) = joint_index.get(joint.name.as_str()) {
            return Err(ImportError::DuplicateJoint {
                name: joint.name.clone(),
                first_line: raw.joints[first].line,
                line: joint.line,
            });
        }
        joint_index.insert(&joint.name, i);
    }
    Ok((link_index, joint_index))
}

/// The links and joints as one tree (the fields of [`Validated`] of the same names).
struct Tree {
    root: usize,
    parent_joint: Vec<Option<usize>>,
    child_joints: Vec<Vec<usize>>,
    joint_links: Vec<(usize, usize)>,
}

/// The tree the joints make of the links: every joint's links defined, one parent per link, one root, no loop.
fn tree(raw: &RawModel, link_index: &NameIndex) -> Result<Tree, ImportError> {
    let mut joint_links = Vec::with_capacity(raw.joints.len());
    for joint in &raw.joints {
        let find = |role: &'static str, link: &str| {
            link_index.get(link).copied().ok_or_else(|| ImportError::UnknownLink {
                joint: joint.name.clone(),
                role,
                link: link.to_owned(),
                line: joint.line,
            })
        };
        joint_links.push((find("parent", &joint.parent)?, find("child", &joint.child)?));
    }
    let mut parent_joint: Vec<Option<usize>> = vec![None; raw.links.len()];
    let mut child_joints: Vec<Vec<usize>> = vec![Vec::new(); raw.links.len()];
    for (j, &(parent, child)) in joint_links.iter().enumerate() {
        if let Some(first) = parent_joint[child] {
            return Err(ImportError::TwoParents {
                link: raw.links[child].name.clone(),
                first_joint: raw.joints[first].name.clone(),
                first_line: raw.joints[first].line,
                joint: raw.joints[j].name.clone(),
                line: raw.joints[j].line,
            });
        }
        parent_joint[child] = Some(j);
        child_joints[parent].push(j);
    }
    let roots: Vec<usize> = (0..raw.links.len()).filter(|&l| parent_joint[l].is_none()).collect();
    if roots.len() > 1 {
        let (trees, isolated): (Vec<usize>, Vec<usize>) = roots.iter().partition(|&&l| !child_joints[l].is_empty());
        let names = |ls: &[usize]| ls.iter().map(|&l| raw.links[l].name.clone()).collect::<Vec<_>>();
        return Err(if trees.len() == 1 {
            ImportError::Disconnected {
                root: raw.links[trees[0]].name.clone(),
                links: names(&isolated),
            }
        } else {
            ImportError::SeveralRoots { roots: names(&roots) }
        });
    }
    let mut reached = vec![false; raw.links.len()];
    let mut count = 0;
    if let Some(&root) = roots.first() {
        let mut stack = vec![root];
        while let Some(l) = stack.pop() {
            reached[l] = true;
            count += 1;
            stack.extend(child_joints[l].iter().map(|&j| joint_links[j].1));
        }
    }
    if count < raw.links.len() {
        return Err(cycle(
            raw,
            &reached,
            &parent_joint,
            &joint_links,
            raw.links.len() - count,
        ));
    }
    Ok(Tree {
        root: roots[0],
        parent_joint,
        child_joints,
        joint_links,
    })
}

/// The error for the `unreachable` links the root does not reach (`reached` false): every unreached link has a parent
/// (it is no root), so following parents from one must loop.
fn cycle(
    raw: &RawModel,
    reached: &[bool],
    parent_joint: &[Option<usize>],
    joint_links: &[(usize, usize)],
    unreachable: usize,
) -> ImportError {
    let start = (0..raw.links.len()).find(|&l| !reached[l]).unwrap_or(0);
    let mut step = vec![usize::MAX; raw.links.len()];
    let mut path = Vec::new();
    let mut link = start;
    while step[link] == usize::MAX {
        step[link] = path.len();
        path.push(link);
        match parent_joint[link] {
            Some(j) => link = joint_links[j].0,
            None => break, // unreachable: a root would have been reached
        }
    }
    let mut cycle: Vec<usize> = path[step[link].min(path.len())..].to_vec();
    cycle.reverse(); // parent to child

    // Start the loop at its link that comes first in the file, so the message does not depend on the search.
    let first_in_file = (0..cycle.len()).min_by_key(|&i| cycle[i]).unwrap_or(0);
    cycle.rotate_left(first_in_file);
    let first = cycle.first().copied().unwrap_or(start);
    let joint = parent_joint[cycle.get(1).copied().unwrap_or(first)].unwrap_or(0);
    let mut names: Vec<String> = cycle.iter().map(|&l| raw.links[l].name.clone()).collect();
    names.push(raw.links[first].name.clone());
    ImportError::Cycle {
        cycle: names,
        joint: raw.joints[joint].name.clone(),
        line: raw.joints[joint].line,
        unreachable,
    }
}

/// Every moving joint's axis has a direction, and no revolute or prismatic limit has `lower > upper`.
fn check_axes_and_limits(raw: &RawModel) -> Result<(), ImportError> {
    for joint in &raw.joints {
        if joint.kind.uses_axis() && joint.axis.amax() == 0.0 {
            return Err(ImportError::Axis {
                joint: joint.name.clone(),
                kind: joint.kind,
                axis: joint.axis.into(),
                line: joint.axis_line,
            });
        }
        if let Some((limit, line)) = joint.limit {
            if let (Some(lower), Some(upper), true) = (
                limit.lower,
                limit.upper,
                matches!(joint.kind, JointKind::Revolute | JointKind::Prismatic),
            ) {
                if lower > upper {
                    return Err(ImportError::LimitInverted {
                        joint: joint.name.clone(),
                        lower,
                        upper,
                        line,
                    });
                }
            }
        }
    }
    Ok(())
}

/// Per joint, the index of its mimic's target when that joint exists. Each mimic is checked as a constraint, or,
/// with [`MimicMode::Independent`], its problems are only noted in `warnings`.
fn mimic_targets(
    raw: &RawModel,
    joint_index: &NameIndex,
    mode: MimicMode,
    warnings: &mut Vec<String>,
) -> Result<Vec<Option<usize>>, ImportError> {
    let mut mimic_target = vec![None; raw.joints.len()];
    for (j, joint) in raw.joints.iter().enumerate() {
        let Some(mimic) = &joint.mimic else { continue };
        let target = joint_index.get(mimic.joint.as_str()).copied();
        mimic_target[j] = target;
        match mode {
            MimicMode::Independent => {
                if let Some(problem) = independent_mimic_problem(raw, j, target) {
                    warnings.push(format!(
                        "joint `{}` (line {}) mimics joint `{}`, {problem} (harmless: mimics are independent)",
                        joint.name, mimic.line, mimic.joint
                    ));
                }
            }
            MimicMode::Constraint => check_mimic_constraint(raw, j, mimic, target)?,
        }
    }
    Ok(mimic_target)
}

/// What would make joint `j`'s mimic of `target` an error as a constraint, worded to follow "mimics joint `…`, ".
fn independent_mimic_problem(raw: &RawModel, j: usize, target: Option<usize>) -> Option<String> {
    let joint = &raw.joints[j];
    match target {
        None => Some("which is not defined".to_owned()),
        Some(t) if t == j => Some("itself".to_owned()),
        Some(t) => {
            let target_joint = &raw.joints[t];
            if joint.kind.degrees_of_freedom() != 1 {
                Some(format!("but is {} itself", joint.kind))
            } else if target_joint.kind.degrees_of_freedom() != 1 {
                Some(format!("which is {}", target_joint.kind))
            } else {
                target_joint
                    .mimic
                    .as_ref()
                    .map(|m| format!("which itself mimics `{}`", m.joint))
            }
        }
    }
}

/// Joint `j`'s `mimic` as a constraint: its `target` exists, is another joint, both have a single coordinate, and
/// the target mimics no third joint.
fn check_mimic_constraint(
    raw: &RawModel,
    j: usize,
    mimic: &RawMimic,
    target: Option<usize>,
) -> Result<(), ImportError> {
    let joint = &raw.joints[j];
    let single = |kind: JointKind| kind.degrees_of_freedom() == 1;
    let Some(t) = target else {
        return Err(ImportError::MimicUnknown {
            joint: joint.name.clone(),
            target: mimic.joint.clone(),
            line: mimic.line,
        });
    };
    if t == j {
        return Err(ImportError::MimicSelf {
            joint: joint.name.clone(),
            line: mimic.line,
        });
    }
    let target_joint = &raw.joints[t];
    if !single(joint.kind) {
        return Err(ImportError::MimicKind {
            joint: joint.name.clone(),
            role: "this joint",
            other: joint.name.clone(),
            kind: joint.kind,
            line: mimic.line,
        });
    }
    if !single(target_joint.kind) {
        return Err(ImportError::MimicKind {
            joint: joint.name.clone(),
            role: "the mimicked joint",
            other: target_joint.name.clone(),
            kind: target_joint.kind,
            line: mimic.line,
        });
    }
    if let Some(next) = &target_joint.mimic {
        return Err(ImportError::MimicChain {
            joint: joint.name.clone(),
            target: target_joint.name.clone(),
            target_target: next.joint.clone(),
            line: mimic.line,
        });
    }
    Ok(())
}

/// Each link's mass is not negative and its inertia is one some mass distribution has, or, with `balance_inertia`, is
/// replaced by the nearest such inertia ([`ImportOptions::balance_inertia`]).
fn check_link_inertias(
    links: &mut [RawLink],
    balance_inertia: bool,
    repairs: &mut Vec<Repair>,
    warnings: &mut Vec<String>,
) -> Result<(), ImportError> {
    for link in links {
        let Some(inertial) = &mut link.inertial else { continue };
        if inertial.mass < 0.0 {
            return Err(ImportError::Mass {
                link: link.name.clone(),
                mass: inertial.mass,
                line: inertial.mass_line,
            });
        }
        let i = &inertial.inertia;
        let Some((moments, axes)) = principal_axes(i) else {
            return Err(ImportError::InertiaNotFinite {
                link: link.name.clone(),
                tensor: [i[(0, 0)], i[(0, 1)], i[(0, 2)], i[(1, 1)], i[(1, 2)], i[(2, 2)]],
                line: inertial.inertia_line,
            });
        };
        let tolerance = ROUND_OFF * inertia_scale(&moments, inertial.mass);
        let negative = moments[0] < -tolerance;
        let triangle = moments[2] > moments[0] + moments[1] + tolerance;
        if (negative || triangle) && balance_inertia {
            let new = balance(moments);
            inertial.inertia = rebuild(&axes, new);
            repairs.push(Repair::InertiaBalanced {
                link: link.name.clone(),
                line: inertial.inertia_line,
                old: moments,
                new,
            });
        } else if negative {
            return Err(ImportError::InertiaIndefinite {
                link: link.name.clone(),
                moments,
                line: inertial.inertia_line,
            });
        } else if triangle {
            return Err(ImportError::InertiaTriangle {
                link: link.name.clone(),
                moments,
                line: inertial.inertia_line,
            });
        }
        if inertial.mass == 0.0 && moments[2] > 0.0 {
            warnings.push(format!(
                "link `{}` (line {}) has mass 0 but principal moments {} kg m²: kept as written",
                link.name,
                inertial.mass_line,
                Moments(&moments)
            ));
        }
    }
    Ok(())
}

/// [`MasslessSubtrees::Freeze`]: per joint, whether it moves a massless subtree and is frozen. Masses are summed
/// child before parent (reverse of a pre-order from the root).
fn freeze_massless_subtrees(raw: &RawModel, tree: &Tree, repairs: &mut Vec<Repair>) -> Vec<bool> {
    let Tree {
        root,
        parent_joint,
        child_joints,
        joint_links,
    } = tree;
    let mut frozen = vec![false; raw.joints.len()];
    let mut order = Vec::with_capacity(raw.links.len());
    let mut stack = vec![*root];
    while let Some(l) = stack.pop() {
        order.push(l);
        stack.extend(child_joints[l].iter().map(|&j| joint_links[j].1));
    }
    let mut subtree_mass: Vec<f64> = raw
        .links
        .iter()
        .map(|l| l.inertial.as_ref().map_or(0.0, |i| i.mass))
        .collect();
    for &l in order.iter().rev() {
        if let Some(j) = parent_joint[l] {
            subtree_mass[joint_links[j].0] += subtree_mass[l];
        }
    }
    for (j, joint) in raw.joints.iter().enumerate() {
        if joint.kind != JointKind::Fixed && subtree_mass[joint_links[j].1] == 0.0 {
            frozen[j] = true;
            repairs.push(Repair::JointFrozen {
                joint: joint.name.clone(),
                kind: joint.kind,
                line: joint.line,
            });
        }
    }
    frozen
}

/// The balancing rule of [`ImportOptions::balance_inertia`] on ascending moments.
fn balance(moments: [f64; 3]) -> [f64; 3] {
    let [a, b, c] = moments.map(|m| m.max(0.0));
    let excess = (c - a - b).max(0.0) / 2.0;
    [a + excess, b + excess, c]
}
