ga_macros::algebra! {
    /// The plane's vector algebra.
    #[allow(dead_code)]
    pub mod vga2 {
        ops = [geometric, reverse];
        types {
            /// A direction in the plane.
            Vector = grades(1);
            /// A rotation.
            Rotor = blades(scalar, e12);
            Multivector = all;
        }
        basis = [e1 = 1, e2 = 1];
        scalar = f32;
    }
}

// Only names the types: what they offer is ga-codegen's to test.
fn main() {
    let _ = std::mem::size_of::<(vga2::Vector, vga2::Rotor, vga2::Multivector)>();
}
