//! The inertia map M, its inverse and the kinetic energy (`docs/theory.md` §4), in the algebra-agnostic form:
//! `M(Ḃ) = m Σᵢ [⟨Ḃ∧lᵢ⟩_Π lᵢ + γᵢ ⟨Ḃ∧tᵢ⟩_Π tᵢ]` with `γᵢ = Iᵢ/m`. Since `⟨X∧tᵢ⟩_Π` and
//! `⟨X∧lᵢ⟩_Π` are X's lᵢ and tᵢ coordinates, M moves the velocity's t-part (v) to the momentum's
//! l-part (p = m v) and the l-part (ω) to the t-part (L = Iω).

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::body::Body;

impl Body {
    /// `M(Ḃ)`: body velocity `(ω; v)` → body momentum `Σ pᵢlᵢ + Lᵢtᵢ`.
    #[inline]
    pub fn momentum<A: Algebra>(&self, velocity: A::Screw) -> A::Screw {
        let v = A::screw_coordinates(velocity);
        A::screw(ScrewCoordinates {
            l: self.mass() * v.t,
            t: self.moments().component_mul(&v.l),
        })
    }

    /// `M⁻¹(Ω)`: body momentum → body velocity.
    #[inline]
    pub fn velocity<A: Algebra>(&self, momentum: A::Screw) -> A::Screw {
        let p = A::screw_coordinates(momentum);
        A::screw(ScrewCoordinates {
            l: p.t.component_div(&self.moments()),
            t: p.l / self.mass(),
        })
    }

    /// `½ ⟨Ḃ ∧ M(Ḃ)⟩_Π = ½(m|v|² + ωᵀIω)` (theory §4; the scalar product is *not* the energy).
    #[inline]
    pub fn kinetic_energy<A: Algebra>(&self, velocity: A::Screw) -> f64 {
        0.5 * A::wedge_pi(velocity, self.momentum::<A>(velocity))
    }
}
