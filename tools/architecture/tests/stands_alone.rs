//! The measuring tools run on a clone with nothing beside it: they read only files the repository carries.

use std::path::{Path, PathBuf};

fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The anchor tools' sources: the wrapper, the runner and the models.
fn anchor_tools() -> Vec<(PathBuf, String)> {
    ["measure", "measure.py", "scenes.py"]
        .iter()
        .map(|name| {
            let path = repository().join("tools/anchors").join(name);
            let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            (path, text)
        })
        .collect()
}

#[test]
fn anchor_tools_read_nothing_outside_the_repository() {
    for (path, text) in anchor_tools() {
        for outside in ["../shared", "reference-set", "example_robot_data", "example-robot-data"] {
            assert!(!text.contains(outside), "{} refers to {outside:?}", path.display());
        }
    }
}

/// Every data file `scenes.py` names (a quoted `*.csv`, `*.json` or `*.urdf`; `{robot}` for each robot it measures)
/// is in `reference/data`.
#[test]
fn every_data_file_the_anchor_models_read_is_in_the_repository() {
    let (_, text) = anchor_tools().pop().expect("scenes.py");
    let data = repository().join("reference/data");
    let mut named = 0;
    for literal in text.split('"').skip(1).step_by(2) {
        if ![".csv", ".json", ".urdf"]
            .iter()
            .any(|extension| literal.ends_with(extension))
        {
            continue;
        }
        for robot in ["ur5", "solo12"] {
            let file = literal.replace("{robot}", robot);
            assert!(
                data.join(&file).is_file() || data.join("robots").join(&file).is_file(),
                "scenes.py reads {file}, which reference/data does not hold"
            );
            named += 1;
        }
    }
    // M1's and M2's references, each robot's facts, trajectory and URDF.
    assert!(
        named >= 2 * 6,
        "only {named} data files found in scenes.py: has its way of naming them changed?"
    );
}
