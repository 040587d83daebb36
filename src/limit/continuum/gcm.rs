//! The greatest convex minorant of `F = ∫f` by its Legendre dual: the
//! candidate minimisers (*features*) of `F(w) − M w`, and the levels `M`
//! where the minimiser jumps (the plateaus; see the module documentation
//! of [`super`]).

use std::cmp::Ordering;

use num_traits::Signed;

use super::{internal, q, Attach, Continuum, Q};
use crate::error::Error;
use crate::limit::surd::Surd;
use crate::scalar::Scalar;

/// A candidate minimiser of `Φ_M(w) = F(w) − M w`.
#[derive(Debug, Clone)]
struct Feature {
    attach: Attach,
    /// `m(M) = c0 + c1 M + c2 M²` where the feature is active.
    poly: [Q; 3],
    /// Arcs: the slopes `[f(a⁺), f(b⁻)]` for which the minimiser is inside.
    range: Option<(Q, Q)>,
    /// Knot: its position; arc: `(f_c, f_s)` with `τ(M) = (M − f_c)/f_s`.
    knot: Option<Q>,
    arc: Option<(Q, Q)>,
}

impl Feature {
    fn valid_open(&self, lo: Option<&Q>, hi: Option<&Q>) -> bool {
        match (&self.range, lo, hi) {
            (None, _, _) => true,
            (Some((a, b)), Some(lo), Some(hi)) => a <= lo && hi <= b,
            _ => false,
        }
    }
    fn valid_at(&self, k: &Q) -> bool {
        match &self.range {
            None => true,
            Some((a, b)) => a <= k && k <= b,
        }
    }
    fn value(&self, k: &Q) -> Q {
        &self.poly[0] + &self.poly[1] * k + &self.poly[2] * k * k
    }
    fn slope(&self, k: &Q) -> Q {
        &self.poly[1] + q(2) * &self.poly[2] * k
    }
    fn position(&self, m: &Surd) -> Surd {
        match (&self.knot, &self.arc) {
            (Some(w), _) => Surd::from_rational(w.clone()),
            (None, Some((fc, fs))) => m.add_rational(&-fc.clone()).mul_rational(&fs.recip()),
            (None, None) => Surd::from_rational(Q::zero()),
        }
    }
}

/// A jump of the minimiser at level `level`: from `from` (position `left`)
/// to `to` (position `right`).
#[derive(Debug, Clone)]
pub(super) struct Event {
    pub(super) level: Surd,
    pub(super) left: Surd,
    pub(super) right: Surd,
    pub(super) from: Attach,
    pub(super) to: Attach,
}

impl Continuum {
    fn features(&self, t: &Q) -> Vec<Feature> {
        let two = q(2);
        let mut feats = Vec::with_capacity(2 * self.pieces.len() + 1);
        let mut big_f = Q::zero(); // F(a) at the current knot
        for (k, p) in self.pieces.iter().enumerate() {
            let (fc, fs) = self.f_coeffs(k, t);
            feats.push(Feature {
                attach: Attach::Knot(k),
                poly: [big_f.clone(), -p.a.clone(), Q::zero()],
                range: None,
                knot: Some(p.a.clone()),
                arc: None,
            });
            if fs.is_positive() {
                let c = &big_f - &fc * &p.a - &fs * &p.a * &p.a / &two;
                feats.push(Feature {
                    attach: Attach::Arc(k),
                    poly: [
                        &c - &fc * &fc / (&two * &fs),
                        &fc / &fs,
                        -(&two * &fs).recip(),
                    ],
                    range: Some((&fc + &fs * &p.a, &fc + &fs * &p.b)),
                    knot: None,
                    arc: Some((fc.clone(), fs.clone())),
                });
            }
            big_f = big_f + &fc * (&p.b - &p.a) + &fs * (&p.b * &p.b - &p.a * &p.a) / &two;
        }
        let last = self.pieces.last().map(|p| p.b.clone()).unwrap_or_else(q1);
        feats.push(Feature {
            attach: Attach::Knot(self.pieces.len()),
            poly: [big_f, -last.clone(), Q::zero()],
            range: None,
            knot: Some(last),
            arc: None,
        });
        feats
    }

    /// The feature active just left (`right = false`) or just right of `k`
    /// among `valid`: lexicographic minimum of `(m(k), ±m'(k), m''(k)/2)`.
    fn limit(feats: &[Feature], valid: &[usize], k: &Q, right: bool) -> Option<usize> {
        let key = |i: usize| {
            let f = &feats[i];
            let d = f.slope(k);
            (f.value(k), if right { d } else { -d }, f.poly[2].clone())
        };
        valid.iter().copied().min_by(|&a, &b| key(a).cmp(&key(b)))
    }

    /// The jump levels strictly inside the bracket `(lo, hi)`, between the
    /// feature `a` active at its left end and `b` active at its right end.
    fn between(
        feats: &[Feature],
        valid: &[usize],
        a: usize,
        b: usize,
        bracket: (Option<&Q>, Option<&Q>),
        events: &mut Vec<Event>,
    ) -> Result<(), Error> {
        let mut stack = vec![(a, b)];
        while let Some((a, b)) = stack.pop() {
            if a == b {
                continue;
            }
            if a > b {
                return Err(internal("active features out of order"));
            }
            let diff = [
                &feats[a].poly[0] - &feats[b].poly[0],
                &feats[a].poly[1] - &feats[b].poly[1],
                &feats[a].poly[2] - &feats[b].poly[2],
            ];
            let level = crossing(&diff)?;
            if let Some(lo) = bracket.0 {
                if level.cmp_rational(lo) != Ordering::Greater {
                    return Err(internal("crossing below its bracket"));
                }
            }
            if let Some(hi) = bracket.1 {
                if level.cmp_rational(hi) != Ordering::Less {
                    return Err(internal("crossing above its bracket"));
                }
            }
            let mut best: Option<(usize, Surd)> = None;
            for &c in valid.iter().filter(|&&c| a < c && c < b) {
                let d = [
                    &feats[c].poly[0] - &feats[a].poly[0],
                    &feats[c].poly[1] - &feats[a].poly[1],
                    &feats[c].poly[2] - &feats[a].poly[2],
                ];
                let v = level.eval_quadratic(&d);
                if v.signum() == Ordering::Less
                    && best
                        .as_ref()
                        .is_none_or(|(_, bv)| v.cmp_exact(bv) == Ordering::Less)
                {
                    best = Some((c, v));
                }
            }
            match best {
                Some((c, _)) => {
                    stack.push((c, b));
                    stack.push((a, c));
                }
                None => events.push(Event {
                    left: feats[a].position(&level),
                    right: feats[b].position(&level),
                    level,
                    from: feats[a].attach,
                    to: feats[b].attach,
                }),
            }
        }
        Ok(())
    }

    /// Every jump of the minimiser `τ(M)`, in increasing `M`.
    pub(super) fn events(&self, t: &Q) -> Result<Vec<Event>, Error> {
        let feats = self.features(t);
        let mut ks: Vec<Q> = Vec::with_capacity(2 * self.pieces.len());
        for k in 0..self.pieces.len() {
            let (fc, fs) = self.f_coeffs(k, t);
            ks.push(&fc + &fs * &self.pieces[k].a);
            ks.push(&fc + &fs * &self.pieces[k].b);
        }
        ks.sort();
        ks.dedup();
        let last = feats.len() - 1;
        let mut events = Vec::new();
        let mut current = 0usize;
        let mut lo: Option<Q> = None;
        for j in 0..=ks.len() {
            let hi = ks.get(j);
            let valid: Vec<usize> = (0..feats.len())
                .filter(|&i| feats[i].valid_open(lo.as_ref(), hi))
                .collect();
            let target = match hi {
                Some(k) => Self::limit(&feats, &valid, k, false)
                    .ok_or_else(|| internal("no active feature"))?,
                None => last,
            };
            Self::between(
                &feats,
                &valid,
                current,
                target,
                (lo.as_ref(), hi),
                &mut events,
            )?;
            let Some(k) = hi else { break };
            // The minimisers at the knot value k itself.
            let at: Vec<usize> = (0..feats.len()).filter(|&i| feats[i].valid_at(k)).collect();
            let min = at
                .iter()
                .map(|&i| feats[i].value(k))
                .min()
                .ok_or_else(|| internal("no feature at a knot value"))?;
            let kk = Surd::from_rational(k.clone());
            let mut lo_pos: Option<(Q, Attach)> = None;
            let mut hi_pos: Option<(Q, Attach)> = None;
            for &i in at.iter().filter(|&&i| feats[i].value(k) == min) {
                let pos = feats[i]
                    .position(&kk)
                    .as_rational()
                    .cloned()
                    .ok_or_else(|| internal("irrational position at a knot value"))?;
                if lo_pos.as_ref().is_none_or(|(p, _)| pos < *p) {
                    lo_pos = Some((pos.clone(), feats[i].attach));
                }
                if hi_pos.as_ref().is_none_or(|(p, _)| pos > *p) {
                    hi_pos = Some((pos, feats[i].attach));
                }
            }
            if let (Some((l, fa)), Some((r, fb))) = (lo_pos, hi_pos) {
                if r > l {
                    events.push(Event {
                        level: kk,
                        left: Surd::from_rational(l),
                        right: Surd::from_rational(r),
                        from: fa,
                        to: fb,
                    });
                }
            }
            let next_hi = ks.get(j + 1);
            let valid_next: Vec<usize> = (0..feats.len())
                .filter(|&i| feats[i].valid_open(Some(k), next_hi))
                .collect();
            current = Self::limit(&feats, &valid_next, k, true)
                .ok_or_else(|| internal("no active feature"))?;
            lo = Some(k.clone());
        }
        Ok(events)
    }
}

fn q1() -> Q {
    <Q as Scalar>::one()
}

/// The root of the increasing `c0 + c1 M + c2 M²` inside its bracket: the
/// one where the derivative `2c2 M + c1 = +√disc ≥ 0`.
fn crossing(c: &[Q; 3]) -> Result<Surd, Error> {
    if c[2].is_zero() {
        if c[1].is_zero() {
            return Err(internal("two features with parallel minimum values"));
        }
        return Ok(Surd::from_rational(-&c[0] / &c[1]));
    }
    let disc = &c[1] * &c[1] - q(4) * &c[2] * &c[0];
    let root = Surd::sqrt_of(&disc).ok_or_else(|| internal("negative discriminant"))?;
    let den = (q(2) * &c[2]).recip();
    Ok(root.add_rational(&-c[1].clone()).mul_rational(&den))
}
