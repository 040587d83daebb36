//! The profile region by region: the free stretches (`X = X⁰ + tU⁰`,
//! `Λ = 0`) and the plateaus (`X = w + M`, `U` the mean of `U⁰`, `Λ` its
//! running integral), over the blocks they overlap.

use std::cmp::Ordering;

use num_traits::Signed;

use super::gcm::Event;
use super::{internal, q, Continuum, Plateau, Segment, Q};
use crate::error::Error;
use crate::limit::surd::Surd;
use crate::scalar::Scalar;

impl Continuum {
    /// The blocks overlapping `[l, r]`, with the overlap ends.
    fn overlaps(&self, l: &Surd, r: &Surd) -> Vec<(usize, Surd, Surd)> {
        let mut out = Vec::new();
        for (k, p) in self.pieces.iter().enumerate() {
            let lo = if l.cmp_rational(&p.a) == Ordering::Greater {
                l.clone()
            } else {
                Surd::from_rational(p.a.clone())
            };
            let hi = if r.cmp_rational(&p.b) == Ordering::Less {
                r.clone()
            } else {
                Surd::from_rational(p.b.clone())
            };
            if hi.cmp_exact(&lo) == Ordering::Greater {
                out.push((k, lo, hi));
            }
        }
        out
    }

    pub(super) fn free_region(
        &self,
        l: &Surd,
        r: &Surd,
        t: &Q,
        segments: &mut Vec<Segment<Surd>>,
    ) -> Result<(), Error> {
        let s = |v: &Q| Surd::from_rational(v.clone());
        for (k, lo, hi) in self.overlaps(l, r) {
            let (_, fs) = self.f_coeffs(k, t);
            if !fs.is_positive() {
                return Err(internal("a non-increasing stretch was left free"));
            }
            let p = &self.pieces[k];
            segments.push(Segment {
                w0: lo,
                w1: hi,
                block: k,
                plateau: None,
                x: [s(&(&p.x0[0] + t * &p.u0[0])), s(&(&p.x0[1] + t * &p.u0[1]))],
                u: [s(&p.u0[0]), s(&p.u0[1])],
                lambda: [s(&Q::zero()), s(&Q::zero()), s(&Q::zero())],
            });
        }
        Ok(())
    }

    pub(super) fn plateau_region(
        &self,
        ev: &Event,
        t: &Q,
        segments: &mut Vec<Segment<Surd>>,
        plateaus: &mut Vec<Plateau<Surd>>,
    ) -> Result<(), Error> {
        let mismatch = || internal("surd fields mismatch on a plateau");
        let parts = self.overlaps(&ev.left, &ev.right);
        let two = q(2);
        // ∫ U⁰ over the plateau.
        let mut integral = Surd::from_rational(Q::zero());
        for (k, lo, hi) in &parts {
            let p = &self.pieces[*k];
            let d1 = hi.checked_sub(lo).ok_or_else(mismatch)?;
            let d2 = hi.square().checked_sub(&lo.square()).ok_or_else(mismatch)?;
            let part = d1
                .mul_rational(&p.u0[0])
                .checked_add(&d2.mul_rational(&(&p.u0[1] / &two)))
                .ok_or_else(mismatch)?;
            integral = integral.checked_add(&part).ok_or_else(mismatch)?;
        }
        let length = ev.right.checked_sub(&ev.left).ok_or_else(mismatch)?;
        let mean = integral.checked_div(&length).ok_or_else(mismatch)?;
        let index = plateaus.len();
        let zero = Surd::from_rational(Q::zero());
        let one = Surd::from_rational(q(1));
        let mut acc = zero.clone(); // Λ at the left end of the current part
        for (k, lo, hi) in parts {
            let p = &self.pieces[k];
            let (u, lambda) = if t.is_zero() {
                (
                    [
                        Surd::from_rational(p.u0[0].clone()),
                        Surd::from_rational(p.u0[1].clone()),
                    ],
                    [zero.clone(), zero.clone(), zero.clone()],
                )
            } else {
                // Λ(w) = acc + (u0c − Ū)(w − lo) + u0s (w² − lo²)/2.
                let c1 = mean.neg().add_rational(&p.u0[0]);
                let c2 = Surd::from_rational(&p.u0[1] / &two);
                let c0 = acc
                    .checked_sub(&c1.checked_mul(&lo).ok_or_else(mismatch)?)
                    .and_then(|v| v.checked_sub(&c2.checked_mul(&lo.square())?))
                    .ok_or_else(mismatch)?;
                let at_hi = c0
                    .checked_add(&c1.checked_mul(&hi).ok_or_else(mismatch)?)
                    .and_then(|v| v.checked_add(&c2.checked_mul(&hi.square())?))
                    .ok_or_else(mismatch)?;
                acc = at_hi;
                ([mean.clone(), zero.clone()], [c0, c1, c2])
            };
            segments.push(Segment {
                w0: lo,
                w1: hi,
                block: k,
                plateau: Some(index),
                x: [ev.level.clone(), one.clone()],
                u,
                lambda,
            });
        }
        if !t.is_zero() && acc.signum() != Ordering::Equal {
            return Err(internal("Λ does not return to 0 at the end of a plateau"));
        }
        plateaus.push(Plateau {
            w0: ev.left.clone(),
            w1: ev.right.clone(),
            level: ev.level.clone(),
            velocity: mean,
            attach: (ev.from, ev.to),
        });
        Ok(())
    }
}
