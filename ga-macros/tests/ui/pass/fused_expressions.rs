ga_macros::algebra! {
    /// 3D projective geometric algebra with fused expressions.
    pub mod pga {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types {
            Motor = grades(0, 2, 4);
            Line = grades(2);
            Point = grades(3);
            // So that every product of the types above has a result type.
            Plane = grades(1);
            Odd = grades(1, 3);
        }
        // A call of an expression declared further down.
        fn chained(m: Motor, l: Line) -> Line = moved_line(m, moved_line(m, l));
        // Also emitted as the motor's 6×6 line map: `moved_line_map(m)`, then `apply` per line.
        #[linear(l)]
        fn moved_line(m: Motor, l: Line) -> Line = m * l * ~m;
        // Without `-> Type`, the smallest declared type holding the result.
        fn moved_point(m: Motor, p: Point) = m * p * ~m;
        fn twice(m: Motor, t: f64) -> Motor = 2.0 * t * m + m.grade_2() / 2.0 - (m ^ m).grade_4();
        fn weight(m: Motor) -> f64 = m.norm_squared();
        // Linear maps in a scalar parameter (one column) and onto a bare scalar (one row).
        #[linear(t)]
        fn scaled(m: Motor, t: f64) -> Motor = t * m;
        #[linear(l)]
        fn inner(a: Line, l: Line) -> f64 = (a * l).grade_0();
        // A parameter named like the map builder's entry locals (`entry_0_0`, …), which are then named apart.
        #[linear(l)]
        fn entries(entry_0_0: Motor, l: Line) -> Line = entry_0_0 * l * ~entry_0_0;
        fn methods(m: Motor, l: Line) -> Motor = -m.geometric(l).reverse() + m.regressive(l) * 0.25e1 | m;
    }
}

use pga::{Line, Motor, Point};

fn main() {
    // Small integer coefficients: every product and sum below is exact in f64, whatever the order.
    let m = Motor::from_array([1.0, 2.0, -1.0, 3.0, 1.0, -2.0, 1.0, 2.0]);
    let l = Line::from_array([1.0, -2.0, 3.0, 2.0, 1.0, -1.0]);
    let p = Point::from_array([2.0, -1.0, 3.0, 1.0]);

    let reference: Line = (m * l * m.reverse()).grade_2();
    assert_eq!(pga::moved_line(m, l), reference);
    let moved: Point = pga::moved_point(m, p);
    assert_eq!(moved, (m * p * m.reverse()).grade_3());
    assert_eq!(pga::chained(m, l), pga::moved_line(m, reference));
    let map: pga::MovedLineMap = pga::moved_line_map(m);
    assert_eq!(map.apply(l), reference);
    const MAP: pga::MovedLineMap = pga::moved_line_map(Motor::from_array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]));
    assert_eq!(MAP.apply(l), l);
    assert_eq!(pga::entries_map(m).apply(l), reference);

    let scaled: pga::ScaledMap = pga::scaled_map(m);
    assert_eq!(scaled.apply(3.0), pga::scaled(m, 3.0));
    assert_eq!(pga::inner_map(l).apply(l), pga::inner(l, l));
    assert_eq!(pga::inner(l, l), (l * l).scalar);

    let weight: f64 = pga::weight(m);
    assert_eq!(weight, (m * m.reverse()).scalar);

    let expected: Motor = 2.0 * 3.0 * m + Motor::from(m.grade_2() / 2.0) - Motor::from((m ^ m).grade_4());
    assert_eq!(pga::twice(m, 3.0), expected);

    // `|` binds loosest, as in Rust: (-(m l)~ + (m & l) * 2.5) ⌋ m.
    let left = -(m * l).reverse() + Motor::from((m & l) * 2.5);
    assert_eq!(pga::methods(m, l), (left | m).into());
}
