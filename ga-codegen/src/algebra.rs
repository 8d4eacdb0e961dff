//! The validated algebra model: basis vectors with their metric (diagonal, or a general symmetric
//! form), blade naming, and the declared sparse types resolved to blade lists.

use crate::blade::{self, BladeMask, BladeNaming, SCALAR_NAME};
use crate::declaration::{AlgebraDeclaration, Layout, Lowering, ScalarType};
use crate::error::{collect, Error, NameProblem};
use crate::expression::ExpressionDeclaration;
use crate::metric::Metric;
use crate::naming::{map_builder_name, map_type_name, snake_case, trait_name};
use crate::operation::Operation;

// Also here, with the other limits a declaration is checked against (`ga-macros` documents them together).
pub use crate::blade::MAX_DIMENSION;

/// `Multivector = all` is refused above this dimension: its products would have 4ⁿ terms.
pub const MAX_FULL_MULTIVECTOR_DIMENSION: usize = 10;

/// At most this many fields (blades) in one declared type: 2¹⁰ = 1024, the size `all` is allowed
/// at [`MAX_FULL_MULTIVECTOR_DIMENSION`]. The product of two types has up to (fields)² terms, so this
/// keeps every product within the ~10⁶ terms of the largest full multivector product; bigger types
/// (`grades(0, 1, …, 11)` in 11 dimensions has 2048 fields, `grades(16)` in 32 dimensions 601 080 390)
/// would build for many minutes or exhaust memory. The count is checked before any blade is listed.
pub const MAX_TYPE_FIELDS: usize = 1 << MAX_FULL_MULTIVECTOR_DIMENSION;

/// Words that cannot be identifiers in emitted code, in any edition: strict and reserved keywords
/// (`try` from 2018, `gen` from 2024).
pub const KEYWORDS: &[&str] = &[
    "abstract", "as", "async", "await", "become", "box", "break", "const", "continue", "crate", "do", "dyn", "else",
    "enum", "extern", "false", "final", "fn", "for", "gen", "if", "impl", "in", "let", "loop", "macro", "match", "mod",
    "move", "mut", "override", "priv", "pub", "ref", "return", "Self", "self", "static", "struct", "super", "trait",
    "true", "try", "type", "typeof", "unsafe", "unsized", "use", "virtual", "where", "while", "yield",
];

/// One coefficient of a declared type: the field `name` holds `sign ×` the coefficient of the
/// canonical blade `blade` (sign −1 for a permuted name such as `e31`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Field {
    /// The field's identifier in the emitted struct (as declared, possibly a permuted name).
    pub name: String,
    /// The canonical blade whose coefficient the field stores.
    pub blade: BladeMask,
    /// +1, or −1 when the declared name permutes the canonical blade's basis vectors oddly.
    pub sign: i64,
}

/// A declared sparse type with its fields in storage order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SparseType {
    /// The type's name, as declared.
    pub name: String,
    /// One field per stored blade, in declaration (storage) order.
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
    /// The floating-point type of the emitted coefficients.
    pub scalar: ScalarType,
    /// The basis vector names, in bit order (`basis_names[i]` is bit `i` of a blade mask).
    pub basis_names: Vec<String>,
    /// The bilinear form: diagonal squares or a general symmetric matrix.
    pub metric: Metric,
    /// How blade masks are named and blade names parsed in this basis.
    pub naming: BladeNaming,
    /// The declared types, in declaration order.
    pub types: Vec<SparseType>,
    /// The operations to emit.
    pub operations: Vec<Operation>,
    /// The lowerings chosen per product; the others are chosen by size.
    pub lowering: Vec<(Operation, Lowering)>,
    /// The named expressions to fuse, their names, parameters and types checked (their bodies are
    /// checked as they are fused, see [`crate::fuse`]).
    pub expressions: Vec<ExpressionDeclaration>,
}

impl Algebra {
    /// Validates a declaration. Every error names the offending item (see [`Error::location`]).
    ///
    /// ```
    /// use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, Error};
    /// use ga_codegen::{Layout, ScalarType, TypeDeclaration};
    ///
    /// // 3D PGA (e0² = 0) with a point stored as (e032, e013, e021, e123).
    /// let basis = [("e0", 0), ("e1", 1), ("e2", 1), ("e3", 1)]
    ///     .map(|(name, square)| BasisVectorDeclaration { name: name.into(), square });
    /// let point = ["e032", "e013", "e021", "e123"].map(String::from).to_vec();
    /// let mut declaration = AlgebraDeclaration {
    ///     scalar: ScalarType::F64,
    ///     basis: basis.to_vec(),
    ///     metric: None,
    ///     types: vec![TypeDeclaration { name: "Point".into(), layout: Layout::Blades(point) }],
    ///     operations: None,
    ///     lowering: vec![],
    ///     expressions: vec![],
    /// };
    /// let algebra = Algebra::new(&declaration)?;
    /// let point = algebra.type_named("Point").unwrap();
    /// // The permuted name `e032` stores minus the coefficient of the canonical blade e023.
    /// assert_eq!(algebra.blade_name(point.fields[0].blade), "e023");
    /// assert_eq!(point.fields[0].sign, -1);
    ///
    /// // Without a metric matrix a basis vector must square to −1, 0 or +1.
    /// declaration.basis[1].square = 2;
    /// assert!(matches!(Algebra::new(&declaration), Err(Error::InvalidSquare { index: 1, square: 2, .. })));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
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
        collect(basis.iter().enumerate().map(|(index, vector)| {
            if let Err(problem) = check_identifier(&vector.name) {
                return Err(Error::InvalidBasisName {
                    index,
                    name: vector.name.clone(),
                    problem,
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
            Ok(())
        }))?;
        let basis_names: Vec<String> = basis.iter().map(|v| v.name.clone()).collect();
        let naming = BladeNaming::new(&basis_names);
        check_blade_names(&basis_names, &naming)?;
        let metric = match &declaration.metric {
            None => Metric::diagonal(basis.iter().map(|v| v.square).collect())?,
            Some(rows) if rows.len() != basis.len() => {
                return Err(Error::MetricSize {
                    rows: rows.len(),
                    expected: basis.len(),
                })
            }
            Some(rows) => Metric::from_matrix(rows)?,
        };
        let n = basis.len();
        let operations = listed_operations(declaration)?;
        check_lowering(declaration, &operations)?;

        // Each type is checked on its own, so that mistakes in several are reported together.
        let types = collect(declaration.types.iter().enumerate().map(|(ty_index, declared)| {
            check_type_name(declaration, &operations, ty_index)?;
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
                    // Counted before any blade is listed: `grades(16)` in 32 dimensions would list 6 · 10⁸.
                    let count: u64 = grades.iter().map(|&grade| binomial(n as u64, grade as u64)).sum();
                    if count > MAX_TYPE_FIELDS as u64 {
                        return Err(too_many_fields(ty_index, &declared.name, count));
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
                    if names.len() > MAX_TYPE_FIELDS {
                        return Err(too_many_fields(ty_index, &declared.name, names.len() as u64));
                    }
                    for (item, name) in names.iter().enumerate() {
                        if let Err(problem) = check_identifier(name) {
                            return Err(Error::InvalidBladeName {
                                ty_index,
                                item,
                                ty: declared.name.clone(),
                                blade: name.clone(),
                                problem,
                            });
                        }
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
            Ok(SparseType {
                name: declared.name.clone(),
                fields,
            })
        }))?;

        Ok(Algebra {
            scalar: declaration.scalar,
            basis_names,
            metric,
            naming,
            types,
            operations,
            lowering: declaration.lowering.clone(),
            expressions: declaration.expressions.clone(),
        })
        .and_then(|algebra| {
            check_expressions(&algebra)?;
            Ok(algebra)
        })
    }

    /// The lowering the declaration chooses for `operation`, if any (otherwise it is chosen by size, see
    /// [`crate::table`]).
    pub fn declared_lowering(&self, operation: Operation) -> Option<Lowering> {
        self.lowering.iter().find(|(op, _)| *op == operation).map(|&(_, l)| l)
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

/// Whether `name` can be an identifier of emitted code: a Rust identifier (Unicode XID, as rustc
/// accepts), not a keyword of any edition, not raw (`r#type`: the emitted code forms other names from
/// it, such as `geometric_r#type`, which no identifier can spell).
pub fn check_identifier(name: &str) -> Result<(), NameProblem> {
    if name.starts_with("r#") {
        return Err(NameProblem::Raw);
    }
    if KEYWORDS.contains(&name) {
        return Err(NameProblem::Keyword);
    }
    // The same check rustc makes (XID_Start or `_`, then XID_Continue; not `_` alone); the string must
    // be one identifier token and nothing else (no spaces, no comments).
    match syn::parse_str::<syn::Ident>(name) {
        Ok(ident) if ident == name => Ok(()),
        _ => Err(NameProblem::NotAnIdentifier),
    }
}

/// Every expression has a valid name of its own, parameters with distinct valid names, and parameter and
/// result types that are declared types or the scalar type.
fn check_expressions(algebra: &Algebra) -> Result<(), Error> {
    let known = |name: &str| name == algebra.scalar.name() || algebra.type_named(name).is_some();
    // Each expression is checked on its own, so that mistakes in several are reported together.
    collect(algebra.expressions.iter().enumerate().map(|(index, expression)| {
        let name = &expression.name;
        if let Err(problem) = check_identifier(name) {
            return Err(Error::InvalidExpressionName {
                index,
                name: name.clone(),
                problem,
            });
        }
        if algebra.expressions[..index].iter().any(|earlier| earlier.name == *name) {
            return Err(Error::DuplicateExpression {
                index,
                name: name.clone(),
            });
        }
        let unknown_type = |parameter, type_name: &str| Error::UnknownExpressionType {
            index,
            parameter,
            expression: name.clone(),
            type_name: type_name.to_string(),
            scalar: algebra.scalar.name().to_string(),
        };
        for (parameter, declared) in expression.parameters.iter().enumerate() {
            if let Err(problem) = check_identifier(&declared.name) {
                return Err(Error::InvalidParameterName {
                    index,
                    parameter,
                    expression: name.clone(),
                    name: declared.name.clone(),
                    problem,
                });
            }
            if expression.parameters[..parameter]
                .iter()
                .any(|p| p.name == declared.name)
            {
                return Err(Error::DuplicateParameter {
                    index,
                    parameter,
                    expression: name.clone(),
                    name: declared.name.clone(),
                });
            }
            if !known(&declared.type_name) {
                return Err(unknown_type(Some(parameter), &declared.type_name));
            }
        }
        if let Some(result) = expression.result.as_ref().filter(|result| !known(result)) {
            return Err(unknown_type(None, result));
        }
        if let Some(linear) = &expression.linear {
            if !expression.parameters.iter().any(|p| p.name == *linear) {
                return Err(Error::UnknownLinearParameter {
                    index,
                    expression: name.clone(),
                    parameter: linear.clone(),
                });
            }
            let clash = |name: String, taken: String| Error::MapNameClash {
                index,
                expression: expression.name.clone(),
                name,
                taken,
            };
            let map = map_type_name(&expression.name);
            if algebra.type_named(&map).is_some() {
                return Err(clash(map, "is a declared type".to_string()));
            }
            let mut earlier_maps = algebra.expressions[..index].iter().filter(|e| e.linear.is_some());
            if let Some(other) = earlier_maps.find(|e| map_type_name(&e.name) == map) {
                return Err(clash(map, format!("is the type of the linear map of `{}`", other.name)));
            }
            let builder = map_builder_name(name);
            if let Some(other) = algebra.expressions.iter().find(|e| e.name == builder) {
                return Err(clash(builder, format!("is the expression `{}`", other.name)));
            }
        }
        Ok(())
    }))
    .map(drop)
}

/// Every chosen lowering is of an emitted product, once.
fn check_lowering(declaration: &AlgebraDeclaration, operations: &[Operation]) -> Result<(), Error> {
    for (index, &(operation, _)) in declaration.lowering.iter().enumerate() {
        let name = operation.name().to_string();
        if !operation.is_binary() {
            return Err(Error::LoweringOfUnary { index, name });
        }
        if !operations.contains(&operation) {
            return Err(Error::LoweringNotEmitted { index, name });
        }
        if declaration.lowering[..index].iter().any(|&(op, _)| op == operation) {
            return Err(Error::DuplicateLowering { index, name });
        }
    }
    Ok(())
}

/// The operations to emit, each listed once.
fn listed_operations(declaration: &AlgebraDeclaration) -> Result<Vec<Operation>, Error> {
    match &declaration.operations {
        None => Ok(Operation::ALL.to_vec()),
        Some(listed) => {
            for (index, op) in listed.iter().enumerate() {
                if listed[..index].contains(op) {
                    return Err(Error::DuplicateOperation {
                        index,
                        name: op.name().to_string(),
                    });
                }
            }
            Ok(listed.clone())
        }
    }
}

/// Blade names must name one blade each, and be identifiers: blade names join basis vector names
/// (see [`BladeNaming`]), so a basis vector name must not read as a join of others, and no blade may
/// be called `scalar` (the grade-0 blade) or a keyword. Checked on the naming rule, without listing
/// the 2ⁿ names.
fn check_blade_names(basis_names: &[String], naming: &BladeNaming) -> Result<(), Error> {
    // Joined with `_`, names without `_` split back uniquely into their basis vectors; a `_` inside a
    // basis vector name makes some blade names readable in two ways (`x_y` is the vector `x_y` and
    // x ∧ y). The prefix is alphabetic, so a `_` in a name is in its part that gets joined.
    if naming.separator() == "_" && basis_names.len() >= 2 {
        if let Some(index) = basis_names.iter().position(|name| name.contains('_')) {
            let name = &basis_names[index];
            // Pieces between `_` never match a name containing `_`: any blade found is another one.
            let clash = naming
                .factors(name)
                .ok()
                .map(|factors| factors.iter().map(|&i| basis_names[i].clone()).collect());
            return Err(Error::SeparatorInBasisName {
                index,
                name: name.clone(),
                clash,
            });
        }
    }
    let factors = |blade: BladeMask| -> (usize, Vec<String>) {
        let indices: Vec<usize> = (0..basis_names.len()).filter(|i| blade & (1 << i) != 0).collect();
        let last = *indices.last().expect("a non-zero blade has a factor");
        (last, indices.into_iter().map(|i| basis_names[i].clone()).collect())
    };
    if let Some(blade) = naming.canonical_blade(SCALAR_NAME) {
        let (index, factors) = factors(blade);
        return Err(Error::ScalarBladeName { index, factors });
    }
    for keyword in KEYWORDS {
        if let Some(blade) = naming.canonical_blade(keyword) {
            let (index, factors) = factors(blade);
            return Err(Error::KeywordBladeName {
                index,
                blade: keyword.to_string(),
                factors,
            });
        }
    }
    Ok(())
}

/// A type name must be an identifier, declared once, free in the emitted module and distinct from
/// the other types' names in snake case (they become method names).
///
/// Names the emitted module refers to are refused rather than qualified, so that the emitted code
/// stays as it is: the trait of each emitted binary operation (`Geometric`, `Sandwich`, …), `From`
/// (the conversions implement it unqualified), `core` (the root of every operator trait path), `str`
/// (the type of `BLADES`) and the scalar type. Other std names (`Add`, `Into`, `Default`, …) are free:
/// emitted code spells them `core::ops::Add` or uses them only through derives.
fn check_type_name(declaration: &AlgebraDeclaration, operations: &[Operation], index: usize) -> Result<(), Error> {
    let name = &declaration.types[index].name;
    if let Err(problem) = check_identifier(name) {
        return Err(Error::InvalidTypeName {
            index,
            name: name.clone(),
            problem,
        });
    }
    let earlier = &declaration.types[..index];
    if earlier.iter().any(|earlier| earlier.name == *name) {
        return Err(Error::DuplicateTypeName {
            index,
            name: name.clone(),
        });
    }
    let binary = operations.iter().copied().filter(|op| op.is_binary());
    let clash = if let Some(operation) = binary.clone().find(|&op| trait_name(op) == *name) {
        Some(format!(
            "the trait `{name}` the module defines for the `{}` operation",
            operation.name()
        ))
    } else {
        match name.as_str() {
            "From" => Some("`From`, the conversion trait the module implements between its types".to_string()),
            "core" => Some("`core`, the crate the module names its operator traits by (`core::ops::Add`)".to_string()),
            "str" => Some("`str`, the type of the blade names in each type's `BLADES`".to_string()),
            scalar if scalar == declaration.scalar.name() => {
                Some(format!("`{scalar}`, the scalar type of every coefficient"))
            }
            _ => None,
        }
    };
    if let Some(clash) = clash {
        return Err(Error::ReservedTypeName {
            index,
            name: name.clone(),
            clash,
        });
    }
    if let Some(operation) = binary.clone().next() {
        let method_suffix = snake_case(name);
        if let Some(other) = earlier
            .iter()
            .find(|earlier| snake_case(&earlier.name) == method_suffix)
        {
            return Err(Error::TypeMethodCollision {
                index,
                name: name.clone(),
                other: other.name.clone(),
                method_suffix,
                operation: operation.name().to_string(),
            });
        }
    }
    Ok(())
}

fn too_many_fields(ty_index: usize, ty: &str, fields: u64) -> Error {
    Error::TooManyFields {
        ty_index,
        ty: ty.to_string(),
        fields,
        max: MAX_TYPE_FIELDS,
        max_dimension: MAX_FULL_MULTIVECTOR_DIMENSION,
    }
}

/// C(n, k), exact: n ≤ [`MAX_DIMENSION`] = 32, so every intermediate product stays below 2⁴⁰.
fn binomial(n: u64, k: u64) -> u64 {
    if k > n {
        return 0;
    }
    let k = k.min(n - k);
    // After step i, `c` is C(n − k + i, i): an integer, and c · (n − k + i + 1) is divisible by i + 1.
    (0..k).fold(1, |c, i| c * (n - k + i + 1) / (i + 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binomials_are_exact_up_to_the_largest_dimension() {
        assert_eq!(binomial(32, 16), 601_080_390);
        assert_eq!(binomial(11, 0), 1);
        assert_eq!(binomial(11, 11), 1);
        assert_eq!(binomial(10, 12), 0);
        assert_eq!((0..=32).map(|k| binomial(32, k)).sum::<u64>(), 1 << 32);
        assert_eq!((0..=11).map(|k| binomial(11, k)).sum::<u64>(), 2048);
    }

    #[test]
    fn identifiers_are_checked_as_rustc_does() {
        assert_eq!(check_identifier("e1"), Ok(()));
        assert_eq!(check_identifier("α"), Ok(()));
        assert_eq!(check_identifier("_x"), Ok(()));
        assert_eq!(check_identifier("Motor"), Ok(()));
        for name in ["", "_", "1e", "e 1", " e1", "e1 /* */", "e-1", "a::b", "∧"] {
            assert_eq!(check_identifier(name), Err(NameProblem::NotAnIdentifier), "{name:?}");
        }
        for name in ["fn", "Self", "try", "gen", "async", "type"] {
            assert_eq!(check_identifier(name), Err(NameProblem::Keyword), "{name:?}");
        }
        assert_eq!(check_identifier("r#type"), Err(NameProblem::Raw));
        assert_eq!(check_identifier("r#e1"), Err(NameProblem::Raw));
    }
}
