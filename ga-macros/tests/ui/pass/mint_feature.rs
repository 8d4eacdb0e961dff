//! `features = [mint]`: a vector of three orthonormal grade-1 blades converts to and from
//! `mint::Vector3`, a rotor `scalar, e12, e13, e23` to and from `mint::Quaternion` such that the
//! rotor's `transform` and the quaternion's `q v q*` rotate alike. Other types get no conversion.

ga_macros::algebra! {
    #[allow(dead_code)]
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1];
        types {
            Vector = grades(1);
            Rotor = blades(scalar, e23, e31, e12);
            Bivector = grades(2);
        }
        ops = [reverse, transform];
        features = [mint];
    }
}

use vga::Transform as _;

/// `q v q*` for a Hamilton quaternion: v + 2 q.v × (q.v × v + s v).
fn rotate(q: mint::Quaternion<f64>, v: mint::Vector3<f64>) -> mint::Vector3<f64> {
    let cross = |a: [f64; 3], b: [f64; 3]| [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    let (u, x) = ([q.v.x, q.v.y, q.v.z], [v.x, v.y, v.z]);
    let inner = cross(u, x);
    let t = cross(u, [inner[0] + q.s * x[0], inner[1] + q.s * x[1], inner[2] + q.s * x[2]]);
    mint::Vector3 { x: x[0] + 2.0 * t[0], y: x[1] + 2.0 * t[1], z: x[2] + 2.0 * t[2] }
}

fn close(a: mint::Vector3<f64>, b: mint::Vector3<f64>) -> bool {
    (a.x - b.x).abs() < 1e-12 && (a.y - b.y).abs() < 1e-12 && (a.z - b.z).abs() < 1e-12
}

fn main() {
    let v = vga::Vector { e1: 1.0, e2: 2.0, e3: 3.0 };
    let m: mint::Vector3<f64> = v.into();
    assert_eq!((m.x, m.y, m.z), (1.0, 2.0, 3.0));
    assert_eq!(vga::Vector::from(m), v);

    // A turn by 0.7 rad about the unit axis (2, 3, 6)/7, as a quaternion.
    let (half, axis) = (0.35_f64, [2.0 / 7.0, 3.0 / 7.0, 6.0 / 7.0]);
    let q = mint::Quaternion {
        v: mint::Vector3 { x: half.sin() * axis[0], y: half.sin() * axis[1], z: half.sin() * axis[2] },
        s: half.cos(),
    };
    let r = vga::Rotor::from(q);
    let back: mint::Quaternion<f64> = r.into();
    assert_eq!((back.s, back.v.x, back.v.y, back.v.z), (q.s, q.v.x, q.v.y, q.v.z));
    assert!(close(r.transform(v).into(), rotate(q, v.into())));
    // A quarter turn about z takes e1 to e2, as cos(π/4) − sin(π/4) e12 does.
    let quarter = std::f64::consts::FRAC_PI_4;
    let z = vga::Rotor::from(mint::Quaternion { v: mint::Vector3 { x: 0.0, y: 0.0, z: quarter.sin() }, s: quarter.cos() });
    assert_eq!((z.scalar, z.e12), (quarter.cos(), -quarter.sin()));
    assert!(close(z.transform(vga::Vector { e1: 1.0, e2: 0.0, e3: 0.0 }).into(), mint::Vector3 { x: 0.0, y: 1.0, z: 0.0 }));

    // The mint trait that names each type's mint type.
    fn mint_of<T: mint::IntoMint>(value: T) -> T::MintType {
        value.into()
    }
    assert_eq!(mint_of(v), m);
}
