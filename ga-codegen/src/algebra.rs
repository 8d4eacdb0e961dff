//! The validated algebra model: basis vectors with their metric (diagonal, or a general symmetric
//! form), blade naming, and the declared sparse types resolved to blade lists.

use crate::blade::{self, BladeMask, BladeNaming};
use crate::declaration::{AlgebraDeclaration, Layout, ScalarType};
use crate::error::Error;
use crate::metric::Metric;
use crate::operation::Operation;

/// At most this many basis vectors: blades are `u32` masks.
pub const MAX_DIMENSION: usize = 32;

/// `Multivector = all` is refused above this dimension: its products would have 4ⁿ terms.
pub const MAX_FULL_MULTIVECTOR_DIMENSION: usize = 10;

/// One coefficient of a declared type: the field `name` holds `sign ×` the coefficient of the
/// canonical blade `blade` (sign −1 for a permuted name such as `e31`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Field {
    pub name: String,
    pub blade: BladeMask,
    pub sign: i64,
}

/// A declared sparse type with its fields in storage order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SparseType {
    pub name: String,
    pub fields: Vec<Field>,
}

impl SparseType {
    /// The field that stores `blade`, if any.
    pub fn field_of(&self, blade: BladeMask) -> Option<&Field> {
        self.fields.iter().find(|field| field.blade == blade)
    }

    /// Whether every blade in `blades` has a field in this type.
    pub fn holds(&self, blades: &[BladeMask]) -> bool {
        blades.iter().all(|&b| self.field_of(b).is_some())
    }
}

/// A validated algebra: what the expansion and emission stages work on.
#[derive(Clone, Debug)]
pub struct Algebra {
    pub scalar: ScalarType,
    pub basis_names: Vec<String>,
    pub metric: Metric,
    pub naming: BladeNaming,
    pub types: Vec<SparseType>,
    /// The operations to emit.
    pub operations: Vec<Operation>,
}

impl Algebra {
    /// Validates a declaration. Every error names the offending item (see [`Error::location`]).
    pub fn new(declaration: &AlgebraDeclaration) -> Result<Algebra, Error> {
        let basis = &declaration.basis;
        if basis.is_empty() {
            return Err(Error::EmptyBasis);
        }
        if basis.len() > MAX_DIMENSION {
            return Err(Error::TooManyBasisVectors {
                count: basis.len(),
                max: MAX_DIMENSION,
            });
        }
        for (index, vector) in basis.iter().enumerate() {
            if !is_identifier(&vector.name) {
                return Err(Error::InvalidBasisName {
                    index,
                    name: vector.name.clone(),
                });
            }
            if basis[..index].iter().any(|earlier| earlier.name == vector.name) {
                return Err(Error::DuplicateBasisName {
                    index,
                    name: vector.name.clone(),
                });
            }
            if declaration.metric.is_none() && !matches!(vector.square, -1..=1) {
                return Err(Error::InvalidSquare {
                    index,
                    name: vector.name.clone(),
                    square: vector.square,
                });
            }
        }
        let basis_names: Vec<String> = basis.iter().map(|v| v.name.clone()).collect();
        let metric = match &declaration.metric {
            None => Metric::diagonal(basis.iter().map(|v| v.square).collect()),
            Some(rows) if rows.len() != basis.len() => {
                return Err(Error::MetricSize {
                    rows: rows.len(),
                    expected: basis.len(),
                })
            }
            Some(rows) => Metric::from_matrix(rows)?,
        };
        let naming = BladeNaming::new(&basis_names);
        let n = basis.len();

        let mut types = Vec::with_capacity(declaration.types.len());
        for (ty_index, declared) in declaration.types.iter().enumerate() {
            if declaration.types[..ty_index]
                .iter()
                .any(|earlier| earlier.name == declared.name)
            {
                return Err(Error::DuplicateTypeName {
                    index: ty_index,
                    name: declared.name.clone(),
                });
            }
            let mut fields: Vec<Field> = Vec::new();
            let mut push = |blade: BladeMask, sign: i64, name: String, item: usize| -> Result<(), Error> {
                if fields.iter().any(|f| f.blade == blade) {
                    return Err(Error::DuplicateBlade {
                        ty_index,
                        item,
                        ty: declared.name.clone(),
                        blade: name,
                    });
                }
                fields.push(Field { name, blade, sign });
                Ok(())
            };
            match &declared.layout {
                Layout::All => {
                    if n > MAX_FULL_MULTIVECTOR_DIMENSION {
                        return Err(Error::AllTooLarge {
                            ty_index,
                            ty: declared.name.clone(),
                            dimension: n,
                            blades: 1u64 << n,
                            products: 1u64 << (2 * n).min(63),
                            max_dimension: MAX_FULL_MULTIVECTOR_DIMENSION,
                        });
                    }
                    for b in blade::canonical_blades(n) {
                        push(b, 1, naming.name(b), 0)?;
                    }
                }
                Layout::Grades(grades) => {
                    for (item, &grade) in grades.iter().enumerate() {
                        if grade as usize > n {
                            return Err(Error::GradeOutOfRange {
                                ty_index,
                                item,
                                ty: declared.name.clone(),
                                grade,
                                max: n as u32,
                            });
                        }
                        if grades[..item].contains(&grade) {
                            return Err(Error::DuplicateBlade {
                                ty_index,
                                item,
                                ty: declared.name.clone(),
                                blade: format!("grade {grade}"),
                            });
                        }
                    }
                    let mut sorted = grades.clone();
                    sorted.sort_unstable();
                    for grade in sorted {
                        for b in blade::blades_of_grade(n, grade) {
                            push(b, 1, naming.name(b), 0)?;
                        }
                    }
                }
                Layout::Blades(names) => {
                    for (item, name) in names.iter().enumerate() {
                        let (blade, sign) = naming.parse(name).map_err(|reason| Error::UnknownBlade {
                            ty_index,
                            item,
                            ty: declared.name.clone(),
                            blade: name.clone(),
                            reason,
                        })?;
                        push(blade, sign, name.clone(), item)?;
                    }
                }
            }
            if fields.is_empty() {
                return Err(Error::EmptyType {
                    index: ty_index,
                    name: declared.name.clone(),
                });
            }
            types.push(SparseType {
                name: declared.name.clone(),
                fields,
            });
        }

        let operations = match &declaration.operations {
            None => Operation::ALL.to_vec(),
            Some(listed) => {
                for (index, op) in listed.iter().enumerate() {
                    if listed[..index].contains(op) {
                        return Err(Error::DuplicateOperation {
                            index,
                            name: op.name().to_string(),
                        });
                    }
                }
                listed.clone()
            }
        };
        Ok(Algebra {
            scalar: declaration.scalar,
            basis_names,
            metric,
            naming,
            types,
            operations,
        })
    }

    /// The number of basis vectors.
    pub fn dimension(&self) -> usize {
        self.basis_names.len()
    }

    /// The declared type called `name`.
    pub fn type_named(&self, name: &str) -> Option<&SparseType> {
        self.types.iter().find(|t| t.name == name)
    }

    /// The canonical name of a blade.
    pub fn blade_name(&self, blade: BladeMask) -> String {
        self.naming.name(blade)
    }

    /// The smallest declared type holding every blade in `blades` (ties: the one declared first).
    pub fn smallest_type_holding(&self, blades: &[BladeMask]) -> Option<&SparseType> {
        self.types
            .iter()
            .filter(|t| t.holds(blades))
            .min_by_key(|t| t.fields.len())
    }
}

fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}
