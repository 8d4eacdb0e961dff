ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Vector = grades(1);
            Rotor = grades(0, 2);
        }
        // Each malformed expression is reported; `negative_half` is well formed.
        fn or(a: Vector, b: Vector) -> Rotor = a || b;
        fn not(a: Vector) -> Vector = !a;
        fn reverse_twice(r: Rotor) -> Rotor = r.reverse(r);
        fn tiny(a: Vector) -> Vector = 1e-30 * a;
        fn negative_half(a: Vector) -> Vector = a / -0.5;
        fn half(a: Vector) -> Vector = a / 0.0;
        fn block(a: Vector) -> Vector { a }
    }
}

fn main() {}
