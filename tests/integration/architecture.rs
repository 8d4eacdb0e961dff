//! The sizes every crate keeps (docs/architecture.md): no hand-written source file over 1200 lines, no function
//! over 200, in the libraries, their tests, benchmarks and examples, and the tools. The module order is each library
//! crate's own test (`tests/integration/module_order.rs`).

#[test]
fn sources_are_small_enough_to_read() {
    architecture::assert_sizes(
        env!("CARGO_MANIFEST_DIR"),
        &[
            "ga-codegen",
            "ga-macros",
            "dynamics",
            "urdf-import",
            "scene-file",
            "reference",
            "scenarios",
            "report",
            "tools",
            "src",
            "tests",
            "examples",
            "benches",
        ],
    );
}
