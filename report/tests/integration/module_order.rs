//! The modules of report read one way, in the order `src/lib.rs` declares them (the shared machinery, the families, the
//! scene job, the job and its command line): each refers only to modules before it, so that every part can be read
//! knowing only the parts before it (docs/architecture.md).

#[test]
fn modules_refer_only_to_earlier_modules() {
    architecture::assert_modules_in_order(env!("CARGO_MANIFEST_DIR"));
}
