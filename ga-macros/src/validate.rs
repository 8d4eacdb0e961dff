//! From the AST to a [`ga_codegen::AlgebraDeclaration`] the compiler accepts. Errors the macro can
//! see on its own (scalar names, number literals, operation names, attributes) are reported here,
//! all at once; the algebra's own rules are left to [`ga_codegen::Algebra::new`], whose errors
//! [`locate`] turns into `syn::Error`s at the offending tokens.

use ga_codegen::{
    Algebra, AlgebraDeclaration, BasisVectorDeclaration, Error, Layout, Location, Operation, Rational64, ScalarType,
    TypeDeclaration,
};
use quote::ToTokens;
use syn::{Attribute, BinOp, Expr, ExprBinary, ExprLit, ExprUnary, Ident, Lit, UnOp};

use crate::diagnostics::{both, collect};
use crate::parse::{AlgebraInput, BasisEntry, LayoutSyntax, MetricRow, TypeEntry};

/// The declaration written in `input`, checked by the compiler.
pub fn validate(input: &AlgebraInput) -> syn::Result<AlgebraDeclaration> {
    let scalar = scalar_type(&input.scalar);
    let has_metric = input.metric.is_some();
    let basis = collect(input.basis.vectors.iter().map(|entry| basis_vector(entry, has_metric)));
    let metric = input
        .metric
        .as_ref()
        .map(|metric| collect(metric.rows.iter().map(metric_row)));
    let types = collect(input.types.iter().map(type_declaration));
    let operations = input.ops.as_ref().map(|names| collect(names.iter().map(operation)));
    let (metric, operations) = (metric.transpose(), operations.transpose());
    let ((((scalar, basis), metric), types), operations) =
        both(both(both(both(scalar, basis), metric), types), operations)?;
    let declaration = AlgebraDeclaration {
        scalar,
        basis,
        metric,
        types,
        operations,
    };
    // `generate` checks this too, but checking here makes every declaration that leaves this module
    // one the compiler accepts, which the tests can see without emitting any code.
    Algebra::new(&declaration).map_err(|error| locate(input, &error))?;
    Ok(declaration)
}

/// The compiler's `error` as a `syn::Error` at the tokens of `input` it is about.
pub fn locate(input: &AlgebraInput, error: &Error) -> syn::Error {
    syn::Error::new_spanned(offending_tokens(input, error), error)
}

fn offending_tokens<'a>(input: &'a AlgebraInput, error: &Error) -> &'a dyn ToTokens {
    let module_name = &input.name;
    match error.location() {
        // Errors about the basis as a whole read best next to the basis.
        Location::Algebra if matches!(error, Error::EmptyBasis | Error::TooManyBasisVectors { .. }) => &input.basis.key,
        Location::Algebra => module_name,
        Location::Basis(index) => match input.basis.vectors.get(index) {
            Some(BasisEntry {
                square: Some(square), ..
            }) if matches!(error, Error::InvalidSquare { .. }) => square,
            Some(vector) => &vector.name,
            None => module_name,
        },
        Location::Metric => match &input.metric {
            Some(metric) => &metric.key,
            None => module_name,
        },
        Location::MetricRow(row) => match input.metric.as_ref().and_then(|metric| metric.rows.get(row)) {
            Some(row) => row,
            None => module_name,
        },
        Location::MetricEntry { row, column } => {
            let row = input.metric.as_ref().and_then(|metric| metric.rows.get(row));
            match row.and_then(|row| row.entries.get(column)) {
                Some(entry) => entry,
                None => module_name,
            }
        }
        Location::Type(index) => match input.types.get(index) {
            Some(entry) => &entry.name,
            None => module_name,
        },
        Location::TypeItem { ty, item } => match input.types.get(ty) {
            Some(entry) => entry.layout.item(item).unwrap_or(&entry.name),
            None => module_name,
        },
        Location::Operation(index) => match input.ops.as_ref().and_then(|names| names.get(index)) {
            Some(name) => name,
            None => module_name,
        },
    }
}

fn scalar_type(name: &Ident) -> syn::Result<ScalarType> {
    ScalarType::from_name(&name.to_string()).ok_or_else(|| {
        syn::Error::new(
            name.span(),
            format!("unknown scalar type `{name}`: expected f32 or f64"),
        )
    })
}

/// A basis vector with its square, or — when a `metric` matrix gives the squares — its name alone.
fn basis_vector(entry: &BasisEntry, has_metric: bool) -> syn::Result<BasisVectorDeclaration> {
    let square = match (&entry.square, has_metric) {
        (Some(square), false) => {
            let magnitude: i64 = square.magnitude.base10_parse()?;
            if square.minus.is_some() {
                -magnitude
            } else {
                magnitude
            }
        }
        // Not read by the compiler: the metric's diagonal is the square.
        (None, true) => 0,
        (Some(square), true) => {
            return Err(syn::Error::new_spanned(
                square,
                format!(
                    "basis vector `{}` has a square, but the `metric` matrix gives the squares: \
                     with a metric, list only the names of the basis vectors",
                    entry.name
                ),
            ))
        }
        (None, false) => {
            return Err(syn::Error::new(
                entry.name.span(),
                format!(
                    "basis vector `{0}` has no square: write `{0} = 1`, `{0} = -1` or `{0} = 0`, \
                     or give every inner product in a `metric` matrix",
                    entry.name
                ),
            ))
        }
    };
    Ok(BasisVectorDeclaration {
        name: entry.name.to_string(),
        square,
    })
}

fn metric_row(row: &MetricRow) -> syn::Result<Vec<Rational64>> {
    collect(row.entries.iter().map(rational))
}

/// A metric entry: an integer or a fraction of integers, optionally negative (`1`, `-1`, `1/2`, `-1/2`).
fn rational(entry: &Expr) -> syn::Result<Rational64> {
    let (numerator, denominator) = match entry {
        Expr::Binary(ExprBinary {
            left,
            op: BinOp::Div(_),
            right,
            ..
        }) => (signed_integer(left, entry)?, integer(right, entry)?),
        _ => (signed_integer(entry, entry)?, 1),
    };
    if denominator == 0 {
        return Err(syn::Error::new_spanned(
            entry,
            "a metric entry cannot have a zero denominator",
        ));
    }
    Ok(Rational64::new(numerator, denominator))
}

/// `n` or `-n` for an integer literal `n`; any other expression is an error at `entry`, the whole
/// metric entry it belongs to.
fn signed_integer(expression: &Expr, entry: &Expr) -> syn::Result<i64> {
    match expression {
        Expr::Unary(ExprUnary {
            op: UnOp::Neg(_),
            expr: magnitude,
            ..
        }) => Ok(-integer(magnitude, entry)?),
        _ => integer(expression, entry),
    }
}

fn integer(expression: &Expr, entry: &Expr) -> syn::Result<i64> {
    match expression {
        Expr::Lit(ExprLit { lit: Lit::Int(int), .. }) => int.base10_parse(),
        _ => Err(syn::Error::new_spanned(
            entry,
            "a metric entry must be a rational number: an integer or a fraction such as `1/2` or `-1/2`",
        )),
    }
}

fn type_declaration(entry: &TypeEntry) -> syn::Result<TypeDeclaration> {
    let attributes = collect(entry.attrs.iter().map(documentation_only));
    let layout = match &entry.layout {
        LayoutSyntax::Grades(grades) => collect(grades.iter().map(|grade| grade.base10_parse())).map(Layout::Grades),
        LayoutSyntax::Blades(blades) => Ok(Layout::Blades(blades.iter().map(Ident::to_string).collect())),
        LayoutSyntax::All => Ok(Layout::All),
    };
    let (_, layout) = both(attributes, layout)?;
    Ok(TypeDeclaration {
        name: entry.name.to_string(),
        layout,
    })
}

/// Doc comments are carried onto the emitted struct; any other attribute (a derive, a cfg) would
/// apply to the struct but not to the operations emitted for it, so it is refused.
fn documentation_only(attribute: &Attribute) -> syn::Result<()> {
    if attribute.path().is_ident("doc") {
        Ok(())
    } else {
        Err(syn::Error::new_spanned(
            attribute,
            "only doc comments are allowed on a type declaration",
        ))
    }
}

fn operation(name: &Ident) -> syn::Result<Operation> {
    Operation::from_name(&name.to_string()).ok_or_else(|| {
        let valid: Vec<String> = Operation::ALL.iter().map(|op| format!("`{}`", op.name())).collect();
        syn::Error::new(
            name.span(),
            format!("unknown operation `{name}`: expected one of {}", valid.join(", ")),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn declaration(source: &str) -> syn::Result<AlgebraDeclaration> {
        validate(&syn::parse_str(source)?)
    }

    fn messages(source: &str) -> Vec<String> {
        match declaration(source) {
            Ok(declaration) => panic!("expected errors, got {declaration:?}"),
            Err(errors) => errors.into_iter().map(|error| error.to_string()).collect(),
        }
    }

    #[test]
    fn settings_map_to_the_declaration_in_any_order() {
        let declaration = declaration(
            "pub mod pga {
                ops = [geometric, reverse];
                types {
                    /// A rigid motion.
                    Motor = grades(0, 2, 4);
                    Translator = blades(scalar, e01, e02, e03);
                    Multivector = all;
                }
                basis = [e0 = 0, e1 = 1, e2 = 1, e3 = -1];
                scalar = f32;
            }",
        )
        .unwrap();
        assert_eq!(
            declaration,
            AlgebraDeclaration {
                scalar: ScalarType::F32,
                basis: [("e0", 0), ("e1", 1), ("e2", 1), ("e3", -1)]
                    .map(|(name, square)| BasisVectorDeclaration {
                        name: name.to_string(),
                        square
                    })
                    .to_vec(),
                metric: None,
                types: vec![
                    TypeDeclaration {
                        name: "Motor".to_string(),
                        layout: Layout::Grades(vec![0, 2, 4]),
                    },
                    TypeDeclaration {
                        name: "Translator".to_string(),
                        layout: Layout::Blades(["scalar", "e01", "e02", "e03"].map(String::from).to_vec()),
                    },
                    TypeDeclaration {
                        name: "Multivector".to_string(),
                        layout: Layout::All,
                    },
                ],
                operations: Some(vec![Operation::Geometric, Operation::Reverse]),
            }
        );
    }

    #[test]
    fn permuted_blade_names_pass_through_unchanged() {
        let declaration = declaration(
            "mod vga { scalar = f64; basis = [e1 = 1, e2 = 1, e3 = 1]; types { Bivector = blades(e23, e31, e12); } }",
        )
        .unwrap();
        assert_eq!(
            declaration.types[0].layout,
            Layout::Blades(["e23", "e31", "e12"].map(String::from).to_vec())
        );
        assert_eq!(declaration.operations, None);
    }

    #[test]
    fn a_metric_gives_rational_entries_and_leaves_the_basis_names_only() {
        let declaration = declaration(
            "mod null {
                scalar = f64;
                basis = [e1, n0, ninf];
                metric = [[1, 0, 0], [0, 0, -1/2], [0, -1 / 2, 0]];
                types { Vector = grades(1); }
            }",
        )
        .unwrap();
        let (zero, one, half) = (Rational64::from(0), Rational64::from(1), Rational64::new(1, 2));
        assert_eq!(
            declaration.metric,
            Some(vec![
                vec![one, zero, zero],
                vec![zero, zero, -half],
                vec![zero, -half, zero]
            ])
        );
        let names: Vec<&str> = declaration.basis.iter().map(|v| v.name.as_str()).collect();
        assert_eq!(names, ["e1", "n0", "ninf"]);
    }

    #[test]
    fn independent_mistakes_are_reported_together() {
        let errors = messages(
            "mod bad {
                scalar = f16;
                basis = [e1 = 99999999999999999999];
                types { #[derive(Hash)] Vector = grades(1); }
                ops = [geometric, wedge];
            }",
        );
        assert_eq!(errors.len(), 4, "{errors:?}");
        assert_eq!(errors[0], "unknown scalar type `f16`: expected f32 or f64");
        assert_eq!(errors[1], "number too large to fit in target type");
        assert_eq!(errors[2], "only doc comments are allowed on a type declaration");
        assert!(errors[3].starts_with("unknown operation `wedge`: expected one of `geometric`, `outer`"));
    }

    #[test]
    fn compiler_errors_keep_their_message() {
        let errors = messages("mod vga { scalar = f64; basis = [e1 = 1, e2 = -2]; types { Vector = grades(1); } }");
        assert_eq!(errors, ["basis vector `e2` squares to -2; a square must be 1, -1 or 0"]);
    }

    #[test]
    fn compiler_errors_point_at_the_offending_tokens() {
        let input: AlgebraInput = syn::parse_str(
            "mod vga {
                scalar = f64;
                basis = [e1 = 1, e2 = -2];
                types { Vector = grades(1); Pair = blades(e1, e3); Empty = grades(); }
                ops = [outer, reverse];
            }",
        )
        .unwrap();
        let tokens = |error: Error| offending_tokens(&input, &error).to_token_stream().to_string();
        let invalid_square = Error::InvalidSquare {
            index: 1,
            name: "e2".to_string(),
            square: -2,
        };
        assert_eq!(tokens(invalid_square), "- 2");
        let duplicate_name = Error::DuplicateBasisName {
            index: 1,
            name: "e2".to_string(),
        };
        assert_eq!(tokens(duplicate_name), "e2");
        let unknown_blade = Error::UnknownBlade {
            ty_index: 1,
            item: 1,
            ty: "Pair".to_string(),
            blade: "e3".to_string(),
            reason: String::new(),
        };
        assert_eq!(tokens(unknown_blade), "e3");
        let empty = Error::EmptyType {
            index: 2,
            name: "Empty".to_string(),
        };
        assert_eq!(tokens(empty), "Empty");
        let duplicate_operation = Error::DuplicateOperation {
            index: 1,
            name: "reverse".to_string(),
        };
        assert_eq!(tokens(duplicate_operation), "reverse");
        assert_eq!(tokens(Error::EmptyBasis), "basis");
        let no_result = Error::NoResultType {
            operation: "geometric".to_string(),
            lhs: "Vector".to_string(),
            rhs: "Vector".to_string(),
            blades: Vec::new(),
        };
        assert_eq!(tokens(no_result), "vga");
    }
}
