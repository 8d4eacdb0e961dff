//! `#[derive(serde::Serialize, serde::Deserialize)]` on a declared type: the fields are named after
//! the blades.

ga_macros::algebra! {
    #[allow(dead_code)]
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1];
        types {
            /// A direction.
            #[derive(serde::Serialize, serde::Deserialize)]
            Vector = grades(1);
            #[derive(serde::Serialize, serde::Deserialize)]
            #[serde(deny_unknown_fields)]
            Rotor = blades(scalar, e12, e31, e23);
        }
        ops = [reverse];
    }
}

fn main() {
    let v = vga::Vector { e1: 1.0, e2: -2.5, e3: 0.125 };
    let json = serde_json::to_string(&v).unwrap();
    assert_eq!(json, r#"{"e1":1.0,"e2":-2.5,"e3":0.125}"#);
    assert_eq!(serde_json::from_str::<vga::Vector>(&json).unwrap(), v);

    let r = vga::Rotor::from_array([0.5, 0.5, -0.5, 0.5]);
    let back: vga::Rotor = serde_json::from_str(&serde_json::to_string(&r).unwrap()).unwrap();
    assert_eq!(back, r);
    // The helper attribute reached the struct.
    assert!(serde_json::from_str::<vga::Rotor>(r#"{"scalar":1,"e12":0,"e31":0,"e23":0,"e4":0}"#).is_err());
}
