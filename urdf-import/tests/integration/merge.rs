//! Stage 3 (merge): links joined by fixed joints become one body with exactly merged mass properties; bodies in
//! root-first, parent-before-child order; joint frames composed through the fixed chain.

use crate::common;

use common::{frame, import, joint, link, robot, UR_ARM};
use nalgebra::{Isometry3, Matrix3, Point3, Vector3};
use urdf_import::pose::pose;
use urdf_import::RigidBody;

fn relative(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    (a - b).amax() / b.amax()
}

/// xyz and rpy text of an isometry (Rust's shortest round-trip formatting).
fn origin_text(iso: &Isometry3<f64>) -> String {
    let t = iso.translation.vector;
    let (r, p, y) = iso.rotation.euler_angles();
    // nalgebra's (roll, pitch, yaw) are URDF's: checked, so the text means this pose.
    assert!((pose([t.x, t.y, t.z], [r, p, y]).to_homogeneous() - iso.to_homogeneous()).amax() < 1e-15);
    format!(r#"xyz="{:?} {:?} {:?}" rpy="{r:?} {p:?} {y:?}""#, t.x, t.y, t.z)
}

fn box_inertia(mass: f64, sides: [f64; 3]) -> [f64; 3] {
    let [a, b, c] = sides.map(|s| s * s);
    [mass / 12.0 * (b + c), mass / 12.0 * (a + c), mass / 12.0 * (a + b)]
}

fn inertial(origin: &str, mass: f64, diagonal: [f64; 3]) -> String {
    format!(
        r#"<inertial><origin {origin}/><mass value="{mass:?}"/><inertia ixx="{:?}" ixy="0" ixz="0" iyy="{:?}" iyz="0" izz="{:?}"/></inertial>"#,
        diagonal[0], diagonal[1], diagonal[2]
    )
}

#[test]
fn a_box_split_across_a_fixed_joint_equals_the_whole_box() {
    // A 3 kg box 0.4 x 0.1 x 0.06 m, centred at c0 and turned by rpy0 in link A; split across its x middle into
    // two halves, the second held by link B on a fixed joint with its own xyz and rpy offset.
    let (mass, sides) = (3.0, [0.4, 0.1, 0.06]);
    let whole = pose([0.1, -0.05, 0.2], [0.3, -0.4, 1.2]);
    let half_1 = whole * Isometry3::translation(-0.1, 0.0, 0.0);
    let half_2 = whole * Isometry3::translation(0.1, 0.0, 0.0);
    let b_in_a = pose([0.3, 0.1, -0.2], [-0.7, 0.5, 2.0]);
    let half_inertia = box_inertia(mass / 2.0, [0.2, 0.1, 0.06]);

    let one = format!(
        "<robot name=\"one\">\n<link name=\"A\">{}</link>\n</robot>",
        inertial(&origin_text(&whole), mass, box_inertia(mass, sides))
    );
    let two = format!(
        "<robot name=\"two\">\n<link name=\"A\">{}</link>\n<link name=\"B\">{}</link>\n\
         <joint name=\"weld\" type=\"fixed\"><parent link=\"A\"/><child link=\"B\"/><origin {}/></joint>\n</robot>",
        inertial(&origin_text(&half_1), mass / 2.0, half_inertia),
        inertial(&origin_text(&(b_in_a.inverse() * half_2)), mass / 2.0, half_inertia),
        origin_text(&b_in_a)
    );
    let (one, two) = (import(&one), import(&two));
    assert_eq!((one.bodies.len(), two.bodies.len(), two.merged_links), (1, 1, 1));
    let (a, b) = (&one.bodies[0], &two.bodies[0]);
    assert_eq!(a.mass, b.mass);
    assert!((a.centre_of_mass - b.centre_of_mass).norm() / a.centre_of_mass.norm() < 1e-14);
    assert!(
        relative(&b.inertia, &a.inertia) < 1e-14,
        "{} vs {}",
        b.inertia,
        a.inertia
    );
    // And both are the box's tensor R I Rᵀ, turned into A's axes: off-diagonal terms included.
    let r = whole.rotation.to_rotation_matrix().into_inner();
    let expected = r * Matrix3::from_diagonal(&Vector3::from(box_inertia(mass, sides))) * r.transpose();
    assert!(expected[(0, 1)].abs() > 1e-3);
    assert!(relative(&a.inertia, &expected) < 1e-14);
    assert!(relative(&b.inertia, &expected) < 1e-14);
    assert!((b.centre_of_mass - whole.translation.vector).norm() < 1e-15);
    assert_eq!(b.links[1].name, "B");
    assert!((b.links[1].pose.to_homogeneous() - b_in_a.to_homogeneous()).amax() < 1e-15);
}

#[test]
fn point_masses_merge_by_the_parallel_axis_theorem() {
    // A base with four point masses on fixed joints (each turned, so their own frames differ): the body's
    // inertia about its centre is Σ m (|d|² 1 − d dᵀ) plus the base's own tensor.
    let tips = [
        ([0.3, 0.0, 0.1], [0.5, 0.0, 0.0], 0.2),
        ([-0.1, 0.4, 0.0], [0.0, 1.0, 0.3], 0.7),
        ([0.0, -0.2, -0.3], [0.2, -0.4, 2.5], 1.1),
        ([0.25, 0.25, 0.25], [3.0, 0.1, -1.0], 0.05),
    ];
    let mut parts = vec![link("base", 2.0, [0.02, 0.03, 0.04])];
    for (i, (xyz, rpy, m)) in tips.iter().enumerate() {
        parts.push(format!(
            "<link name=\"tip{i}\"><inertial><origin xyz=\"0.01 0 0\"/><mass value=\"{m:?}\"/>\
             <inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial></link>\n"
        ));
        parts.push(joint(
            &format!("tip{i}_fixed"),
            "fixed",
            "base",
            &format!("tip{i}"),
            *xyz,
            *rpy,
        ));
    }
    let model = import(&robot("star", &parts));
    assert_eq!((model.bodies.len(), model.merged_links), (1, 4));
    let body = &model.bodies[0];
    let points: Vec<(f64, Vector3<f64>)> = std::iter::once((2.0, Vector3::zeros()))
        .chain(
            tips.iter()
                .map(|(xyz, rpy, m)| (*m, (pose(*xyz, *rpy) * Point3::new(0.01, 0.0, 0.0)).coords)),
        )
        .collect();
    let total: f64 = points.iter().map(|p| p.0).sum();
    let centre = points.iter().fold(Vector3::zeros(), |acc, (m, r)| acc + r * *m) / total;
    let mut expected = Matrix3::from_diagonal(&Vector3::new(0.02, 0.03, 0.04));
    for (m, r) in &points {
        let d = r - centre;
        expected += (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * *m;
    }
    assert!((body.mass - total).abs() < 1e-15);
    assert!((body.centre_of_mass - centre).norm() < 1e-15);
    assert!(relative(&body.inertia, &expected) < 1e-14);
    assert_eq!(body.inertia, body.inertia.transpose()); // exactly symmetric
}

#[test]
fn a_ros_arm_merges_its_massless_frames() {
    let model = common::import(UR_ARM);
    let names: Vec<&str> = model.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "world",
            "shoulder_link",
            "upper_arm_link",
            "forearm_link",
            "wrist_1_link",
            "wrist_2_link",
            "wrist_3_link"
        ]
    );
    assert_eq!((model.joints.len(), model.merged_links), (6, 3));
    let root = &model.bodies[0];
    let root_links: Vec<&str> = root.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(root_links, ["world", "base_link"]);
    assert_eq!(root.mass, 4.0);
    assert!(!model.root_fixed_only);
    let hand: &RigidBody = &model.bodies[6];
    let hand_links: Vec<&str> = hand.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(hand_links, ["wrist_3_link", "ee_link", "tool0"]);
    assert_eq!(hand.mass, 0.1879);
    assert_eq!(hand.centre_of_mass, Vector3::zeros());
    let tool0 = hand.links[2].pose;
    assert!(
        (tool0.to_homogeneous() - pose([0.0, 0.0823, 0.0], [-1.570796325, 0.0, 0.0]).to_homogeneous()).amax() < 1e-15
    );
    // The first joint's frame is in the root body's frame: world and base_link coincide.
    assert_eq!(
        model.joints[0].origin.translation.vector,
        Vector3::new(0.0, 0.0, 0.089159)
    );
    assert_eq!(model.joints[0].parent_link, "base_link");
    assert!(
        model.repairs.is_empty() && model.warnings.is_empty(),
        "{:?} {:?}",
        model.repairs,
        model.warnings
    );
}

#[test]
fn a_60_link_chain_with_27_fixed_joints_has_33_bodies() {
    let mut parts = Vec::new();
    for i in 0..60 {
        parts.push(link(&format!("link{i}"), 1.0 + 0.01 * i as f64, [0.01, 0.012, 0.015]));
    }
    let mut fixed = 0;
    for i in 1..60 {
        let kind = if i % 2 == 0 && i <= 54 { "fixed" } else { "revolute" };
        fixed += usize::from(kind == "fixed");
        let rpy = [0.1 * (i % 3) as f64, -0.2, 0.05 * i as f64];
        parts.push(joint(
            &format!("joint{i}"),
            kind,
            &format!("link{}", i - 1),
            &format!("link{i}"),
            [0.0, 0.02, 0.1],
            rpy,
        ));
    }
    assert_eq!(fixed, 27);
    let model = import(&robot("snake", &parts));
    assert_eq!(
        (model.bodies.len(), model.joints.len(), model.merged_links),
        (33, 32, 27)
    );
    assert_eq!(model.bodies.iter().map(|b| b.links.len()).sum::<usize>(), 60);
    let total: f64 = (0..60).map(|i| 1.0 + 0.01 * i as f64).sum();
    assert!((model.bodies.iter().map(|b| b.mass).sum::<f64>() - total).abs() < 1e-12);
    for (k, j) in model.joints.iter().enumerate() {
        assert_eq!((j.parent, j.child), (k, k + 1), "{}", j.name);
    }
}

#[test]
fn bodies_come_after_their_parents_even_when_the_file_lists_children_first() {
    // The wrist joint is written before the elbow joint, which is written before the shoulder joint.
    let z = [0.0; 3];
    let text = robot(
        "reversed",
        &[
            link("hand", 0.5, [1e-3, 1e-3, 1e-3]),
            link("forearm", 1.0, [1e-2, 1e-2, 1e-3]),
            link("upper_arm", 2.0, [2e-2, 2e-2, 2e-3]),
            link("shoulder", 3.0, [3e-2, 3e-2, 3e-2]),
            frame("base"),
            joint("wrist", "revolute", "forearm", "hand", [0.0, 0.0, 0.3], z),
            joint("elbow", "revolute", "upper_arm", "forearm", [0.0, 0.0, 0.4], z),
            joint("base_fixed", "fixed", "base", "shoulder", z, z),
            joint("shoulder_pitch", "revolute", "shoulder", "upper_arm", z, z),
        ],
    );
    let model = import(&text);
    let names: Vec<&str> = model.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["base", "upper_arm", "forearm", "hand"]);
    let joints: Vec<(&str, usize, usize)> = model
        .joints
        .iter()
        .map(|j| (j.name.as_str(), j.parent, j.child))
        .collect();
    // Joints stay in file order; every parent index is below its child's.
    assert_eq!(joints, [("wrist", 2, 3), ("elbow", 1, 2), ("shoulder_pitch", 0, 1)]);
    assert_eq!(model.bodies[0].mass, 3.0); // the shoulder, fixed to the massless base frame
}
