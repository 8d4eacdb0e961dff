// CGA on a null basis with only the motor type: the motor's complement has blades no type holds.
ga_macros::algebra! {
    pub mod cga {
        scalar = f64;
        basis = [e1, e2, e3, n0, ninf];
        metric = [[1, 0, 0, 0, 0], [0, 1, 0, 0, 0], [0, 0, 1, 0, 0], [0, 0, 0, 0, -1], [0, 0, 0, -1, 0]];
        types { Motor = blades(scalar, e1_e2, e1_e3, e2_e3, e1_ninf, e2_ninf, e3_ninf, e1_e2_e3_ninf); }
    }
}

// With `ops`, the error points at the operation.
ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types { Vector = grades(1); }
        ops = [reverse, geometric];
    }
}

fn main() {}
