//! The modules of scene-file read one way, in the pipeline order `src/lib.rs` declares them (error, names, then the
//! stages: syntax, check, build, and the scene that runs them): each refers only to modules before it, so that every
//! stage can be read knowing only the stages before it (docs/architecture.md).

#[test]
fn modules_refer_only_to_earlier_modules() {
    architecture::assert_modules_in_order(env!("CARGO_MANIFEST_DIR"));
}
