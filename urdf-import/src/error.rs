//! Why a URDF file could not be imported. Every variant names the offending link, joint or element, the numbers
//! involved and the line (1-based) it starts on, so that a messy file can be fixed without a debugger: the
//! message alone points at the place to edit.

use std::fmt;

use crate::joint_kind::JointKind;

/// Formats a list of names as `` `a`, `b`, `c` `` for the messages.
pub(crate) struct Names<'a>(pub &'a [String]);

impl fmt::Display for Names<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, name) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "`{name}`")?;
        }
        Ok(())
    }
}

/// Formats principal moments (kg m²) compactly, with enough digits to see round-off.
pub(crate) struct Moments<'a>(pub &'a [f64; 3]);

impl fmt::Display for Moments<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{:.6e}, {:.6e}, {:.6e}]", self.0[0], self.0[1], self.0[2])
    }
}

/// Why an import failed. Lines are 1-based lines of the URDF text; masses in kg, moments of inertia in kg m².
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ImportError {
    /// The file could not be read (the message is the operating system's).
    #[error("cannot read {path}: {message}")]
    Io {
        /// The path as given.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The text is empty or only white space: often a failed xacro expansion written to the file.
    #[error("the URDF text is empty")]
    Empty,
    /// The text is not well-formed XML.
    #[error("not well-formed XML at line {line}, column {column}: {message}")]
    Xml {
        /// Where the XML parser stopped.
        line: u32,
        /// The column (in characters) on that line.
        column: u32,
        /// The XML parser's message.
        message: String,
    },
    /// Elements nested deeper than [`crate::parse::MAX_NESTING`]: a URDF nests a few levels, and the XML parser
    /// recurses once per level, so a hostile file would exhaust the stack.
    #[error(
        "elements nested more than {limit} deep at line {line}: a URDF nests a few levels (robot, link, visual, \
         geometry, mesh)"
    )]
    TooDeep {
        /// The line of the first element beyond the limit.
        line: u32,
        /// The limit.
        limit: usize,
    },
    /// The root element is not `<robot>`.
    #[error("the root element is <{element}> (line {line}), not <robot>")]
    NotRobot {
        /// The root element's tag.
        element: String,
        /// Its line.
        line: u32,
    },
    /// A `<robot>` without any `<link>`.
    #[error("{} (line {line}) has no <link>: nothing to simulate", robot_label(robot))]
    NoLinks {
        /// The robot's name (empty when it has none).
        robot: String,
        /// The `<robot>` element's line.
        line: u32,
    },
    /// A required attribute is missing (a link or joint without a name, a joint without a type, `<parent>` without
    /// `link`, `<mass>` without `value`, `<inertia>` without one of its six moments, ...).
    #[error("{owner}: <{element}> at line {line} has no `{attribute}` attribute")]
    MissingAttribute {
        /// The link or joint (or the robot) the element belongs to, as "joint `elbow`".
        owner: String,
        /// The element's tag.
        element: String,
        /// The missing attribute.
        attribute: String,
        /// The element's line.
        line: u32,
    },
    /// A required child element is missing (`<parent>` or `<child>` of a joint, `<mass>` or `<inertia>` of an
    /// `<inertial>`).
    #[error("{owner} (line {line}) has no <{element}>")]
    MissingElement {
        /// The link or joint, as "joint `elbow`", or "link `forearm` `<inertial>`" for an inertial.
        owner: String,
        /// The missing element's tag.
        element: String,
        /// The line of the element that should contain it.
        line: u32,
    },
    /// A numeric attribute that does not parse, has the wrong count of numbers (`xyz="1 2"`), or is NaN or
    /// infinite.
    #[error("{owner}: <{element} {attribute}=\"{text}\"> at line {line} is not {}", expected_numbers(*.expected))]
    Number {
        /// The link or joint the element belongs to.
        owner: String,
        /// The element's tag.
        element: String,
        /// The attribute.
        attribute: String,
        /// The attribute's text as written.
        text: String,
        /// How many numbers were expected (1 or 3).
        expected: usize,
        /// The element's line.
        line: u32,
    },
    /// An `<origin xyz>` farther than [`dynamics::state::LARGEST_COORDINATE`] from its parent frame: a typo or the
    /// wrong unit, and beyond the bodies' range.
    #[error(
        "{owner}: <origin xyz=\"{text}\"> at line {line} puts the frame {distance:e} m from its parent's, beyond \
         {limit:e} m (a typo, or millimetres for metres?)"
    )]
    FarOrigin {
        /// The link or joint the origin belongs to.
        owner: String,
        /// The attribute's text as written.
        text: String,
        /// The largest coordinate's size (m).
        distance: f64,
        /// The bound (m).
        limit: f64,
        /// The origin's line.
        line: u32,
    },
    /// A joint type outside revolute, continuous, prismatic, fixed, floating and planar (the URDF "spherical" is
    /// not part of the specification, and a typo lands here too).
    #[error(
        "joint `{joint}` (line {line}) has type \"{kind}\"; URDF joints are revolute, continuous, prismatic, fixed, \
         floating or planar"
    )]
    JointType {
        /// The joint.
        joint: String,
        /// The type as written.
        kind: String,
        /// The joint's line.
        line: u32,
    },
    /// A revolute, continuous, prismatic or planar joint whose `<axis xyz>` has no direction (zero).
    #[error("{kind} joint `{joint}` (line {line}) has axis xyz = {axis:?}, which has no direction")]
    Axis {
        /// The joint.
        joint: String,
        /// Its type.
        kind: JointKind,
        /// The axis as written.
        axis: [f64; 3],
        /// The `<axis>` element's line.
        line: u32,
    },
    /// A revolute or prismatic joint whose `<limit>` has `lower > upper`.
    #[error("joint `{joint}` (line {line}) has limit lower = {lower} above upper = {upper}")]
    LimitInverted {
        /// The joint.
        joint: String,
        /// The lower limit (rad or m).
        lower: f64,
        /// The upper limit (rad or m).
        upper: f64,
        /// The `<limit>` element's line.
        line: u32,
    },
    /// A joint whose `<dynamics>` has a negative damping or friction, which would feed energy in.
    #[error("joint `{joint}` (line {line}) has <dynamics {attribute}=\"{value}\">: it cannot be negative")]
    NegativeDynamics {
        /// The joint.
        joint: String,
        /// `damping` or `friction`.
        attribute: &'static str,
        /// The value given.
        value: f64,
        /// The `<dynamics>` element's line.
        line: u32,
    },
    /// Two links with the same name.
    #[error("link `{name}` is defined twice: at line {first_line} and at line {line}")]
    DuplicateLink {
        /// The name.
        name: String,
        /// The first definition's line.
        first_line: u32,
        /// The second definition's line.
        line: u32,
    },
    /// Two joints with the same name.
    #[error("joint `{name}` is defined twice: at line {first_line} and at line {line}")]
    DuplicateJoint {
        /// The name.
        name: String,
        /// The first definition's line.
        first_line: u32,
        /// The second definition's line.
        line: u32,
    },
    /// A joint naming a parent or child link that is not defined.
    #[error("joint `{joint}` (line {line}) names {role} link `{link}`, which is not defined")]
    UnknownLink {
        /// The joint.
        joint: String,
        /// "parent" or "child".
        role: &'static str,
        /// The undefined link's name.
        link: String,
        /// The joint's line.
        line: u32,
    },
    /// A link that is the child of two joints: a tree has one joint above each link.
    #[error(
        "link `{link}` is the child of two joints: `{first_joint}` (line {first_line}) and `{joint}` (line {line})"
    )]
    TwoParents {
        /// The link.
        link: String,
        /// The first joint naming it as child.
        first_joint: String,
        /// That joint's line.
        first_line: u32,
        /// The second joint naming it as child.
        joint: String,
        /// That joint's line.
        line: u32,
    },
    /// The joints form a closed loop (URDF describes trees only).
    #[error(
        "the joints form a cycle: {} (joint `{joint}`, line {line}); {unreachable} link(s) are not connected to a root",
        cycle.join(" -> ")
    )]
    Cycle {
        /// The links around the loop, parent to child, the first repeated at the end.
        cycle: Vec<String>,
        /// One joint of the loop.
        joint: String,
        /// That joint's line.
        line: u32,
        /// How many links cannot be reached from a root (the loop and whatever hangs below it).
        unreachable: usize,
    },
    /// Two or more links are nobody's child: the file describes several trees, and which one is the robot's base
    /// is not for the importer to guess.
    #[error("{} links are nobody's child, so the file holds several trees: {}", roots.len(), Names(roots))]
    SeveralRoots {
        /// Every root link, in file order.
        roots: Vec<String>,
    },
    /// Links that no joint names: not connected to the tree.
    #[error(
        "link(s) {} are not connected to the tree rooted at `{root}`: no joint names them",
        Names(links)
    )]
    Disconnected {
        /// The root of the tree.
        root: String,
        /// The links that no joint names, in file order.
        links: Vec<String>,
    },
    /// A negative mass.
    #[error("link `{link}` (line {line}) has mass {mass} kg; a mass cannot be negative")]
    Mass {
        /// The link.
        link: String,
        /// The mass as written (kg).
        mass: f64,
        /// The `<mass>` element's line.
        line: u32,
    },
    /// An inertia tensor whose principal moments overflow (entries near `f64::MAX`).
    #[error("link `{link}` (line {line}): the inertia tensor {tensor:?} (ixx ixy ixz iyy iyz izz) is not finite")]
    InertiaNotFinite {
        /// The link.
        link: String,
        /// ixx, ixy, ixz, iyy, iyz, izz (kg m²).
        tensor: [f64; 6],
        /// The `<inertia>` element's line.
        line: u32,
    },
    /// An inertia tensor with a negative principal moment: no mass distribution has it. `balance_inertia` repairs it.
    #[error(
        "link `{link}` (line {line}): the inertia tensor has principal moments {} kg m², one negative; no mass \
         distribution has that (ImportOptions::balance_inertia repairs it)",
        Moments(moments)
    )]
    InertiaIndefinite {
        /// The link.
        link: String,
        /// The principal moments, ascending (kg m²).
        moments: [f64; 3],
        /// The `<inertia>` element's line.
        line: u32,
    },
    /// Principal moments with `I₃ > I₁ + I₂`: no mass distribution has them. `balance_inertia` repairs it.
    #[error(
        "link `{link}` (line {line}): the principal moments {} kg m² break the triangle inequality \
         ({:.6e} > {:.6e} + {:.6e}); no mass distribution has them (ImportOptions::balance_inertia repairs it)",
        Moments(moments), moments[2], moments[0], moments[1]
    )]
    InertiaTriangle {
        /// The link.
        link: String,
        /// The principal moments, ascending (kg m²).
        moments: [f64; 3],
        /// The `<inertia>` element's line.
        line: u32,
    },
    /// A `<mimic>` naming a joint that does not exist.
    #[error("joint `{joint}` (line {line}) mimics joint `{target}`, which is not defined")]
    MimicUnknown {
        /// The mimicking joint.
        joint: String,
        /// The joint it names.
        target: String,
        /// The `<mimic>` element's line.
        line: u32,
    },
    /// A joint mimicking itself.
    #[error("joint `{joint}` (line {line}) mimics itself")]
    MimicSelf {
        /// The joint.
        joint: String,
        /// The `<mimic>` element's line.
        line: u32,
    },
    /// A joint mimicking a joint that itself mimics a third: the chain is not followed (as in urdfdom and
    /// Pinocchio), so the file should name the first joint directly.
    #[error(
        "joint `{joint}` (line {line}) mimics joint `{target}`, which itself mimics `{target_target}`: mimic the \
         driving joint `{target_target}` directly"
    )]
    MimicChain {
        /// The mimicking joint.
        joint: String,
        /// The joint it mimics.
        target: String,
        /// The joint that one mimics.
        target_target: String,
        /// The first `<mimic>` element's line.
        line: u32,
    },
    /// A `<mimic>` on a joint that has no single coordinate (fixed, floating, planar), or mimicking such a joint.
    #[error(
        "joint `{joint}` (line {line}): <mimic> couples single coordinates, but {role} `{other}` is {kind} \
         (only revolute, continuous and prismatic joints mimic or are mimicked)"
    )]
    MimicKind {
        /// The mimicking joint.
        joint: String,
        /// "this joint" or "the mimicked joint".
        role: &'static str,
        /// The joint of the wrong type (the mimicking joint itself or its target).
        other: String,
        /// That joint's type.
        kind: JointKind,
        /// The `<mimic>` element's line.
        line: u32,
    },
    /// After merging across fixed joints, a moving joint's child body has zero mass or a singular inertia: the
    /// dynamics keeps each body's own mass and inertia invertible.
    #[error(
        "joint `{joint}` (line {line}) moves a body (links {}) with mass {mass} kg and principal moments {} kg m² \
         about its centre of mass: the dynamics needs a positive mass and positive moments{}",
        Names(links), Moments(moments), singular_advice(*.massless_subtree)
    )]
    SingularBody {
        /// The moving joint.
        joint: String,
        /// The joint's line.
        line: u32,
        /// The links of its child body, reference link first.
        links: Vec<String>,
        /// The body's mass (kg).
        mass: f64,
        /// The body's principal moments about its centre of mass, ascending (kg m²).
        moments: [f64; 3],
        /// Every body below the joint is massless too (where Pinocchio's ABA returns NaN).
        massless_subtree: bool,
    },
    /// An [`crate::ImportOptions`] value out of range.
    #[error("ImportOptions::{option} = {value} must be positive and finite")]
    Option {
        /// The option's field name.
        option: &'static str,
        /// The value given.
        value: f64,
    },
}

fn robot_label(name: &str) -> String {
    if name.is_empty() {
        "the unnamed <robot>".to_owned()
    } else {
        format!("robot `{name}`")
    }
}

fn expected_numbers(count: usize) -> String {
    match count {
        1 => "a finite number".to_owned(),
        n => format!("{n} finite numbers separated by spaces"),
    }
}

fn singular_advice(massless_subtree: bool) -> &'static str {
    if massless_subtree {
        "; every body below this joint is massless too (the case where Pinocchio returns NaN): \
         MasslessSubtrees::Freeze treats such a joint as fixed, or set bound_mass and bound_inertia"
    } else {
        "; set ImportOptions::bound_mass and bound_inertia to raise them"
    }
}
