//! Isotonic regression (`df:tKN`) and the projection onto
//! `K = {x : x_{i+1} − x_i ≥ 2r}` (`df:KN`, `prop:proj-micro`) of a column
//! of doubles, each read as the exact dyadic rational it is, on machine
//! integers: the dyadic path ([`super`]) at `t = 0` with no velocities.
//!
//! With `2r = a / (b_o 2^{b_s})` (`b_o` odd; `a = 0` for the isotonic
//! regression) and `ex` the least exponent of the nonzero `z_i` (and of
//! `2^{−b_s}` when `a > 0`),
//!
//! `z_i − 2r i = X̃_i 2^{ex} / b_o`, `X̃_i = b_o m_i 2^{e_i − ex} − R i`,
//! `R = a 2^{−b_s − ex}`,
//!
//! with `X̃_i` in `i128`. Unlike [`super::Dyadic::from_doubles`] the column
//! need not lie in `K`: it is any point, and its projection is the PAVA of
//! `X̃` (pairs `(X̃_i, 0)`, plain isotonic regression) on `i128` sums, or
//! 256-bit ones beyond the `i128` bound, shifted back by `+ 2r i` on the
//! integers and rounded once to the nearest double (ties to even). No `f64`
//! arithmetic: each input is read bit by bit (`decompose` in the parent module).
//!
//! `None` when a value is not finite, the radius's terms do not fit 64
//! bits, or a scaled value leaves `i128` (exponents too far apart): the
//! general projection ([`crate::projection::project_k`]) then answers.

use num_rational::BigRational;
use num_traits::Zero;

use super::{bits, decompose, shl_exact, split_odd, Columns, Dyadic};

/// The isotonic regression of `z` (non-decreasing, equal weights), each
/// value the nearest double of the exact one; `None` off the path (module
/// documentation).
pub fn isotonic_doubles(z: &[f64]) -> Option<Vec<f64>> {
    project_doubles(z, &BigRational::zero())
}

/// `P_K(z)` for `K = {x : x_{i+1} − x_i ≥ 2r}` (`df:KN`), each value the
/// nearest double of the exact one; `None` off the path (module
/// documentation) or for a negative radius.
pub fn project_doubles(z: &[f64], radius: &BigRational) -> Option<Vec<f64>> {
    if z.is_empty() {
        return Some(Vec::new());
    }
    let shifted = shifted(z, radius)?;
    shifted.blocks_at(&BigRational::zero())?.positions()
}

/// The column `X̃` of `z` at the scale of its least exponent, as a
/// [`Dyadic`] scene with zero velocities (not checked against `K`: any
/// point projects).
fn shifted(z: &[f64], radius: &BigRational) -> Option<Dyadic> {
    let n = z.len();
    let (a, b_odd, b_s) = split_odd(&(radius + radius))?;
    let parts = z
        .iter()
        .map(|&d| decompose(d))
        .collect::<Option<Vec<_>>>()?;
    let least = parts.iter().filter(|p| p.0 != 0).map(|p| p.1).min();
    // `2^{−b_s}` joins the scale only when 2r is not zero.
    let ex = match (least, a) {
        (Some(e), 0) => e,
        (Some(e), _) => e.min(-b_s),
        (None, 0) => 0,
        (None, _) => -b_s,
    };
    let two_r = if a == 0 {
        0
    } else {
        shl_exact(i128::from(a), u64::try_from(-b_s - ex).ok()?)?
    };
    let b = i128::from(b_odd);
    let mut x = Vec::with_capacity(n);
    let mut shift = 0i128;
    let mut widest = 0u128;
    for &(m, e) in &parts {
        // A zero's exponent is not counted in `ex`: its `X̃` is `−R i`.
        let scaled = if m == 0 {
            0
        } else {
            shl_exact(i128::from(m) * b, u64::try_from(e - ex).ok()?)?
        };
        let v = scaled.checked_sub(shift)?;
        widest |= v.unsigned_abs();
        x.push(v);
        shift = shift.checked_add(two_r)?;
    }
    drop(parts);
    let x_bits = bits(widest);
    Some(Dyadic {
        radius: radius.clone(),
        columns: Columns::new(x, vec![0; n], x_bits, 0),
        ex,
        eu: ex,
        b_odd,
        two_r,
        x_bits,
        u_bits: 0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::SplitMix64;
    use crate::projection;
    use num_bigint::BigInt;

    /// The oracle: the generic projection on the exact values, each
    /// rounded by [`crate::rational::nearest_f64`] (`±∞` beyond range).
    fn generic(z: &[f64], radius: &BigRational) -> Vec<u64> {
        let exact: Vec<BigRational> = z
            .iter()
            .map(|&d| BigRational::from_float(d).unwrap())
            .collect();
        let two_r = radius + radius;
        let out = if two_r.is_zero() {
            projection::isotonic(&exact)
        } else {
            projection::project_k(&exact, &two_r)
        };
        out.iter()
            .map(|q| {
                crate::rational::nearest_f64(q)
                    .unwrap_or(if q > &BigRational::zero() {
                        f64::INFINITY
                    } else {
                        f64::NEG_INFINITY
                    })
                    .to_bits()
            })
            .collect()
    }

    /// A double of a random kind: full mantissa at mixed exponents, small
    /// integers (ties, constant runs), ±0, subnormals.
    fn random_double(rng: &mut SplitMix64, spread: u64) -> f64 {
        let sign = if rng.next_u64() % 2 == 0 { 1.0 } else { -1.0 };
        match rng.next_u64() % 6 {
            0 => sign * (rng.next_u64() % 4) as f64,
            1 => -0.0,
            2 if spread > 1100 => f64::from_bits(rng.next_u64() % (1 << 52)) * sign,
            _ => {
                let mantissa = rng.next_u64() >> 11 | 1 << 52;
                let e = (rng.next_u64() % spread) as i32 - (spread / 2) as i32;
                sign * (mantissa as f64) * 2f64.powi(e - 52)
            }
        }
    }

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }

    /// Agreement, bit for bit, with the generic path on random columns;
    /// returns how many the fast path answered.
    fn agree(radius: &BigRational, spread: u64, cases: usize, seed: u64) -> usize {
        let mut rng = SplitMix64::new(seed);
        let mut answered = 0;
        for case in 0..cases {
            let n = match case % 5 {
                0 => (case / 5) % 3,
                _ => 1 + (rng.next_u64() % 60) as usize,
            };
            let mut z: Vec<f64> = (0..n).map(|_| random_double(&mut rng, spread)).collect();
            if case % 7 == 3 {
                // A sorted column with constant runs: many ties.
                z.sort_by(f64::total_cmp);
            }
            let got = project_doubles(&z, radius);
            if let Some(got) = got {
                answered += 1;
                let got: Vec<u64> = got.iter().map(|x| x.to_bits()).collect();
                assert_eq!(got, generic(&z, radius), "z = {z:?}, r = {radius}");
            }
        }
        answered
    }

    /// Isotonic regression: full mantissas over a few binades (i128 sums),
    /// over dozens (256-bit sums), subnormals and zeros of both signs.
    #[test]
    fn isotonic_agrees_with_the_generic_path() {
        let zero = BigRational::zero();
        assert_eq!(agree(&zero, 8, 1000, 1), 1000);
        assert!(agree(&zero, 60, 600, 2) > 550);
        assert!(agree(&zero, 70, 600, 4) > 300);
        assert!(agree(&zero, 2000, 300, 3) > 30);
        // 125-bit columns: the PAVA on 256-bit sums.
        let z = [
            (1.0 + f64::EPSILON) * 2f64.powi(72),
            f64::EPSILON,
            -(2f64.powi(72)),
        ];
        let blocks = shifted(&z, &zero).and_then(|d| d.blocks_at(&zero));
        assert_eq!(
            blocks.map(|b| b.width()),
            Some(crate::fast::kernel::Width::I256)
        );
        let got: Vec<u64> = isotonic_doubles(&z)
            .unwrap()
            .iter()
            .map(|x| x.to_bits())
            .collect();
        assert_eq!(got, generic(&z, &zero));
        assert_eq!(isotonic_doubles(&[]), Some(vec![]));
        assert_eq!(isotonic_doubles(&[-0.0]).map(|v| v[0].to_bits()), Some(0));
        assert_eq!(isotonic_doubles(&[1.0, f64::NAN]), None);
        // 1/3 of 2: a block mean rounded once, to the nearest double.
        assert_eq!(
            isotonic_doubles(&[1.0, 1.0, -0.0]),
            Some(vec![2.0 / 3.0; 3])
        );
    }

    /// The projection onto `K`: dyadic radii, a radius with an odd
    /// denominator, doubles of mixed exponents.
    #[test]
    fn projection_agrees_with_the_generic_path() {
        for (i, r) in [q(1, 8), q(3, 1 << 20), q(1, 6), q(5, 7 << 10)]
            .iter()
            .enumerate()
        {
            let seed = 10 + i as u64;
            assert_eq!(agree(r, 8, 500, seed), 500, "r = {r}");
            assert!(agree(r, 50, 300, seed) > 250, "r = {r}");
        }
        // A radius of 2^-1100: the scale leaves i128, the general path.
        let tiny = BigRational::new(1.into(), BigInt::from(1) << 1100);
        assert_eq!(project_doubles(&[1.0, 0.0], &tiny), None);
        assert_eq!(project_doubles(&[1.0, 0.0], &-q(1, 2)), None);
    }
}
