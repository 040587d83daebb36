//! The fast exact kernels against the generic `BigRational` oracle, on
//! random data scaled to every width and at random times — the overflow
//! edges included: `prop:proj-micro`'s `x(t) = P_K(x⁰ + t u⁰)` must come
//! out the same whatever integer type computed it.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::One;
use proptest::prelude::*;

use sticky::fast::adaptive::adaptive_blocks_at;
use sticky::fast::kernel::{self, blocks_at, IntegerData, Width};
use sticky::generate::{initial_data, Limits};
use sticky::projection;
use sticky::InitialData;

/// The data, every position scaled by `2^scale` and shifted by
/// `2^offset + 1/3`: large scales push `b_Y` across the `i128` and 256-bit
/// bounds, the offset adds digits that no width absorbs by cancellation.
fn scaled(bytes: &[u8], max_n: usize, scale: u32, offset: u32) -> InitialData<BigRational> {
    let data = initial_data(
        bytes,
        Limits {
            max_n,
            ..Limits::default()
        },
    );
    let s = BigRational::from_integer(BigInt::one() << scale);
    let o = BigRational::from_integer(BigInt::one() << offset)
        + BigRational::new(BigInt::one(), BigInt::from(3));
    let x = data.positions().iter().map(|x| x * &s + &o).collect();
    let r = data.radius() * &s;
    let u = data.velocities().iter().map(|u| u * &s).collect();
    InitialData::new(r, x, u).expect("scaling and shifting keep the data admissible")
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: if cfg!(debug_assertions) { 64 } else { 512 },
        ..ProptestConfig::default()
    })]

    /// Kernel and adaptive solver equal the generic path, field by field.
    #[test]
    fn kernels_equal_the_oracle(
        bytes in proptest::collection::vec(any::<u8>(), 0..200),
        max_n in 1usize..40,
        scale in 0u32..300,
        offset in 0u32..330,
        tn in 0i64..1000,
        td in 1i64..1000,
    ) {
        let data = scaled(&bytes, max_n, scale, offset);
        let d = IntegerData::new(&data);
        let t = BigRational::new(BigInt::from(tn), BigInt::from(td));
        let want = projection::state_at(&data, &t).unwrap();
        prop_assert_eq!(kernel::state_at(&d, &t).unwrap(), want);
        prop_assert_eq!(adaptive_blocks_at(&d, &t).blocks, blocks_at(&d, &t));
    }
}

/// The proptest ranges above reach every width (a guard against a generator
/// that silently stops exercising one).
#[test]
fn the_ranges_reach_every_width() {
    let bytes: Vec<u8> = (0..120u8).map(|b| b.wrapping_mul(37)).collect();
    let t = BigRational::new(BigInt::from(7), BigInt::from(3));
    let width = |scale, offset| {
        blocks_at(&IntegerData::new(&scaled(&bytes, 30, scale, offset)), &t).width()
    };
    assert_eq!(width(0, 0), Width::I128);
    assert_eq!(width(0, 100), Width::I256);
    assert_eq!(width(250, 0), Width::Big);
    assert_eq!(width(0, 320), Width::Big);
}
