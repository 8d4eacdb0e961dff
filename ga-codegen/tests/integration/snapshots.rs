//! Snapshots of the formatted expansion of key products: review a diff here like code.
use crate::common;

use ga_codegen::{emit, functions, Algebra, Operation};

/// The formatted code of `lhs.operation(rhs)` alone.
fn function_source(declaration: &ga_codegen::AlgebraDeclaration, operation: Operation, lhs: &str, rhs: &str) -> String {
    let mut declaration = declaration.clone();
    declaration.operations = Some(vec![operation]);
    let algebra = Algebra::new(&declaration).unwrap();
    let index = |name: &str| algebra.types.iter().position(|t| t.name == name).unwrap();
    let function = functions::binary(&algebra, operation, index(lhs), index(rhs)).unwrap();
    ga_codegen::pretty(&emit::binary_function(&algebra, &function)).unwrap()
}

#[test]
fn pga_motor_times_motor() {
    insta::assert_snapshot!(function_source(&common::pga(), Operation::Geometric, "Motor", "Motor"));
}

#[test]
fn pga_motor_sandwich_point() {
    insta::assert_snapshot!(function_source(&common::pga(), Operation::Sandwich, "Motor", "Point"));
}

/// DCGA's polar of a torus at a point of the second copy, `w ⌋ T` (`dynamics::surfaces::dcga`): a first-copy
/// vector, each coefficient a short sum, the null pairs' −1 carried as signs.
#[test]
fn dcga_polar_of_a_turned_torus() {
    insta::assert_snapshot!(function_source(
        &common::dcga(),
        Operation::LeftContraction,
        "Second",
        "Turned"
    ));
}

#[test]
fn cga_even_times_even() {
    insta::assert_snapshot!(function_source(&common::cga(), Operation::Geometric, "Even", "Even"));
}

#[test]
fn pga_motor_transform_point() {
    insta::assert_snapshot!(function_source(&common::pga(), Operation::Transform, "Motor", "Point"));
}

/// The same sandwich lowered to tables (two stages of products and loops), as big products are.
#[test]
fn pga_motor_sandwich_point_by_tables() {
    let mut declaration = common::pga();
    declaration.lowering = vec![(Operation::Sandwich, ga_codegen::Lowering::Table)];
    insta::assert_snapshot!(function_source(&declaration, Operation::Sandwich, "Motor", "Point"));
}

#[test]
fn null_cga_motor_times_motor() {
    insta::assert_snapshot!(function_source(
        &common::null_cga(),
        Operation::Geometric,
        "Motor",
        "Motor"
    ));
}

/// The opt-in impls (`Display`, `approx`, `mint`) of a vector and a rotor with permuted blade names.
#[test]
fn vga_features() {
    let declaration = ga_codegen::AlgebraDeclaration {
        scalar: ga_codegen::ScalarType::F32,
        basis: common::basis(&[("e1", 1), ("e2", 1), ("e3", 1)]),
        metric: None,
        types: vec![
            common::grades("Vector", &[1]),
            common::blades("Rotor", &["scalar", "e23", "e31", "e12"]),
        ],
        operations: Some(vec![]),
        lowering: vec![],
        expressions: vec![],
    };
    let algebra = Algebra::new(&declaration).unwrap();
    let features = ga_codegen::features::emit(&algebra, &ga_codegen::Feature::ALL);
    insta::assert_snapshot!(ga_codegen::pretty(&features).unwrap());
}

/// A fused expression, `moved_line(m: Motor, l: Line) = m * l * ~m`: the 36 entries of the motor's line
/// map as locals shared by the six outputs.
#[test]
fn pga_fused_moved_line() {
    use ga_codegen::expression::{Expression, ExpressionKind, Parameter};
    let name = |n: &str| Box::new(Expression::new(ExpressionKind::Parameter(n.into())));
    let product = |a, b| Box::new(Expression::new(ExpressionKind::Binary(Operation::Geometric, a, b)));
    let reverse = Box::new(Expression::new(ExpressionKind::Unary(Operation::Reverse, name("m"))));
    let parameter = |name: &str, ty: &str| Parameter {
        name: name.into(),
        type_name: ty.into(),
    };
    let mut declaration = common::pga();
    declaration.expressions = vec![ga_codegen::ExpressionDeclaration {
        name: "moved_line".into(),
        parameters: vec![parameter("m", "Motor"), parameter("l", "Line")],
        result: Some("Line".into()),
        body: *product(product(name("m"), name("l")), reverse),
        linear: Some("l".into()),
        doc: Some("The line `l` moved by the motor `m`.\n\nThe user's words come first.".into()),
    }];
    let algebra = Algebra::new(&declaration).unwrap();
    insta::assert_snapshot!(ga_codegen::pretty(&emit::fused_function(&algebra, 0).unwrap()).unwrap());
}

/// The closed forms of `exp` on PGA's lines and `log` on its motors (`ga_codegen::transcendental`): the invariants'
/// polynomials as locals, then the series or trigonometric coefficients and the result blade by blade.
#[test]
fn pga_closed_forms() {
    use ga_codegen::expression::{Expression, ExpressionKind, Parameter};
    let call = |function: &str, argument: &str| {
        let parameter = Expression::new(ExpressionKind::Parameter(argument.into()));
        Expression::new(ExpressionKind::Call(function.into(), vec![parameter]))
    };
    let declared =
        |name: &str, parameter: &str, ty: &str, result: &str, function: &str| ga_codegen::ExpressionDeclaration {
            name: name.into(),
            parameters: vec![Parameter {
                name: parameter.into(),
                type_name: ty.into(),
            }],
            result: Some(result.into()),
            body: call(function, parameter),
            linear: None,
            doc: None,
        };
    let mut declaration = common::pga();
    declaration.expressions = vec![
        declared("exp_line", "b", "Line", "Motor", "exp"),
        declared("log_motor", "m", "Motor", "Line", "log"),
    ];
    let algebra = Algebra::new(&declaration).unwrap();
    let emitted: Vec<String> = (0..2)
        .map(|index| ga_codegen::pretty(&emit::fused_function(&algebra, index).unwrap()).unwrap())
        .collect();
    insta::assert_snapshot!(emitted.join("\n"));
}
