ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types { Vector = grades(1); }
        features = [display, serde, display];
    }
}

// PGA's grade-1 type is a plane (`e0` squares to 0): no mint type means that.
ga_macros::algebra! {
    mod pga {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types { Plane = grades(1); Multivector = all; }
        features = [mint];
    }
}

fn main() {}
