//! This crate keeps its own rules.

#[test]
fn modules_refer_only_to_earlier_modules() {
    architecture::assert_modules_in_order(env!("CARGO_MANIFEST_DIR"));
}
