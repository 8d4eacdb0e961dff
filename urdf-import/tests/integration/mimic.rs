//! Stage 2 (validate), mimics: a gripper whose second finger mimics the first, and every invalid mimic, as an
//! error with `MimicMode::Constraint` and as a warning with `MimicMode::Independent`.

use crate::common;

use common::{assert_message, error, import, import_with, line_of};
use urdf_import::{ImportError, ImportOptions, JointKind, MimicMode};

/// A Panda-style hand on a wrist: `panda_joint7` (revolute), the fixed hand, two prismatic fingers; `finger2`
/// holds the second finger joint's `<mimic>` line (or nothing), `kind2` its type.
fn gripper(kind2: &str, mimic: &str) -> String {
    format!(
        r#"<?xml version="1.0" ?>
<robot name="panda">
  <link name="panda_link7">
    <inertial><mass value="0.735"/><inertia ixx="0.0125" ixy="-0.0003" ixz="-0.0007" iyy="0.0100" iyz="-0.0007" izz="0.0081"/></inertial>
  </link>
  <link name="panda_link8"><inertial><mass value="0.5"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <joint name="panda_joint7" type="revolute">
    <origin rpy="1.5707963 0 0" xyz="0.088 0 0"/>
    <parent link="panda_link7"/><child link="panda_link8"/>
    <axis xyz="0 0 1"/>
    <limit effort="12" lower="-2.9" upper="2.9" velocity="2.61"/>
  </joint>
  <link name="panda_hand">
    <inertial><mass value="0.73"/><inertia ixx="0.0025" ixy="0" ixz="0" iyy="0.0005" iyz="0" izz="0.0027"/></inertial>
  </link>
  <joint name="panda_hand_joint" type="fixed">
    <parent link="panda_link8"/><child link="panda_hand"/>
    <origin rpy="0 0 -0.785398163397" xyz="0 0 0.107"/>
  </joint>
  <link name="panda_leftfinger">
    <inertial><mass value="0.015"/><inertia ixx="2.375e-6" ixy="0" ixz="0" iyy="2.375e-6" iyz="0" izz="7.5e-7"/></inertial>
  </link>
  <link name="panda_rightfinger">
    <inertial><mass value="0.015"/><inertia ixx="2.375e-6" ixy="0" ixz="0" iyy="2.375e-6" iyz="0" izz="7.5e-7"/></inertial>
  </link>
  <joint name="panda_finger_joint1" type="prismatic">
    <parent link="panda_hand"/><child link="panda_leftfinger"/>
    <origin rpy="0 0 0" xyz="0 0 0.0584"/>
    <axis xyz="0 1 0"/>
    <dynamics damping="0.3"/>
    <limit effort="100" lower="0.0" upper="0.04" velocity="0.2"/>
  </joint>
  <joint name="panda_finger_joint2" type="{kind2}">
    <parent link="panda_hand"/><child link="panda_rightfinger"/>
    <origin rpy="0 0 0" xyz="0 0 0.0584"/>
    <axis xyz="0 -1 0"/>
    <limit effort="100" lower="0.0" upper="0.04" velocity="0.2"/>
    {mimic}
  </joint>
</robot>
"#
    )
}

fn independent() -> ImportOptions {
    ImportOptions {
        mimic: MimicMode::Independent,
        ..ImportOptions::default()
    }
}

#[test]
fn a_mimic_finger_points_at_its_driving_joint() {
    let text = gripper(
        "prismatic",
        r#"<mimic joint="panda_finger_joint1" multiplier="-1" offset="0.001"/>"#,
    );
    let model = import(&text);
    assert_eq!(model.mimic, MimicMode::Constraint);
    let names: Vec<&str> = model.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, ["panda_joint7", "panda_finger_joint1", "panda_finger_joint2"]);
    let mimic = model.joints[2].mimic.as_ref().unwrap();
    assert_eq!(
        (mimic.joint.as_str(), mimic.index, mimic.multiplier, mimic.offset),
        ("panda_finger_joint1", Some(1), -1.0, 0.001)
    );
    assert_eq!(model.joints[1].damping, 0.3);
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
}

#[test]
fn a_mimic_of_an_undefined_joint() {
    // As in alex_psyonic_hands.urdf, where `Left_index_q2` mimics `index_q1` (the hand's prefix was lost).
    let text = gripper(
        "prismatic",
        r#"<mimic joint="finger_joint1" multiplier="1" offset="0"/>"#,
    );
    let e = error(&text);
    let line = line_of(&text, "<mimic");
    assert_eq!(
        e,
        ImportError::MimicUnknown {
            joint: "panda_finger_joint2".to_owned(),
            target: "finger_joint1".to_owned(),
            line
        }
    );
    assert_message(
        &e,
        &["`panda_finger_joint2`", "`finger_joint1`", &format!("line {line}")],
    );

    // Independent: recorded with no index, and noted.
    let model = import_with(&text, &independent());
    let mimic = model.joints[2].mimic.as_ref().unwrap();
    assert_eq!((mimic.joint.as_str(), mimic.index), ("finger_joint1", None));
    assert!(
        model
            .warnings
            .iter()
            .any(|w| w.contains("`finger_joint1`") && w.contains("not defined")),
        "{:?}",
        model.warnings
    );
    assert_eq!(model.mimic, MimicMode::Independent);
}

#[test]
fn a_mimic_of_itself() {
    let text = gripper("prismatic", r#"<mimic joint="panda_finger_joint2"/>"#);
    let e = error(&text);
    assert_eq!(
        e,
        ImportError::MimicSelf {
            joint: "panda_finger_joint2".to_owned(),
            line: line_of(&text, "<mimic")
        }
    );
    assert_message(&e, &["`panda_finger_joint2`", "itself"]);
    assert!(!import_with(&text, &independent()).warnings.is_empty());
}

#[test]
fn a_mimic_chain_names_both_joints() {
    // finger 2 mimics finger 1, which mimics the wrist.
    let text = gripper("prismatic", r#"<mimic joint="panda_finger_joint1"/>"#).replace(
        r#"<dynamics damping="0.3"/>"#,
        r#"<dynamics damping="0.3"/><mimic joint="panda_joint7" multiplier="0.01"/>"#,
    );
    let e = error(&text);
    assert_eq!(
        e,
        ImportError::MimicChain {
            joint: "panda_finger_joint2".to_owned(),
            target: "panda_finger_joint1".to_owned(),
            target_target: "panda_joint7".to_owned(),
            line: line_of(&text, r#"<mimic joint="panda_finger_joint1""#),
        }
    );
    assert_message(
        &e,
        &["`panda_finger_joint2`", "`panda_finger_joint1`", "`panda_joint7`"],
    );
    let model = import_with(&text, &independent());
    assert_eq!(model.joints[2].mimic.as_ref().unwrap().index, Some(1));
    assert!(model
        .warnings
        .iter()
        .any(|w| w.contains("itself mimics `panda_joint7`")));
}

#[test]
fn a_mimic_on_a_fixed_or_floating_joint() {
    // talos_reduced.urdf: gripper joints made fixed, their <mimic> left in place.
    for (kind, expected) in [
        ("fixed", JointKind::Fixed),
        ("floating", JointKind::Floating),
        ("planar", JointKind::Planar),
    ] {
        let text = gripper(kind, r#"<mimic joint="panda_finger_joint1" multiplier="1"/>"#);
        let e = error(&text);
        assert_eq!(
            e,
            ImportError::MimicKind {
                joint: "panda_finger_joint2".to_owned(),
                role: "this joint",
                other: "panda_finger_joint2".to_owned(),
                kind: expected,
                line: line_of(&text, "<mimic"),
            }
        );
        assert_message(&e, &["`panda_finger_joint2`", kind]);
        let model = import_with(&text, &independent());
        assert!(
            model
                .warnings
                .iter()
                .any(|w| w.contains(&format!("but is {kind} itself"))),
            "{:?}",
            model.warnings
        );
    }
}

#[test]
fn a_mimic_of_a_joint_without_a_single_coordinate() {
    // finger 1 made planar: finger 2 cannot follow three coordinates.
    let text = gripper("prismatic", r#"<mimic joint="panda_finger_joint1"/>"#).replace(
        r#"name="panda_finger_joint1" type="prismatic""#,
        r#"name="panda_finger_joint1" type="planar""#,
    );
    let e = error(&text);
    assert!(
        matches!(&e, ImportError::MimicKind { role: "the mimicked joint", other, kind: JointKind::Planar, .. } if other == "panda_finger_joint1"),
        "{e:?}"
    );
}

#[test]
fn mimic_indices_skip_fixed_joints() {
    // A fixed joint listed between the driving joint and its mimic does not shift the index.
    let text = gripper("prismatic", r#"<mimic joint="panda_joint7"/>"#);
    let model = import(&text);
    assert_eq!(model.joints[2].mimic.as_ref().unwrap().index, Some(0));
    assert_eq!(model.joints[0].name, "panda_joint7");
}
