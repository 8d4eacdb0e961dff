//! Declarations shared by the ga-codegen integration tests.
#![allow(dead_code)] // each test binary uses a subset

use ga_codegen::{AlgebraDeclaration, BasisVectorDeclaration, Layout, ScalarType, TypeDeclaration};

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

/// The PGA of the issue: e0 first (bit 0), Plane, Line, Point, Motor, Translator, Multivector.
pub fn pga() -> AlgebraDeclaration {
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: basis(&[("e0", 0), ("e1", 1), ("e2", 1), ("e3", 1)]),
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
    }
}

/// CGA Cl(4,1) on e1..e5 with the even subalgebra.
pub fn cga() -> AlgebraDeclaration {
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: basis(&[("e1", 1), ("e2", 1), ("e3", 1), ("e4", 1), ("e5", -1)]),
        types: vec![
            grades("Vector", &[1]),
            grades("Even", &[0, 2, 4]),
            TypeDeclaration {
                name: "Multivector".to_string(),
                layout: Layout::All,
            },
        ],
        operations: None,
    }
}
