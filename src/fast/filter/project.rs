//! The certified filter on a column of doubles `z`: its projection onto
//! `K = {x : x_{i+1} − x_i ≥ 2r}` (`df:KN`) and, for `r = 0`, its isotonic
//! regression (non-decreasing, equal weights), each value the nearest
//! double of the exact one.
//!
//! This is the state's filter (module documentation of [`super`]) at
//! `t = 0` with `x⁰ = z`: `P_K(z)_i = m_B + 2r i` with `m_B` the mean of
//! `z_j − 2r j` over the block `B` of `i` (`df:translat-x`,
//! `prop:proj-micro`). The error analysis there needs nothing of `x⁰` but
//! `G ≥ max|ẑ_i|`, here `max|z| + 2r N`; `ẑ_i = fl(z_i − fl(2r i))`, the
//! product by `t` being an exact zero. What changes is only the heuristic
//! that makes a block final: `z` need not be sorted, so the floor at `i`
//! (a lower bound of the later `ẑ`) is the least `ẑ` from `i` on: within
//! a run of the PAVA ([`pava::FLIGHTS`] particles) from the run's own
//! `ẑ`, past it from the least `ẑ` of each chunk of particles from there
//! on, found by a first pass.
//!
//! `t` is `−0.0`: `fl(−0 · z_i)` has the sign opposite to `z_i`'s, so a
//! one-particle block's position `fl(z_i + fl(−0 · z_i))` is `+0` for
//! `z_i = ±0`, the double every exact path gives for the value zero.

use num_rational::BigRational;
use num_traits::{Signed, Zero};

use super::pava::{self, Context, Floor};
use super::{exact_double, in_range, Magnitudes, MAX_N};

/// The particles of one chunk of the floors: one run of the PAVA.
const CHUNK_BITS: u32 = pava::FLIGHTS.trailing_zeros();

/// `P_K(z)` (`radius` `r ≥ 0`; `r = 0`: the isotonic regression) written
/// into `out`, each value the nearest double of the exact one: `Some`
/// when the certificate proves it, `None` when a value is not finite or
/// out of the filter's range, `2r` is not a double in range, `N` is above
/// [`MAX_N`], `out` is not `N` long, or a check fails (the exact paths then
/// answer). On `None` `out` holds anything.
pub fn project_into(z: &[f64], radius: &BigRational, out: &mut [f64]) -> Option<()> {
    project_with(z, radius, out, pava::PARALLEL_MIN, CHUNK_BITS)
}

/// [`project_into`] on two threads from `parallel_min` particles on, the
/// floors by chunks of `2^chunk_bits` particles.
fn project_with(
    z: &[f64],
    radius: &BigRational,
    out: &mut [f64],
    parallel_min: usize,
    chunk_bits: u32,
) -> Option<()> {
    let n = z.len();
    if n == 0 || n > MAX_N || out.len() != n || radius.is_negative() {
        return None;
    }
    let two_r = if radius.is_zero() {
        0.0
    } else {
        exact_double(&(radius + radius)).filter(|&d| in_range(d))?
    };
    let (floors, magnitudes) = chunk_floors(z, two_r, chunk_bits)?;
    if !magnitudes.in_range() {
        return None;
    }
    let g = super::eft::up(magnitudes.largest + two_r * n as f64);
    let cx = Context::new(z, z, -0.0, two_r, g);
    let floor = Suffix {
        floors: &floors,
        chunk_bits,
        slack: 64.0 * cx.ug(),
    };
    pava::run(cx, out, parallel_min, floor).map(|_| ())
}

/// The projection's floor at `i`: the least `ẑ_j`, `j ≥ i`, less `slack`
/// (a margin for the float sums the PAVA compares with it).
#[derive(Clone, Copy)]
struct Suffix<'a> {
    /// The least `ẑ` of each chunk of `2^chunk_bits` particles and of
    /// those after it ([`chunk_floors`]).
    floors: &'a [f64],
    chunk_bits: u32,
    slack: f64,
}

impl Floor for Suffix<'_> {
    /// Replaced by [`Self::run`].
    #[inline(always)]
    fn at(&self, _: usize, _: f64, _: f64) -> f64 {
        f64::NEG_INFINITY
    }

    /// The least `ẑ` from each particle of the run on: the run's own,
    /// then the chunks' from the end of the run on (a chunk that begins
    /// before it counts its earlier particles too, which only lowers it).
    #[inline(always)]
    fn run(&self, i0: usize, zs: &[f64], lows: &mut [f64]) {
        let next = (i0 + zs.len()) >> self.chunk_bits;
        let mut below = self.floors.get(next).copied().unwrap_or(f64::INFINITY);
        for (low, &z) in lows.iter_mut().zip(zs).rev() {
            below = below.min(z);
            *low = below - self.slack;
        }
    }
}

/// In one pass over `z`: for each chunk of `2^chunk_bits` particles the
/// least `fl(z_i − fl(2r i))` from that chunk to the end, and the
/// magnitudes of `z` ([`Magnitudes`]). `None` when a value is an infinity
/// or a NaN.
fn chunk_floors(z: &[f64], two_r: f64, chunk_bits: u32) -> Option<(Vec<f64>, Magnitudes)> {
    let mut magnitudes: Option<Magnitudes> = None;
    let mut floors = Vec::with_capacity((z.len() >> chunk_bits) + 1);
    for (c, chunk) in z.chunks(1 << chunk_bits).enumerate() {
        let these = Magnitudes::of(chunk)?;
        magnitudes = Some(magnitudes.map_or(these, |m| m.and(these)));
        // `c 2^chunk_bits + j` as a double: exact, `i < 2⁵³`.
        let base = (c << chunk_bits) as f64;
        let least = chunk
            .iter()
            .enumerate()
            .fold(f64::INFINITY, |least, (j, &v)| {
                least.min(v - two_r * (base + f64::from(j as u32)))
            });
        floors.push(least);
    }
    let mut below = f64::INFINITY;
    for f in floors.iter_mut().rev() {
        below = below.min(*f);
        *f = below;
    }
    Some((floors, magnitudes?))
}

#[cfg(test)]
mod tests {
    use num_rational::BigRational;
    use num_traits::{ToPrimitive, Zero};

    use super::project_with;
    use crate::generate::SplitMix64;

    fn q(v: f64) -> BigRational {
        BigRational::from_float(v).unwrap()
    }

    /// The exact projection's nearest doubles (+0 for zero).
    fn exact(z: &[f64], radius: &BigRational) -> Vec<u64> {
        let zq: Vec<BigRational> = z.iter().map(|&v| q(v)).collect();
        let two_r = radius + radius;
        crate::projection::project_k(&zq, &two_r)
            .iter()
            .map(|v| v.to_f64().unwrap().to_bits())
            .collect()
    }

    /// Columns of several kinds: sorted with room (nearly every block
    /// alone), a random walk (blocks of a few), reversed runs (pooling
    /// across chunks), signed zeros; on one thread and two, chunks of 2 to
    /// 16 particles (a block often spans them). Every certified answer is
    /// the exact one, bit for bit, and most are certified.
    #[test]
    fn certified_projections_are_the_exact_ones() {
        let mut rng = SplitMix64::new(0x150);
        let mut unit = || rng.unit();
        let (mut certified, mut cases) = ([0; 4], [0; 4]);
        for case in 0..240 {
            let n = 1 + (case * 7) % 200;
            let kind = case % 4;
            let mut acc = 0.0f64;
            let z: Vec<f64> = (0..n)
                .map(|i| match kind {
                    0 => {
                        acc += 1.0 + unit();
                        acc
                    }
                    1 => {
                        acc += unit() - 0.4;
                        acc
                    }
                    2 => ((i % 9) as f64) * -0.37 + (i / 9) as f64 + 1e-3 * unit(),
                    _ => [0.0, -0.0, 1.5, -2.25][i % 4] * (i % 3) as f64,
                })
                .collect();
            let radius = [BigRational::zero(), q(0.125), q(3e-7)][case % 3].clone();
            let want = exact(&z, &radius);
            let parallel_min = [usize::MAX, 2][case % 2];
            let chunk_bits = 1 + (case % 4) as u32;
            cases[kind] += 1;
            let mut out = vec![f64::NAN; n];
            if project_with(&z, &radius, &mut out, parallel_min, chunk_bits).is_some() {
                certified[kind] += 1;
                let got: Vec<u64> = out.iter().map(|v| v.to_bits()).collect();
                assert_eq!(got, want, "case {case}");
            }
        }
        // Sorted with room: every case; the others pool into blocks that
        // may be too large or near a tie; the signed zeros tie often.
        assert_eq!(certified[0], cases[0]);
        assert!(
            certified[1] >= 40 && certified[2] >= 40,
            "{certified:?} of {cases:?}"
        );
        assert!(certified[3] > 0, "{certified:?} of {cases:?}");
    }

    /// A block that pools across the end of a run of the PAVA (its floor
    /// then comes from the chunks after the run) is certified and exact,
    /// with the radius's shift `2r i` in the floors, on one thread and two.
    #[test]
    fn a_block_across_runs_is_certified() {
        let radius = q(0.125);
        let run = crate::fast::filter::pava::FLIGHTS;
        // `z_i − 2r i` rises by 1/64 a particle, except for a dip of eight
        // particles just after the first run: the end of the first run
        // pools with it.
        let z: Vec<f64> = (0..3 * run)
            .map(|i| {
                let dip = if (run..run + 8).contains(&i) {
                    -1.0
                } else {
                    0.0
                };
                0.25 * i as f64 + i as f64 / 64.0 + dip
            })
            .collect();
        let want = exact(&z, &radius);
        for parallel_min in [usize::MAX, 2] {
            let mut out = vec![f64::NAN; z.len()];
            assert!(project_with(&z, &radius, &mut out, parallel_min, 8).is_some());
            let got: Vec<u64> = out.iter().map(|v| v.to_bits()).collect();
            assert_eq!(got, want);
        }
    }

    /// Refused: a NaN, an infinity, a value out of range (in the first
    /// chunk of several too), a negative radius, an output of another
    /// length, an empty column, and a tie (two equal values pool into a
    /// block whose split is not strict).
    #[test]
    fn what_it_cannot_prove_is_refused() {
        let zero = BigRational::zero();
        let mut out = vec![0.0; 3];
        for z in [
            [0.0, f64::NAN, 1.0],
            [0.0, f64::INFINITY, 1.0],
            [0.0, 1e-200, 2f64.powi(400)],
            [1.0, 1.0, 2.0],
        ] {
            assert!(
                project_with(&z, &zero, &mut out, usize::MAX, 2).is_none(),
                "{z:?}"
            );
        }
        // A value out of range in the first of several chunks.
        let far = [-(2f64.powi(400)), 0.0, 1.0, 2.0, 3.0];
        let mut five = [0.0; 5];
        assert!(project_with(&far, &zero, &mut five, usize::MAX, 1).is_none());
        // A lone −0 is the value zero: +0, as the exact paths give it.
        let ok = [-0.0, 1.0, 2.0];
        assert!(project_with(&ok, &zero, &mut out, usize::MAX, 2).is_some());
        let bits: Vec<u64> = out.iter().map(|v| v.to_bits()).collect();
        assert_eq!(bits, [0, 1f64.to_bits(), 2f64.to_bits()]);
        assert!(project_with(&ok, &q(-0.5), &mut out, usize::MAX, 2).is_none());
        assert!(project_with(&ok, &zero, &mut out[..2], usize::MAX, 2).is_none());
        assert!(project_with(&[], &zero, &mut [], usize::MAX, 2).is_none());
    }
}
