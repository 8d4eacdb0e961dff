// Unicode identifiers (XID), as Rust accepts them, for basis vectors and types.
#![allow(mixed_script_confusables, confusable_idents, uncommon_codepoints)]

ga_macros::algebra! {
    pub mod vga {
        scalar = f64;
        basis = [α = 1, β = 1];
        types {
            Vector = grades(1);
            Rotor = grades(0, 2);
            Пара = blades(β_α);
            Multivector = all;
        }
        ops = [geometric, outer, reverse];
    }
}

use vga::Outer as _;

fn main() {
    let a = vga::Vector { α: 1.0, β: 2.0 };
    let b = vga::Vector { α: 3.0, β: 4.0 };
    let product: vga::Rotor = a * b;
    assert_eq!(product, vga::Rotor { scalar: 11.0, α_β: -2.0 });
    assert_eq!(vga::Rotor::BLADES, ["scalar", "α_β"]);
    // `β_α` stores −`α_β`; the `const fn` form is named after the type in snake case.
    let pair: vga::Пара = a.outer_пара(vga::Пара { β_α: 1.0 });
    assert_eq!(pair, vga::Пара { β_α: 0.0 });
    let wedge: vga::Пара = a.outer(b);
    assert_eq!(wedge.β_α, 2.0);
    assert_eq!(product.reverse().α_β, 2.0);
}
