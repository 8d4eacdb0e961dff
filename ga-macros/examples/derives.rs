//! Declared types in the ecosystem: derives from other crates on the emitted structs (serde,
//! bytemuck) and the opt-in `Display`, `approx` and `mint` impls.
//!
//! Run with `cargo run -p ga-macros --example derives`.

ga_macros::algebra! {
    /// 3D euclidean geometric algebra in `f32`, as a renderer would store it.
    pub mod vga {
        scalar = f32;
        basis = [e1 = 1, e2 = 1, e3 = 1];
        types {
            /// A direction.
            #[derive(serde::Serialize, serde::Deserialize, bytemuck::Pod, bytemuck::Zeroable)]
            Vector = grades(1);
            /// A rotation: the scalar and the three bivectors (a quaternion's four numbers).
            #[derive(serde::Serialize, serde::Deserialize, bytemuck::Pod, bytemuck::Zeroable)]
            #[repr(C, align(16))]
            Rotor = blades(scalar, e12, e13, e23);
        }
        ops = [reverse, transform];
        features = [display, approx, mint];
    }
}

use vga::Transform as _;

fn main() {
    // A sixth of a turn about the z axis: cos(θ/2) − sin(θ/2) e12 turns e1 towards e2 by θ.
    let half = std::f32::consts::PI / 6.0;
    let rotor = vga::Rotor {
        scalar: half.cos(),
        e12: -half.sin(),
        ..vga::Rotor::ZERO
    };
    let x = vga::Vector {
        e1: 1.0,
        e2: 0.0,
        e3: 0.0,
    };
    let turned = rotor.transform(x);
    println!("rotor:  {rotor:.4}");
    println!("turned: {turned:.4}");
    approx::assert_relative_eq!(
        turned,
        vga::Vector {
            e1: 0.5,
            e2: 0.75_f32.sqrt(),
            e3: 0.0
        },
        epsilon = 1e-6
    );

    // serde: the fields are named after the blades.
    let json = serde_json::to_string(&rotor).unwrap();
    println!("JSON:   {json}");
    assert_eq!(serde_json::from_str::<vga::Rotor>(&json).unwrap(), rotor);

    // bytemuck: a slice of rotors is a slice of floats (16-byte aligned, no padding).
    let rotors = [rotor, rotor.reverse()];
    let floats: &[f32] = bytemuck::cast_slice(&rotors);
    println!("floats: {floats:?}");
    assert_eq!(floats.len(), 8);

    // mint: the same rotation as a quaternion, for libraries that take `mint` types.
    let quaternion: mint::Quaternion<f32> = rotor.into();
    println!(
        "quaternion: s = {:.4}, v = ({:.4}, {:.4}, {:.4})",
        quaternion.s, quaternion.v.x, quaternion.v.y, quaternion.v.z
    );
    assert_eq!(vga::Rotor::from(quaternion), rotor);
}
