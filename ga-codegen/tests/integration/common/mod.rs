//! Declarations and random algebras shared by the ga-codegen integration tests.

use ga_codegen::metric::Metric;
use ga_codegen::{
    AlgebraDeclaration, BasisVectorDeclaration, Evaluator, Layout, Operation, Rational64, ScalarType, TypeDeclaration,
};
use proptest::prelude::*;

pub fn basis(vectors: &[(&str, i64)]) -> Vec<BasisVectorDeclaration> {
    vectors
        .iter()
        .map(|&(name, square)| BasisVectorDeclaration {
            name: name.to_string(),
            square,
        })
        .collect()
}

pub fn grades(name: &str, grades: &[u32]) -> TypeDeclaration {
    TypeDeclaration {
        name: name.to_string(),
        layout: Layout::Grades(grades.to_vec()),
    }
}

pub fn blades(name: &str, blades: &[&str]) -> TypeDeclaration {
    TypeDeclaration {
        name: name.to_string(),
        layout: Layout::Blades(blades.iter().map(|b| b.to_string()).collect()),
    }
}

/// The PGA of the original design: e0 first (bit 0), Plane, Line, Point, Motor, Translator, Multivector.
pub fn pga() -> AlgebraDeclaration {
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: basis(&[("e0", 0), ("e1", 1), ("e2", 1), ("e3", 1)]),
        metric: None,
        types: vec![
            grades("Plane", &[1]),
            grades("Line", &[2]),
            grades("Point", &[3]),
            grades("Motor", &[0, 2, 4]),
            blades("Translator", &["scalar", "e01", "e02", "e03"]),
            TypeDeclaration {
                name: "Multivector".to_string(),
                layout: Layout::All,
            },
        ],
        operations: None,
        lowering: vec![],
        expressions: vec![],
    }
}

/// CGA Cl(4,1) on e1..e5 with the even subalgebra.
pub fn cga() -> AlgebraDeclaration {
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: basis(&[("e1", 1), ("e2", 1), ("e3", 1), ("e4", 1), ("e5", -1)]),
        metric: None,
        types: vec![
            grades("Vector", &[1]),
            grades("Even", &[0, 2, 4]),
            TypeDeclaration {
                name: "Multivector".to_string(),
                layout: Layout::All,
            },
        ],
        operations: None,
        lowering: vec![],
        expressions: vec![],
    }
}

/// CGA on the null basis e1, e2, e3, n0, ninf with n0 · ninf = −1 (squares from the metric): vectors,
/// rigid motors (1, eᵢⱼ, eᵢ∞, e123∞: the PGA motor's shape), the even subalgebra and everything.
pub fn null_cga() -> AlgebraDeclaration {
    let entry = |i: usize, j: usize| match (i.min(j), i.max(j)) {
        (3, 4) => Rational64::from_integer(-1),
        (i, j) if i == j && i < 3 => Rational64::from_integer(1),
        _ => Rational64::from_integer(0),
    };
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: basis(&[("e1", 0), ("e2", 0), ("e3", 0), ("n0", 0), ("ninf", 0)]),
        metric: Some((0..5).map(|i| (0..5).map(|j| entry(i, j)).collect()).collect()),
        types: vec![
            grades("Vector", &[1]),
            blades(
                "Motor",
                &[
                    "scalar",
                    "e1_e2",
                    "e1_e3",
                    "e2_e3",
                    "e1_ninf",
                    "e2_ninf",
                    "e3_ninf",
                    "e1_e2_e3_ninf",
                ],
            ),
            grades("Even", &[0, 2, 4]),
            TypeDeclaration {
                name: "Multivector".to_string(),
                layout: Layout::All,
            },
        ],
        operations: None,
        lowering: vec![],
        expressions: vec![],
    }
}

/// DCGA Cl(8,2) on two null bases, as `dynamics::surfaces::dcga` declares it: two CGA copies, a vector of each and
/// a turned torus (the four null blades and the nine `eᵢ ∧ eⱼ₊₅`).
pub fn dcga() -> AlgebraDeclaration {
    let names = ["e1", "e2", "e3", "no1", "ni1", "e6", "e7", "e8", "no2", "ni2"];
    let entry = |i: usize, j: usize| match (i.min(j), i.max(j)) {
        (3, 4) | (8, 9) => Rational64::from_integer(-1),
        (i, j) if i == j && !matches!(i, 3 | 4 | 8 | 9) => Rational64::from_integer(1),
        _ => Rational64::from_integer(0),
    };
    let cross: Vec<String> = ["e1", "e2", "e3"]
        .iter()
        .flat_map(|a| ["e6", "e7", "e8"].map(|b| format!("{a}_{b}")))
        .collect();
    let mut turned = vec!["no1_no2", "no1_ni2", "ni1_no2", "ni1_ni2"];
    turned.extend(cross.iter().map(String::as_str));
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: basis(&names.map(|n| (n, 0))),
        metric: Some((0..10).map(|i| (0..10).map(|j| entry(i, j)).collect()).collect()),
        types: vec![
            blades("First", &["e1", "e2", "e3", "no1", "ni1"]),
            blades("Second", &["e6", "e7", "e8", "no2", "ni2"]),
            blades("Turned", &turned),
        ],
        operations: None,
        lowering: vec![],
        expressions: vec![],
    }
}

/// Random diagonal signatures, degenerate ones included.
pub fn signature() -> impl Strategy<Value = Vec<i64>> {
    prop::collection::vec(prop_oneof![Just(1i64), Just(-1), Just(0)], 1..=6)
}

/// A metric entry: mostly 0 off the diagonal, dyadic so that products stay exact in f64.
fn metric_entry(off_diagonal: bool) -> impl Strategy<Value = Rational64> {
    let zero_weight = if off_diagonal { 6 } else { 1 };
    prop_oneof![
        zero_weight => Just(Rational64::from_integer(0)),
        2 => Just(Rational64::from_integer(1)),
        2 => Just(Rational64::from_integer(-1)),
        1 => Just(Rational64::new(1, 2)),
        1 => Just(Rational64::new(-1, 2)),
        1 => Just(Rational64::from_integer(2)),
    ]
}

/// A random symmetric form (the upper triangle drawn, mirrored), small enough for exact arithmetic.
pub fn general_metric() -> impl Strategy<Value = Vec<Vec<Rational64>>> {
    (1usize..=5)
        .prop_flat_map(|n| {
            let upper: Vec<usize> = (0..n * (n + 1) / 2).collect();
            let entries: Vec<_> = upper
                .iter()
                .map(|&k| {
                    let (i, j) = upper_index(n, k);
                    metric_entry(i != j)
                })
                .collect();
            entries.prop_map(move |values| {
                let mut rows = vec![vec![Rational64::from_integer(0); n]; n];
                for (k, value) in values.into_iter().enumerate() {
                    let (i, j) = upper_index(n, k);
                    rows[i][j] = value;
                    rows[j][i] = value;
                }
                rows
            })
        })
        .prop_filter("entries too large for exact coefficients", |rows| {
            Metric::from_matrix(rows).is_ok()
        })
}

/// The `k`-th entry (i ≤ j) of an n×n upper triangle, row by row.
fn upper_index(n: usize, mut k: usize) -> (usize, usize) {
    for i in 0..n {
        if k < n - i {
            return (i, i + k);
        }
        k -= n - i;
    }
    unreachable!("k < n(n+1)/2")
}

/// An orthogonal basis given by its squares, or a general form.
#[derive(Clone, Debug)]
pub enum Form {
    Squares(Vec<i64>),
    Matrix(Vec<Vec<Rational64>>),
}

impl Form {
    pub fn dimension(&self) -> usize {
        match self {
            Form::Squares(squares) => squares.len(),
            Form::Matrix(rows) => rows.len(),
        }
    }

    /// The basis vectors with these names, and the metric matrix if the form has one.
    pub fn basis(&self, names: &[String]) -> (Vec<BasisVectorDeclaration>, Option<Vec<Vec<Rational64>>>) {
        let (squares, metric) = match self {
            Form::Squares(squares) => (squares.clone(), None),
            Form::Matrix(rows) => (vec![0; rows.len()], Some(rows.clone())),
        };
        let named: Vec<(&str, i64)> = names.iter().map(String::as_str).zip(squares).collect();
        (basis(&named), metric)
    }

    /// A declaration on this form (basis e1, e2, …) with these types and operations (`None`: all).
    pub fn declaration(&self, types: Vec<TypeDeclaration>, operations: Option<Vec<Operation>>) -> AlgebraDeclaration {
        let names: Vec<String> = (1..=self.dimension()).map(|i| format!("e{i}")).collect();
        let (basis, metric) = self.basis(&names);
        AlgebraDeclaration {
            scalar: ScalarType::F64,
            basis,
            metric,
            types,
            operations,
            lowering: vec![],
            expressions: vec![],
        }
    }

    pub fn evaluator(&self) -> Evaluator {
        match self {
            Form::Squares(squares) => Evaluator::new(squares).unwrap(),
            Form::Matrix(rows) => Evaluator::with_metric(Metric::from_matrix(rows).unwrap()),
        }
    }
}

pub fn form() -> impl Strategy<Value = Form> {
    prop_oneof![
        signature().prop_map(Form::Squares),
        general_metric().prop_map(Form::Matrix)
    ]
}
