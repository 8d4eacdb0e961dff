//! The macro's diagnostics, as the user sees them: each `tests/ui/*.rs` must fail to compile with
//! the errors in its `.stderr`; each `tests/ui/pass/*.rs` must compile.

#[test]
fn ui() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/ui/*.rs");
    cases.pass("tests/ui/pass/*.rs");
}
