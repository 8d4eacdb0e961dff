//! Opt-in impls of ecosystem traits for the declared types, emitted only when asked for (the
//! `features = [display, approx, mint]` setting of `algebra!`, or [`crate::generate_with_features`]):
//!
//! - [`Feature::Display`]: `core::fmt::Display`, the non-zero coefficients as a sum of blades,
//!   `1.5 + 2*e12 - 0.5*e0123` (see [`display`]).
//! - [`Feature::Approx`]: `::approx::AbsDiffEq`, `RelativeEq` and `UlpsEq`, coefficient by coefficient
//!   with the scalar's own tolerances; the user's crate must depend on `approx` (0.5).
//! - [`Feature::Mint`]: `From` conversions both ways between a type and the `mint` type it maps to,
//!   and `mint::IntoMint` naming that type, for the types [`mint_mapping`] maps and nothing for the
//!   others; the user's crate must depend on `mint` (0.5.8 or later, for `IntoMint`).
//!
//! The types themselves and every other emitted item are the same with or without features.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

use crate::algebra::{Algebra, SparseType};
use crate::blade::{grade, BladeMask};

/// An opt-in group of trait impls for every declared type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Feature {
    /// `core::fmt::Display`.
    Display,
    /// `approx::{AbsDiffEq, RelativeEq, UlpsEq}`.
    Approx,
    /// Conversions to and from `mint` types.
    Mint,
}

impl Feature {
    /// Every feature, in the order their impls are emitted.
    pub const ALL: [Feature; 3] = [Feature::Display, Feature::Approx, Feature::Mint];

    /// The name in `features = [...]`: `display`, `approx` or `mint`.
    pub fn name(self) -> &'static str {
        match self {
            Feature::Display => "display",
            Feature::Approx => "approx",
            Feature::Mint => "mint",
        }
    }

    /// The feature called `name`, if any.
    ///
    /// ```
    /// use ga_codegen::Feature;
    ///
    /// assert_eq!(Feature::from_name("approx"), Some(Feature::Approx));
    /// assert_eq!(Feature::from_name("serde"), None);
    /// // Every feature is found by its own name.
    /// assert!(Feature::ALL.into_iter().all(|feature| Feature::from_name(feature.name()) == Some(feature)));
    /// ```
    pub fn from_name(name: &str) -> Option<Feature> {
        Feature::ALL.into_iter().find(|feature| feature.name() == name)
    }
}

/// The `mint` type a declared type converts to and from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MintType {
    /// `mint::Vector2`.
    Vector2,
    /// `mint::Vector3`.
    Vector3,
    /// `mint::Vector4`.
    Vector4,
    /// `mint::Quaternion`.
    Quaternion,
}

impl MintType {
    /// The type's name in `mint` (`Vector3`).
    pub fn name(self) -> &'static str {
        match self {
            MintType::Vector2 => "Vector2",
            MintType::Vector3 => "Vector3",
            MintType::Vector4 => "Vector4",
            MintType::Quaternion => "Quaternion",
        }
    }
}

/// How a declared type maps to a `mint` type: each component of the mint value (`x`, `y`, `z`, `w`
/// of a vector; `v.x`, `v.y`, `v.z`, `s` of a quaternion, in that order) is `sign ×` a field.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MintMapping {
    /// The `mint` type the declared type converts to and from.
    pub mint: MintType,
    /// `(field index, sign)` per component.
    pub components: Vec<(usize, i64)>,
}

/// The `mint` type `ty` converts to and from, if the mapping is unambiguous. Two kinds of types map,
/// and only these:
///
/// - **Vectors.** 2, 3 or 4 fields, each a grade-1 blade, whose basis vectors are orthonormal (each
///   squares to +1, any two are orthogonal): `mint::Vector2`/`Vector3`/`Vector4`, with `x`, `y`, `z`,
///   `w` the coefficients in *basis order* (the first basis vector is `x`), whatever the storage
///   order. `Vector = grades(1)` of a 3D euclidean algebra, or `blades(e1, e2, e3)` of PGA, is a
///   `mint::Vector3`; PGA's `grades(1)` (a plane: `e0` is null) and CGA's vectors are not vectors of
///   a euclidean space and do not map.
/// - **Rotors.** 4 fields: the scalar and the three bivectors of three orthonormal basis vectors
///   a, b, c (in basis order), e.g. `blades(scalar, e12, e13, e23)` or `blades(scalar, e23, e31,
///   e12)`: `mint::Quaternion`, with `s` = scalar, `v.x` = −e_bc, `v.y` = e_ac = −e_ca and `v.z` =
///   −e_ab. With these signs a unit rotor `R` and its quaternion `q` rotate alike: `R x ~R` (the
///   emitted `transform`) is `q x q*` for the vector `x` mapped as above, so `cos θ/2 − sin θ/2 e12`
///   and the quaternion `cos θ/2 + sin θ/2 k` both turn e1 towards e2 by θ.
///
/// Anything else (a point, a motor, a grade-1 type over a null or negative vector, a bivector alone)
/// has no single meaning as a mint type, so it gets no conversion.
pub fn mint_mapping(algebra: &Algebra, ty: &SparseType) -> Option<MintMapping> {
    let vectors: BladeMask = ty.fields.iter().fold(0, |mask, field| mask | field.blade);
    let basis: Vec<usize> = (0..algebra.dimension()).filter(|&i| vectors & (1 << i) != 0).collect();
    let orthonormal = basis.iter().all(|&i| {
        algebra.metric.square(i) == 1.into() && basis.iter().all(|&j| i == j || algebra.metric.inner(i, j) == 0.into())
    });
    if !orthonormal {
        return None;
    }
    // The field holding the canonical blade of these basis vectors, with the sign that turns the
    // field into that blade's coefficient.
    let field = |indices: &[usize]| {
        let blade = indices.iter().fold(0, |mask: BladeMask, &i| mask | (1 << i));
        ty.fields
            .iter()
            .position(|field| field.blade == blade)
            .map(|index| (index, ty.fields[index].sign))
    };
    let grades: Vec<u32> = ty.fields.iter().map(|field| grade(field.blade)).collect();
    if grades.iter().all(|&g| g == 1) {
        let mint = match ty.fields.len() {
            2 => MintType::Vector2,
            3 => MintType::Vector3,
            4 => MintType::Vector4,
            _ => return None,
        };
        let components = basis.iter().map(|&i| field(&[i])).collect::<Option<Vec<_>>>()?;
        return Some(MintMapping { mint, components });
    }
    let mut sorted = grades;
    sorted.sort_unstable();
    if sorted == [0, 2, 2, 2] && basis.len() == 3 {
        let (a, b, c) = (basis[0], basis[1], basis[2]);
        let negated = |(index, sign): (usize, i64)| (index, -sign);
        let components = vec![
            negated(field(&[b, c])?),
            field(&[a, c])?,
            negated(field(&[a, b])?),
            field(&[])?,
        ];
        return Some(MintMapping {
            mint: MintType::Quaternion,
            components,
        });
    }
    None
}

/// The impls of `features` for every declared type of `algebra`.
pub fn emit(algebra: &Algebra, features: &[Feature]) -> TokenStream {
    let scalar = format_ident!("{}", algebra.scalar.name());
    let mut items = TokenStream::new();
    for feature in Feature::ALL.into_iter().filter(|feature| features.contains(feature)) {
        for ty in &algebra.types {
            items.extend(match feature {
                Feature::Display => display(ty, &scalar),
                Feature::Approx => approx(ty, &scalar),
                Feature::Mint => mint_mapping(algebra, ty)
                    .map(|mapping| mint(ty, &scalar, &mapping))
                    .unwrap_or_default(),
            });
        }
    }
    items
}

/// `impl core::fmt::Display`: the non-zero coefficients in storage order, each followed by `*` and
/// its field's blade name (none for `scalar`), joined by ` + ` or ` - ` (the sign of the coefficient):
/// `1.5 + 2*e12 - 0.5*e0123`. Coefficients equal to zero (either sign) are skipped, and a value
/// whose coefficients are all zero prints `0`. A precision (`{:.3}`) applies to every coefficient;
/// other formatting flags are ignored. NaN prints as `+ NaN*e1`.
///
/// The `*` keeps `2*e12` from reading as 2·10¹², and the text is a valid Rust expression over
/// blade constants of those names.
pub fn display(ty: &SparseType, scalar: &Ident) -> TokenStream {
    let name = format_ident!("{}", ty.name);
    let count = Literal::usize_unsuffixed(ty.fields.len());
    let terms = ty.fields.iter().map(|field| {
        let ident = format_ident!("{}", field.name);
        let suffix = if field.blade == 0 {
            String::new()
        } else {
            format!("*{}", field.name)
        };
        quote! { (self.#ident, #suffix) }
    });
    let doc = format!(
        " The non-zero coefficients as a sum of blades, e.g. `{}`; `0` if all are zero. A precision \
         (`{{:.3}}`) applies to each coefficient.",
        example(ty)
    );
    quote! {
        impl core::fmt::Display for #name {
            #[doc = #doc]
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                let terms: [(#scalar, &core::primitive::str); #count] = [#(#terms),*];
                let mut empty = true;
                for (value, blade) in terms {
                    if value == 0.0 {
                        continue;
                    }
                    let negative = value < 0.0;
                    let magnitude = if negative { -value } else { value };
                    match (empty, negative) {
                        (true, false) => {}
                        (true, true) => f.write_str("-")?,
                        (false, false) => f.write_str(" + ")?,
                        (false, true) => f.write_str(" - ")?,
                    }
                    match f.precision() {
                        Some(precision) => core::write!(f, "{:.*}", precision, magnitude)?,
                        None => core::write!(f, "{}", magnitude)?,
                    }
                    f.write_str(blade)?;
                    empty = false;
                }
                if empty {
                    let zero: #scalar = 0.0;
                    match f.precision() {
                        Some(precision) => core::write!(f, "{:.*}", precision, zero)?,
                        None => core::write!(f, "{}", zero)?,
                    }
                }
                Ok(())
            }
        }
    }
}

/// What `display` prints for the first (up to) three fields set to 1, −2 and 0.5.
fn example(ty: &SparseType) -> String {
    let mut text = String::new();
    for (field, value) in ty.fields.iter().zip(["1", "2", "0.5"]) {
        let sign = match (text.is_empty(), value) {
            (true, _) => "",
            (false, "2") => " - ",
            (false, _) => " + ",
        };
        let blade = if field.blade == 0 {
            String::new()
        } else {
            format!("*{}", field.name)
        };
        text.push_str(&format!("{sign}{value}{blade}"));
    }
    text
}

/// `::approx::{AbsDiffEq, RelativeEq, UlpsEq}`: every coefficient within the tolerance, by the
/// scalar's own impls and with its default tolerances. Primitive types are named by their `core`
/// paths, which a declared type cannot shadow (`core` is a reserved type name).
pub fn approx(ty: &SparseType, scalar: &Ident) -> TokenStream {
    let name = format_ident!("{}", ty.name);
    quote! {
        impl ::approx::AbsDiffEq for #name {
            type Epsilon = #scalar;
            #[inline]
            fn default_epsilon() -> #scalar {
                <#scalar as ::approx::AbsDiffEq>::default_epsilon()
            }
            /// Every coefficient within `epsilon` of the other's.
            #[inline]
            fn abs_diff_eq(&self, other: &Self, epsilon: #scalar) -> core::primitive::bool {
                let (lhs, rhs) = (self.to_array(), other.to_array());
                lhs.iter()
                    .zip(rhs.iter())
                    .all(|(a, b)| <#scalar as ::approx::AbsDiffEq>::abs_diff_eq(a, b, epsilon))
            }
        }
        impl ::approx::RelativeEq for #name {
            #[inline]
            fn default_max_relative() -> #scalar {
                <#scalar as ::approx::RelativeEq>::default_max_relative()
            }
            /// Every coefficient relatively equal to the other's.
            #[inline]
            fn relative_eq(&self, other: &Self, epsilon: #scalar, max_relative: #scalar) -> core::primitive::bool {
                let (lhs, rhs) = (self.to_array(), other.to_array());
                lhs.iter().zip(rhs.iter()).all(|(a, b)| {
                    <#scalar as ::approx::RelativeEq>::relative_eq(a, b, epsilon, max_relative)
                })
            }
        }
        impl ::approx::UlpsEq for #name {
            #[inline]
            fn default_max_ulps() -> core::primitive::u32 {
                <#scalar as ::approx::UlpsEq>::default_max_ulps()
            }
            /// Every coefficient within `max_ulps` units in the last place of the other's.
            #[inline]
            fn ulps_eq(&self, other: &Self, epsilon: #scalar, max_ulps: core::primitive::u32) -> core::primitive::bool {
                let (lhs, rhs) = (self.to_array(), other.to_array());
                lhs.iter()
                    .zip(rhs.iter())
                    .all(|(a, b)| <#scalar as ::approx::UlpsEq>::ulps_eq(a, b, epsilon, max_ulps))
            }
        }
    }
}

/// `From` both ways between `ty` and its mint type (see [`mint_mapping`]), and `IntoMint`.
pub fn mint(ty: &SparseType, scalar: &Ident, mapping: &MintMapping) -> TokenStream {
    let name = format_ident!("{}", ty.name);
    let mint_type = format_ident!("{}", mapping.mint.name());
    let signed = |tokens: TokenStream, sign: i64| if sign < 0 { quote!(-#tokens) } else { tokens };
    // Component paths in the mint value, in `components` order.
    let paths: Vec<TokenStream> = match mapping.mint {
        MintType::Quaternion => vec![quote!(v.x), quote!(v.y), quote!(v.z), quote!(s)],
        _ => ["x", "y", "z", "w"]
            .iter()
            .take(mapping.components.len())
            .map(|c| {
                let c = format_ident!("{c}");
                quote!(#c)
            })
            .collect(),
    };
    let read_field = |&(index, sign): &(usize, i64)| {
        let field = format_ident!("{}", ty.fields[index].name);
        signed(quote!(value.#field), sign)
    };
    let to_mint = match mapping.mint {
        MintType::Quaternion => {
            let [x, y, z, s] = [0, 1, 2, 3].map(|i| read_field(&mapping.components[i]));
            quote! { ::mint::Quaternion { v: ::mint::Vector3 { x: #x, y: #y, z: #z }, s: #s } }
        }
        _ => {
            let names = paths.iter();
            let values = mapping.components.iter().map(read_field);
            quote! { ::mint::#mint_type { #(#names: #values),* } }
        }
    };
    let mut from_mint: Vec<(usize, TokenStream)> = mapping
        .components
        .iter()
        .zip(&paths)
        .map(|(&(index, sign), path)| {
            let field = format_ident!("{}", ty.fields[index].name);
            let value = signed(quote!(value.#path), sign);
            (index, quote! { #field: #value })
        })
        .collect();
    from_mint.sort_by_key(|(index, _)| *index);
    let from_mint = from_mint.into_iter().map(|(_, tokens)| tokens);
    let to_doc = format!(" The `mint::{}` of a `{}`.", mapping.mint.name(), ty.name);
    let from_doc = format!(" The `{}` of a `mint::{}`.", ty.name, mapping.mint.name());
    quote! {
        impl From<#name> for ::mint::#mint_type<#scalar> {
            #[doc = #to_doc]
            #[inline]
            fn from(value: #name) -> Self {
                #to_mint
            }
        }
        impl From<::mint::#mint_type<#scalar>> for #name {
            #[doc = #from_doc]
            #[inline]
            fn from(value: ::mint::#mint_type<#scalar>) -> Self {
                #name { #(#from_mint),* }
            }
        }
        impl ::mint::IntoMint for #name {
            type MintType = ::mint::#mint_type<#scalar>;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::declaration::{AlgebraDeclaration, BasisVectorDeclaration, Layout, ScalarType, TypeDeclaration};

    fn algebra(basis: &[(&str, i64)], types: &[(&str, Layout)]) -> Algebra {
        Algebra::new(&AlgebraDeclaration {
            scalar: ScalarType::F64,
            basis: basis
                .iter()
                .map(|&(name, square)| BasisVectorDeclaration {
                    name: name.to_string(),
                    square,
                })
                .collect(),
            metric: None,
            types: types
                .iter()
                .map(|(name, layout)| TypeDeclaration {
                    name: name.to_string(),
                    layout: layout.clone(),
                })
                .collect(),
            operations: Some(vec![]),
            lowering: vec![],
            expressions: vec![],
        })
        .unwrap()
    }

    fn blades(names: &[&str]) -> Layout {
        Layout::Blades(names.iter().map(|name| name.to_string()).collect())
    }

    fn mappings(algebra: &Algebra) -> Vec<Option<MintMapping>> {
        algebra.types.iter().map(|ty| mint_mapping(algebra, ty)).collect()
    }

    #[test]
    fn feature_names_round_trip() {
        for feature in Feature::ALL {
            assert_eq!(Feature::from_name(feature.name()), Some(feature));
        }
        assert_eq!(Feature::from_name("serde"), None);
    }

    #[test]
    fn euclidean_vectors_and_rotors_map_in_basis_order() {
        let vga = algebra(
            &[("e1", 1), ("e2", 1), ("e3", 1)],
            &[
                ("Vector", Layout::Grades(vec![1])),
                ("Shuffled", blades(&["e3", "e1", "e2"])),
                ("Rotor", blades(&["scalar", "e12", "e13", "e23"])),
                ("Permuted", blades(&["e23", "e31", "e12", "scalar"])),
                ("Bivector", Layout::Grades(vec![2])),
                ("Pair", blades(&["e1", "e2"])),
            ],
        );
        let vector = |components: Vec<(usize, i64)>| MintMapping {
            mint: if components.len() == 3 {
                MintType::Vector3
            } else {
                MintType::Vector2
            },
            components,
        };
        let quaternion = |components| MintMapping {
            mint: MintType::Quaternion,
            components,
        };
        assert_eq!(
            mappings(&vga),
            [
                Some(vector(vec![(0, 1), (1, 1), (2, 1)])),
                Some(vector(vec![(1, 1), (2, 1), (0, 1)])),
                // x = −e23, y = e13, z = −e12, s = scalar.
                Some(quaternion(vec![(3, -1), (2, 1), (1, -1), (0, 1)])),
                // e31 stores −e13, so y = e13 = −e31.
                Some(quaternion(vec![(0, -1), (1, -1), (2, -1), (3, 1)])),
                None,
                Some(vector(vec![(0, 1), (1, 1)])),
            ]
        );
    }

    #[test]
    fn null_and_negative_vectors_do_not_map() {
        let pga = algebra(
            &[("e0", 0), ("e1", 1), ("e2", 1), ("e3", 1)],
            &[
                ("Plane", Layout::Grades(vec![1])),
                ("Direction", blades(&["e1", "e2", "e3"])),
                ("Ideal", blades(&["e0", "e1"])),
                ("Motor", Layout::Grades(vec![0, 2, 4])),
                ("Rotor", blades(&["scalar", "e12", "e13", "e23"])),
                ("Translator", blades(&["scalar", "e01", "e02", "e03"])),
            ],
        );
        let found: Vec<Option<MintType>> = mappings(&pga)
            .into_iter()
            .map(|mapping| mapping.map(|m| m.mint))
            .collect();
        assert_eq!(
            found,
            [
                None,
                Some(MintType::Vector3),
                None,
                None,
                Some(MintType::Quaternion),
                None
            ]
        );
        let spacetime = algebra(&[("t", -1), ("x", 1), ("y", 1)], &[("Event", Layout::Grades(vec![1]))]);
        assert_eq!(mappings(&spacetime), [None]);
    }

    #[test]
    fn display_docs_show_an_example() {
        let vga = algebra(
            &[("e1", 1), ("e2", 1)],
            &[
                ("Rotor", blades(&["scalar", "e12"])),
                ("Vector", Layout::Grades(vec![1])),
            ],
        );
        assert_eq!(example(&vga.types[0]), "1 - 2*e12");
        assert_eq!(example(&vga.types[1]), "1*e1 - 2*e2");
    }
}
