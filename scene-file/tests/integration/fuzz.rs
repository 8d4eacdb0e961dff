//! The scene-file parser under hostile input ("Nothing silent"): arbitrary text, arbitrary bytes and
//! TOML-ish fragments, and the shipped scene files mutated (lines deleted, duplicated, swapped or inserted,
//! numbers replaced by extreme values, strings emptied or renamed, the file cut short) give a scene or an error,
//! never a panic. Where a file parses, what the scene job does before its run (layout, joint geometries,
//! the system in each requested algebra; the schedule and stabilisation are checked parts of the scene) succeeds, as
//! `Scene::parse` promises, and
//! a run cut to at most a few steps ends in a simulation or an error, never a panic.

use std::ops::Range;
use std::path::Path;

use dynamics::{Cga, Pga};
use nalgebra::{UnitQuaternion, Vector3};
use proptest::prelude::*;
use scene_file::{joint_violations, AlgebraKind, CheckedScene, FileAlgebra, JointGeometry, Pose, Scene, SceneFile};

/// The shipped scene files, read when the test is compiled.
const SCENES: [(&str, &str); 9] = [
    ("heavy_top.toml", include_str!("../../../scenes/heavy_top.toml")),
    (
        "limited_double_pendulum.toml",
        include_str!("../../../scenes/limited_double_pendulum.toml"),
    ),
    (
        "double_pendulum.toml",
        include_str!("../../../scenes/double_pendulum.toml"),
    ),
    ("four_bar.toml", include_str!("../../../scenes/four_bar.toml")),
    ("chain.toml", include_str!("../../../scenes/chain.toml")),
    ("bead_on_torus.toml", include_str!("../../../scenes/bead_on_torus.toml")),
    (
        "rod_on_ellipsoid.toml",
        include_str!("../../../scenes/rod_on_ellipsoid.toml"),
    ),
    (
        "turntable_pendulum.toml",
        include_str!("../../../scenes/turntable_pendulum.toml"),
    ),
    (
        "stack_and_billiards.toml",
        include_str!("../../../scenes/stack_and_billiards.toml"),
    ),
];

/// The shipped robot files (their URDF paths relative to the scenes folder).
const ROBOT_SCENES: [(&str, &str); 3] = [
    ("ur5.toml", include_str!("../../../scenes/ur5.toml")),
    ("solo12.toml", include_str!("../../../scenes/solo12.toml")),
    ("ur5_paddle.toml", include_str!("../../../scenes/ur5_paddle.toml")),
];

/// The folder the shipped scene files' paths are relative to.
fn scenes() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

/// The most steps (per algebra) of the run made from a file that parses.
const MAX_RUN_STEPS: usize = 20;

/// The longest run (s) made from a file that parses: the shipped files sample every 0.01 s.
const MAX_RUN_DURATION: f64 = 1.0;

/// The most steps of an adaptive run made from a file that parses (its sample interval: the shipped files take a
/// few).
const MAX_ADAPTIVE_STEPS: usize = 10_000;

/// Values that break naive arithmetic, spelled as TOML writes them (and some it refuses: integers that overflow
/// i64, exponents past f64's range, hexadecimal where a float is expected).
const EXTREME_NUMBERS: &[&str] = &[
    "0",
    "0.0",
    "-0.0",
    "1",
    "-1",
    "-1.0",
    "2",
    "0.5",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "nan",
    "-nan",
    "inf",
    "+inf",
    "-inf",
    "1e-320",
    "-1e-320",
    "5e-324",
    "2.2250738585072014e-308",
    "1e-15",
    "1e15",
    "9223372036854775807",
    "-9223372036854775808",
    "99999999999999999999",
    "-99999999999999999999",
    "1e1000",
    "0x10",
    "1_000",
];

/// Strings that replace a string value: empty, unknown names, and the known names of other fields (a body's
/// name where a joint's reference was, `pinning`, a splitting integrator…), to reach the checks past toml's.
const STRING_VALUES: &[&str] = &[
    "",
    "unknown",
    "world",
    "tool0",
    "wrist_3_link",
    "elbow_joint",
    "paddle",
    "paddle_hinge",
    "free",
    "fixed",
    "universal",
    "constant_rate",
    "sine",
    "enforce",
    "independent",
    "ur5_robot.urdf",
    "link1",
    "crank",
    "body",
    "low er",
    "é∂",
    "pga",
    "cga",
    "both",
    "pinning",
    "virtual_power",
    "strang",
    "yoshida4",
    "rkmk4",
    "baumgarte",
    "none",
    "hinge",
    "prismatic",
    "planar",
    "point_on_sphere",
    "point_on_circle",
    "gravity",
    "couple",
    "force",
    "rod",
    "sphere",
];

/// Whole lines inserted into a file: fields it lacks, and tables that conflict with its layout.
const EXTRA_LINES: &[&str] = &[
    "stabilisation = \"baumgarte\"",
    "baumgarte = { alpha = 1e308, beta = nan }",
    "baumgarte = { alpha = 10.0, beta = 10.0 }",
    "sample_interval = 1e-300",
    "sample_interval = 0.02",
    "sample_interval = 1e300",
    "max_start_correction = 0.0",
    "max_start_correction = -1.0",
    "max_start_correction = nan",
    "max_start_correction = inf",
    "max_start_correction = 1e300",
    "max_start_correction = 1e-300",
    "max_start_correction = \"big\"",
    "algebra = \"cga\"",
    "integrator = \"yoshida4\"",
    "formulation = \"pinning\"",
    "acceleration = [0.0, 1e308, -1e308]",
    "forces = [{ kind = \"couple\", moment = [1e308, 1e308, 1e308] }]",
    "[[body]]",
    "[body]",
    "[initial]",
    "[[joint]]",
    "[[constraints]]",
    "kind = \"point_on_circle\"",
    "initial.orientation = { axis = [1e308, 1e308, 0.0], angle = 1e308 }",
    "initial.orientation = { quaternion = [1e308, 1e308, 1e308, 1e308] }",
    "initial.orientation = { quaternion = [1e-320, 0.0, 0.0, 0.0] }",
    "principal_moments = [1e-320, 1e-320, 1e-320]",
    "between = [\"world\", \"world\"]",
];

/// A number where a number was, as TOML writes it.
fn number() -> impl Strategy<Value = String> {
    let float = |value: f64| {
        if value.is_nan() {
            "nan".to_owned()
        } else if value.is_infinite() {
            if value > 0.0 { "inf" } else { "-inf" }.to_owned()
        } else {
            format!("{value:?}")
        }
    };
    prop_oneof![
        4 => prop::sample::select(EXTREME_NUMBERS).prop_map(str::to_owned),
        1 => any::<f64>().prop_map(float),
        1 => (-10.0f64..10.0).prop_map(float),
        1 => any::<i64>().prop_map(|i| i.to_string()),
    ]
}

/// One edit of a file; the indices pick a line, token or byte modulo their count.
#[derive(Clone, Debug)]
enum Mutation {
    DeleteLine(usize),
    DuplicateLine(usize),
    SwapLines(usize, usize),
    InsertLine(usize, &'static str),
    ReplaceNumber(usize, String),
    ReplaceString(usize, String),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let index = any::<usize>();
    prop_oneof![
        1 => index.prop_map(Mutation::DeleteLine),
        1 => index.prop_map(Mutation::DuplicateLine),
        1 => (index, index).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        1 => (index, prop::sample::select(EXTRA_LINES)).prop_map(|(at, line)| Mutation::InsertLine(at, line)),
        5 => (index, number()).prop_map(|(at, value)| Mutation::ReplaceNumber(at, value)),
        2 => (
            index,
            prop_oneof![3 => prop::sample::select(STRING_VALUES).prop_map(str::to_owned), 1 => "[a-z_]{0,10}"],
        )
            .prop_map(|(at, value)| Mutation::ReplaceString(at, value)),
        1 => index.prop_map(Mutation::Truncate),
    ]
}

/// The byte ranges of the number tokens and of the contents of the quoted strings, outside comments.
fn tokens(text: &str) -> (Vec<Range<usize>>, Vec<Range<usize>>) {
    let bytes = text.as_bytes();
    let (mut numbers, mut strings) = (Vec::new(), Vec::new());
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'#' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
            }
            b'"' => {
                let start = i + 1;
                i = start;
                while i < bytes.len() && bytes[i] != b'"' && bytes[i] != b'\n' {
                    i += if bytes[i] == b'\\' { 2 } else { 1 };
                }
                let end = i.min(bytes.len());
                strings.push(start..end);
                i = end + 1;
            }
            b'-' | b'+' | b'0'..=b'9'
                if i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || matches!(bytes[i - 1], b'_' | b'.')) =>
            {
                let start = i;
                i += 1;
                while i < bytes.len()
                    && (bytes[i].is_ascii_alphanumeric() || matches!(bytes[i], b'.' | b'_' | b'+' | b'-'))
                {
                    i += 1;
                }
                if bytes[start..i].iter().any(u8::is_ascii_digit) {
                    numbers.push(start..i);
                }
            }
            _ => i += 1,
        }
    }
    (numbers, strings)
}

fn replace(text: &str, range: &Range<usize>, by: &str) -> String {
    format!("{}{by}{}", &text[..range.start], &text[range.end..])
}

impl Mutation {
    fn apply(&self, text: &str) -> String {
        let mut lines: Vec<&str> = text.split('\n').collect();
        let line = |at: usize| at % lines.len();
        match self {
            Mutation::DeleteLine(at) => {
                lines.remove(line(*at));
            }
            Mutation::DuplicateLine(at) => {
                let at = line(*at);
                lines.insert(at, lines[at]);
            }
            Mutation::SwapLines(a, b) => {
                let (a, b) = (line(*a), line(*b));
                lines.swap(a, b);
            }
            Mutation::InsertLine(at, extra) => {
                let at = line(*at);
                lines.insert(at, extra);
            }
            Mutation::ReplaceNumber(at, value) => {
                let (numbers, _) = tokens(text);
                return match numbers.get(at % numbers.len().max(1)) {
                    Some(range) => replace(text, range, value),
                    None => text.to_owned(),
                };
            }
            Mutation::ReplaceString(at, value) => {
                let (_, strings) = tokens(text);
                return match strings.get(at % strings.len().max(1)) {
                    Some(range) => replace(text, range, value),
                    None => text.to_owned(),
                };
            }
            Mutation::Truncate(at) => {
                let mut end = at % (text.len() + 1);
                while !text.is_char_boundary(end) {
                    end -= 1;
                }
                return text[..end].to_owned();
            }
        }
        lines.join("\n")
    }
}

/// Runs the scene of `file` (a robot's URDF relative to `folder`) cut to one sample interval in algebra `A`, if that
/// is at most [`MAX_RUN_STEPS`] fixed steps or [`MAX_RUN_DURATION`], adaptive steps at most [`MAX_ADAPTIVE_STEPS`]: a
/// simulation of every body with every sample's joint violations, or an error that says something.
fn short_run<A: FileAlgebra>(file: &SceneFile, folder: &Path, joints: &[JointGeometry]) -> Result<(), TestCaseError> {
    let mut short = file.clone();
    short.duration = short.sample_interval;
    // An adaptive run has no step count to bound beforehand: a sample interval mutated to 1e300 s would run until
    // the step limit.
    if short.duration.is_nan() || short.duration > MAX_RUN_DURATION {
        return Ok(());
    }
    let short = match Scene::new(short, folder) {
        Ok(short) => short,
        Err(error) => {
            prop_assert!(!error.to_string().is_empty());
            return Ok(());
        }
    };
    if short.checked().schedule.step_count() > MAX_RUN_STEPS {
        return Ok(());
    }
    // An adaptive run's steps are bounded too: a mutated scene can need ever smaller ones (a turntable 1e15 m long
    // with a rider 9 m off its point ran past 100 s for 0.01 s simulated).
    let checked = short.checked();
    let mut schedule = checked.schedule.clone();
    if schedule.tolerance().is_some() {
        schedule = (schedule.with_step_limit(MAX_ADAPTIVE_STEPS)).map_err(|e| TestCaseError::fail(e.to_string()))?;
    }
    let system = short.system::<A>().map_err(|e| TestCaseError::fail(e.to_string()))?;
    match system.run(dynamics::integrate::Integrator::from(checked.integrator), &schedule) {
        Ok(run) => {
            let system = short.system::<A>().map_err(|e| TestCaseError::fail(e.to_string()))?;
            prop_assert_eq!(run.bodies.len(), system.body_names().len());
            for k in 0..run.bodies[0].len() {
                let poses: Vec<Pose> = run.bodies.iter().map(|b| (b[k].position, b[k].orientation)).collect();
                let _ = joint_violations(joints, &poses).fold(0.0, f64::max);
                let _ = system.joint_violation(&poses, None);
            }
        }
        Err(error) => prop_assert!(!error.to_string().is_empty()),
    }
    Ok(())
}

/// Parses `text`: an error that says something, or a scene whose every step before the run succeeds and whose
/// short run ends without a panic.
fn check(text: &str) -> Result<(), TestCaseError> {
    check_in(text, Path::new(""))
}

/// [`check`], with a robot's URDF relative to `folder`.
fn check_in(text: &str, folder: &Path) -> Result<(), TestCaseError> {
    let scene = match Scene::parse_in(text, folder) {
        Ok(scene) => scene,
        Err(error) => {
            prop_assert!(!error.to_string().is_empty());
            return Ok(());
        }
    };
    let ok = |what: &str, result: Result<(), scene_file::SceneFileError>| {
        result.map_err(|e| TestCaseError::fail(format!("parsed, but {what} failed: {e}")))
    };
    let file = SceneFile::parse(text).expect("the scene parsed");
    let layout = &scene.checked().layout;
    // Joints to robot links are placed by the system only (`SceneSystem::joint_violation`).
    let joints = match layout.joint_geometries() {
        Ok(joints) => joints,
        Err(e) if e.to_string().contains("only the built system places") => Vec::new(),
        Err(e) => return Err(TestCaseError::fail(format!("joint geometries: {e}"))),
    };
    for algebra in scene.checked().algebra.algebras() {
        match algebra {
            AlgebraKind::Pga => {
                ok("the PGA system", scene.system::<Pga>().map(drop))?;
                short_run::<Pga>(&file, folder, &joints)?;
            }
            AlgebraKind::Cga => {
                ok("the CGA system", scene.system::<Cga>().map(drop))?;
                short_run::<Cga>(&file, folder, &joints)?;
            }
        }
    }
    Ok(())
}

/// Punctuation and table headers of scene files.
const PUNCTUATION: &[&str] = &[
    "\n",
    " ",
    " = ",
    "=",
    "[",
    "]",
    "[[",
    "]]",
    "{",
    "}",
    ",",
    ".",
    "\"",
    "#",
    "'",
    "[body]",
    "[[body]]",
    "[initial]",
    "[[forces]]",
    "[[constraints]]",
    "[[joint]]",
    "[baumgarte]",
    "[robot]",
    "[[spring]]",
    "[[couple]]",
    "[[joint_torque]]",
    "[[joint_damping]]",
    "[[pd]]",
];

/// The keys of scene files.
const KEYS: &[&str] = &[
    "dt",
    "duration",
    "sample_interval",
    "title",
    "algebra",
    "integrator",
    "stabilisation",
    "max_start_correction",
    "baumgarte",
    "body",
    "initial",
    "forces",
    "constraints",
    "joint",
    "name",
    "between",
    "mass",
    "shape",
    "principal_moments",
    "kind",
    "size",
    "length",
    "axial_moment",
    "height",
    "radius",
    "position",
    "orientation",
    "axis",
    "angle",
    "degrees",
    "quaternion",
    "body_angular_velocity",
    "velocity",
    "acceleration",
    "force",
    "point",
    "moment",
    "formulation",
    "body_point",
    "world_point",
    "reference_point",
    "body_axis",
    "world_axis",
    "reference_axis",
    "body_normal",
    "world_normal",
    "normal",
    "offset",
    "centre",
    "alpha",
    "beta",
    "robot",
    "urdf",
    "root",
    "q",
    "v",
    "drive",
    "spring",
    "pd",
    "target",
    "kp",
];

/// Values of scene files, good and bad.
const VALUES: &[&str] = &[
    "\"rod\"",
    "\"cuboid\"",
    "\"cone\"",
    "\"sphere\"",
    "\"gravity\"",
    "\"couple\"",
    "\"ball_joint\"",
    "\"hinge\"",
    "\"prismatic\"",
    "\"point_on_circle\"",
    "\"pinning\"",
    "\"world\"",
    "\"tool0\"",
    "\"elbow_joint\"",
    "\"universal\"",
    "\"fixed\"",
    "\"a\"",
    "\"cga\"",
    "\"strang\"",
    "\"baumgarte\"",
    "1e-3",
    "1.0",
    "0.0",
    "-1",
    "0",
    "10.0",
    "1e308",
    "nan",
    "inf",
    "-inf",
    "1e-320",
    "[0.0, 0.0, 1.0]",
    "[1.0, 1.0, 1.0]",
    "[1e308, 0.0, 0.0]",
    "[1e-320, 0.0, 0.0]",
    "[]",
    "true",
    "{}",
    "{ kind = \"sphere\", radius = 1e-320 }",
    "[\"a\", \"world\"]",
];

/// A file made of scene-file pieces: keys, tables, values and punctuation in any order.
fn toml_ish() -> impl Strategy<Value = String> {
    let piece = prop_oneof![
        prop::sample::select(PUNCTUATION),
        prop::sample::select(KEYS),
        prop::sample::select(VALUES),
    ];
    prop::collection::vec(piece, 0..60).prop_map(|pieces| pieces.concat())
}

/// Every joint kind and the fields it has, each a vector (`[x, y, z]`) but for `offset` and `radius`.
const JOINTS: [(&str, &[&str]); 11] = [
    ("ball_joint", &["body_point", "world_point"]),
    ("universal", &["body_point", "body_axis", "world_point", "world_axis"]),
    ("fixed", &["position"]),
    ("hinge", &["body_point", "body_axis", "world_point", "world_axis"]),
    ("cylindrical", &["body_point", "body_axis", "world_point", "world_axis"]),
    (
        "prismatic",
        &[
            "body_point",
            "body_axis",
            "body_normal",
            "world_point",
            "world_axis",
            "world_normal",
        ],
    ),
    ("planar", &["body_point", "body_normal", "world_point", "world_normal"]),
    ("point_on_plane", &["body_point", "normal", "offset"]),
    ("point_on_line", &["body_point", "world_point", "world_axis"]),
    ("point_on_sphere", &["body_point", "centre", "radius"]),
    ("point_on_circle", &["body_point", "centre", "radius", "normal"]),
];

/// The shapes and the fields they have (all positive numbers).
const SHAPES: [(&str, &[&str]); 4] = [
    ("cuboid", &["size"]),
    ("rod", &["length", "axial_moment"]),
    ("cone", &["height", "radius"]),
    ("sphere", &["radius"]),
];

/// Values a sensible file has: coordinates, and (the first ones) positive lengths and masses.
const SENSIBLE: [&str; 6] = ["0.5", "1.0", "0.25", "2.0", "-0.5", "0.0"];
const SENSIBLE_POSITIVE: usize = 4;

/// How many values a [`joint_scene`] draws at most.
const SLOTS: usize = 64;

/// The values of a [`joint_scene`], in the order it asks for them.
struct Values {
    /// Per slot, an index into [`SENSIBLE`].
    sensible: Vec<usize>,
    /// (slot, extreme number) pairs.
    extreme: Vec<(usize, String)>,
    next: usize,
}

impl Values {
    /// The next value: extreme if drawn so, else sensible (positive where asked).
    fn scalar(&mut self, positive: bool) -> String {
        let index = self.sensible[self.next % SLOTS];
        self.scalar_or(SENSIBLE[if positive { index % SENSIBLE_POSITIVE } else { index }])
    }

    /// The next value: extreme if drawn so, else `sensible`.
    fn scalar_or(&mut self, sensible: &str) -> String {
        let slot = self.next % SLOTS;
        self.next += 1;
        match self.extreme.iter().find(|(at, _)| *at == slot) {
            Some((_, number)) => number.clone(),
            None => sensible.to_owned(),
        }
    }

    fn vector(&mut self, positive: bool) -> String {
        let (x, y, z) = (self.scalar(positive), self.scalar(positive), self.scalar(positive));
        format!("[{x}, {y}, {z}]")
    }
}

/// One joint of any kind and formulation, holding a body to the world or (named bodies) to a second body that
/// hangs from the world by a ball joint, with sensible values of which `extremes` are replaced by extreme ones:
/// the shipped files have ball joints and hinges only.
fn joint_scene(extremes: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = String> {
    let names = |names: &'static [&'static str]| prop::sample::select(names);
    (
        (0..JOINTS.len(), 0..SHAPES.len(), any::<bool>()),
        (
            names(&["virtual_power", "pinning"]),
            names(&["pga", "cga", "both"]),
            names(&["projection", "baumgarte", "none"]),
            names(&["rk4", "rkmk4", "rkmk4-body", "rkmk6-body"]),
        ),
        prop::collection::vec(0..SENSIBLE.len(), SLOTS),
        prop::collection::vec((0..SLOTS, number()), extremes),
    )
        .prop_map(|((joint, shape, named), names, sensible, extreme)| {
            let values = Values {
                sensible,
                extreme,
                next: 0,
            };
            joint_scene_text(JOINTS[joint], SHAPES[shape], named, names, values)
        })
}

/// The text of a [`joint_scene`]: `names` are the formulation, algebra, stabilisation and integrator.
fn joint_scene_text(
    (joint_kind, joint_fields): (&str, &[&str]),
    (shape_kind, shape_fields): (&str, &[&str]),
    named: bool,
    (formulation, algebra, stabilisation, integrator): (&str, &str, &str, &str),
    mut values: Values,
) -> String {
    let shape: Vec<String> = shape_fields
        .iter()
        .map(|&field| match field {
            "size" => format!("size = {}", values.vector(true)),
            // Small, or the rod's moments break the triangle inequality.
            "axial_moment" => format!("axial_moment = {}", values.scalar_or("1e-3")),
            _ => format!("{field} = {}", values.scalar(true)),
        })
        .collect();
    let body = format!(
        "mass = {}\nshape = {{ kind = \"{shape_kind}\", {} }}\n",
        values.scalar(true),
        shape.join(", ")
    );
    let initial = [
        format!("position = {}", values.vector(false)),
        format!(
            "orientation = {{ axis = {}, angle = {} }}",
            values.vector(false),
            values.scalar(false)
        ),
        format!("body_angular_velocity = {}", values.vector(false)),
        format!("velocity = {}", values.vector(false)),
    ];
    let acceleration = values.vector(false);
    let geometry: String = joint_fields
        .iter()
        .map(|&field| match field {
            "offset" => format!("{field} = {}\n", values.scalar(false)),
            "radius" => format!("{field} = {}\n", values.scalar(true)),
            _ => format!("{field} = {}\n", values.vector(false)),
        })
        .collect();
    let mut text = format!(
        "algebra = \"{algebra}\"\nintegrator = \"{integrator}\"\nstabilisation = \"{stabilisation}\"\n\
         dt = 1e-3\nduration = 0.01\n"
    );
    if named {
        text += "[[body]]\nname = \"anchor\"\nmass = 1.0\nshape = { kind = \"sphere\", radius = 0.1 }\n\
                 initial.position = [0.0, 0.0, -0.5]\n";
        text += &format!("[[body]]\nname = \"held\"\n{body}");
        text += &format!("forces = [{{ kind = \"gravity\", acceleration = {acceleration} }}]\n");
        for line in &initial {
            text += &format!("initial.{line}\n");
        }
        text += "[[joint]]\nname = \"pivot\"\nbetween = [\"anchor\", \"world\"]\nkind = \"ball_joint\"\n\
                 body_point = [0.0, 0.0, 0.5]\nworld_point = [0.0, 0.0, 0.0]\n";
        text += "[[joint]]\nname = \"under test\"\nbetween = [\"held\", \"anchor\"]\n";
    } else {
        text += &format!("[body]\n{body}[initial]\n{}\n", initial.join("\n"));
        text += &format!("[[forces]]\nkind = \"gravity\"\nacceleration = {acceleration}\n");
        text += "[[constraints]]\n";
    }
    text + &format!("formulation = \"{formulation}\"\nkind = \"{joint_kind}\"\n{geometry}")
}

/// The keys whose arrays are directions (axes and normals, of any length) or rotations (quaternions,
/// normalised): any positive multiple means the same. (Not the normal of a point on a plane, whose length
/// divides the offset.)
const DIRECTION_KEYS: [&str; 9] = [
    "axis",
    "body_axis",
    "world_axis",
    "reference_axis",
    "normal",
    "body_normal",
    "world_normal",
    "reference_normal",
    "quaternion",
];

/// Multiples that keep every digit of a direction but whose squares overflow or underflow (1e160 and above,
/// 1e-160 and below), or neither.
const DIRECTION_SCALES: [f64; 8] = [1e-300, 1e-200, 1e-160, 0.1, 3.0, 1e160, 1e300, 1e307];

/// The byte ranges of the arrays (`[` to `]`) written after a direction key, outside comments.
fn direction_arrays(text: &str) -> Vec<Range<usize>> {
    let plane = text.contains("kind = \"point_on_plane\"");
    let mut arrays = Vec::new();
    let mut line_start = 0;
    for line in text.split_inclusive('\n') {
        let code = &line[..line.find('#').unwrap_or(line.len())];
        for key in DIRECTION_KEYS.into_iter().filter(|&key| !(plane && key == "normal")) {
            let pattern = format!("{key} = [");
            for (at, _) in code.match_indices(&pattern) {
                let before = code[..at].chars().next_back();
                if before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.') {
                    continue;
                }
                let open = at + pattern.len() - 1;
                if let Some(close) = code[open..].find(']') {
                    arrays.push(line_start + open..line_start + open + close + 1);
                }
            }
        }
        line_start += line.len();
    }
    arrays.sort_by_key(|range| range.start);
    arrays
}

/// The run of `text` over one sample interval in algebra `A`: every body's (position, orientation) per sample.
fn first_samples<A: FileAlgebra>(text: &str) -> Result<Vec<Vec<Pose>>, String> {
    let mut file = SceneFile::parse(text).map_err(|e| e.to_string())?;
    file.duration = file.sample_interval;
    let scene = Scene::new(file, Path::new("")).map_err(|e| e.to_string())?;
    let run = scene.simulate::<A>().map_err(|e| e.to_string())?;
    Ok(run
        .bodies
        .iter()
        .map(|samples| samples.iter().map(|s| (s.position, s.orientation)).collect())
        .collect())
}

/// What a scene file says before anything is solved: each body's initial rotation, and each joint's violation
/// with the bodies at a few poses.
fn meaning(text: &str) -> Result<(Vec<UnitQuaternion<f64>>, Vec<f64>), String> {
    let file = SceneFile::parse(text).map_err(|e| e.to_string())?;
    let scene = CheckedScene::new(file, Path::new("")).map_err(|e| e.to_string())?;
    let layout = &scene.layout;
    let rotations: Vec<UnitQuaternion<f64>> = layout.bodies.iter().map(|b| b.initial.orientation).collect();
    let joints = layout.joint_geometries().map_err(|e| e.to_string())?;
    let mut violations = Vec::new();
    for pose in 0..4 {
        let poses: Vec<Pose> = (0..layout.bodies.len())
            .map(|body| {
                let t = (pose * 3 + body) as f64;
                (
                    Vector3::new(0.3 * t, -0.2 * t + 0.1, 0.5 - 0.1 * t),
                    UnitQuaternion::from_euler_angles(0.4 * t, 0.7 - 0.3 * t, 0.2 * t),
                )
            })
            .collect();
        violations.extend(joint_violations(&joints, &poses));
    }
    Ok((rotations, violations))
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        // A failing input goes into a plain regression test below, not a file beside this one.
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config(512))]

    /// Any printable text.
    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,300}") {
        check(&text)?;
    }

    /// Any bytes, decoded with replacement characters.
    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        check(&String::from_utf8_lossy(&bytes))?;
    }

    /// Keys, tables, values and punctuation of scene files in any order.
    #[test]
    fn toml_fragments_never_panic(text in toml_ish()) {
        check(&text)?;
    }

    /// One joint of each kind with extreme values.
    #[test]
    fn joints_with_extreme_values_never_panic(text in joint_scene(0..=3)) {
        check(&text)?;
    }

    /// The shipped robot files with one to three edits (a robot, links, drives, force elements).
    #[test]
    fn mutated_robot_files_never_panic(
        which in 0..ROBOT_SCENES.len(),
        mutations in prop::collection::vec(mutation(), 1..=3),
    ) {
        let mut text = ROBOT_SCENES[which].1.to_owned();
        for mutation in &mutations {
            text = mutation.apply(&text);
        }
        check_in(&text, &scenes())?;
    }

    /// The shipped scene files with one to three edits.
    #[test]
    fn mutated_scene_files_never_panic(
        which in 0..SCENES.len(),
        mutations in prop::collection::vec(mutation(), 1..=3),
    ) {
        let mut text = SCENES[which].1.to_owned();
        for mutation in &mutations {
            text = mutation.apply(&text);
        }
        check(&text)?;
    }
}

proptest! {
    #![proptest_config(config(256))]

    /// Axes, normals and quaternions multiplied by positive numbers, so large or small that their squares
    /// overflow or underflow, mean the same: each body's initial rotation and each joint's violation at a few
    /// poses are those of the scene as written, in the shipped files and in sensible scenes of every joint kind;
    /// and the shipped files (which start on their joints) run the same. Once an axis of 1e-300 had "no
    /// direction", one of 1e308 gave a wrong rotation, and a normal of 1e300 became the zero vector.
    #[test]
    fn scaled_directions_mean_the_same(
        (shipped, text) in prop_oneof![
            prop::sample::select(SCENES.as_slice()).prop_map(|(_, text)| (true, text.to_owned())),
            joint_scene(0..=0).prop_map(|text| (false, text)),
        ],
        scales in prop::collection::vec(prop::sample::select(DIRECTION_SCALES.as_slice()), 1..=16),
    ) {
        let mut scaled = text.clone();
        // From the last, so that the earlier ranges stay valid.
        for (index, range) in direction_arrays(&text).into_iter().enumerate().rev() {
            let values: Vec<String> = text[range.start + 1..range.end - 1]
                .split(',')
                .map(|v| format!("{:?}", v.trim().parse::<f64>().expect("a number") * scales[index % scales.len()]))
                .collect();
            scaled.replace_range(range, &format!("[{}]", values.join(", ")));
        }
        let context = || format!("{text}\nscaled:\n{scaled}");
        match (meaning(&text), meaning(&scaled)) {
            (Ok((rotations, violations)), Ok((scaled_rotations, scaled_violations))) => {
                for (a, b) in rotations.iter().zip(&scaled_rotations) {
                    prop_assert!(a.angle_to(b) < 1e-12, "rotation {a} became {b}\n{}", context());
                }
                for (a, b) in violations.iter().zip(&scaled_violations) {
                    prop_assert!((a - b).abs() < 1e-12, "violation {a} became {b}\n{}", context());
                }
            }
            (Err(_), Err(_)) => {}
            (written, scaled) => {
                return Err(TestCaseError::fail(format!("{written:?} became {scaled:?}\n{}", context())));
            }
        }
        if shipped {
            let run = |text: &str| match Scene::parse(text).map(|s| s.checked().algebra.algebras()[0]) {
                Ok(AlgebraKind::Pga) | Err(_) => first_samples::<Pga>(text),
                Ok(AlgebraKind::Cga) => first_samples::<Cga>(text),
            };
            let written = run(&text).expect("the shipped file runs");
            let scaled_run = run(&scaled).map_err(|e| TestCaseError::fail(format!("{e}\n{}", context())))?;
            for (body, (a, b)) in written.iter().zip(&scaled_run).enumerate() {
                for ((p, q), (r, s)) in a.iter().zip(b) {
                    let (distance, angle) = ((p - r).norm(), q.angle_to(s));
                    prop_assert!(
                        distance < 1e-12 && angle < 1e-12,
                        "body {body}: {distance:e} m, {angle:e} rad from the file as written\n{}",
                        context()
                    );
                }
            }
        }
    }
}

/// The shipped files parse and pass every check unedited.
#[test]
fn shipped_scene_files_pass_the_checks() {
    for (name, text) in SCENES {
        assert!(Scene::parse(text).is_ok(), "{name}");
        check(text).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    for (name, text) in ROBOT_SCENES {
        Scene::parse_in(text, &scenes()).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_in(text, &scenes()).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

/// The tokenizer finds the numbers and strings the mutations replace, not those in comments or names.
#[test]
fn tokens_are_numbers_and_strings_outside_comments() {
    let text = "# 30° \"not\"\nname = \"link1\"\nsize = [0.05, -1e-3, 2] # 4\nkey_2 = 1_000\n";
    let (numbers, strings) = tokens(text);
    let numbers: Vec<&str> = numbers.iter().map(|r| &text[r.clone()]).collect();
    let strings: Vec<&str> = strings.iter().map(|r| &text[r.clone()]).collect();
    assert_eq!(numbers, ["0.05", "-1e-3", "2", "1_000"]);
    assert_eq!(strings, ["link1"]);
}

/// The heavy top with `from` replaced by `to`.
fn heavy_top_with(from: &str, to: &str) -> String {
    let text = SCENES[0].1;
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1)
}

/// A sphere at rest at (0, 0, 0.5), held by `joint` (the lines of a `[[constraints]]` entry).
fn held_sphere(joint: &str) -> String {
    format!(
        "dt = 1e-3\nduration = 0.01\n[body]\nmass = 1.0\nshape = {{ kind = \"sphere\", radius = 0.1 }}\n[initial]\n\
         position = [0.0, 0.0, 0.5]\n[[constraints]]\n{joint}\n"
    )
}

/// Found by `scaled_directions_mean_the_same`: orientation axes whose squared length overflowed became the zero
/// vector (an axis of 1e308 with 30° gave no rotation at all, without a word), and those whose squared length
/// underflowed had "no direction"; quaternions likewise (1e308 failed as a "non-finite residual").
#[test]
fn orientations_of_any_scale_are_the_rotation_written() {
    let axis = "orientation = { axis = [1.0, 0.0, 0.0], degrees = 30.0 }";
    let (written, _) = meaning(SCENES[0].1).unwrap();
    for to in [
        "orientation = { axis = [1e308, 0.0, 0.0], degrees = 30.0 }",
        "orientation = { axis = [1e-300, 0.0, 0.0], degrees = 30.0 }",
        "orientation = { axis = [5e-324, 0.0, 0.0], degrees = 30.0 }",
        "orientation = { quaternion = [0.9659258262890683e308, 0.25881904510252074e308, 0.0, 0.0] }",
        "orientation = { quaternion = [0.9659258262890683e-300, 0.25881904510252074e-300, 0.0, 0.0] }",
    ] {
        let text = heavy_top_with(axis, to);
        assert!(Scene::parse(&text).is_ok(), "{to}");
        let (rotations, _) = meaning(&text).unwrap();
        let angle = rotations[0].angle_to(&written[0]);
        assert!(angle < 1e-15, "{to}: {angle:e} rad from the rotation written");
    }
    let (turned, _) = meaning(&heavy_top_with(
        axis,
        "orientation = { quaternion = [1e308, 1e308, 0.0, 0.0] }",
    ))
    .unwrap();
    assert!((turned[0].angle() - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
}

/// Found by `scaled_directions_mean_the_same`: a plane's normal of 1e300 became the zero vector (refused with "plane
/// normal [[0.0, 0.0, 0.0]] has no direction") and a prismatic joint's normal of 1e300 was "zero or along the axis".
/// Now they are the planes written; an offset over a normal so short that the plane is out of range is refused,
/// naming the offset.
#[test]
fn joint_normals_of_any_scale_are_the_geometry_written() {
    let prismatic = |body_normal: &str| {
        held_sphere(&format!(
            "kind = \"prismatic\"\nbody_point = [0.0, 0.0, 0.0]\nbody_axis = [0.0, 0.0, 1.0]\n\
             body_normal = {body_normal}\nworld_point = [0.0, 0.0, 0.5]\nworld_axis = [0.0, 0.0, 1.0]\n\
             world_normal = [1.0, 0.0, 0.0]"
        ))
    };
    let plane = |normal: &str, offset: &str| {
        held_sphere(&format!(
            "kind = \"point_on_plane\"\nbody_point = [0.0, 0.0, 0.0]\nnormal = {normal}\noffset = {offset}"
        ))
    };
    for (written, scaled) in [
        (prismatic("[1.0, 0.0, 0.0]"), prismatic("[1e300, 0.0, 0.0]")),
        (prismatic("[1.0, 0.0, 0.0]"), prismatic("[1e-300, 0.0, 0.0]")),
        (plane("[0.0, 0.0, 1.0]", "0.5"), plane("[0.0, 0.0, 1e300]", "5e299")),
        (plane("[0.0, 0.0, 1.0]", "0.5"), plane("[0.0, 0.0, 1e-300]", "5e-301")),
    ] {
        assert!(Scene::parse(&scaled).is_ok(), "{scaled}");
        let ((_, expected), (_, violations)) = (meaning(&written).unwrap(), meaning(&scaled).unwrap());
        for (a, b) in expected.iter().zip(&violations) {
            assert!((a - b).abs() < 1e-15, "{a} became {b}: {scaled}");
        }
    }
    let message = Scene::parse(&plane("[0.0, 0.0, 1e-320]", "0.5"))
        .unwrap_err()
        .to_string();
    assert!(
        message.contains(
            "constraint 1 (point on plane): offset: 0.5 over the normal's length [0.0, 0.0, 1e-320] is not finite"
        ),
        "{message}"
    );
}
