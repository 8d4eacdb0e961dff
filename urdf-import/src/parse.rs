//! Stage 1: URDF text → [`RawModel`], the links and joints as written, each with its line.
//!
//! Only syntax is checked here: XML well-formedness, the `<robot>` root, required attributes and elements,
//! numbers (Rust's `f64` parser after trimming; NaN and infinities refused, since they would only surface later
//! as NaN accelerations far from their cause) and joint types. Meaning (names that resolve, a tree, physical
//! inertias, mimics) is [`crate::validate`]'s job. Elements the dynamics does not use (visual, collision,
//! material, gazebo, transmission, sensor, ...) are skipped; the top-level ones are counted in
//! [`RawModel::ignored`] so a caller can see what was dropped.

use nalgebra::{Isometry3, Matrix3, Vector3};
use roxmltree::{Document, Node, ParsingOptions};

use crate::error::ImportError;
pub use crate::joint_kind::JointKind;
use crate::pose::pose;

/// A joint's `<limit>`, each attribute `None` when absent (the URDF specification requires `effort` and
/// `velocity` on revolute and prismatic joints, but real files omit them, and a missing bound is not a zero bound).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Limit {
    /// Lower position limit (rad or m).
    pub lower: Option<f64>,
    /// Upper position limit (rad or m).
    pub upper: Option<f64>,
    /// Largest effort (N m or N).
    pub effort: Option<f64>,
    /// Largest speed (rad/s or m/s).
    pub velocity: Option<f64>,
}

/// A link's `<inertial>` as written.
#[derive(Clone, Debug, PartialEq)]
pub struct Inertial {
    /// The inertia frame in the link frame: its origin is the centre of mass, its axes those of `inertia`.
    pub origin: Isometry3<f64>,
    /// Mass (kg), finite (sign checked by validation).
    pub mass: f64,
    /// The full symmetric tensor about the centre of mass in the inertia frame's axes (kg m²).
    pub inertia: Matrix3<f64>,
    /// The `<inertial>` element's line.
    pub line: u32,
    /// The `<mass>` element's line.
    pub mass_line: u32,
    /// The `<inertia>` element's line.
    pub inertia_line: u32,
}

/// A `<collision>` element's geometry as written (m).
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// `<sphere radius>`.
    Sphere {
        /// m.
        radius: f64,
    },
    /// `<box size>`: edge lengths along the collision frame's axes.
    Box {
        /// m.
        size: [f64; 3],
    },
    /// `<cylinder radius length>`, its axis the collision frame's z.
    Cylinder {
        /// m.
        radius: f64,
        /// m.
        length: f64,
    },
    /// `<mesh filename scale>`.
    Mesh {
        /// As written, often a `package://` address.
        filename: String,
        /// Per axis (default 1).
        scale: [f64; 3],
    },
}

/// A link's `<collision>`: its geometry in the collision frame `origin` (in the link frame).
#[derive(Clone, Debug, PartialEq)]
pub struct Collision {
    /// The collision frame in the link frame.
    pub origin: Isometry3<f64>,
    /// The shape.
    pub geometry: Geometry,
    /// The `<collision>` element's line.
    pub line: u32,
}

/// A `<link>` as written.
#[derive(Clone, Debug, PartialEq)]
pub struct RawLink {
    /// Its name.
    pub name: String,
    /// The `<link>` element's line.
    pub line: u32,
    /// Its mass properties; `None` when the link has no `<inertial>` (a massless frame).
    pub inertial: Option<Inertial>,
    /// Its well-formed `<collision>` elements, in file order (malformed ones are noted in [`RawModel::warnings`]: the
    /// dynamics does not need them, and a robot that loads without them should not fail for them).
    pub collisions: Vec<Collision>,
}

/// A joint's `<mimic>` as written.
#[derive(Clone, Debug, PartialEq)]
pub struct RawMimic {
    /// The mimicked joint's name.
    pub joint: String,
    /// `q = multiplier q_mimicked + offset`; default 1.
    pub multiplier: f64,
    /// Default 0 (rad or m).
    pub offset: f64,
    /// The `<mimic>` element's line.
    pub line: u32,
}

/// A `<joint>` as written.
#[derive(Clone, Debug, PartialEq)]
pub struct RawJoint {
    /// Its name.
    pub name: String,
    /// Its type.
    pub kind: JointKind,
    /// The `<joint>` element's line.
    pub line: u32,
    /// The child link frame in the parent link frame at q = 0 (`<origin>`, default identity).
    pub origin: Isometry3<f64>,
    /// The parent link's name.
    pub parent: String,
    /// The child link's name.
    pub child: String,
    /// `<axis xyz>` as written, not normalised (default (1, 0, 0)).
    pub axis: Vector3<f64>,
    /// The `<axis>` element's line, or the joint's when absent.
    pub axis_line: u32,
    /// The `<limit>`, if any, and its line.
    pub limit: Option<(Limit, u32)>,
    /// `<dynamics damping>` (N m s/rad or N s/m), default 0.
    pub damping: f64,
    /// `<dynamics friction>` (N m or N), default 0.
    pub friction: f64,
    /// The `<mimic>`, if any.
    pub mimic: Option<RawMimic>,
}

/// A parsed URDF: links and joints in file order.
#[derive(Clone, Debug, PartialEq)]
pub struct RawModel {
    /// The robot's name (empty when the file gives none, which [`RawModel::warnings`] notes).
    pub name: String,
    /// The `<robot>` element's line.
    pub line: u32,
    /// Links in file order.
    pub links: Vec<RawLink>,
    /// Joints in file order.
    pub joints: Vec<RawJoint>,
    /// Top-level elements other than `<link>` and `<joint>`, by tag, with how many there were (file order of first
    /// appearance).
    pub ignored: Vec<(String, usize)>,
    /// Things a reader should know that are not errors.
    pub warnings: Vec<String>,
}

/// Byte offset → line, by binary search over the line starts: `Document::text_pos_at` rescans the text from the
/// start on every call, which is quadratic over a file of a thousand elements.
struct Lines {
    starts: Vec<usize>,
}

impl Lines {
    fn new(text: &str) -> Lines {
        let mut starts = vec![0];
        starts.extend(
            text.bytes()
                .enumerate()
                .filter(|&(_, b)| b == b'\n')
                .map(|(i, _)| i + 1),
        );
        Lines { starts }
    }

    fn line(&self, offset: usize) -> u32 {
        u32::try_from(self.starts.partition_point(|&s| s <= offset)).unwrap_or(u32::MAX)
    }
}

/// The deepest nesting of elements accepted. The XML parser recurses once per level; a URDF nests five or six.
pub const MAX_NESTING: usize = 256;

/// The byte offset of the first start tag nested deeper than `limit`, if any, by a scan that knows only what can hide
/// a `<`: comments, CDATA, processing instructions, the DOCTYPE, quoted attribute values. Malformed text is left to
/// the XML parser, which then sees a nesting within the limit.
fn too_deep(text: &str, limit: usize) -> Option<usize> {
    let bytes = text.as_bytes();
    let skip_past = |from: usize, end: &str| text[from..].find(end).map_or(bytes.len(), |k| from + k + end.len());
    let (mut depth, mut at) = (0usize, 0usize);
    while let Some(k) = text[at..].find('<') {
        let start = at + k;
        let rest = &text[start..];
        at = if rest.starts_with("<!--") {
            skip_past(start, "-->")
        } else if rest.starts_with("<![CDATA[") {
            skip_past(start, "]]>")
        } else if rest.starts_with("<?") {
            skip_past(start, "?>")
        } else if rest.starts_with("<!") {
            // A DOCTYPE, with its internal subset in brackets.
            let close = rest.find('>').map_or(bytes.len(), |k| start + k);
            match rest.find('[') {
                Some(open) if start + open < close => skip_past(start, "]>"),
                _ => close + 1,
            }
        } else {
            // A tag: to its `>` outside quotes.
            let mut end = start + 1;
            let mut quote = None;
            while end < bytes.len() {
                match (quote, bytes[end]) {
                    (None, b'"' | b'\'') => quote = Some(bytes[end]),
                    (Some(q), b) if b == q => quote = None,
                    (None, b'>') => break,
                    _ => {}
                }
                end += 1;
            }
            if rest.starts_with("</") {
                depth = depth.saturating_sub(1);
            } else if bytes.get(end.saturating_sub(1)) != Some(&b'/') {
                depth += 1;
                if depth > limit {
                    return Some(start);
                }
            }
            end + 1
        };
        if at >= bytes.len() {
            break;
        }
    }
    None
}

/// Parses URDF text into a [`RawModel`].
///
/// ```
/// let raw = urdf_import::parse::parse(r#"<robot name="r"><link name="base"/></robot>"#)?;
/// assert_eq!((raw.name.as_str(), raw.links.len()), ("r", 1));
/// # Ok::<(), urdf_import::ImportError>(())
/// ```
pub fn parse(text: &str) -> Result<RawModel, ImportError> {
    if text.trim().is_empty() {
        return Err(ImportError::Empty);
    }
    if let Some(offset) = too_deep(text, MAX_NESTING) {
        return Err(ImportError::TooDeep {
            line: Lines::new(text).line(offset),
            limit: MAX_NESTING,
        });
    }
    // A DTD is allowed: some exporters write one, and roxmltree still guards against entity expansion bombs.
    let options = ParsingOptions {
        allow_dtd: true,
        ..ParsingOptions::default()
    };
    let doc = Document::parse_with_options(text, options).map_err(|e| ImportError::Xml {
        line: e.pos().row,
        column: e.pos().col,
        message: e.to_string(),
    })?;
    let lines = Lines::new(text);
    let at = |node: Node| lines.line(node.range().start);
    let robot = doc.root_element();
    if robot.tag_name().name() != "robot" {
        return Err(ImportError::NotRobot {
            element: qualified_name(robot),
            line: at(robot),
        });
    }
    let mut model = RawModel {
        name: robot.attribute("name").unwrap_or("").to_owned(),
        line: at(robot),
        links: Vec::new(),
        joints: Vec::new(),
        ignored: Vec::new(),
        warnings: Vec::new(),
    };
    if model.name.is_empty() {
        model
            .warnings
            .push(format!("<robot> (line {}) has no name", model.line));
    }
    let mut xacro = 0;
    for node in robot.children().filter(Node::is_element) {
        match urdf_tag(node) {
            Some("link") => model
                .links
                .push(parse_link(node, &model.name, &at, &mut model.warnings)?),
            Some("joint") => model.joints.push(parse_joint(node, &model.name, &at)?),
            _ => {
                let tag = qualified_name(node);
                if node.tag_name().namespace().is_some_and(|ns| ns.contains("xacro")) {
                    xacro += 1;
                }
                match model.ignored.iter_mut().find(|(t, _)| *t == tag) {
                    Some((_, count)) => *count += 1,
                    None => model.ignored.push((tag, 1)),
                }
            }
        }
    }
    if xacro > 0 {
        model.warnings.push(format!(
            "{xacro} top-level xacro element(s) ignored: is this an unexpanded .xacro file? Run xacro first"
        ));
    }
    if model.links.is_empty() {
        return Err(ImportError::NoLinks {
            robot: model.name,
            line: model.line,
        });
    }
    Ok(model)
}

/// The tag's local name when the element is in no namespace or the default one (so `<xacro:property>` is never
/// taken for a URDF element).
fn urdf_tag<'a>(node: Node<'a, '_>) -> Option<&'a str> {
    match node.tag_name().namespace() {
        Some(ns) if node.lookup_prefix(ns).is_some() => None,
        _ => Some(node.tag_name().name()),
    }
}

/// The tag as written, with its prefix when it has one.
fn qualified_name(node: Node) -> String {
    let name = node.tag_name().name();
    match node.tag_name().namespace().and_then(|ns| node.lookup_prefix(ns)) {
        Some(prefix) => format!("{prefix}:{name}"),
        None => name.to_owned(),
    }
}

/// The first child element with this URDF tag.
fn child<'a, 'i>(node: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    node.children().find(|c| c.is_element() && urdf_tag(*c) == Some(tag))
}

/// What a number's error message needs to point at its element.
struct Site<'s, F: Fn(Node) -> u32> {
    owner: &'s str,
    at: &'s F,
}

impl<F: Fn(Node) -> u32> Site<'_, F> {
    fn missing_attribute(&self, node: Node, attribute: &str) -> ImportError {
        ImportError::MissingAttribute {
            owner: self.owner.to_owned(),
            element: qualified_name(node),
            attribute: attribute.to_owned(),
            line: (self.at)(node),
        }
    }

    fn required<'a>(&self, node: Node<'a, '_>, attribute: &str) -> Result<&'a str, ImportError> {
        node.attribute(attribute)
            .ok_or_else(|| self.missing_attribute(node, attribute))
    }

    /// `N` finite numbers separated by white space, or `None` when the attribute is absent.
    fn numbers<const N: usize>(&self, node: Node, attribute: &str) -> Result<Option<[f64; N]>, ImportError> {
        let Some(text) = node.attribute(attribute) else {
            return Ok(None);
        };
        let bad = || ImportError::Number {
            owner: self.owner.to_owned(),
            element: qualified_name(node),
            attribute: attribute.to_owned(),
            text: text.to_owned(),
            expected: N,
            line: (self.at)(node),
        };
        let mut values = [0.0; N];
        let mut words = text.split_whitespace();
        for value in values.iter_mut() {
            *value = words
                .next()
                .and_then(|w| w.parse::<f64>().ok())
                .filter(|v| v.is_finite())
                .ok_or_else(bad)?;
        }
        if words.next().is_some() {
            return Err(bad());
        }
        Ok(Some(values))
    }

    fn number(&self, node: Node, attribute: &str) -> Result<Option<f64>, ImportError> {
        Ok(self.numbers::<1>(node, attribute)?.map(|[v]| v))
    }

    fn required_number(&self, node: Node, attribute: &str) -> Result<f64, ImportError> {
        self.number(node, attribute)?
            .ok_or_else(|| self.missing_attribute(node, attribute))
    }

    /// An `<origin xyz rpy>` child (identity when absent, each attribute defaulting to zeros).
    fn origin(&self, parent: Node) -> Result<Isometry3<f64>, ImportError> {
        let Some(origin) = child(parent, "origin") else {
            return Ok(Isometry3::identity());
        };
        let xyz = self.numbers::<3>(origin, "xyz")?.unwrap_or([0.0; 3]);
        let distance = xyz.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let limit = dynamics::state::LARGEST_COORDINATE;
        if distance > limit {
            return Err(ImportError::FarOrigin {
                owner: self.owner.to_owned(),
                text: origin.attribute("xyz").unwrap_or_default().to_owned(),
                distance,
                limit,
                line: (self.at)(origin),
            });
        }
        let rpy = self.numbers::<3>(origin, "rpy")?.unwrap_or([0.0; 3]);
        Ok(pose(xyz, rpy))
    }
}

/// The `name` attribute of a link or joint of `robot`.
fn element_name(node: Node, robot: &str, at: &impl Fn(Node) -> u32) -> Result<String, ImportError> {
    let robot_owner = format!("robot `{robot}`");
    let site = Site {
        owner: &robot_owner,
        at,
    };
    Ok(site.required(node, "name")?.to_owned())
}

fn parse_link(
    node: Node,
    robot: &str,
    at: &impl Fn(Node) -> u32,
    warnings: &mut Vec<String>,
) -> Result<RawLink, ImportError> {
    let name = element_name(node, robot, at)?;
    let owner = format!("link `{name}`");
    let site = Site { owner: &owner, at };
    let inertial = match child(node, "inertial") {
        None => None,
        Some(inertial) => {
            let missing = |element: &str| ImportError::MissingElement {
                owner: format!("link `{name}` <inertial>"),
                element: element.to_owned(),
                line: at(inertial),
            };
            let mass_node = child(inertial, "mass").ok_or_else(|| missing("mass"))?;
            let inertia_node = child(inertial, "inertia").ok_or_else(|| missing("inertia"))?;
            let mut moments = [0.0; 6];
            for (value, key) in moments.iter_mut().zip(["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]) {
                *value = site.required_number(inertia_node, key)?;
            }
            let [ixx, ixy, ixz, iyy, iyz, izz] = moments;
            Some(Inertial {
                origin: site.origin(inertial)?,
                mass: site.required_number(mass_node, "value")?,
                inertia: Matrix3::new(ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz),
                line: at(inertial),
                mass_line: at(mass_node),
                inertia_line: at(inertia_node),
            })
        }
    };
    let mut collisions = Vec::new();
    for element in node.children().filter(|c| urdf_tag(*c) == Some("collision")) {
        match parse_collision(element, &site) {
            Ok(collision) => collisions.push(collision),
            Err(reason) => warnings.push(format!(
                "link `{name}`: the <collision> at line {} is skipped: {reason}",
                at(element)
            )),
        }
    }
    Ok(RawLink {
        name,
        line: at(node),
        inertial,
        collisions,
    })
}

/// A `<collision>`'s origin and geometry, or why it cannot be read.
fn parse_collision(element: Node, site: &Site<'_, impl Fn(Node) -> u32>) -> Result<Collision, String> {
    let geometry = child(element, "geometry").ok_or("it has no <geometry>")?;
    let shape = geometry
        .children()
        .find(|c| c.is_element())
        .ok_or("its <geometry> is empty")?;
    let number = |attribute: &str| {
        site.required_number(shape, attribute)
            .map_err(|error| error.to_string())
    };
    let geometry = match urdf_tag(shape) {
        Some("sphere") => Geometry::Sphere {
            radius: number("radius")?,
        },
        Some("box") => Geometry::Box {
            size: site
                .numbers::<3>(shape, "size")
                .map_err(|error| error.to_string())?
                .ok_or("its <box> has no size")?,
        },
        Some("cylinder") => Geometry::Cylinder {
            radius: number("radius")?,
            length: number("length")?,
        },
        Some("mesh") => Geometry::Mesh {
            filename: site
                .required(shape, "filename")
                .map_err(|error| error.to_string())?
                .to_owned(),
            scale: site
                .numbers::<3>(shape, "scale")
                .map_err(|error| error.to_string())?
                .unwrap_or([1.0; 3]),
        },
        _ => return Err(format!("<{}> is not a URDF geometry", qualified_name(shape))),
    };
    Ok(Collision {
        origin: site.origin(element).map_err(|error| error.to_string())?,
        geometry,
        line: (site.at)(element),
    })
}

fn parse_joint(node: Node, robot: &str, at: &impl Fn(Node) -> u32) -> Result<RawJoint, ImportError> {
    let name = element_name(node, robot, at)?;
    let owner = format!("joint `{name}`");
    let site = Site { owner: &owner, at };
    let line = at(node);
    let type_text = site.required(node, "type")?;
    let kind = JointKind::from_urdf(type_text.trim()).ok_or_else(|| ImportError::JointType {
        joint: name.clone(),
        kind: type_text.to_owned(),
        line,
    })?;
    let link_of = |tag: &str| -> Result<String, ImportError> {
        let element = child(node, tag).ok_or_else(|| ImportError::MissingElement {
            owner: owner.clone(),
            element: tag.to_owned(),
            line,
        })?;
        Ok(site.required(element, "link")?.to_owned())
    };
    let parent = link_of("parent")?;
    let child_link = link_of("child")?;
    let (axis, axis_line) = match child(node, "axis") {
        Some(axis) => (site.numbers::<3>(axis, "xyz")?.unwrap_or([1.0, 0.0, 0.0]), at(axis)),
        None => ([1.0, 0.0, 0.0], line),
    };
    let limit = match child(node, "limit") {
        None => None,
        Some(limit) => Some((
            Limit {
                lower: site.number(limit, "lower")?,
                upper: site.number(limit, "upper")?,
                effort: site.number(limit, "effort")?,
                velocity: site.number(limit, "velocity")?,
            },
            at(limit),
        )),
    };
    let (damping, friction) = match child(node, "dynamics") {
        None => (0.0, 0.0),
        Some(d) => {
            let coefficient = |attribute: &'static str| match site.number(d, attribute)? {
                Some(value) if value < 0.0 => Err(ImportError::NegativeDynamics {
                    joint: name.clone(),
                    attribute,
                    value,
                    line: at(d),
                }),
                value => Ok(value.unwrap_or(0.0)),
            };
            (coefficient("damping")?, coefficient("friction")?)
        }
    };
    let mimic = match child(node, "mimic") {
        None => None,
        Some(m) => Some(RawMimic {
            joint: site.required(m, "joint")?.to_owned(),
            multiplier: site.number(m, "multiplier")?.unwrap_or(1.0),
            offset: site.number(m, "offset")?.unwrap_or(0.0),
            line: at(m),
        }),
    };
    Ok(RawJoint {
        name,
        kind,
        line,
        origin: site.origin(node)?,
        parent,
        child: child_link,
        axis: Vector3::from(axis),
        axis_line,
        limit,
        damping,
        friction,
        mimic,
    })
}
