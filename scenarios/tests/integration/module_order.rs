//! The modules of scenarios read one way, in the order `src/lib.rs` declares them: each refers only to modules
//! before it, so that every module can be read knowing only the modules before it (docs/architecture.md).

#[test]
fn modules_refer_only_to_earlier_modules() {
    architecture::assert_modules_in_order(env!("CARGO_MANIFEST_DIR"));
}
