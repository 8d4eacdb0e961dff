//! Compile-fail cases (trybuild): the compile-time CGA ≡ PGA check rejects a wrong coordinate map.

#[test]
fn wrong_screw_map_does_not_compile() {
    trybuild::TestCases::new().compile_fail("tests/ui/wrong_screw_map.rs");
}
