//! CGA ≡ PGA, checked at compile time.
//!
//! The simulator is one generic source; it is only right for both algebras if their screw algebras
//! (span{lᵢ, tᵢ} with the commutator product: se(3)) have the same structure constants through the
//! coordinate maps, and if the reciprocal pairing `⟨X ∧ Y⟩_Π` (power, energy; `docs/theory.md` §3–§4) agrees.
//! [`assert_same_screw_algebra!`](crate::assert_same_screw_algebra) evaluates both with the generated `const fn` products for every
//! pair of basis screws and fails the build if anything differs.

/// Fails compilation unless two screw algebras agree on the commutator and the Π-pairing of every
/// pair of basis screws. Each algebra is given as
/// `from_coordinates, commutator, pairing, to_coordinates` (all `const fn`), with coordinates
/// `[l₁, l₂, l₃, t₁, t₂, t₃]`.
///
/// The crate's own maps pass (the crate compiles with this check on them):
///
/// ```
/// dynamics::assert_same_screw_algebra!(
///     dynamics::pga::line_from_coordinates, dynamics::pga::generated::Line::commutator_line,
///     dynamics::pga::wedge_pi, dynamics::pga::line_coordinates;
///     dynamics::cga::screw_from_coordinates, dynamics::cga::generated::Screw::commutator_screw,
///     dynamics::cga::wedge_pi, dynamics::cga::screw_coordinates;
/// );
/// ```
///
/// A CGA map that reads l₁ and l₃ swapped, consistently in both directions (a plausible slip that relabels the
/// screws), fails the build with the constant evaluation's panic (E0080), "the two screw algebras have different
/// commutator structure constants":
///
/// ```compile_fail,E0080
/// use dynamics::cga::generated::Screw;
/// use dynamics::cga::{screw_coordinates, screw_from_coordinates};
///
/// const fn from_swapped(c: [f64; 6]) -> Screw {
///     screw_from_coordinates([c[2], c[1], c[0], c[3], c[4], c[5]])
/// }
///
/// const fn to_swapped(s: Screw) -> [f64; 6] {
///     let c = screw_coordinates(s);
///     [c[2], c[1], c[0], c[3], c[4], c[5]]
/// }
///
/// dynamics::assert_same_screw_algebra!(
///     dynamics::pga::line_from_coordinates, dynamics::pga::generated::Line::commutator_line,
///     dynamics::pga::wedge_pi, dynamics::pga::line_coordinates;
///     from_swapped, Screw::commutator_screw, dynamics::cga::wedge_pi, to_swapped;
/// );
/// ```
#[macro_export]
macro_rules! assert_same_screw_algebra {
    ($from_a:path, $commutator_a:path, $pairing_a:path, $to_a:path;
     $from_b:path, $commutator_b:path, $pairing_b:path, $to_b:path $(;)?) => {
        const _: () = {
            let mut i = 0;
            while i < 6 {
                let mut j = 0;
                while j < 6 {
                    let mut x = [0.0; 6];
                    x[i] = 1.0;
                    let mut y = [0.0; 6];
                    y[j] = 1.0;
                    let commutator_a = $to_a($commutator_a($from_a(x), $from_a(y)));
                    let commutator_b = $to_b($commutator_b($from_b(x), $from_b(y)));
                    let mut k = 0;
                    while k < 6 {
                        assert!(
                            commutator_a[k] == commutator_b[k],
                            "the two screw algebras have different commutator structure constants"
                        );
                        k += 1;
                    }
                    assert!(
                        $pairing_a($from_a(x), $from_a(y)) == $pairing_b($from_b(x), $from_b(y)),
                        "the two screw algebras have different reciprocal (Π) pairings"
                    );
                    j += 1;
                }
                i += 1;
            }
        };
    };
}

assert_same_screw_algebra!(
    crate::pga::line_from_coordinates, crate::pga::generated::Line::commutator_line,
    crate::pga::wedge_pi, crate::pga::line_coordinates;
    crate::cga::screw_from_coordinates, crate::cga::generated::Screw::commutator_screw,
    crate::cga::wedge_pi, crate::cga::screw_coordinates;
);
