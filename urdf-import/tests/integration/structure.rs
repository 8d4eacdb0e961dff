//! Stage 2 (validate), the tree: duplicate names, undefined links, two parents, cycles, several roots, links not
//! connected; and a valid root with two subtrees.

use crate::common;

use common::{assert_message, error, frame, import, joint, line_of, link, robot};
use urdf_import::ImportError;

const Z: [f64; 3] = [0.0; 3];

fn body(name: &str) -> String {
    link(name, 1.0, [0.01, 0.01, 0.01])
}

#[test]
fn duplicate_link_and_joint_names() {
    let text = robot(
        "dup",
        &[
            body("base_link"),
            body("arm"),
            body("base_link"),
            joint("j1", "revolute", "base_link", "arm", Z, Z),
        ],
    );
    let e = error(&text);
    let first = line_of(&text, r#"<link name="base_link""#);
    let second = first
        + 1
        + text
            .lines()
            .skip(first as usize)
            .position(|l| l.contains(r#"<link name="base_link""#))
            .unwrap() as u32;
    assert_eq!(
        e,
        ImportError::DuplicateLink {
            name: "base_link".to_owned(),
            first_line: first,
            line: second
        }
    );
    assert_message(
        &e,
        &["`base_link`", &format!("line {first}"), &format!("line {second}")],
    );

    let text = robot(
        "dup",
        &[
            body("base_link"),
            body("arm"),
            body("hand"),
            joint("j1", "revolute", "base_link", "arm", Z, Z),
            joint("j1", "revolute", "arm", "hand", Z, Z),
        ],
    );
    let e = error(&text);
    assert!(matches!(&e, ImportError::DuplicateJoint { name, first_line, line } if name == "j1" && first_line < line));
    assert_message(&e, &["joint `j1`", "defined twice"]);
}

#[test]
fn a_joint_naming_an_undefined_link() {
    // A typo in the child's name, as after renaming a link in one place only.
    let text = robot(
        "typo",
        &[
            body("base_link"),
            body("upper_arm_link"),
            joint("shoulder_lift_joint", "revolute", "base_link", "upper_arm", Z, Z),
        ],
    );
    let e = error(&text);
    let line = line_of(&text, r#"<joint name="shoulder_lift_joint""#);
    assert_eq!(
        e,
        ImportError::UnknownLink {
            joint: "shoulder_lift_joint".to_owned(),
            role: "child",
            link: "upper_arm".to_owned(),
            line
        }
    );
    assert_message(
        &e,
        &[
            "`shoulder_lift_joint`",
            "child link `upper_arm`",
            &format!("line {line}"),
        ],
    );
    let text = robot("typo", &[body("a"), body("b"), joint("j", "fixed", "world", "b", Z, Z)]);
    assert!(matches!(error(&text), ImportError::UnknownLink { role: "parent", link, .. } if link == "world"));
}

#[test]
fn a_link_with_two_parents() {
    let text = robot(
        "loop",
        &[
            body("base"),
            body("left"),
            body("right"),
            body("bar"),
            joint("left_joint", "revolute", "base", "left", Z, Z),
            joint("right_joint", "revolute", "base", "right", Z, Z),
            joint("left_bar", "revolute", "left", "bar", Z, Z),
            joint("right_bar", "revolute", "right", "bar", Z, Z),
        ],
    );
    let e = error(&text);
    assert_eq!(
        e,
        ImportError::TwoParents {
            link: "bar".to_owned(),
            first_joint: "left_bar".to_owned(),
            first_line: line_of(&text, r#"<joint name="left_bar""#),
            joint: "right_bar".to_owned(),
            line: line_of(&text, r#"<joint name="right_bar""#),
        }
    );
    assert_message(&e, &["`bar`", "`left_bar`", "`right_bar`"]);
}

#[test]
fn a_cycle_names_its_links() {
    // base is a root; a -> b -> c -> a is a loop with nothing above it.
    let text = robot(
        "cycle",
        &[
            body("base"),
            body("a"),
            body("b"),
            body("c"),
            body("d"),
            joint("base_d", "revolute", "base", "d", Z, Z),
            joint("ab", "revolute", "a", "b", Z, Z),
            joint("bc", "revolute", "b", "c", Z, Z),
            joint("ca", "revolute", "c", "a", Z, Z),
        ],
    );
    let e = error(&text);
    let ImportError::Cycle {
        cycle,
        joint: in_loop,
        line,
        unreachable,
    } = &e
    else {
        panic!("{e:?}")
    };
    assert_eq!(cycle, &["a", "b", "c", "a"]);
    assert_eq!((in_loop.as_str(), *unreachable), ("ab", 3));
    assert_eq!(*line, line_of(&text, &format!(r#"<joint name="{in_loop}""#)));
    assert_message(&e, &["a -> b -> c -> a"]);

    // Every link in the loop: no root at all.
    let text = robot(
        "ring",
        &[
            body("a"),
            body("b"),
            joint("ab", "revolute", "a", "b", Z, Z),
            joint("ba", "revolute", "b", "a", Z, Z),
        ],
    );
    assert!(matches!(error(&text), ImportError::Cycle { unreachable: 2, .. }));
    // A link as its own parent.
    let text = robot(
        "self",
        &[
            body("a"),
            body("b"),
            joint("ab", "revolute", "a", "b", Z, Z),
            joint("bb", "fixed", "b", "b", Z, Z),
        ],
    );
    assert!(matches!(error(&text), ImportError::TwoParents { .. }));
    let text = robot(
        "self",
        &[
            body("a"),
            body("b"),
            joint("aa", "fixed", "a", "a", Z, Z),
            joint("bb", "fixed", "b", "b", Z, Z),
        ],
    );
    let e = error(&text);
    assert!(
        matches!(&e, ImportError::Cycle { cycle, .. } if cycle == &["a", "a"]),
        "{e:?}"
    );
}

#[test]
fn two_trees_name_every_root() {
    // Two robots pasted into one file: an arm, and a mobile base with a caster.
    let text = robot(
        "two",
        &[
            body("arm_base"),
            body("arm_link"),
            body("base_footprint"),
            body("caster"),
            body("head"),
            body("camera"),
            joint("arm_joint", "revolute", "arm_base", "arm_link", Z, Z),
            joint("caster_joint", "continuous", "base_footprint", "caster", Z, Z),
            joint("camera_joint", "fixed", "head", "camera", Z, Z),
        ],
    );
    let e = error(&text);
    assert_eq!(
        e,
        ImportError::SeveralRoots {
            roots: vec!["arm_base".to_owned(), "base_footprint".to_owned(), "head".to_owned()]
        }
    );
    assert_message(&e, &["3 links", "`arm_base`", "`base_footprint`", "`head`"]);
}

#[test]
fn a_link_no_joint_names_is_not_connected() {
    let text = robot(
        "stray",
        &[
            body("base_link"),
            body("arm"),
            frame("camera_optical_frame"),
            joint("j", "revolute", "base_link", "arm", Z, Z),
        ],
    );
    let e = error(&text);
    assert_eq!(
        e,
        ImportError::Disconnected {
            root: "base_link".to_owned(),
            links: vec!["camera_optical_frame".to_owned()]
        }
    );
    assert_message(&e, &["`camera_optical_frame`", "`base_link`"]);
}

#[test]
fn a_root_with_two_subtrees_is_one_tree() {
    // A torso with two arms: the root has two children trees, which is fine.
    let text = robot(
        "torso",
        &[
            body("torso"),
            body("l_upper"),
            body("l_lower"),
            body("r_upper"),
            body("r_lower"),
            joint("l_shoulder", "revolute", "torso", "l_upper", [0.0, 0.2, 0.0], Z),
            joint("r_shoulder", "revolute", "torso", "r_upper", [0.0, -0.2, 0.0], Z),
            joint("l_elbow", "revolute", "l_upper", "l_lower", [0.0, 0.0, -0.3], Z),
            joint("r_elbow", "revolute", "r_upper", "r_lower", [0.0, 0.0, -0.3], Z),
        ],
    );
    let model = import(&text);
    let names: Vec<&str> = model.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["torso", "l_upper", "r_upper", "l_lower", "r_lower"]); // joint file order
    let pairs: Vec<(usize, usize)> = model.joints.iter().map(|j| (j.parent, j.child)).collect();
    assert_eq!(pairs, [(0, 1), (0, 2), (1, 3), (2, 4)]);
}
