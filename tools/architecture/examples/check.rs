//! Prints each rule's violations for the crates named on the command line (folders relative to the workspace
//! root; folders that are no library crate get the size checks alone), and the sizes over the limits in them: `cargo run -p architecture --example check -- dynamics report`.

use std::path::Path;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap();
    let crates: Vec<String> = std::env::args().skip(1).collect();
    for name in &crates {
        let directory = root.join(name);
        if !directory.join("src/lib.rs").exists() {
            continue;
        }
        let violations = architecture::order::order_violations(&directory);
        println!("{name}: {} modules refer forward", violations.len());
        println!("  order: {}", architecture::order::module_order(&directory).join(" "));
        for line in violations {
            println!("  {line}");
        }
    }
    let directories: Vec<&str> = crates.iter().map(String::as_str).collect();
    for line in architecture::sizes::size_violations(&root, &directories) {
        println!("{line}");
    }
}
