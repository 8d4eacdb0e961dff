//! Prints the exact cost (multiplies, adds) of the headline PGA and CGA products, as the compiler's
//! cost model counts the emitted code, and how long `ga_codegen::generate` takes to expand the
//! standard PGA and CGA type sets, the null-basis CGA and Cl(9,6) (vectors and bivectors) with every
//! operation.
//!
//! ```sh
//! cargo run --release --example costs
//! ```

use std::time::Instant;

use ga_codegen::{
    functions, Algebra, AlgebraDeclaration, BasisVectorDeclaration, Cost, Expression, ExpressionDeclaration,
    ExpressionKind, Layout, Operation, Parameter, ScalarType, TypeDeclaration,
};

fn basis(vectors: &[(&str, i64)]) -> Vec<BasisVectorDeclaration> {
    vectors
        .iter()
        .map(|&(name, square)| BasisVectorDeclaration {
            name: name.to_string(),
            square,
        })
        .collect()
}

fn declared(name: &str, layout: Layout) -> TypeDeclaration {
    TypeDeclaration {
        name: name.to_string(),
        layout,
    }
}

/// PGA Cl(3,0,1) with e0 first, and the types of the README and docs/compiler.md.
fn pga() -> AlgebraDeclaration {
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: basis(&[("e0", 0), ("e1", 1), ("e2", 1), ("e3", 1)]),
        types: vec![
            declared("Plane", Layout::Grades(vec![1])),
            declared("Line", Layout::Grades(vec![2])),
            declared("Point", Layout::Grades(vec![3])),
            declared("Motor", Layout::Grades(vec![0, 2, 4])),
            declared(
                "Translator",
                Layout::Blades(["scalar", "e01", "e02", "e03"].map(String::from).to_vec()),
            ),
            declared("Multivector", Layout::All),
        ],
        operations: None,
        lowering: vec![],
        expressions: vec![],
        metric: None,
    }
}

/// CGA Cl(4,1): vectors, the even subalgebra (versors of rigid motions live there) and everything.
fn cga() -> AlgebraDeclaration {
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: basis(&[("e1", 1), ("e2", 1), ("e3", 1), ("e4", 1), ("e5", -1)]),
        types: vec![
            declared("Vector", Layout::Grades(vec![1])),
            declared("Even", Layout::Grades(vec![0, 2, 4])),
            declared("Multivector", Layout::All),
        ],
        operations: None,
        lowering: vec![],
        expressions: vec![],
        metric: None,
    }
}

/// CGA on e1, e2, e3, n0, ninf with n0·ninf = −1: a rigid motor (1, eᵢⱼ, eᵢ∞, e123∞) has 8 components.
fn null_basis_cga() -> AlgebraDeclaration {
    let metric = [
        [1, 0, 0, 0, 0],
        [0, 1, 0, 0, 0],
        [0, 0, 1, 0, 0],
        [0, 0, 0, 0, -1],
        [0, 0, 0, -1, 0],
    ];
    let blades = |names: &[&str]| Layout::Blades(names.iter().map(|n| n.to_string()).collect());
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: basis(&[("e1", 0), ("e2", 0), ("e3", 0), ("e4", 0), ("e5", 0)]),
        types: vec![
            declared(
                "Motor",
                blades(&["scalar", "e12", "e13", "e23", "e15", "e25", "e35", "e1235"]),
            ),
            declared("Even", Layout::Grades(vec![0, 2, 4])),
            declared("Multivector", Layout::All),
        ],
        operations: None,
        lowering: vec![],
        expressions: vec![],
        metric: Some(
            metric
                .iter()
                .map(|row| row.iter().map(|&x| ga_codegen::Rational64::from(x)).collect())
                .collect(),
        ),
    }
}

/// Cl(9,6), the quadric conformal algebra's 15 dimensions, with scalars, vectors and bivectors and the six
/// operations that keep grades 0 to 2 (as in `ga-codegen/tests/integration/large_algebras.rs`; the geometric product of
/// two bivectors has grade 4, which no declared type holds).
fn cl_9_6() -> AlgebraDeclaration {
    let names: Vec<String> = (1..=15).map(|i| format!("e{i}")).collect();
    let vectors: Vec<(&str, i64)> = names
        .iter()
        .enumerate()
        .map(|(i, name)| (name.as_str(), if i < 9 { 1 } else { -1 }))
        .collect();
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: basis(&vectors),
        types: vec![
            declared("Scalar", Layout::Grades(vec![0])),
            declared("Vector", Layout::Grades(vec![1])),
            declared("Bivector", Layout::Grades(vec![2])),
        ],
        operations: Some(vec![
            Operation::Commutator,
            Operation::LeftContraction,
            Operation::RightContraction,
            Operation::ScalarProduct,
            Operation::HestenesInner,
            Operation::FatDot,
        ]),
        lowering: vec![],
        expressions: vec![],
        metric: None,
    }
}

fn binary_cost(algebra: &Algebra, operation: Operation, lhs: &str, rhs: &str) -> Cost {
    functions::cost(algebra, operation, lhs, Some(rhs))
        .expect("the declared types have a result type")
        .unwrap_or_else(|| panic!("{lhs} {} {rhs} is emitted", operation.name()))
}

/// `declaration` with `fn moved_line(m: Motor, l: Line) -> Line = m * l * ~m;`, linear in `l`.
fn moved_line(mut declaration: AlgebraDeclaration) -> AlgebraDeclaration {
    let node = |kind| Box::new(Expression::new(kind));
    let name = |n: &str| node(ExpressionKind::Parameter(n.into()));
    let moved = ExpressionKind::Binary(
        Operation::Geometric,
        node(ExpressionKind::Binary(Operation::Geometric, name("m"), name("l"))),
        node(ExpressionKind::Unary(Operation::Reverse, name("m"))),
    );
    let parameter = |name: &str, ty: &str| Parameter {
        name: name.into(),
        type_name: ty.into(),
    };
    declaration.expressions = vec![ExpressionDeclaration {
        name: "moved_line".into(),
        parameters: vec![parameter("m", "Motor"), parameter("l", "Line")],
        result: Some("Line".into()),
        body: Expression::new(moved),
        linear: Some("l".into()),
        doc: None,
    }];
    declaration
}

fn row(label: &str, cost: Cost) {
    println!("| {label} | {} | {} |", cost.multiplies, cost.adds);
}

/// Wall time of `generate` (the whole macro expansion minus parsing), and the emitted size.
fn expansion(name: &str, declaration: &AlgebraDeclaration) {
    let start = Instant::now();
    let tokens = ga_codegen::generate(declaration).expect("the declaration is valid");
    let elapsed = start.elapsed();
    let size = tokens.to_string().len();
    println!(
        "| {name} | {} | {:.2} s | {:.1} MB |",
        declaration.types.len(),
        elapsed.as_secs_f64(),
        size as f64 / 1e6
    );
}

fn main() {
    let pga_declaration = pga();
    let cga_declaration = cga();
    let pga = Algebra::new(&pga_declaration).expect("PGA is valid");
    let cga = Algebra::new(&cga_declaration).expect("CGA is valid");

    println!("| product | multiplies | adds |");
    println!("|---|---|---|");
    row(
        "PGA Motor × Motor",
        binary_cost(&pga, Operation::Geometric, "Motor", "Motor"),
    );
    row(
        "PGA Motor sandwich Point (fused)",
        binary_cost(&pga, Operation::Sandwich, "Motor", "Point"),
    );
    // Without the fused sandwich: Motor × Point has grades 1 and 3, which only the full Multivector
    // holds, so the second product is Multivector × Motor (the reverse itself only flips signs).
    let first = binary_cost(&pga, Operation::Geometric, "Motor", "Point");
    let second = binary_cost(&pga, Operation::Geometric, "Multivector", "Motor");
    row(
        "PGA (Motor × Point) × ~Motor, two products (Motor × Point + Multivector × Motor)",
        first + second,
    );
    // A motor on a line, m * l * ~m, fused into one function, and as the motor's 6×6 line map.
    let pga_fused = Algebra::new(&moved_line(pga_declaration.clone())).expect("the expression is valid");
    let fused = ga_codegen::fuse::fuse(&pga_fused, 0).expect("the expression fuses");
    row("PGA `m * l * ~m` (Motor, Line), fused expression", fused.cost);
    row(
        "PGA Motor sandwich Line (the emitted `sandwich`)",
        binary_cost(&pga, Operation::Sandwich, "Motor", "Line"),
    );
    let map = ga_codegen::fuse::linear_map(&pga_fused, 0, 1).expect("the expression is linear in the line");
    row("PGA `moved_line_map(m)`: the 6×6 line map of a motor", map.cost);
    row("PGA `MovedLineMap::apply` (each further line)", map.apply_cost());
    row(
        "PGA Motor `transform` Point (unit motor)",
        binary_cost(&pga, Operation::Transform, "Motor", "Point"),
    );
    row(
        "CGA Even × Even",
        binary_cost(&cga, Operation::Geometric, "Even", "Even"),
    );
    row(
        "CGA Even `transform` Vector (unit versor)",
        binary_cost(&cga, Operation::Transform, "Even", "Vector"),
    );
    let null = Algebra::new(&null_basis_cga()).expect("the null-basis CGA is valid");
    row(
        "null-basis CGA Motor × Motor (8 components)",
        binary_cost(&null, Operation::Geometric, "Motor", "Motor"),
    );
    row(
        "null-basis CGA Even × Even",
        binary_cost(&null, Operation::Geometric, "Even", "Even"),
    );
    row(
        "PGA Multivector × Multivector",
        binary_cost(&pga, Operation::Geometric, "Multivector", "Multivector"),
    );
    row(
        "CGA Multivector × Multivector",
        binary_cost(&cga, Operation::Geometric, "Multivector", "Multivector"),
    );

    println!();
    println!("| algebra (all operations unless stated) | types | `generate` wall time | emitted source |");
    println!("|---|---|---|---|");
    expansion("PGA Cl(3,0,1)", &pga_declaration);
    expansion("CGA Cl(4,1)", &cga_declaration);
    expansion("null-basis CGA", &null_basis_cga());
    expansion("Cl(9,6), six grade-keeping operations", &cl_9_6());
}
