//! Which products are unrolled and which are tabled, and the checks on a declared lowering.
use crate::common;

use ga_codegen::functions::{self, Code};
use ga_codegen::table::{MAX_UNROLLED_LOCALS, MAX_UNROLLED_TERMS};
use ga_codegen::{
    Algebra, AlgebraDeclaration, Error, Evaluator, Layout, Location, Lowering, Operation, TypeDeclaration,
};

fn cl51(lowering: Vec<(Operation, Lowering)>) -> AlgebraDeclaration {
    let basis: Vec<(String, i64)> = (1..=6).map(|i| (format!("e{i}"), if i < 6 { 1 } else { -1 })).collect();
    let basis: Vec<(&str, i64)> = basis.iter().map(|(n, s)| (n.as_str(), *s)).collect();
    AlgebraDeclaration {
        scalar: ga_codegen::ScalarType::F64,
        basis: common::basis(&basis),
        metric: None,
        types: vec![TypeDeclaration {
            name: "Multivector".into(),
            layout: Layout::All,
        }],
        operations: Some(vec![Operation::Geometric, Operation::Sandwich, Operation::Reverse]),
        lowering,
        expressions: vec![],
    }
}

#[test]
fn big_products_are_tabled_and_small_ones_unrolled() {
    let algebra = Algebra::new(&cl51(vec![])).unwrap();
    // 64 × 64 = 4096 monomials: unrolled.
    let geometric = functions::binary(&algebra, Operation::Geometric, 0, 0).unwrap();
    const { assert!(4096 <= MAX_UNROLLED_TERMS) };
    assert!(matches!(geometric.code, Code::Unrolled(_)));
    assert_eq!((geometric.cost.multiplies, geometric.cost.adds), (4096, 4032));
    // The sandwich: far beyond the limit; two stages of 64 × 64 products.
    let sandwich = functions::binary(&algebra, Operation::Sandwich, 0, 0).unwrap();
    let Code::Table(table) = &sandwich.code else {
        panic!("the full Cl(5,1) sandwich is tabled")
    };
    assert_eq!(table.stages.len(), 2);
    assert_eq!(table.entries(), 2 * 4096);
    assert_eq!((sandwich.cost.multiplies, sandwich.cost.adds), (4 * 4096, 2 * 4096));
    // Declared unrolled, it is (with thousands of hoisted locals: what used to overflow rustc in debug).
    let unrolled = Algebra::new(&cl51(vec![(Operation::Sandwich, Lowering::Unrolled)])).unwrap();
    let sandwich = functions::binary(&unrolled, Operation::Sandwich, 0, 0).unwrap();
    let Code::Unrolled(program) = &sandwich.code else {
        panic!("declared unrolled")
    };
    assert!(program.locals.len() > MAX_UNROLLED_LOCALS);
    // The figures the docs quote (ga_codegen::table, the algebra! docs).
    let expansion = ga_codegen::expand::sandwich(&algebra, &algebra.types[0], &algebra.types[0]);
    assert_eq!((expansion.term_count(), program.locals.len()), (68_608, 4223));
}

#[test]
fn declared_lowerings_are_checked() {
    let error = |lowering| Algebra::new(&cl51(lowering)).unwrap_err();
    let unary = error(vec![(Operation::Reverse, Lowering::Table)]);
    assert!(matches!(unary, Error::LoweringOfUnary { index: 0, .. }), "{unary}");
    let missing = error(vec![
        (Operation::Geometric, Lowering::Table),
        (Operation::Outer, Lowering::Table),
    ]);
    assert!(
        matches!(missing, Error::LoweringNotEmitted { index: 1, .. }),
        "{missing}"
    );
    assert_eq!(missing.location(), Location::Lowering(1));
    let twice = error(vec![
        (Operation::Sandwich, Lowering::Table),
        (Operation::Sandwich, Lowering::Unrolled),
    ]);
    assert!(matches!(twice, Error::DuplicateLowering { index: 1, .. }), "{twice}");
    assert_eq!(twice.to_string(), "the lowering of `sandwich` is chosen twice");
}

#[test]
fn tabled_code_states_its_lowering_in_its_doc() {
    let mut declaration = cl51(vec![]);
    declaration.operations = Some(vec![Operation::Sandwich]);
    let code = ga_codegen::pretty(&ga_codegen::generate(&declaration).unwrap()).unwrap();
    assert!(code.contains("Table-driven: 8192 products in two stages"));
    assert!(code.contains("pub const fn sandwich_multivector"));
}

/// The biggest sandwich a declaration can ask for (full multivectors in 10 dimensions: 2³⁰ products) is
/// tabled without the exact expansion, and still equals the evaluator.
#[test]
fn sandwiches_too_big_to_expand_are_tabled_by_reach() {
    let names: Vec<String> = (1..=10).map(|i| format!("e{i}")).collect();
    let squares: Vec<i64> = (0..10).map(|i| if i < 7 { 1 } else { -1 }).collect();
    let basis: Vec<(&str, i64)> = names.iter().map(String::as_str).zip(squares.iter().copied()).collect();
    let declaration = |lowering| AlgebraDeclaration {
        scalar: ga_codegen::ScalarType::F64,
        basis: common::basis(&basis),
        metric: None,
        types: vec![TypeDeclaration {
            name: "Multivector".into(),
            layout: Layout::All,
        }],
        operations: Some(vec![Operation::Sandwich]),
        lowering,
        expressions: vec![],
    };
    let algebra = Algebra::new(&declaration(vec![])).unwrap();
    let sandwich = functions::binary(&algebra, Operation::Sandwich, 0, 0).unwrap();
    let Code::Table(table) = &sandwich.code else {
        panic!("tabled")
    };
    assert_eq!(table.entries(), 2 << 20);
    // Sparse operands (a few blades each), exact in integers.
    let mut a = vec![0.0; 1024];
    let mut x = vec![0.0; 1024];
    for (k, blade) in [0usize, 3, 96, 517, 1023].into_iter().enumerate() {
        a[blade] = k as f64 - 2.0;
        x[(blade * 7 + 5) % 1024] = 3.0 - k as f64;
    }
    // `Layout::All` stores blades in canonical order (grade, then lexicographic): map to masks.
    let masks: Vec<usize> = algebra.types[0].fields.iter().map(|f| f.blade as usize).collect();
    let to_fields = |dense: &[f64]| masks.iter().map(|&m| dense[m]).collect::<Vec<f64>>();
    let got = sandwich.code.evaluate(&to_fields(&a), &to_fields(&x));
    let expected = Evaluator::of(&algebra).binary(Operation::Sandwich, &a, &x).unwrap();
    for (blade, value) in expected.iter().enumerate() {
        assert_eq!(
            got.get(&(blade as u32)).copied().unwrap_or(0.0),
            *value,
            "blade {blade:b}"
        );
    }
    // Declared unrolled, it is refused at its lowering.
    let error = Algebra::new(&declaration(vec![(Operation::Sandwich, Lowering::Unrolled)]))
        .and_then(|algebra| functions::binary(&algebra, Operation::Sandwich, 0, 0))
        .unwrap_err();
    assert!(
        matches!(
            error,
            Error::TooBigToUnroll {
                index: 0,
                products: 1_073_741_824,
                ..
            }
        ),
        "{error}"
    );
}

/// A stage's entries survive their encoding as bytes, in both index widths: `u16` while every index fits, `u32`
/// once one (here an output position of a stage reaching 70 000 blades) does not.
#[test]
fn encoded_tables_read_back_as_their_entries() {
    use ga_codegen::table::{EncodedStage, Entry, Source, Stage};
    use num_rational::Rational64;
    let stage = |largest_output: usize| Stage {
        left: Source::Lhs,
        right: Source::Rhs,
        blades: (0..=largest_output as u32).collect(),
        entries: [(3, 1, 0, -2), (0, 0, 7, 1), (1023, 2, largest_output, -2)]
            .map(|(left, right, output, c)| Entry {
                left,
                right,
                output,
                coefficient: Rational64::new(c, 3),
            })
            .to_vec(),
    };
    for (largest_output, width) in [(65_534, 2), (70_000, 4)] {
        let stage = stage(largest_output);
        let encoded = EncodedStage::new(&stage);
        assert_eq!(encoded.width, width);
        assert_eq!(encoded.bytes.len(), 3 * 4 * width);
        assert_eq!(encoded.coefficients, [Rational64::new(-2, 3), Rational64::new(1, 3)]);
        let read: Vec<[usize; 4]> = encoded.entries().collect();
        assert_eq!(read, [[3, 1, 0, 0], [0, 0, 7, 1], [1023, 2, largest_output, 0]]);
    }
    // Many distinct coefficients (a general metric's), each used twice: every entry reads back its own.
    let coefficients: Vec<Rational64> = (1..=40).map(|n| Rational64::new(n, 7)).collect();
    let many = Stage {
        left: Source::Lhs,
        right: Source::Rhs,
        blades: vec![0],
        entries: (0..80)
            .map(|e| Entry {
                left: e,
                right: 0,
                output: 0,
                coefficient: coefficients[e % 40],
            })
            .collect(),
    };
    let encoded = EncodedStage::new(&many);
    assert_eq!(encoded.coefficients, coefficients);
    for (e, [i, _, _, n]) in encoded.entries().enumerate() {
        assert_eq!((i, encoded.coefficients[n]), (e, coefficients[e % 40]));
    }
}

/// Keeping some outputs of a tabled sandwich (a transform keeps the operand's grades) gives the table built for
/// those outputs alone.
#[test]
fn a_table_keeping_some_outputs_is_the_table_built_for_them() {
    use ga_codegen::table::Table;
    let algebra = Algebra::new(&cl51(vec![])).unwrap();
    let full = &algebra.types[0];
    let whole = Table::sandwich(&algebra, full, full, None);
    let odd: Vec<u32> = whole
        .output_blades()
        .iter()
        .copied()
        .filter(|b| b.count_ones() % 2 == 1)
        .rev()
        .collect();
    assert_eq!(odd.len(), 32);
    let kept = whole.clone().keeping(&odd);
    assert_eq!(kept, Table::sandwich(&algebra, full, full, Some(&odd)));
    assert!(kept.entries() < whole.entries());
}

/// A declaration whose functions take more build work than the limit is refused at the type whose function
/// crossed it; the work counts a table entry once and an unrolled multiply `UNROLLED_MULTIPLY_WORK` times.
#[test]
fn declarations_beyond_the_build_work_limit_are_refused() {
    use ga_codegen::functions::{MAX_BUILD_WORK, UNROLLED_MULTIPLY_WORK};
    let algebra = Algebra::new(&cl51(vec![(Operation::Sandwich, Lowering::Table)])).unwrap();
    let geometric = functions::binary(&algebra, Operation::Geometric, 0, 0).unwrap();
    assert!(matches!(geometric.code, Code::Unrolled(_)));
    assert_eq!(geometric.build_work(), UNROLLED_MULTIPLY_WORK * 4096);
    let sandwich = functions::binary(&algebra, Operation::Sandwich, 0, 0).unwrap();
    let Code::Table(table) = &sandwich.code else {
        panic!("declared tabled")
    };
    assert_eq!(sandwich.build_work(), table.entries());
    // Every function of the declaration: reverse, the sum and difference, the geometric product, the sandwich.
    let reverse = &functions::unary(&algebra, Operation::Reverse, 0).unwrap()[0];
    let sums: usize = [false, true]
        .into_iter()
        .filter_map(|subtract| functions::sum(&algebra, 0, 0, subtract))
        .map(|f| f.build_work())
        .sum();
    let total = reverse.build_work() + sums + geometric.build_work() + sandwich.build_work();
    assert!(ga_codegen::emit::emit_within(&algebra, total).is_ok());
    let error = ga_codegen::emit::emit_within(&algebra, total - 1).unwrap_err();
    assert_eq!(
        error,
        Error::TooMuchCode {
            ty_index: 0,
            ty: "Multivector".into(),
            work: total,
            limit: total - 1,
            unrolled_multiply: UNROLLED_MULTIPLY_WORK,
        }
    );
    assert_eq!(error.location(), Location::Type(0));
    assert!(
        error.to_string().contains("declare only the operations you use"),
        "{error}"
    );
    assert!(total < MAX_BUILD_WORK);
    // No work allowed: the reverse (sign flips, no arithmetic) passes, the first sum is refused; any declaration
    // fits under usize::MAX.
    assert_eq!(reverse.build_work(), 0);
    assert!(matches!(
        ga_codegen::emit::emit_within(&algebra, 0),
        Err(Error::TooMuchCode { work, limit: 0, .. }) if work > 0 && work < total
    ));
    assert!(ga_codegen::emit::emit_within(&algebra, usize::MAX).is_ok());
}
