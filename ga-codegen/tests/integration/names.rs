//! Names and sizes the compiler must refuse (or accept) before emitting anything: every error is
//! returned by `generate` (never a panic, never code rustc rejects) with the location of its token.
use crate::common;

use std::time::{Duration, Instant};

use ga_codegen::algebra::{MAX_FULL_MULTIVECTOR_DIMENSION, MAX_TYPE_FIELDS};
use ga_codegen::{
    generate, Algebra, AlgebraDeclaration, Error, Layout, Location, NameProblem, Operation, ScalarType, TypeDeclaration,
};

/// `types` over an orthonormal basis with these names, every operation emitted.
fn declaration(basis: &[&str], types: Vec<TypeDeclaration>) -> AlgebraDeclaration {
    let squares: Vec<(&str, i64)> = basis.iter().map(|&name| (name, 1)).collect();
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: common::basis(&squares),
        metric: None,
        types,
        operations: None,
        lowering: vec![],
        expressions: vec![],
    }
}

/// A vector type named `name` and the full multivector (so that every result has a type).
fn named(name: &str) -> AlgebraDeclaration {
    declaration(
        &["e1", "e2"],
        vec![common::grades(name, &[1]), common::grades("Multivector", &[0, 1, 2])],
    )
}

fn refused(declaration: &AlgebraDeclaration) -> Error {
    let error = generate(declaration).expect_err("the declaration must be refused");
    assert_eq!(
        Algebra::new(declaration).err(),
        Some(error.clone()),
        "generate and Algebra::new agree"
    );
    error
}

/// The emitted code of an accepted declaration parses as Rust.
fn accepted(declaration: &AlgebraDeclaration) -> String {
    let tokens = generate(declaration).unwrap();
    ga_codegen::pretty(&tokens).unwrap()
}

#[test]
fn type_names_must_be_plain_identifiers() {
    for (name, problem) in [
        ("r#type", NameProblem::Raw),
        ("r#Motor", NameProblem::Raw),
        ("fn", NameProblem::Keyword),
        ("Self", NameProblem::Keyword),
        ("gen", NameProblem::Keyword),
        ("", NameProblem::NotAnIdentifier),
        ("Two Words", NameProblem::NotAnIdentifier),
        ("3D", NameProblem::NotAnIdentifier),
        ("Motor<T>", NameProblem::NotAnIdentifier),
    ] {
        let error = refused(&named(name));
        assert_eq!(
            error,
            Error::InvalidTypeName {
                index: 0,
                name: name.to_string(),
                problem
            }
        );
        assert_eq!(error.location(), Location::Type(0));
    }
    assert_eq!(refused(&named("fn")).to_string(), "type name `fn` is a Rust keyword");
    assert_eq!(
        refused(&named("r#type")).to_string(),
        "type name `r#type` is a raw identifier, which is not supported here: choose a name that needs no `r#`"
    );
}

#[test]
fn basis_and_blade_names_must_be_plain_identifiers() {
    let error = refused(&declaration(&["e1", "r#e2"], vec![common::grades("Vector", &[1])]));
    assert_eq!(
        error,
        Error::InvalidBasisName {
            index: 1,
            name: "r#e2".to_string(),
            problem: NameProblem::Raw
        }
    );
    assert_eq!(error.location(), Location::Basis(1));
    assert!(matches!(
        Algebra::new(&declaration(&["e1", "self"], vec![common::grades("Vector", &[1])])),
        Err(Error::InvalidBasisName {
            problem: NameProblem::Keyword,
            ..
        })
    ));
    // `for` is the blade `fo` ∧ `fr` written in another order (its canonical name is `fro`).
    let permuted_keyword = declaration(&["fr", "fo"], vec![common::blades("Pair", &["fro", "for"])]);
    let error = refused(&permuted_keyword);
    assert_eq!(error.location(), Location::TypeItem { ty: 0, item: 1 });
    assert_eq!(error.to_string(), "blade name `for` in type `Pair` is a Rust keyword");
}

#[test]
fn unicode_identifiers_are_accepted() {
    let source = accepted(&declaration(
        &["α", "β"],
        vec![
            common::grades("Vecteur", &[1]),
            common::grades("Rotor", &[0, 2]),
            common::grades("Ω", &[0, 1, 2]),
        ],
    ));
    assert!(source.contains("pub α_β: f64"), "{source}");
    assert!(
        source.contains("pub const fn geometric_ω(self, rhs: Ω) -> Ω"),
        "{source}"
    );
}

#[test]
fn a_type_may_have_at_most_1024_fields() {
    assert_eq!(MAX_TYPE_FIELDS, 1 << MAX_FULL_MULTIVECTOR_DIMENSION);
    let names: Vec<String> = (0..32).map(|i| format!("e{i}")).collect();
    let basis: Vec<&str> = names.iter().map(String::as_str).collect();
    // 601 080 390 blades: refused from their count, without listing them.
    let start = Instant::now();
    let error = refused(&declaration(&basis, vec![common::grades("Middle", &[16])]));
    assert!(start.elapsed() < Duration::from_secs(2), "took {:?}", start.elapsed());
    assert_eq!(
        error,
        Error::TooManyFields {
            ty_index: 0,
            ty: "Middle".to_string(),
            fields: 601_080_390,
            max: 1024,
            max_dimension: 10
        }
    );
    assert_eq!(error.location(), Location::Type(0));
    assert_eq!(
        error.to_string(),
        "type `Middle` would have 601080390 fields; a declared type may have at most 1024 \
         (a full multivector in 10 dimensions): declare fewer grades or blades"
    );
    // Every grade of 32 dimensions: 2³² fields, counted exactly.
    let all_grades: Vec<u32> = (0..=32).collect();
    assert!(matches!(
        Algebra::new(&declaration(&basis, vec![common::grades("Everything", &all_grades)])),
        Err(Error::TooManyFields {
            fields: 4_294_967_296,
            ..
        })
    ));

    // 11 dimensions: every grade is the 2048 blades `all` is refused for.
    let every_grade: Vec<u32> = (0..=11).collect();
    let error = refused(&declaration(
        &basis[..11],
        vec![common::grades("Vector", &[1]), common::grades("Full", &every_grade)],
    ));
    assert!(
        matches!(
            error,
            Error::TooManyFields {
                ty_index: 1,
                fields: 2048,
                ..
            }
        ),
        "{error:?}"
    );
    // 10 dimensions: every grade is 1024 fields, allowed (validated only: emitting takes half a minute).
    let every_grade: Vec<u32> = (0..=10).collect();
    let algebra = Algebra::new(&declaration(&basis[..10], vec![common::grades("Full", &every_grade)])).unwrap();
    assert_eq!(algebra.types[0].fields.len(), 1024);
    // Listed blades count too.
    let many: Vec<&str> = std::iter::repeat_n("e0", MAX_TYPE_FIELDS + 1).collect();
    assert!(matches!(
        Algebra::new(&declaration(&basis, vec![common::blades("Listed", &many)])),
        Err(Error::TooManyFields { fields: 1025, .. })
    ));
}

#[test]
fn a_basis_vector_name_must_not_read_as_a_blade_of_others() {
    let error = refused(&declaration(&["x", "y", "x_y"], vec![common::grades("Vector", &[1])]));
    assert_eq!(
        error,
        Error::SeparatorInBasisName {
            index: 2,
            name: "x_y".to_string(),
            clash: Some(vec!["x".to_string(), "y".to_string()])
        }
    );
    assert_eq!(error.location(), Location::Basis(2));
    assert_eq!(
        error.to_string(),
        "basis vector name `x_y` contains `_`, which joins the names of basis vectors into blade names in this \
         basis, so `x_y` would also name the blade `x` ∧ `y`: name the basis vectors without `_`"
    );
    // Written in the other order, it would still be ambiguous in `blades(…)`.
    assert!(matches!(
        Algebra::new(&declaration(&["x", "y", "y_x"], vec![])),
        Err(Error::SeparatorInBasisName {
            index: 2,
            clash: Some(_),
            ..
        })
    ));
    // No blade reads `n_0` today, but `n_0` ∧ `n_inf` would be `n_0__inf`, whose pieces are not names.
    let error = refused(&declaration(
        &["e1", "n_0", "n_inf"],
        vec![common::grades("Vector", &[1])],
    ));
    assert_eq!(
        error.to_string(),
        "basis vector name `n_0` contains `_`, which joins the names of basis vectors into blade names in this \
         basis, so a blade name could be read in more than one way: name the basis vectors without `_`"
    );
    // Where nothing is joined with `_`, a `_` is harmless: `e_` and `e1` give `e_1`, `x_y` alone nothing.
    accepted(&declaration(
        &["e_", "e1"],
        vec![
            common::grades("Vector", &[1]),
            common::grades("Multivector", &[0, 1, 2]),
        ],
    ));
    accepted(&declaration(
        &["x_y"],
        vec![common::grades("Vector", &[1]), common::grades("Multivector", &[0, 1])],
    ));
}

#[test]
fn no_blade_may_be_called_scalar_or_a_keyword() {
    let error = refused(&declaration(&["e1", "scalar"], vec![common::grades("Vector", &[1])]));
    assert_eq!(
        error,
        Error::ScalarBladeName {
            index: 1,
            factors: vec!["scalar".to_string()]
        }
    );
    assert_eq!(error.location(), Location::Basis(1));
    assert_eq!(
        error.to_string(),
        "`scalar` names the grade-0 blade, so it cannot also name the basis vector `scalar`: rename it"
    );
    // `scal` + `a` + `r`.
    let error = refused(&declaration(&["scala", "scalr"], vec![common::grades("Vector", &[1])]));
    assert_eq!(error.location(), Location::Basis(1));
    assert_eq!(
        error.to_string(),
        "`scalar` names the grade-0 blade, so it cannot also name the blade `scala` ∧ `scalr`: \
         rename basis vector `scalr`"
    );
    // `f` + `o` + `r`.
    let error = refused(&declaration(&["fo", "fr", "fx"], vec![common::grades("Vector", &[1])]));
    assert_eq!(
        error,
        Error::KeywordBladeName {
            index: 1,
            blade: "for".to_string(),
            factors: vec!["fo".to_string(), "fr".to_string()]
        }
    );
    assert_eq!(
        error.to_string(),
        "the blade `fo` ∧ `fr` would be named `for`, a Rust keyword, which cannot name its field: \
         rename basis vector `fr`"
    );
}

#[test]
fn type_names_the_module_uses_are_refused() {
    for (name, clash) in [
        (
            "Geometric",
            "the trait `Geometric` the module defines for the `geometric` operation",
        ),
        (
            "Sandwich",
            "the trait `Sandwich` the module defines for the `sandwich` operation",
        ),
        (
            "LeftContraction",
            "the trait `LeftContraction` the module defines for the `left_contraction` operation",
        ),
        (
            "From",
            "`From`, the conversion trait the module implements between its types",
        ),
        (
            "core",
            "`core`, the crate the module names its operator traits by (`core::ops::Add`)",
        ),
        ("str", "`str`, the type of the blade names in each type's `BLADES`"),
        ("f64", "`f64`, the scalar type of every coefficient"),
    ] {
        let error = refused(&named(name));
        assert_eq!(
            error,
            Error::ReservedTypeName {
                index: 0,
                name: name.to_string(),
                clash: clash.to_string()
            }
        );
        assert_eq!(error.location(), Location::Type(0));
        assert_eq!(
            error.to_string(),
            format!("type name `{name}` clashes with {clash}: rename the type")
        );
    }
    // std names the emitted code qualifies (or only derives) are free, and so are the traits of
    // operations not emitted.
    for name in [
        "Add", "Mul", "Neg", "Into", "Default", "Clone", "Debug", "Output", "Rhs", "f32",
    ] {
        accepted(&named(name));
    }
    let mut only_outer = named("Geometric");
    only_outer.operations = Some(vec![Operation::Outer, Operation::Reverse]);
    accepted(&only_outer);
}

#[test]
fn type_names_must_differ_in_snake_case() {
    let mut declaration = named("FooBar");
    declaration.types.push(TypeDeclaration {
        name: "Foo_bar".to_string(),
        layout: Layout::Grades(vec![0]),
    });
    let error = refused(&declaration);
    assert_eq!(
        error,
        Error::TypeMethodCollision {
            index: 2,
            name: "Foo_bar".to_string(),
            other: "FooBar".to_string(),
            method_suffix: "foo_bar".to_string(),
            operation: "geometric".to_string()
        }
    );
    assert_eq!(error.location(), Location::Type(2));
    assert_eq!(
        error.to_string(),
        "types `FooBar` and `Foo_bar` would both give methods named `geometric_foo_bar` (the `const fn` form of \
         `geometric` with that type on the right): both names are `foo_bar` in snake case; rename one of them"
    );
    // Without binary operations there are no such methods.
    declaration.operations = Some(vec![Operation::Reverse]);
    accepted(&declaration);
}
