//! Stage 4 (bodies, after merging): every body a moving joint carries needs a positive mass and positive
//! principal moments; massless subtrees; the repairs `MasslessSubtrees::Freeze`, `bound_mass`, `bound_inertia`;
//! the massless root.

use crate::common;

use common::{assert_message, error, error_with, import, import_with, line_of};
use nalgebra::{Matrix3, Vector3};
use urdf_import::validate::principal_axes;
use urdf_import::{FrozenJoint, ImportError, ImportOptions, JointKind, MasslessSubtrees, Repair};

/// A leg whose foot, a 50 g point mass (zero tensor), hangs on a joint of type `foot_joint`.
fn leg(foot_joint: &str) -> String {
    format!(
        r#"<robot name="leg">
  <link name="trunk">
    <inertial><mass value="6.0"/><inertia ixx="0.05" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.12"/></inertial>
  </link>
  <link name="thigh">
    <inertial><origin xyz="0 0 -0.1"/><mass value="1.0"/><inertia ixx="4e-3" ixy="0" ixz="0" iyy="4e-3" iyz="0" izz="4e-4"/></inertial>
  </link>
  <link name="shank">
    <inertial><origin xyz="0 0 -0.1"/><mass value="0.3"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-4"/></inertial>
  </link>
  <link name="foot">
    <collision><geometry><sphere radius="0.02"/></geometry></collision>
    <inertial><mass value="0.05"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
  </link>
  <joint name="hip" type="revolute">
    <parent link="trunk"/><child link="thigh"/><axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="30" velocity="10"/>
  </joint>
  <joint name="knee" type="revolute">
    <parent link="thigh"/><child link="shank"/><origin xyz="0 0 -0.2"/><axis xyz="0 1 0"/>
    <limit lower="-2.5" upper="0" effort="30" velocity="10"/>
  </joint>
  <joint name="ankle" type="{foot_joint}">
    <parent link="shank"/><child link="foot"/><origin xyz="0 0 -0.2"/><axis xyz="0 1 0"/>
    <limit lower="-0.5" upper="0.5" effort="10" velocity="10"/>
  </joint>
</robot>
"#
    )
}

/// Romeo-style hand: a massless `LHand` joint carrying a massless finger chain (all links mass 0), beside a
/// massive wrist; the finger joints mimic `LHand`.
const ROMEO_HAND: &str = r#"<robot name="romeo">
  <link name="LWristPitchLink">
    <inertial><mass value="0.27"/><inertia ixx="2e-4" ixy="0" ixz="0" iyy="2e-4" iyz="0" izz="1e-4"/></inertial>
  </link>
  <link name="LFinger11Link">
    <inertial><origin rpy="0 0 0" xyz="0 0 0"/><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
  </link>
  <link name="LFinger12Link">
    <inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
  </link>
  <link name="LFinger13Link"/>
  <link name="LFingerTip"/>
  <joint name="LHand" type="revolute">
    <parent link="LWristPitchLink"/><child link="LFinger11Link"/><origin xyz="0.07 0 0"/><axis xyz="1 0 0"/>
    <limit effort="0.5" lower="0" upper="1" velocity="5"/>
  </joint>
  <joint name="LFinger12" type="revolute">
    <parent link="LFinger11Link"/><child link="LFinger12Link"/><origin xyz="0.02 0 0"/><axis xyz="0 1 0"/>
    <limit effort="0.5" lower="0" upper="1" velocity="5"/>
    <mimic joint="LHand" multiplier="1" offset="0"/>
  </joint>
  <joint name="LFinger13" type="revolute">
    <parent link="LFinger12Link"/><child link="LFinger13Link"/><origin xyz="0.02 0 0"/><axis xyz="0 1 0"/>
    <limit effort="0.5" lower="0" upper="1" velocity="5"/>
    <mimic joint="LHand" multiplier="1" offset="0"/>
  </joint>
  <joint name="LFingerTip_fixed" type="fixed">
    <parent link="LFinger13Link"/><child link="LFingerTip"/><origin xyz="0.02 0 0"/>
  </joint>
</robot>
"#;

/// Human-style hip: a spherical joint as three revolute joints through two massless virtual links, the thigh
/// (massive) below.
const HUMAN_HIP: &str = r#"<robot name="human">
  <link name="pelvis">
    <inertial><mass value="10"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
  </link>
  <link name="left_upperleg_virtual"/>
  <link name="left_upperleg_virtual_2"/>
  <link name="left_upperleg">
    <inertial><origin xyz="0 0 -0.2"/><mass value="8"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.02"/></inertial>
  </link>
  <joint name="left_hip_Z" type="revolute">
    <origin xyz="0 0.1 -0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <parent link="pelvis"/><child link="left_upperleg_virtual"/>
    <limit effort="120" velocity="12.0" lower="-1" upper="1"/>
  </joint>
  <joint name="left_hip_X" type="revolute">
    <origin xyz="0 0 0" rpy="0 -0 0"/><axis xyz="1 0 0"/>
    <parent link="left_upperleg_virtual"/><child link="left_upperleg_virtual_2"/>
    <limit effort="120" velocity="12.0" lower="-1.047196667" upper="1.570795"/>
  </joint>
  <joint name="left_hip_Y" type="revolute">
    <origin xyz="0 0 0" rpy="0 -0 0"/><axis xyz="0 -1 0"/>
    <parent link="left_upperleg_virtual_2"/><child link="left_upperleg"/>
    <limit effort="120" velocity="12.0" lower="-1" upper="1"/>
  </joint>
</robot>
"#;

#[test]
fn a_point_mass_foot_on_a_moving_joint_is_singular() {
    let text = leg("revolute");
    let e = error(&text);
    let line = line_of(&text, r#"<joint name="ankle""#);
    assert_eq!(
        e,
        ImportError::SingularBody {
            joint: "ankle".to_owned(),
            line,
            links: vec!["foot".to_owned()],
            mass: 0.05,
            moments: [0.0; 3],
            massless_subtree: false,
        }
    );
    assert_message(
        &e,
        &[
            "`ankle`",
            "`foot`",
            "0.05 kg",
            "[0.000000e0, 0.000000e0, 0.000000e0]",
            &format!("line {line}"),
        ],
    );
    assert!(!e.to_string().contains("Pinocchio"));
}

#[test]
fn a_point_mass_foot_on_a_fixed_joint_merges_into_the_shank() {
    let model = import(&leg("fixed"));
    assert_eq!(model.bodies.len(), 3);
    let shank = &model.bodies[2];
    assert_eq!(
        shank.links.iter().map(|l| l.name.as_str()).collect::<Vec<_>>(),
        ["shank", "foot"]
    );
    assert!((shank.mass - 0.35).abs() < 1e-15);
    // Centre: (0.3 × −0.1 + 0.05 × −0.2) / 0.35.
    assert!((shank.centre_of_mass.z - (-0.03 - 0.01) / 0.35).abs() < 1e-15);
}

#[test]
fn bound_inertia_repairs_the_point_mass_foot_and_changes_only_that() {
    let options = ImportOptions {
        bound_inertia: Some(1e-6),
        ..ImportOptions::default()
    };
    let model = import_with(&leg("revolute"), &options);
    assert_eq!(
        model.repairs,
        vec![Repair::InertiaRaised {
            body: "foot".to_owned(),
            old: [0.0; 3],
            new: [1e-6; 3]
        }]
    );
    let foot = &model.bodies[3];
    assert_eq!(foot.inertia, Matrix3::identity() * 1e-6);
    assert_eq!((foot.mass, foot.centre_of_mass), (0.05, Vector3::zeros()));
    // Every other body is as without the option.
    let plain = import(&leg("fixed"));
    assert_eq!(model.bodies[..2], plain.bodies[..2]);
    // bound_mass alone does not help a point mass: still singular.
    let mass_only = ImportOptions {
        bound_mass: Some(1e-3),
        ..ImportOptions::default()
    };
    assert!(matches!(
        error_with(&leg("revolute"), &mass_only),
        ImportError::SingularBody { .. }
    ));
}

#[test]
fn bound_inertia_keeps_the_principal_axes_and_raises_only_small_moments() {
    // A thin rod turned 30° about z: moments (1e-8, 2e-3, 2e-3); only the axial one is raised.
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let axial = Vector3::new(c, s, 0.0);
    let tensor = Matrix3::identity() * 2e-3 - axial * axial.transpose() * (2e-3 - 1e-8);
    let text = leg("fixed").replace(
        r#"<inertia ixx="4e-3" ixy="0" ixz="0" iyy="4e-3" iyz="0" izz="4e-4"/>"#,
        &format!(
            r#"<inertia ixx="{:?}" ixy="{:?}" ixz="0" iyy="{:?}" iyz="0" izz="2e-3"/>"#,
            tensor[(0, 0)],
            tensor[(0, 1)],
            tensor[(1, 1)]
        ),
    );
    let options = ImportOptions {
        bound_inertia: Some(1e-5),
        ..ImportOptions::default()
    };
    let model = import_with(&text, &options);
    let [Repair::InertiaRaised { body, old, new }] = model.repairs.as_slice() else {
        panic!("{:?}", model.repairs)
    };
    assert_eq!(body, "thigh");
    assert!(
        (old[0] - 1e-8).abs() < 1e-17 && (old[2] - 2e-3).abs() < 1e-17,
        "{old:?}"
    );
    assert_eq!(new[0], 1e-5);
    assert_eq!((new[1], new[2]), (old[1], old[2]));
    let thigh = &model.bodies[1];
    assert!((thigh.inertia * axial - axial * 1e-5).norm() < 1e-15); // same axis, raised moment
    assert!((thigh.inertia * Vector3::z() - Vector3::z() * 2e-3).norm() < 1e-15);
    let (moments, _) = principal_axes(&thigh.inertia).unwrap();
    assert!((moments[0] - 1e-5).abs() < 1e-16);
}

#[test]
fn a_massless_subtree_is_an_error_that_says_so() {
    let e = error(ROMEO_HAND);
    let line = line_of(ROMEO_HAND, r#"<joint name="LHand""#);
    assert_eq!(
        e,
        ImportError::SingularBody {
            joint: "LHand".to_owned(),
            line,
            links: vec!["LFinger11Link".to_owned()],
            mass: 0.0,
            moments: [0.0; 3],
            massless_subtree: true,
        }
    );
    assert_message(
        &e,
        &[
            "`LHand`",
            "`LFinger11Link`",
            "mass 0 kg",
            "massless",
            "Pinocchio",
            "Freeze",
            &format!("line {line}"),
        ],
    );
}

#[test]
fn freeze_makes_the_massless_subtree_a_massless_part_of_its_parent() {
    let options = ImportOptions {
        massless_subtrees: MasslessSubtrees::Freeze,
        ..ImportOptions::default()
    };
    let model = import_with(ROMEO_HAND, &options);
    assert_eq!((model.bodies.len(), model.joints.len(), model.merged_links), (1, 0, 4));
    let line = |name: &str| line_of(ROMEO_HAND, &format!("<joint name=\"{name}\""));
    let frozen = |name: &str| FrozenJoint {
        name: name.to_owned(),
        kind: JointKind::Revolute,
        position: 0.0,
        body: 0,
        line: line(name),
    };
    assert_eq!(
        model.frozen_joints,
        vec![frozen("LHand"), frozen("LFinger12"), frozen("LFinger13")]
    );
    let repaired: Vec<Repair> = ["LHand", "LFinger12", "LFinger13"]
        .map(|name| Repair::JointFrozen {
            joint: name.to_owned(),
            kind: JointKind::Revolute,
            line: line(name),
        })
        .into();
    assert_eq!(model.repairs, repaired);
    // The wrist's mass properties are unchanged; the fingers sit where q = 0 puts them.
    let wrist = &model.bodies[0];
    assert_eq!((wrist.mass, wrist.centre_of_mass), (0.27, Vector3::zeros()));
    assert_eq!(wrist.inertia, Matrix3::from_diagonal(&Vector3::new(2e-4, 2e-4, 1e-4)));
    let tip = wrist.links.iter().find(|l| l.name == "LFingerTip").unwrap();
    assert!((tip.pose.translation.vector - Vector3::new(0.13, 0.0, 0.0)).norm() < 1e-15);
}

#[test]
fn a_massless_body_with_mass_below_is_not_a_massless_subtree() {
    let e = error(HUMAN_HIP);
    assert!(
        matches!(&e, ImportError::SingularBody { joint, massless_subtree: false, mass, .. } if joint == "left_hip_Z" && *mass == 0.0),
        "{e:?}"
    );
    assert!(!e.to_string().contains("Pinocchio"));
    // Freezing does not apply: the thigh below has mass.
    let freeze = ImportOptions {
        massless_subtrees: MasslessSubtrees::Freeze,
        ..ImportOptions::default()
    };
    assert_eq!(error_with(HUMAN_HIP, &freeze), e);
}

#[test]
fn bound_mass_and_bound_inertia_give_virtual_links_a_small_body() {
    let options = ImportOptions {
        bound_mass: Some(1e-3),
        bound_inertia: Some(1e-6),
        ..ImportOptions::default()
    };
    let model = import_with(HUMAN_HIP, &options);
    let mut expected = Vec::new();
    for body in ["left_upperleg_virtual", "left_upperleg_virtual_2"] {
        expected.push(Repair::MassRaised {
            body: body.to_owned(),
            old: 0.0,
            new: 1e-3,
        });
        expected.push(Repair::InertiaRaised {
            body: body.to_owned(),
            old: [0.0; 3],
            new: [1e-6; 3],
        });
    }
    assert_eq!(model.repairs, expected);
    assert_eq!(model.bodies[1].mass, 1e-3);
    assert_eq!(model.bodies[1].centre_of_mass, Vector3::zeros());
    // The thigh (8 kg) and the pelvis (the root) are untouched.
    assert_eq!(model.bodies[3].mass, 8.0);
    assert_eq!(model.bodies[0].mass, 10.0);
}

#[test]
fn bound_mass_raises_a_light_body_and_keeps_its_centre_and_inertia() {
    let options = ImportOptions {
        bound_mass: Some(0.1),
        ..ImportOptions::default()
    };
    let model = import_with(&leg("fixed"), &options);
    assert!(model.repairs.is_empty(), "{:?}", model.repairs); // the shank with its foot weighs 0.35 kg
    let options = ImportOptions {
        bound_mass: Some(0.5),
        ..ImportOptions::default()
    };
    let model = import_with(&leg("fixed"), &options);
    let old = 0.3 + 0.05;
    assert_eq!(
        model.repairs,
        vec![Repair::MassRaised {
            body: "shank".to_owned(),
            old,
            new: 0.5
        }]
    );
    let plain = import(&leg("fixed"));
    assert_eq!(model.bodies[2].mass, 0.5);
    assert_eq!(model.bodies[2].centre_of_mass, plain.bodies[2].centre_of_mass);
    assert_eq!(model.bodies[2].inertia, plain.bodies[2].inertia);
}

#[test]
fn a_massless_root_is_recorded_not_refused() {
    // An arm bolted to a `world` frame by a revolute joint: the root is massless, fine when fixed to the world.
    let text = r#"<robot name="pendulum">
  <link name="world"/>
  <link name="bob"><inertial><origin xyz="0 0 -1"/><mass value="1"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <joint name="pivot" type="continuous"><parent link="world"/><child link="bob"/><axis xyz="0 1 0"/></joint>
</robot>"#;
    let model = import(text);
    assert!(model.root_fixed_only);
    assert!(model
        .warnings
        .iter()
        .any(|w| w.contains("`world`") && w.contains("fixed to the world")));
    // Bounds never touch the root.
    let model = import_with(text, &ImportOptions::repair_all(1e-3, 1e-6));
    assert!(model.root_fixed_only && model.repairs.is_empty(), "{:?}", model.repairs);
    assert_eq!(model.bodies[0].mass, 0.0);
    // A root with mass and inertia is not flagged.
    assert!(!import(&leg("fixed")).root_fixed_only);
}

#[test]
fn floating_and_planar_joints_need_invertible_bodies_too() {
    for kind in ["floating", "planar"] {
        let e = error(&leg(kind));
        assert!(
            matches!(&e, ImportError::SingularBody { joint, .. } if joint == "ankle"),
            "{kind}: {e:?}"
        );
    }
}

#[test]
fn bad_options_are_refused() {
    for value in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let options = ImportOptions {
            bound_mass: Some(value),
            ..ImportOptions::default()
        };
        let e = error_with(&leg("fixed"), &options);
        assert!(
            matches!(
                e,
                ImportError::Option {
                    option: "bound_mass",
                    ..
                }
            ),
            "{e:?}"
        );
        let options = ImportOptions {
            bound_inertia: Some(value),
            ..ImportOptions::default()
        };
        assert!(matches!(
            error_with(&leg("fixed"), &options),
            ImportError::Option {
                option: "bound_inertia",
                ..
            }
        ));
    }
}
