//! URDF's rpy convention: R = Rz(yaw) Ry(pitch) Rx(roll), fixed axes, roll first; checked against matrices written
//! out by hand, and through the importer.

use crate::common;

use common::{frame, import, joint, link, robot};
use nalgebra::{Matrix3, Point3, Vector3};
use urdf_import::pose::{pose, rpy_rotation};

fn rx(a: f64) -> Matrix3<f64> {
    Matrix3::new(1.0, 0.0, 0.0, 0.0, a.cos(), -a.sin(), 0.0, a.sin(), a.cos())
}

fn ry(a: f64) -> Matrix3<f64> {
    Matrix3::new(a.cos(), 0.0, a.sin(), 0.0, 1.0, 0.0, -a.sin(), 0.0, a.cos())
}

fn rz(a: f64) -> Matrix3<f64> {
    Matrix3::new(a.cos(), -a.sin(), 0.0, a.sin(), a.cos(), 0.0, 0.0, 0.0, 1.0)
}

#[test]
fn a_quarter_yaw_maps_x_to_y() {
    let r = rpy_rotation([0.0, 0.0, std::f64::consts::FRAC_PI_2]);
    assert!((r * Vector3::x() - Vector3::y()).norm() < 1e-15);
    assert!((r * Vector3::y() + Vector3::x()).norm() < 1e-15);
    // A quarter roll maps y to z, a quarter pitch z to x.
    let roll = rpy_rotation([std::f64::consts::FRAC_PI_2, 0.0, 0.0]);
    assert!((roll * Vector3::y() - Vector3::z()).norm() < 1e-15);
    let pitch = rpy_rotation([0.0, std::f64::consts::FRAC_PI_2, 0.0]);
    assert!((pitch * Vector3::z() - Vector3::x()).norm() < 1e-15);
}

#[test]
fn a_composite_rpy_is_rz_ry_rx_built_by_hand() {
    for rpy in [[0.3, -0.7, 1.9], [-2.5, 1.2, -0.4], [1.0, 0.0, 0.5]] {
        let by_hand = rz(rpy[2]) * ry(rpy[1]) * rx(rpy[0]);
        let ours = rpy_rotation(rpy).to_rotation_matrix().into_inner();
        assert!((ours - by_hand).amax() < 1e-15, "{rpy:?}: {ours} vs {by_hand}");
        // The other order (roll applied last) differs: the check can fail.
        let wrong = rx(rpy[0]) * ry(rpy[1]) * rz(rpy[2]);
        assert!((ours - wrong).amax() > 1e-3);
    }
    // The pose maps child points to parent points: p_parent = R p_child + xyz.
    let iso = pose([1.0, -2.0, 0.5], [0.3, -0.7, 1.9]);
    let p = Point3::new(0.2, 0.4, -0.1);
    let expected = rz(1.9) * ry(-0.7) * rx(0.3) * p.coords + Vector3::new(1.0, -2.0, 0.5);
    assert!(((iso * p).coords - expected).norm() < 1e-15);
}

#[test]
fn joint_origins_compose_through_fixed_joints_in_the_parent_body_frame() {
    // base --fixed (rpy)--> mount --revolute--> arm: the revolute joint's origin in base's frame is the
    // composition of the two origins.
    let (xyz1, rpy1) = ([0.1, 0.2, 0.3], [0.4, -0.2, 1.1]);
    let (xyz2, rpy2) = ([-0.5, 0.05, 0.7], [-1.3, 0.6, 0.25]);
    let text = robot(
        "mount",
        &[
            link("base", 5.0, [0.1, 0.1, 0.1]),
            frame("mount"),
            link("arm", 1.0, [0.01, 0.01, 0.01]),
            joint("base_to_mount", "fixed", "base", "mount", xyz1, rpy1),
            joint("shoulder", "revolute", "mount", "arm", xyz2, rpy2),
        ],
    );
    let model = import(&text);
    let expected = pose(xyz1, rpy1) * pose(xyz2, rpy2);
    let origin = model.joints[0].origin;
    let r_expected = rz(rpy1[2]) * ry(rpy1[1]) * rx(rpy1[0]) * rz(rpy2[2]) * ry(rpy2[1]) * rx(rpy2[0]);
    assert!((origin.rotation.to_rotation_matrix().into_inner() - r_expected).amax() < 1e-15);
    assert!((origin.translation.vector - expected.translation.vector).norm() < 1e-15);
    assert_eq!(model.bodies[0].links[1].name, "mount");
    assert!((model.bodies[0].links[1].pose.translation.vector - Vector3::from(xyz1)).norm() < 1e-15);
}
