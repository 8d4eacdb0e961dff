//! The seven reference algebras, declared exactly as in the reference data (basis vectors in bit
//! order with their squares). Only the operations the reference covers are emitted.

ga_macros::algebra! {
    /// Cl(3,0,0): Euclidean 3D (VGA).
    pub mod cl300 {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1];
        types {
            Multivector = all;
        }
        ops = [geometric, outer, left_contraction, right_contraction, scalar_product, hestenes_inner, fat_dot,
               regressive, reverse, involute, conjugate, right_complement, left_complement, polarity];
    }
}

ga_macros::algebra! {
    /// Cl(3,0,1): projective (PGA), e0 first.
    pub mod cl301 {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types {
            Multivector = all;
        }
        ops = [geometric, outer, left_contraction, right_contraction, scalar_product, hestenes_inner, fat_dot,
               regressive, reverse, involute, conjugate, right_complement, left_complement, polarity];
    }
}

ga_macros::algebra! {
    /// Cl(4,1,0): conformal (CGA).
    pub mod cl410 {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1, e4 = 1, e5 = -1];
        types {
            Multivector = all;
        }
        ops = [geometric, outer, left_contraction, right_contraction, scalar_product, hestenes_inner, fat_dot,
               regressive, reverse, involute, conjugate, right_complement, left_complement, polarity];
    }
}

ga_macros::algebra! {
    /// Cl(1,3,0): spacetime (STA).
    pub mod cl130 {
        scalar = f64;
        basis = [e0 = 1, e1 = -1, e2 = -1, e3 = -1];
        types {
            Multivector = all;
        }
        ops = [geometric, outer, left_contraction, right_contraction, scalar_product, hestenes_inner, fat_dot,
               regressive, reverse, involute, conjugate, right_complement, left_complement, polarity];
    }
}

ga_macros::algebra! {
    /// Cl(2,0,2): two null vectors first.
    pub mod cl202 {
        scalar = f64;
        basis = [e1 = 0, e2 = 0, e3 = 1, e4 = 1];
        types {
            Multivector = all;
        }
        ops = [geometric, outer, left_contraction, right_contraction, scalar_product, hestenes_inner, fat_dot,
               regressive, reverse, involute, conjugate, right_complement, left_complement, polarity];
    }
}

ga_macros::algebra! {
    /// Cl(0,3,0): the quaternions' algebra.
    pub mod cl030 {
        scalar = f64;
        basis = [e1 = -1, e2 = -1, e3 = -1];
        types {
            Multivector = all;
        }
        ops = [geometric, outer, left_contraction, right_contraction, scalar_product, hestenes_inner, fat_dot,
               regressive, reverse, involute, conjugate, right_complement, left_complement, polarity];
    }
}

ga_macros::algebra! {
    /// Cl(4,4,0): 256 blades.
    pub mod cl440 {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1, e4 = 1, e5 = -1, e6 = -1, e7 = -1, e8 = -1];
        types {
            Multivector = all;
        }
        ops = [geometric, outer, left_contraction, right_contraction, scalar_product, hestenes_inner, fat_dot,
               regressive, reverse, involute, conjugate, right_complement, left_complement, polarity];
    }
}
