//! Compile-fail cases (trybuild): the compile-time CGA ≡ PGA check rejects a wrong coordinate map; a `Body`
//! cannot be written as a struct literal (its fields are private, so every body passed `Body::new`'s checks).

#[test]
fn wrong_screw_map_does_not_compile() {
    trybuild::TestCases::new().compile_fail("tests/ui/wrong_screw_map.rs");
}

#[test]
fn body_struct_literal_does_not_compile() {
    trybuild::TestCases::new().compile_fail("tests/ui/body_literal.rs");
}
