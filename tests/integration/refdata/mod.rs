//! Every operation of the reference data (clifford 1.5.1, cross-checked against kingdon 3.0.0 and an
//! independent implementation; see tests/data/README.md) through macro-generated code, in all seven
//! algebras. Integer cases must match exactly, float cases to 1e-12 relative.
//!
//! The reference stores dense coefficients indexed by blade bitmask; `Multivector::BLADES` gives our
//! field order, so each test maps between the two by blade name (the reference calls the scalar `1`).

mod algebras;

use serde_json::Value;

/// An operation of the reference data applied by generated code to dense field arrays.
type Apply<'a> = &'a dyn Fn(&str, &[f64], &[f64]) -> Vec<f64>;

/// Checks every case of every operation in one reference file; returns the number of cases checked.
fn check_file(json: &str, blades: &[&str], apply: Apply) -> usize {
    let data: Value = serde_json::from_str(json).expect("reference JSON parses");
    let reference_blades: Vec<String> = data["blades"]
        .as_array()
        .expect("blades")
        .iter()
        .map(|b| match b.as_str().expect("blade name") {
            "1" => "scalar".to_string(),
            name => name.to_string(),
        })
        .collect();
    // Our field i holds the reference coefficient at index position[i].
    let position: Vec<usize> = blades
        .iter()
        .map(|name| {
            reference_blades
                .iter()
                .position(|b| b == name)
                .unwrap_or_else(|| panic!("blade {name} missing"))
        })
        .collect();
    assert_eq!(
        position.len(),
        reference_blades.len(),
        "the full multivector has every blade"
    );
    let to_fields = |dense: &Value| -> Vec<f64> {
        let dense: Vec<f64> = dense
            .as_array()
            .expect("coefficients")
            .iter()
            .map(|x| x.as_f64().expect("number"))
            .collect();
        position.iter().map(|&p| dense[p]).collect()
    };
    let mut checked = 0;
    let ops = data["ops"].as_object().expect("ops");
    assert_eq!(ops.len(), 14, "all 14 operations are present");
    for (op, spec) in ops {
        for (index, case) in spec["cases"].as_array().expect("cases").iter().enumerate() {
            let a = to_fields(&case["a"]);
            let b = if case["b"].is_null() {
                vec![]
            } else {
                to_fields(&case["b"])
            };
            let expected = to_fields(&case["result"]);
            let got = apply(op, &a, &b);
            let exact = case["values"] == "int";
            let scale = expected.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for (field, (g, e)) in got.iter().zip(&expected).enumerate() {
                let error = (g - e).abs();
                let ok = if exact { error == 0.0 } else { error <= 1e-12 * scale };
                assert!(ok, "{op} case {index}, blade {}: got {g}, expected {e}", blades[field]);
            }
            checked += 1;
        }
    }
    checked
}

/// Declares a test for one reference file against one generated module.
macro_rules! reference_test {
    ($test:ident, $module:ident, $file:literal, dual = $dual:ident) => {
        #[test]
        fn $test() {
            use algebras::$module::*;
            let apply = |op: &str, a: &[f64], b: &[f64]| -> Vec<f64> {
                let a = Multivector::from_array(a.try_into().expect("length"));
                let b = || Multivector::from_array(b.try_into().expect("length"));
                let scalar = |s: f64| {
                    let mut out = Multivector::ZERO;
                    out.scalar = s;
                    out
                };
                let result = match op {
                    "gp" => a.geometric(b()),
                    "op" => a.outer(b()),
                    "lc" => a.left_contraction(b()),
                    "rc" => a.right_contraction(b()),
                    "sp" => scalar(a.scalar_product(b())),
                    "hip" => a.hestenes_inner(b()),
                    "fat_dot" => a.fat_dot(b()),
                    "vee" => a.regressive(b()),
                    "reverse" => a.reverse(),
                    "involute" => a.involute(),
                    "conjugate" => a.conjugate(),
                    "dual" => a.$dual(),
                    "right_complement" => a.right_complement(),
                    "left_complement" => a.left_complement(),
                    other => panic!("unknown reference operation {other}"),
                };
                result.to_array().to_vec()
            };
            let checked = check_file(
                include_str!(concat!("../../data/refdata/", $file)),
                Multivector::BLADES,
                &apply,
            );
            assert_eq!(checked, 14 * 50);
        }
    };
}

reference_test!(vga_cl300, cl300, "cl300.json", dual = polarity);
reference_test!(pga_cl301, cl301, "cl301.json", dual = right_complement);
reference_test!(cga_cl410, cl410, "cl410.json", dual = polarity);
reference_test!(sta_cl130, cl130, "cl130.json", dual = polarity);
reference_test!(cl202, cl202, "cl202.json", dual = right_complement);
reference_test!(cl030, cl030, "cl030.json", dual = polarity);
reference_test!(cl440, cl440, "cl440.json", dual = polarity);
