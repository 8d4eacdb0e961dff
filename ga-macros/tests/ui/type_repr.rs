ga_macros::algebra! {
    mod vga {
        scalar = f32;
        basis = [e1 = 1, e2 = 1];
        types {
            #[repr(C, packed)]
            Vector = grades(1);
            #[repr(transparent)]
            Rotor = grades(0, 2);
            #[cfg_attr(target_os = "none", repr(u8))]
            Scalar = blades(scalar);
        }
    }
}

fn main() {}
