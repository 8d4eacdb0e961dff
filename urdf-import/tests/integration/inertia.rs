//! Stage 2 (validate), link inertias: negative mass, non-finite, indefinite and triangle-breaking tensors, the
//! round-off allowed, and the `balance_inertia` repair.

use crate::common;

use common::{assert_message, error, error_with, import, import_with, line_of};
use nalgebra::{Matrix3, Vector3};
use urdf_import::validate::principal_axes;
use urdf_import::{ImportError, ImportOptions, Repair};

/// A pelvis (the root, 8 kg) and one link on a revolute joint, with this `<inertial>` body.
fn hip(inertial: &str) -> String {
    format!(
        r#"<robot name="biped">
  <link name="pelvis">
    <inertial><mass value="8.0"/><inertia ixx="0.08" ixy="0" ixz="0" iyy="0.06" iyz="0" izz="0.1"/></inertial>
  </link>
  <link name="thigh">
    <visual><geometry><cylinder radius="0.05" length="0.4"/></geometry></visual>
    <inertial>
      <origin xyz="0 0 -0.2" rpy="0 0 0"/>
      {inertial}
    </inertial>
  </link>
  <joint name="hip_pitch" type="revolute">
    <parent link="pelvis"/>
    <child link="thigh"/>
    <axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="100" velocity="5"/>
  </joint>
</robot>
"#
    )
}

fn balance() -> ImportOptions {
    ImportOptions {
        balance_inertia: true,
        ..ImportOptions::default()
    }
}

#[test]
fn a_negative_mass_names_link_mass_and_line() {
    let text = hip(r#"<mass value="-1.5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.002"/>"#);
    let e = error(&text);
    let line = line_of(&text, "<mass value=\"-1.5\"");
    assert_eq!(
        e,
        ImportError::Mass {
            link: "thigh".to_owned(),
            mass: -1.5,
            line
        }
    );
    assert_message(&e, &["`thigh`", "-1.5 kg", &format!("line {line}")]);
    // balance_inertia does not touch masses.
    assert!(matches!(error_with(&text, &balance()), ImportError::Mass { .. }));
}

#[test]
fn an_indefinite_tensor_names_link_moments_and_line() {
    // ixy larger than the diagonal: eigenvalues 0.13, -0.03 in the xy plane, 0.01 along z.
    let text = hip(r#"<mass value="5.11"/><inertia ixx="0.05" ixy="0.08" ixz="0" iyy="0.05" iyz="0" izz="0.01"/>"#);
    let e = error(&text);
    let line = line_of(&text, "<inertia ixx=\"0.05\"");
    let ImportError::InertiaIndefinite {
        link,
        moments,
        line: at,
    } = &e
    else {
        panic!("{e:?}")
    };
    assert_eq!((link.as_str(), *at), ("thigh", line));
    for (m, expected) in moments.iter().zip([-0.03, 0.01, 0.13]) {
        assert!((m - expected).abs() < 1e-15, "{moments:?}");
    }
    assert_message(
        &e,
        &[
            "`thigh`",
            "-3.000000e-2",
            "1.300000e-1",
            "negative",
            &format!("line {line}"),
        ],
    );
}

#[test]
fn a_triangle_break_names_link_moments_and_line() {
    // PR2's sensor_mount_link: 1e-3, 1e-3, 1e-2.
    let text = hip(r#"<mass value="0.05"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.01"/>"#);
    let e = error(&text);
    let line = line_of(&text, "<inertia ixx=\"0.001\"");
    assert_eq!(
        e,
        ImportError::InertiaTriangle {
            link: "thigh".to_owned(),
            moments: [0.001, 0.001, 0.01],
            line
        }
    );
    assert_message(
        &e,
        &[
            "`thigh`",
            "1.000000e-2 > 1.000000e-3 + 1.000000e-3",
            &format!("line {line}"),
        ],
    );

    // ANYmal's dummy base inertia, every entry 1e-6: rank one, moments (0, 0, 3e-6), which breaks it too.
    let text =
        hip(r#"<mass value="1e-6"/><inertia ixx="1e-6" ixy="1e-6" ixz="1e-6" iyy="1e-6" iyz="1e-6" izz="1e-6"/>"#);
    let e = error(&text);
    assert!(
        matches!(&e, ImportError::InertiaTriangle { moments, .. } if (moments[2] - 3e-6).abs() < 1e-20),
        "{e:?}"
    );
}

#[test]
fn the_triangle_equality_and_round_off_pass() {
    // A thin plate: I₃ = I₁ + I₂ exactly, and within the 1e-9 relative round-off.
    for izz in ["0.3", "0.30000000001"] {
        let text = hip(&format!(
            r#"<mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="{izz}"/>"#
        ));
        assert_eq!(import(&text).bodies[1].inertia[(2, 2)], izz.parse::<f64>().unwrap());
    }
    // Beyond it: an error.
    let text = hip(r#"<mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3000001"/>"#);
    assert!(matches!(error(&text), ImportError::InertiaTriangle { .. }));
}

#[test]
fn noise_on_a_zero_tensor_is_a_point_mass_not_an_indefinite_tensor() {
    // iCub's head: 1.34 kg with `ixz="2.40741e-35"` and zeros. As a link it is a point mass (its round-off is
    // measured against the mass times 1 m²); fixed to a skull with an inertia, the body is fine.
    let text = r#"<robot name="icub">
  <link name="neck"><inertial><mass value="0.5"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <link name="skull"><inertial><mass value="0.3"/><inertia ixx="2e-3" ixy="0" ixz="0" iyy="2e-3" iyz="0" izz="2e-3"/></inertial></link>
  <link name="head">
    <inertial>
      <mass value="1.33687"/>
      <origin xyz="0.0185 -0.1108 6.78454e-18" rpy="0 -0 0"/>
      <inertia ixx="0" ixy="0" ixz="2.40741e-35" iyy="0" iyz="0" izz="0"/>
    </inertial>
  </link>
  <joint name="neck_yaw" type="revolute"><parent link="neck"/><child link="skull"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <joint name="head_fixed" type="fixed"><parent link="skull"/><child link="head"/></joint>
</robot>"#;
    let model = import(text);
    assert_eq!(model.bodies[1].links.len(), 2);
    assert!((model.bodies[1].mass - 1.63687).abs() < 1e-15);
}

#[test]
fn an_overflowing_tensor_is_not_finite() {
    let text = hip(r#"<mass value="1"/><inertia ixx="1e308" ixy="1e308" ixz="0" iyy="1e308" iyz="0" izz="1e308"/>"#);
    let e = error(&text);
    assert!(
        matches!(&e, ImportError::InertiaNotFinite { link, tensor, .. } if link == "thigh" && tensor[1] == 1e308),
        "{e:?}"
    );
    assert_message(&e, &["`thigh`", "not finite"]);
}

#[test]
fn a_massless_link_with_an_inertia_is_kept_and_noted() {
    // Bolt's feet: mass 0 but a tensor. Fixed to the shin, the tensor is added as written.
    let text = r#"<robot name="bolt">
  <link name="shin"><inertial><mass value="0.2"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-4"/></inertial></link>
  <link name="FL_FOOT"><inertial><mass value="0"/><inertia ixx="5.3e-7" ixy="0" ixz="0" iyy="5.7e-7" iyz="0" izz="8.4e-7"/></inertial></link>
  <joint name="foot_fixed" type="fixed"><parent link="shin"/><child link="FL_FOOT"/><origin xyz="0 0 -0.16"/></joint>
</robot>"#;
    let model = import(text);
    assert!(
        model
            .warnings
            .iter()
            .any(|w| w.contains("`FL_FOOT`") && w.contains("mass 0")),
        "{:?}",
        model.warnings
    );
    assert_eq!(model.bodies[0].mass, 0.2);
    assert!((model.bodies[0].inertia[(0, 0)] - (1e-3 + 5.3e-7)).abs() < 1e-18);
}

#[test]
fn balance_raises_negative_moments_then_the_two_smaller_equally() {
    // Indefinite: (-0.03, 0.01, 0.13) -> (0, 0.01, 0.13) -> +0.06 each -> (0.06, 0.07, 0.13).
    let text = hip(r#"<mass value="5.11"/><inertia ixx="0.05" ixy="0.08" ixz="0" iyy="0.05" iyz="0" izz="0.01"/>"#);
    let model = import_with(&text, &balance());
    let [Repair::InertiaBalanced { link, line, old, new }] = model.repairs.as_slice() else {
        panic!("{:?}", model.repairs)
    };
    assert_eq!(
        (link.as_str(), *line),
        ("thigh", line_of(&text, "<inertia ixx=\"0.05\""))
    );
    for (got, expected) in old
        .iter()
        .zip([-0.03, 0.01, 0.13])
        .chain(new.iter().zip([0.06, 0.07, 0.13]))
    {
        assert!((got - expected).abs() < 1e-15, "{old:?} {new:?}");
    }
    // The body has exactly those moments, about the same principal axes, with mass and centre unchanged.
    let thigh = &model.bodies[1];
    let (moments, _) = principal_axes(&thigh.inertia).unwrap();
    for (m, n) in moments.iter().zip(new) {
        assert!((m - n).abs() < 1e-15);
    }
    let diagonal_axis = Vector3::new(1.0, 1.0, 0.0).normalize(); // the eigenvector of 0.13 as written
    assert!(((thigh.inertia * diagonal_axis) - diagonal_axis * 0.13).norm() < 1e-15);
    assert!((thigh.inertia * Vector3::z() - Vector3::z() * 0.07).norm() < 1e-15); // 0.01 + 0.06
    assert_eq!((thigh.mass, thigh.centre_of_mass), (5.11, Vector3::new(0.0, 0.0, -0.2)));
}

#[test]
fn balance_keeps_the_largest_moment_of_a_triangle_break() {
    let text = hip(r#"<mass value="0.05"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.01"/>"#);
    let model = import_with(&text, &balance());
    assert_eq!(
        model.repairs,
        vec![Repair::InertiaBalanced {
            link: "thigh".to_owned(),
            line: line_of(&text, "<inertia ixx=\"0.001\""),
            old: [0.001, 0.001, 0.01],
            new: [0.005, 0.005, 0.01],
        }]
    );
    let expected = Matrix3::from_diagonal(&Vector3::new(0.005, 0.005, 0.01));
    assert!(
        (model.bodies[1].inertia - expected).amax() < 1e-17,
        "{}",
        model.bodies[1].inertia
    );
}

#[test]
fn balance_leaves_valid_links_alone() {
    let text =
        hip(r#"<mass value="2"/><inertia ixx="0.03" ixy="0.001" ixz="-0.002" iyy="0.025" iyz="0.0005" izz="0.01"/>"#);
    let plain = import(&text);
    let balanced = import_with(&text, &balance());
    assert!(balanced.repairs.is_empty());
    assert_eq!(plain.bodies, balanced.bodies);
}
