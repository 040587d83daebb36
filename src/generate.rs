//! Valid initial data from arbitrary bytes, and a small deterministic PRNG.
//!
//! One decoder serves every engine: the agreement tests, proptest and
//! quickcheck (which generate byte vectors and shrink them), the fuzz targets
//! (which hand in raw bytes) and `sticky` itself (random scenes from a seed).
//! Every byte string decodes to admissible data — `x⁰ ∈ K^N` (`df:KN`) and
//! `u⁰ ∈ C_{x⁰}` (`def:velcone`) — so no input is wasted on rejection.
//!
//! The decoder builds the data in translated coordinates (`df:translat-x`) as
//! a sequence of *groups*. A group is either one cluster (particles in
//! contact with one velocity) or a chain of 2–4 clusters built to meet at a
//! single instant `T`: cluster `c` gets a velocity `v_c` (decreasing from left
//! to right) and the translated position `m − T v_c`, so that all of them
//! reach `m` at `T` — simultaneous multi-cluster collisions on purpose.
//! Consecutive groups are separated by a gap that may be zero: a contact at
//! `t = 0`, whose velocities then either agree (the clusters are one) or
//! separate (`u⁰_{i+1} > u⁰_i`, allowed by the velocity cone).

use num_bigint::BigInt;
use num_rational::BigRational;

use crate::initial::{unshift, InitialData};
use crate::quantile::{Block, BlockVelocity, MacroDatum};

/// Reads small integers from a byte string; yields zeros once it is used up.
#[derive(Debug, Clone)]
pub struct ByteSource<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> ByteSource<'a> {
    /// Reads from `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        ByteSource { bytes, pos: 0 }
    }
    /// The next byte (0 when exhausted).
    pub fn byte(&mut self) -> u8 {
        let b = self.bytes.get(self.pos).copied().unwrap_or(0);
        self.pos += 1;
        b
    }
    /// A value in `0..m` (`m ≥ 1`).
    pub fn below(&mut self, m: u32) -> u32 {
        let v = u32::from(self.byte()) << 8 | u32::from(self.byte());
        v % m.max(1)
    }
    /// `true` if any byte is left.
    pub fn has_more(&self) -> bool {
        self.pos < self.bytes.len()
    }
}

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(BigInt::from(n), BigInt::from(d.max(1)))
}

/// Limits for [`initial_data`].
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Largest number of particles.
    pub max_n: usize,
    /// Largest denominator used for gaps, velocities and times.
    pub max_den: u32,
    /// Largest velocity numerator in absolute value.
    pub max_speed: u32,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_n: 200,
            max_den: 8,
            max_speed: 16,
        }
    }
}

/// Decodes `bytes` into admissible initial data (never fails).
///
/// The first byte fixes the radius (the paper's `2r = 1/N` or a small
/// rational). The rest is a sequence of groups (see the module
/// documentation); decoding stops at `limits.max_n` particles or when the
/// bytes run out (at least one particle is always produced).
pub fn initial_data(bytes: &[u8], limits: Limits) -> InitialData<BigRational> {
    let mut src = ByteSource::new(bytes);
    let max_n = limits.max_n.max(1);
    let den = |src: &mut ByteSource| i64::from(1 + src.below(limits.max_den.max(1)));
    let speed = |src: &mut ByteSource, d: i64| {
        let s = i64::from(limits.max_speed.max(1));
        q(i64::from(src.below(2 * s as u32 + 1)) - s, d)
    };
    let radius_code = src.byte() % 4;
    let mut shifted: Vec<BigRational> = Vec::new();
    let mut velocity: Vec<BigRational> = Vec::new();
    let mut last_pos = q(0, 1);
    let mut last_vel: Option<BigRational> = None;
    while shifted.len() < max_n && (shifted.is_empty() || src.has_more()) {
        let room = max_n - shifted.len();
        let kind = src.byte() % 4;
        // Gap to the previous group: zero (contact) one time in four.
        let gap = if src.byte() % 4 == 0 || shifted.is_empty() {
            q(0, 1)
        } else {
            q(i64::from(1 + src.below(16)), den(&mut src))
        };
        if kind == 0 && room >= 2 {
            // A chain of clusters meeting at one instant T.
            let clusters = (2 + src.below(3) as usize).min(room);
            let d = den(&mut src);
            let t = q(i64::from(1 + src.below(12)), den(&mut src));
            let mut speeds: Vec<i64> = Vec::with_capacity(clusters);
            let mut v =
                i64::from(src.below(2 * limits.max_speed.max(1) + 1)) - i64::from(limits.max_speed);
            for _ in 0..clusters {
                speeds.push(v);
                v -= i64::from(1 + src.below(4));
            }
            let v0 = q(speeds[0], d);
            let mut meet = last_pos.clone() + &gap + &(t.clone() * &v0);
            if gap == q(0, 1) && last_vel.as_ref().is_some_and(|lv| *lv > v0) {
                meet += q(1, d);
            }
            let mut left = room;
            for (c, &s) in speeds.iter().enumerate() {
                // Keep at least one particle for each cluster still to come.
                let size = (1 + src.below(3) as usize)
                    .min(left.saturating_sub(clusters - c - 1))
                    .max(1);
                left -= size;
                let v = q(s, d);
                let p = meet.clone() - &(t.clone() * &v);
                for _ in 0..size {
                    shifted.push(p.clone());
                    velocity.push(v.clone());
                }
                last_pos = p;
                last_vel = Some(v);
            }
        } else {
            // One cluster (often a single particle).
            let size = if kind == 1 {
                (1 + src.below(4) as usize).min(room)
            } else {
                1
            };
            let d = den(&mut src);
            let mut v = speed(&mut src, d);
            let pos = last_pos.clone() + &gap;
            if gap == q(0, 1) {
                if let Some(lv) = &last_vel {
                    // Contact: equal velocities (one cluster) or separating.
                    if v < *lv {
                        v = lv.clone() + &q(i64::from(src.byte() % 2), 1);
                    }
                }
            }
            for _ in 0..size {
                shifted.push(pos.clone());
                velocity.push(v.clone());
            }
            last_pos = pos;
            last_vel = Some(v);
        }
    }
    let n = shifted.len();
    let radius = match radius_code {
        0 | 1 => q(1, 2 * n as i64),
        2 => q(1, 2),
        _ => q(1, 64),
    };
    let two_r = radius.clone() + &radius;
    let positions = unshift(&shifted, &two_r);
    // Built admissible by construction; `new` re-checks it.
    match InitialData::new(radius, positions, velocity) {
        Ok(d) => d,
        Err(e) => unreachable_data(e),
    }
}

#[cold]
fn unreachable_data(e: crate::Error) -> InitialData<BigRational> {
    // The construction above only produces admissible data; reaching this is
    // a bug in the decoder, reported loudly in tests.
    panic!("generate::initial_data produced invalid data: {e}")
}

/// Decodes `bytes` into an admissible macroscopic datum `(ρ⁰, u⁰)` under the
/// hypotheses of `thm:main` (never fails): one to four blocks, total mass
/// exactly 1, densities in `(0, 1]`, a constant velocity on every congested
/// block (`hyp:u0`), and on dilute blocks a constant or an affine one.
///
/// It aims at what the hypotheses allow at their edges: congested blocks
/// (density exactly 1) next to dilute ones with no gap between them, velocity
/// jumps at block boundaries in both directions, and masses with small
/// denominators, so that the quantiles `i/N` land on the mass breakpoints for
/// many `N`. Two congested blocks that touch get the same velocity: a jump
/// inside `{ρ⁰ = 1}` would violate `hyp:u0`.
pub fn macro_datum(bytes: &[u8]) -> MacroDatum {
    let mut src = ByteSource::new(bytes);
    let count = 1 + src.below(4) as usize;
    let weights: Vec<i64> = (0..count).map(|_| 1 + i64::from(src.below(4))).collect();
    let total: i64 = weights.iter().sum();
    let mut blocks: Vec<Block> = Vec::with_capacity(count);
    let mut from = q(i64::from(src.below(5)) - 2, 2);
    for (k, w) in weights.iter().enumerate() {
        let mass = q(*w, total);
        let congested = src.below(5) < 2;
        let density = if congested {
            q(1, 1)
        } else {
            let d = [2, 3, 4, 8][src.below(4) as usize];
            q(1 + i64::from(src.below(d as u32 - 1)), d)
        };
        if k > 0 {
            // No gap half of the time: the blocks touch.
            let gap = if src.below(2) == 0 {
                q(0, 1)
            } else {
                q(1 + i64::from(src.below(4)), 4)
            };
            from += gap;
        }
        let to = &from + &mass / &density;
        let speed =
            |src: &mut ByteSource| q(i64::from(src.below(9)) - 4, 1 + i64::from(src.below(2)));
        let velocity = match blocks.last() {
            Some(prev) if congested && prev.density == density && prev.to == from => {
                prev.velocity.clone()
            }
            _ if congested || src.below(2) == 0 => BlockVelocity::Constant(speed(&mut src)),
            _ => BlockVelocity::Affine(speed(&mut src), speed(&mut src)),
        };
        blocks.push(Block {
            from: from.clone(),
            to: to.clone(),
            density,
            velocity,
        });
        from = to;
    }
    MacroDatum::new(blocks).unwrap_or_else(unreachable_datum)
}

#[cold]
fn unreachable_datum(e: crate::Error) -> MacroDatum {
    // The construction above satisfies every check of `MacroDatum::new`.
    panic!("generate::macro_datum produced an invalid datum: {e}")
}

/// The data snapped to the binary grid `2^-bits`, so that every value is a
/// double (for `.npy` files): translated positions (`df:translat-x`),
/// velocities and the radius are each rounded down to the grid. Rounding
/// down is monotone, so the translated positions stay non-decreasing
/// (`x ∈ K^N` for any radius) and equal ones stay equal; velocities keep
/// their order. `None` when the snapped data are not admissible (two
/// distinct translated positions closer than the grid became a contact with
/// approaching velocities), when the radius rounds to 0, or when a value
/// needs more than 53 significant bits.
pub fn dyadic(data: &InitialData<BigRational>, bits: u32) -> Option<InitialData<BigRational>> {
    let scale = BigRational::from_integer(BigInt::from(1) << bits as usize);
    let snap = |q: &BigRational| (q * &scale).floor() / &scale;
    let radius = snap(data.radius());
    let two_r = &radius + &radius;
    let shifted: Vec<BigRational> = data.shifted_positions().iter().map(snap).collect();
    let velocities: Vec<BigRational> = data.velocities().iter().map(snap).collect();
    let positions = unshift(&shifted, &two_r);
    let snapped = InitialData::new(radius, positions, velocities).ok()?;
    let all_doubles = snapped
        .positions()
        .iter()
        .chain(snapped.velocities())
        .chain(std::iter::once(snapped.radius()))
        .all(crate::columns::is_f64);
    all_doubles.then_some(snapped)
}

/// [`dyadic`] as the rows of a `.npy` file: the snapped radius and every
/// `(position, velocity)` as the double it is, the same values bit for bit
/// and `None` exactly when [`dyadic`] gives `None` (tests: against
/// [`dyadic`] on random data). Computed on `i128`: with `x_i = p/d`,
/// `2r = a/b`, the grid index of the translated position is
/// `⌊2^bits (p b − a i d) / (d b)⌋` (`df:translat-x`) and the snapped
/// position is that index plus `2 R i`, `R = ⌊2^bits r⌋`; when a term leaves
/// `i128`, [`dyadic`] itself answers.
pub fn dyadic_doubles(data: &InitialData<BigRational>, bits: u32) -> Option<DyadicRows> {
    match dyadic_words(data, bits) {
        Ok(answer) => answer,
        Err(Overflow) => {
            use crate::scalar::Scalar;
            let d = dyadic(data, bits)?;
            let rows = d
                .positions()
                .iter()
                .zip(d.velocities())
                .map(|(x, u)| (x.to_f64_lossy(), u.to_f64_lossy()))
                .collect();
            Some((d.radius().clone(), rows))
        }
    }
}

/// The snapped radius and the `(position, velocity)` doubles of
/// [`dyadic_doubles`].
pub type DyadicRows = (BigRational, Vec<(f64, f64)>);

/// A term of [`dyadic_words`] left `i128`.
struct Overflow;

fn dyadic_words(
    data: &InitialData<BigRational>,
    bits: u32,
) -> Result<Option<DyadicRows>, Overflow> {
    use num_traits::ToPrimitive;
    let words = |q: &BigRational| Some((q.numer().to_i128()?, q.denom().to_i128()?));
    // ⌊2^bits n / d⌋, d > 0.
    let grid = |n: i128, d: i128| -> Option<i128> {
        n.checked_mul(1i128.checked_shl(bits)?)?
            .checked_div_euclid(d)
    };
    let (rn, rd) = words(data.radius()).ok_or(Overflow)?;
    let big_r = grid(rn, rd).ok_or(Overflow)?;
    let two_r = data.radius() + data.radius();
    let (a, b) = words(&two_r).ok_or(Overflow)?;
    // k / 2^bits is a double iff k has at most 53 significant bits.
    let unit = 2f64.powi(-i32::try_from(bits).map_err(|_| Overflow)?);
    let to_f64 = |k: i128| -> Option<f64> {
        let m = k.unsigned_abs() >> k.trailing_zeros().min(127);
        (k == 0 || 128 - m.leading_zeros() <= 53).then_some(k as f64 * unit)
    };
    if big_r <= 0 {
        return Ok(None);
    }
    let mut rows = Vec::with_capacity(data.n());
    let mut prev: Option<(i128, i128)> = None;
    for (i, (x, u)) in data.positions().iter().zip(data.velocities()).enumerate() {
        let terms = (|| {
            let ii = i128::try_from(i).ok()?;
            let (p, d) = words(x)?;
            let (un, ud) = words(u)?;
            let num = p
                .checked_mul(b)?
                .checked_sub(a.checked_mul(ii)?.checked_mul(d)?)?;
            let k = grid(num, d.checked_mul(b)?)?;
            let position = k.checked_add(big_r.checked_mul(2)?.checked_mul(ii)?)?;
            Some((k, grid(un, ud)?, position))
        })();
        let (k, v, position) = terms.ok_or(Overflow)?;
        // `InitialData::new` on the snapped data: the translated positions
        // never decrease (the floor is monotone); a contact must not
        // approach (`def:velcone`).
        if let Some((k0, v0)) = prev {
            if k < k0 || (k == k0 && v < v0) {
                return Ok(None);
            }
        }
        prev = Some((k, v));
        match (to_f64(position), to_f64(v)) {
            (Some(x), Some(u)) => rows.push((x, u)),
            _ => return Ok(None),
        }
    }
    if to_f64(big_r).is_none() {
        return Ok(None);
    }
    let radius = BigRational::new(BigInt::from(big_r), BigInt::from(1) << bits as usize);
    Ok(Some((radius, rows)))
}

/// SplitMix64: a tiny, well-mixed deterministic generator (for seeds and test
/// data, not for cryptography).
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator started from `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Skips `draws` draws of [`next_u64`](Self::next_u64) (the state moves
    /// by a constant per draw).
    pub fn skip(&mut self, draws: usize) {
        self.0 = self
            .0
            .wrapping_add(0x9E37_79B9_7F4A_7C15u64.wrapping_mul(draws as u64));
    }
    /// A uniform double in `[0, 1)`: the top 53 bits of one draw, over
    /// `2⁵³`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// `len` random bytes.
    pub fn bytes(&mut self, len: usize) -> Vec<u8> {
        (0..len).map(|_| self.next_u64() as u8).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skip_equals_drawing() {
        let mut a = SplitMix64::new(0x5EED);
        let mut b = a.clone();
        for draws in [0, 1, 7, 1000] {
            for _ in 0..draws {
                a.next_u64();
            }
            b.skip(draws);
            assert_eq!(a.next_u64(), b.next_u64(), "{draws}");
        }
    }

    #[test]
    fn every_byte_string_decodes() {
        let mut rng = SplitMix64::new(7);
        for len in 0..200 {
            let bytes = rng.bytes(len);
            let d = initial_data(&bytes, Limits::default());
            assert!(d.n() >= 1 && d.n() <= 200);
        }
        assert!(initial_data(&[], Limits::default()).n() >= 1);
    }

    #[test]
    fn every_byte_string_decodes_to_a_macro_datum() {
        let mut rng = SplitMix64::new(11);
        let (mut congested_next_to_dilute, mut affine) = (0, 0);
        for len in 0..400 {
            let datum = macro_datum(&rng.bytes(len));
            let b = datum.blocks();
            assert!((1..=4).contains(&b.len()));
            for pair in b.windows(2) {
                let one = BigRational::from_integer(1.into());
                if pair[0].to == pair[1].from
                    && (pair[0].density == one) != (pair[1].density == one)
                {
                    congested_next_to_dilute += 1;
                }
            }
            affine += b.iter().filter(|x| !x.velocity.is_constant()).count();
        }
        // The edges of hyp:u0 are reached, not just allowed.
        assert!(congested_next_to_dilute > 20, "{congested_next_to_dilute}");
        assert!(affine > 20, "{affine}");
    }

    #[test]
    fn respects_max_n() {
        let mut rng = SplitMix64::new(1);
        let bytes = rng.bytes(4000);
        let lim = Limits {
            max_n: 37,
            ..Limits::default()
        };
        assert_eq!(initial_data(&bytes, lim).n(), 37);
    }

    /// `dyadic_doubles` against `dyadic` (then `to_f64_lossy`): the same
    /// radius and doubles bit for bit, `None` on the same data, on random
    /// data at fine and coarse grids (coarse ones make snapped contacts
    /// approach: `None`), shifted far off the origin, and with terms off
    /// `i128` (the `BigRational` answer then).
    #[test]
    fn dyadic_doubles_are_dyadic_bit_for_bit() {
        use crate::scalar::Scalar;
        let mut rng = SplitMix64::new(99);
        let (mut some, mut none) = (0, 0);
        for case in 0..300u64 {
            let d = initial_data(&rng.bytes(200), Limits::default());
            let shift = match case % 4 {
                0 => BigRational::from_integer(0.into()),
                1 => BigRational::new((-7i64).into(), 3.into()),
                2 => BigRational::from_integer(BigInt::from(1) << 90usize),
                _ => BigRational::new(1.into(), BigInt::from(3) << 100usize),
            };
            let positions = d.positions().iter().map(|x| x + &shift).collect();
            let d =
                InitialData::new(d.radius().clone(), positions, d.velocities().to_vec()).unwrap();
            let bits = [32, 3, 8, 52][(case / 4 % 4) as usize];
            let want = dyadic(&d, bits).map(|s| {
                let rows: Vec<(u64, u64)> = s
                    .positions()
                    .iter()
                    .zip(s.velocities())
                    .map(|(x, u)| (x.to_f64_lossy().to_bits(), u.to_f64_lossy().to_bits()))
                    .collect();
                (s.radius().clone(), rows)
            });
            let got = dyadic_doubles(&d, bits).map(|(r, rows)| {
                let rows: Vec<(u64, u64)> = rows
                    .iter()
                    .map(|(x, u)| (x.to_bits(), u.to_bits()))
                    .collect();
                (r, rows)
            });
            assert_eq!(got, want, "case {case}, bits {bits}");
            if want.is_some() {
                some += 1;
            } else {
                none += 1;
            }
        }
        assert!(some > 50 && none > 50, "{some} snapped, {none} refused");
        // At the edge of the double: ⌊(10/3) 2^51⌋ has 53 significant
        // bits, ⌊(10/3) 2^52⌋ 54.
        let one = InitialData::new(
            BigRational::new(1.into(), 4.into()),
            vec![BigRational::new(10.into(), 3.into())],
            vec![BigRational::from_integer(0.into())],
        )
        .unwrap();
        assert!(dyadic(&one, 51).is_some() && dyadic_doubles(&one, 51).is_some());
        assert!(dyadic(&one, 52).is_none() && dyadic_doubles(&one, 52).is_none());
    }
}
