//! `#[derive(bytemuck::Pod, bytemuck::Zeroable)]` with `#[repr(C)]` (the emitted struct is always
//! `repr(C)`; writing it is allowed) and `#[repr(align(N))]`: slices of coefficients cast for free.

ga_macros::algebra! {
    #[allow(dead_code)]
    mod pga {
        scalar = f32;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types {
            #[derive(bytemuck::Pod, bytemuck::Zeroable)]
            #[repr(C)]
            Motor = grades(0, 2, 4);
            /// Four `f32`s in one 16-byte aligned block, e.g. for a GPU buffer.
            #[derive(bytemuck::Pod, bytemuck::Zeroable)]
            #[repr(C, align(16))]
            Plane = grades(1);
        }
        ops = [reverse];
    }
}

fn main() {
    let motors = [
        pga::Motor::from_array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]),
        pga::Motor::from_array([9.0, 10.0, 11.0, 12.0, 13.0, 14.0, 15.0, 16.0]),
    ];
    let floats: &[f32] = bytemuck::cast_slice(&motors);
    assert_eq!(floats.len(), 16);
    assert_eq!(floats, (1..=16).map(|i| i as f32).collect::<Vec<_>>());
    let back: &[pga::Motor] = bytemuck::cast_slice(floats);
    assert_eq!(back, motors);
    assert_eq!(<pga::Motor as bytemuck::Zeroable>::zeroed(), pga::Motor::ZERO);

    assert_eq!(std::mem::align_of::<pga::Plane>(), 16);
    let plane = pga::Plane::from_array([1.0, 2.0, 3.0, 4.0]);
    assert_eq!(bytemuck::bytes_of(&plane).len(), 16);
    assert_eq!(bytemuck::cast::<pga::Plane, [f32; 4]>(plane), plane.to_array());
}
