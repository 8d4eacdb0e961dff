//! Stage 1 (parse): what is read, the defaults, and the syntax errors with their element, text and line.

use crate::common;

use common::{assert_message, error, import, line_of, UR_ARM};
use nalgebra::Vector3;
use urdf_import::parse::parse;
use urdf_import::{read_file, ImportError, ImportOptions, JointKind, Limit};

#[test]
fn a_ros_arm_reads_with_its_limits_dynamics_and_ignored_tags() {
    let raw = parse(UR_ARM).unwrap();
    assert_eq!(raw.name, "ur5");
    assert_eq!(raw.links.len(), 10);
    assert_eq!(raw.joints.len(), 9);
    assert_eq!(raw.line, line_of(UR_ARM, "<robot"));
    let pan = &raw.joints[1];
    assert_eq!(
        (pan.name.as_str(), pan.kind),
        ("shoulder_pan_joint", JointKind::Revolute)
    );
    assert_eq!(pan.line, line_of(UR_ARM, r#"<joint name="shoulder_pan_joint""#));
    assert_eq!(pan.limit.unwrap().0.effort, Some(150.0));
    assert_eq!(pan.limit.unwrap().0.velocity, Some(3.15));
    assert_eq!(raw.links[0].inertial, None); // world: no <inertial>
    let base = raw.links[1].inertial.as_ref().unwrap();
    assert_eq!(base.mass, 4.0);
    assert_eq!(base.inertia[(2, 2)], 0.0072);
    assert_eq!(base.mass_line, line_of(UR_ARM, r#"<mass value="4.0"/>"#));
    // gazebo, material and transmission are counted, not read, and never fail the import.
    assert_eq!(
        raw.ignored,
        vec![
            ("gazebo".to_owned(), 1),
            ("material".to_owned(), 1),
            ("transmission".to_owned(), 1)
        ]
    );
    assert!(raw.warnings.is_empty(), "{:?}", raw.warnings);
}

#[test]
fn defaults_axis_limit_dynamics_and_mimic() {
    let text = r#"<robot name="gripper">
  <link name="hand"/>
  <link name="finger">
    <inertial><mass value="0.015"/><inertia ixx="2.4e-6" ixy="0" ixz="0" iyy="2.4e-6" iyz="0" izz="1e-6"/></inertial>
  </link>
  <link name="finger2">
    <inertial><mass value="0.015"/><inertia ixx="2.4e-6" ixy="0" ixz="0" iyy="2.4e-6" iyz="0" izz="1e-6"/></inertial>
  </link>
  <joint name="knuckle" type="continuous">
    <parent link="hand"/><child link="finger"/>
  </joint>
  <joint name="knuckle2" type="prismatic">
    <parent link="hand"/><child link="finger2"/>
    <axis xyz="0 -3 4"/>
    <limit upper="0.04" effort="20"/>
    <dynamics friction="0.5"/>
    <mimic joint="knuckle"/>
  </joint>
</robot>"#;
    let raw = parse(text).unwrap();
    let knuckle = &raw.joints[0];
    assert_eq!(knuckle.axis, Vector3::x()); // no <axis>: (1, 0, 0)
    assert_eq!(knuckle.origin, nalgebra::Isometry3::identity());
    assert_eq!(
        (knuckle.limit, knuckle.damping, knuckle.friction, &knuckle.mimic),
        (None, 0.0, 0.0, &None)
    );
    let knuckle2 = &raw.joints[1];
    let limit = Limit {
        lower: None,
        upper: Some(0.04),
        effort: Some(20.0),
        velocity: None,
    };
    assert_eq!(knuckle2.limit.map(|(l, _)| l), Some(limit)); // which attributes were present
    assert_eq!((knuckle2.damping, knuckle2.friction), (0.0, 0.5));
    let mimic = knuckle2.mimic.as_ref().unwrap();
    assert_eq!(
        (mimic.joint.as_str(), mimic.multiplier, mimic.offset),
        ("knuckle", 1.0, 0.0)
    );

    // After the whole pipeline the axis is normalised: (0, -3, 4)/5.
    let model = import(text);
    let axis = model.joints[1].axis.into_inner();
    assert!((axis - Vector3::new(0.0, -0.6, 0.8)).norm() < 1e-15, "{axis}");
    assert_eq!(model.joints[1].mimic.as_ref().unwrap().index, Some(0));
}

/// Elements nested 100 000 deep (a hostile file) are refused before the XML parser, which recurses once per level,
/// could exhaust the stack: an error naming the line and the limit, from `read` as from the parse. Nested as deep as
/// the limit, they parse; `<` inside comments, CDATA, processing instructions and a DOCTYPE's subset opens nothing,
/// and `/>` inside a quoted attribute value closes nothing.
#[test]
fn nesting_beyond_the_limit_is_refused_naming_the_line() {
    use urdf_import::parse::MAX_NESTING;
    let nested = |depth: usize| {
        format!(
            "<robot name=\"r\">\n<link name=\"base\"/>\n{}{}</robot>\n",
            "<a>".repeat(depth),
            "</a>".repeat(depth)
        )
    };
    for depth in [MAX_NESTING, 100_000] {
        let text = nested(depth);
        let error = urdf_import::read(&text, &urdf_import::ImportOptions::default()).unwrap_err();
        assert_eq!(
            error,
            ImportError::TooDeep {
                line: 3,
                limit: MAX_NESTING
            },
            "{depth}"
        );
        assert_message(&error, &["nested more than 256 deep at line 3"]);
    }
    // The robot counts: 255 more levels are within the limit.
    let within = nested(MAX_NESTING - 1);
    assert!(urdf_import::parse::parse(&within).is_ok());
    let (hidden, closing) = ("<a><b>".repeat(1000), "a/>".repeat(1000));
    let text = format!(
        "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY x \"{hidden}\">]>\n<robot name=\"r\">\n<!-- {hidden} -->\n\
         <link name=\"base\"><![CDATA[{hidden}]]><?pi {hidden}?></link>\n<link name=\"other\" note=\"{closing}\"/>\n</robot>\n"
    );
    assert!(
        urdf_import::parse::parse(&text).is_ok(),
        "{:?}",
        urdf_import::parse::parse(&text).err()
    );
}

#[test]
fn empty_text_not_xml_and_not_a_robot() {
    assert_eq!(error(""), ImportError::Empty);
    assert_eq!(error("  \n\t "), ImportError::Empty);

    let broken = "<robot name=\"r\">\n  <link name=\"a\">\n</robot>\n";
    let e = error(broken);
    assert!(matches!(e, ImportError::Xml { line: 3, .. }), "{e:?}");
    assert_message(&e, &["line 3"]);

    let sdf = "<?xml version=\"1.0\"?>\n<sdf version=\"1.6\">\n  <model name=\"m\"/>\n</sdf>\n";
    let e = error(sdf);
    assert_eq!(
        e,
        ImportError::NotRobot {
            element: "sdf".to_owned(),
            line: 2
        }
    );
    assert_message(&e, &["<sdf>", "line 2"]);
}

#[test]
fn a_robot_without_links_is_an_error_naming_it() {
    // ur3.urdf of example-robot-data: a xacro output with no name and nothing but a comment.
    let text =
        "<?xml version=\"1.0\"?>\n<robot xmlns:xacro=\"http://wiki.ros.org/xacro\">\n  <!-- Author -->\n</robot>\n";
    let e = error(text);
    assert_eq!(
        e,
        ImportError::NoLinks {
            robot: String::new(),
            line: 2
        }
    );
    assert_message(&e, &["unnamed", "line 2", "no <link>"]);
    let e = error("<robot name=\"r2d2\">\n  <joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n</robot>");
    assert_message(&e, &["robot `r2d2`", "line 1"]);
}

#[test]
fn a_bad_number_names_element_attribute_text_and_line() {
    let cases = [
        (r#"<origin xyz="1 2" rpy="0 0 0"/>"#, "origin", "xyz", "1 2", 3),
        (r#"<origin xyz="1 2 3 4"/>"#, "origin", "xyz", "1 2 3 4", 3),
        (
            r#"<origin xyz="0 0 0.1" rpy="0 0 ${pi/2}"/>"#,
            "origin",
            "rpy",
            "0 0 ${pi/2}",
            3,
        ),
        (r#"<origin xyz="0 nan 0"/>"#, "origin", "xyz", "0 nan 0", 3),
        (r#"<origin xyz="0 0 inf"/>"#, "origin", "xyz", "0 0 inf", 3),
        (r#"<origin xyz="0 0 1e400"/>"#, "origin", "xyz", "0 0 1e400", 3),
        (r#"<axis xyz="0,0,1"/>"#, "axis", "xyz", "0,0,1", 3),
        (
            r#"<limit lower="-1.5" upper="1.5rad" effort="10" velocity="1"/>"#,
            "limit",
            "upper",
            "1.5rad",
            1,
        ),
        (r#"<dynamics damping="0.1 0.2"/>"#, "dynamics", "damping", "0.1 0.2", 1),
        (
            r#"<mimic joint="j0" multiplier="minus one"/>"#,
            "mimic",
            "multiplier",
            "minus one",
            1,
        ),
    ];
    for (element, tag, attribute, text, expected) in cases {
        let urdf = format!(
            "<robot name=\"arm\">\n  <link name=\"base\"/>\n  <link name=\"arm\"/>\n  <joint name=\"j0\" type=\"revolute\">\n    \
             <parent link=\"base\"/><child link=\"arm\"/>\n    {element}\n  </joint>\n</robot>\n"
        );
        let e = error(&urdf);
        let line = line_of(&urdf, element);
        assert_eq!(
            e,
            ImportError::Number {
                owner: "joint `j0`".to_owned(),
                element: tag.to_owned(),
                attribute: attribute.to_owned(),
                text: text.to_owned(),
                expected,
                line,
            },
            "{element}"
        );
        assert_message(&e, &["joint `j0`", attribute, text, &format!("line {line}")]);
    }
    // Numbers in an inertia: a link is named.
    let urdf = "<robot name=\"r\">\n<link name=\"torso\">\n<inertial>\n<mass value=\"-\"/>\n\
                <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/>\n</inertial>\n</link>\n</robot>";
    let e = error(urdf);
    assert!(
        matches!(&e, ImportError::Number { owner, attribute, line: 4, .. } if owner == "link `torso`" && attribute == "value")
    );
    // Surrounding white space is trimmed, as in xacro output.
    let urdf = "<robot name=\"r\"><link name=\"torso\"><inertial><mass value=\" 2.5 \"/>\
                <inertia ixx=\" 1\" ixy=\"0\" ixz=\"0\" iyy=\"1 \" iyz=\"0\" izz=\"1\"/></inertial></link></robot>";
    assert_eq!(import(urdf).bodies[0].mass, 2.5);
}

/// An origin beyond the bodies' range (1e6 m) names its joint or link, the text and the line, for joints, inertials
/// and collisions alike; one just within it is read.
#[test]
fn origins_beyond_the_bodies_range_are_named() {
    for (owner, element, text) in [
        ("joint `j0`", "<origin xyz=\"1e10 0 0\"/>", "1e10 0 0"),
        ("joint `j0`", "<origin xyz=\"0 -2e6 0\" rpy=\"0 0 1\"/>", "0 -2e6 0"),
    ] {
        let urdf = format!(
            "<robot name=\"arm\">\n  <link name=\"base\"/>\n  <link name=\"arm\"/>\n  <joint name=\"j0\" type=\"fixed\">\n    \
             <parent link=\"base\"/><child link=\"arm\"/>\n    {element}\n  </joint>\n</robot>\n"
        );
        let e = error(&urdf);
        let line = line_of(&urdf, element);
        assert!(
            matches!(&e, ImportError::FarOrigin { line: l, .. } if *l == line),
            "{e}"
        );
        assert_message(&e, &[owner, text, &format!("line {line}"), "beyond 1e6 m"]);
    }
    let urdf =
        "<robot name=\"r\">\n<link name=\"torso\">\n<inertial>\n<origin xyz=\"0 0 3e7\"/>\n<mass value=\"1\"/>\n\
                <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/>\n</inertial>\n</link>\n</robot>";
    assert_message(&error(urdf), &["link `torso`", "0 0 3e7", "line 4", "3e7 m"]);
    let within = "<robot name=\"r\"><link name=\"torso\"><inertial><origin xyz=\"0 0 1e6\"/><mass value=\"2\"/>\
                  <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link></robot>";
    assert_eq!(import(within).bodies[0].mass, 2.0);
}

#[test]
fn missing_attributes_and_elements_are_named() {
    let e = error("<robot name=\"r\">\n  <link/>\n</robot>");
    assert_eq!(
        e,
        ImportError::MissingAttribute {
            owner: "robot `r`".to_owned(),
            element: "link".to_owned(),
            attribute: "name".to_owned(),
            line: 2
        }
    );
    let e = error("<robot name=\"r\">\n  <link name=\"a\"/><link name=\"b\"/>\n  <joint name=\"j\"><parent link=\"a\"/><child link=\"b\"/></joint>\n</robot>");
    assert_message(&e, &["joint `j`", "`type`", "line 3"]);
    let e = error("<robot name=\"r\">\n  <link name=\"a\"/><link name=\"b\"/>\n  <joint name=\"j\" type=\"fixed\">\n    <child link=\"b\"/>\n  </joint>\n</robot>");
    assert_eq!(
        e,
        ImportError::MissingElement {
            owner: "joint `j`".to_owned(),
            element: "parent".to_owned(),
            line: 3
        }
    );
    let e = error("<robot name=\"r\">\n  <link name=\"a\">\n    <inertial>\n      <mass value=\"1\"/>\n      <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" izz=\"1\"/>\n    </inertial>\n  </link>\n</robot>");
    assert_message(&e, &["link `a`", "<inertia>", "`iyz`", "line 5"]);
    let e = error("<robot name=\"r\">\n  <link name=\"a\">\n    <inertial>\n      <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/>\n    </inertial>\n  </link>\n</robot>");
    assert_message(&e, &["link `a`", "<mass>", "line 3"]);
}

#[test]
fn an_unknown_joint_type_names_joint_type_and_line() {
    for kind in ["spherical", "revolve", "Revolute", "ball"] {
        let urdf = format!(
            "<robot name=\"human\">\n  <link name=\"pelvis\"/>\n  <link name=\"thigh\"/>\n  \
             <joint name=\"left_hip\" type=\"{kind}\">\n    <parent link=\"pelvis\"/><child link=\"thigh\"/>\n  </joint>\n</robot>"
        );
        let e = error(&urdf);
        assert_eq!(
            e,
            ImportError::JointType {
                joint: "left_hip".to_owned(),
                kind: kind.to_owned(),
                line: 4
            }
        );
        assert_message(&e, &["`left_hip`", kind, "line 4"]);
    }
}

#[test]
fn a_zero_axis_on_a_moving_joint_is_an_error_but_not_on_fixed_or_floating() {
    for kind in ["revolute", "continuous", "prismatic", "planar"] {
        let urdf = format!(
            "<robot name=\"r\">\n  <link name=\"a\"/>\n  <link name=\"b\"><inertial><mass value=\"1\"/>\
             <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n  \
             <joint name=\"slider\" type=\"{kind}\">\n    <parent link=\"a\"/><child link=\"b\"/>\n    \
             <axis xyz=\"0 0 0\"/>\n    <limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/>\n  </joint>\n</robot>"
        );
        let e = error(&urdf);
        assert!(
            matches!(&e, ImportError::Axis { joint, axis: [0.0, 0.0, 0.0], line: 6, .. } if joint == "slider"),
            "{e:?}"
        );
        assert_message(&e, &[kind, "`slider`", "[0.0, 0.0, 0.0]", "line 6"]);
        // The same file with a fixed or floating joint imports: the axis means nothing there.
        let fixed = urdf.replace(&format!("type=\"{kind}\""), "type=\"fixed\"");
        assert_eq!(import(&fixed).bodies.len(), 1);
        let floating = urdf.replace(&format!("type=\"{kind}\""), "type=\"floating\"");
        assert_eq!(import(&floating).joints[0].kind, urdf_import::JointKind::Floating);
    }
    // Tiny and huge axes are directions all the same.
    for (text, expected) in [("0 1e-300 0", Vector3::y()), ("0 0 -1e300", -Vector3::z())] {
        let urdf = format!(
            "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"><inertial><mass value=\"1\"/>\
             <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\
             <joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"{text}\"/></joint></robot>"
        );
        assert_eq!(import(&urdf).joints[0].axis.into_inner(), expected, "{text}");
    }
}

#[test]
fn an_inverted_limit_is_an_error() {
    let urdf = "<robot name=\"r\">\n<link name=\"a\"/>\n<link name=\"b\"><inertial><mass value=\"1\"/>\
                <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n\
                <joint name=\"elbow\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\n\
                <limit lower=\"2.5\" upper=\"-2.5\" effort=\"1\" velocity=\"1\"/></joint>\n</robot>";
    let e = error(urdf);
    assert_eq!(
        e,
        ImportError::LimitInverted {
            joint: "elbow".to_owned(),
            lower: 2.5,
            upper: -2.5,
            line: 5
        }
    );
    assert_message(&e, &["`elbow`", "2.5", "-2.5", "line 5"]);
}

#[test]
fn xacro_leftovers_are_a_warning_and_other_tags_never_fail() {
    let urdf = r#"<robot name="r" xmlns:xacro="http://wiki.ros.org/xacro">
  <xacro:include filename="$(find robot)/urdf/arm.xacro"/>
  <sensor name="imu"><parent link="base"/></sensor>
  <ros2_control name="hw" type="system"/>
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual><geometry><box size="1 1 1"/></geometry></visual><self_collision_checking/></link>
</robot>"#;
    let model = import(urdf);
    assert!(
        model.warnings.iter().any(|w| w.contains("xacro")),
        "{:?}",
        model.warnings
    );
    assert_eq!(model.ignored.len(), 3);
}

#[test]
fn read_file_names_a_missing_path() {
    let e = read_file("/nonexistent/robot.urdf", &ImportOptions::default()).unwrap_err();
    assert!(matches!(&e, ImportError::Io { path, .. } if path == "/nonexistent/robot.urdf"));
    assert_message(&e, &["/nonexistent/robot.urdf"]);
}

/// A negative `<dynamics>` damping or friction would feed energy in: refused naming the joint, the attribute, the
/// value and the line, rather than dropped; zero is no damping.
#[test]
fn negative_joint_dynamics_are_refused() {
    let with = |dynamics: &str| {
        format!(
            "<robot name=\"r\">\n<link name=\"a\"/>\n<link name=\"b\"/>\n<joint name=\"hinge\" type=\"continuous\">\n\
             <parent link=\"a\"/><child link=\"b\"/>\n{dynamics}\n</joint>\n</robot>\n"
        )
    };
    for (dynamics, attribute, value) in [
        ("<dynamics damping=\"-1\"/>", "damping", -1.0),
        ("<dynamics damping=\"0.5\" friction=\"-0.1\"/>", "friction", -0.1),
    ] {
        let error = error(&with(dynamics));
        assert_eq!(
            error,
            ImportError::NegativeDynamics {
                joint: "hinge".to_owned(),
                attribute,
                value,
                line: 6
            }
        );
        assert_message(&error, &["joint `hinge` (line 6)", attribute, "cannot be negative"]);
    }
    assert!(parse(&with("<dynamics damping=\"0\" friction=\"0\"/>")).is_ok());
}
