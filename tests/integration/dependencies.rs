//! What a user of `dynamics` compiles: none of our reference data, and one version of `syn` (two
//! versions of the parser double the proc-macro build time of every user crate).

use std::collections::BTreeSet;
use std::process::Command;

/// `(name, version)` of every package in `dynamics`' normal (non-dev) dependency tree, from `cargo tree`
/// on the locked versions.
fn normal_dependencies_of_dynamics() -> BTreeSet<(String, String)> {
    let output = Command::new(env!("CARGO"))
        .args([
            "tree",
            "--locked",
            "--offline",
            "-p",
            "dynamics",
            "-e",
            "normal",
            "--prefix",
            "none",
        ])
        .args(["--format", "{p}"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("cargo runs");
    assert!(
        output.status.success(),
        "cargo tree failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout)
        .expect("cargo tree prints UTF-8")
        .lines()
        .filter_map(|line| {
            let mut words = line.split_whitespace();
            Some((
                words.next()?.to_owned(),
                words.next()?.trim_start_matches('v').to_owned(),
            ))
        })
        .collect()
}

#[test]
fn dynamics_compiles_no_reference_data_and_one_syn() {
    let packages = normal_dependencies_of_dynamics();
    assert!(
        packages.iter().any(|(name, _)| name == "ga-macros"),
        "the tree was read: {packages:?}"
    );
    for test_data in ["reference", "scenarios", "report"] {
        assert!(
            !packages.iter().any(|(name, _)| name == test_data),
            "dynamics depends on {test_data}"
        );
    }
    let syn_versions: Vec<_> = packages.iter().filter(|(name, _)| name == "syn").collect();
    assert_eq!(
        syn_versions.len(),
        1,
        "syn versions in a user's build: {syn_versions:?}"
    );
}
