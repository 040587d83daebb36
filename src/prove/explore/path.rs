//! One comparison decided on the path running: from the path condition
//! alone when it implies the answer, by replaying a forced decision, or by
//! asking the solver which outcomes are feasible (the first is taken, the
//! others queued as [`Branch`]es).

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use num_rational::BigRational;
use num_traits::Signed;

use super::{
    flip, sign_bit, union_rel, Branch, Decision, Entailment, Model, PathState, Rel, NEG, POS, ZERO,
};
use crate::prove::eliminate::{Atom, Constraint};
use crate::prove::poly::Poly;
use crate::prove::smt::Sat;

/// The outcome a constant takes: the first of `outcomes` its sign allows.
pub(super) fn constant_outcome(c: &BigRational, outcomes: &[Rel]) -> usize {
    let b = sign_bit(c);
    outcomes.iter().position(|r| r.mask() & b != 0).unwrap_or(0)
}

/// The comparison being decided: the polynomial as written and normalised,
/// the outcomes offered, and the texts the solver is sent.
struct Comparison<'a> {
    /// The polynomial as the program wrote it.
    p: &'a Poly,
    /// Its normalised form (positive leading coefficient), the key of the
    /// sign masks.
    np: Poly,
    /// Whether normalising changed its sign.
    flipped: bool,
    /// The sign conditions offered, covering every sign of `p`.
    outcomes: &'a [Rel],
    /// `p` as SMT-LIB text, so that the sign conditions read right.
    ptext: String,
    /// The fingerprint of the comparison ([`Decision::fingerprint`]).
    fingerprint: u64,
}

/// An outcome found feasible, with a point taking it when the solver gave one.
struct Feasible {
    outcome: usize,
    model: Option<Vec<BigRational>>,
}

impl PathState {
    /// Takes the outcome `rel` of the comparison of `p` (normalised `np`):
    /// recorded in the sign masks and the path condition, and kept as a
    /// constraint of the path.
    fn keep(&mut self, c: &Comparison, rel: Rel, entailment: Entailment) {
        self.record(&c.np, c.flipped, rel, Some(rel.smt(&c.ptext)), entailment);
        self.cons.push(Constraint::Atom(Atom {
            poly: c.p.clone(),
            rel,
        }));
    }

    fn record(
        &mut self,
        np: &Poly,
        flipped: bool,
        rel: Rel,
        text: Option<String>,
        entailment: Entailment,
    ) {
        let m = if flipped {
            flip(rel.mask())
        } else {
            rel.mask()
        };
        let e = self.masks.entry(np.clone()).or_insert(NEG | ZERO | POS);
        *e &= m;
        if let Some(t) = text {
            if entailment == Entailment::Branched {
                self.pc.push(t.clone());
            }
            self.full_pc.push(t);
        }
    }

    /// Which of `outcomes` holds for `p` on this path (see the module
    /// documentation).
    pub(super) fn decide(&mut self, p: &Poly, outcomes: &[Rel]) -> usize {
        if let Some(c) = p.as_constant() {
            return constant_outcome(&c, outcomes);
        }
        let (np, lead) = p.normalized();
        let flipped = lead.is_negative();
        let known = self.masks.get(&np).copied().unwrap_or(NEG | ZERO | POS);
        let known = if flipped { flip(known) } else { known };
        let candidates: Vec<usize> = (0..outcomes.len())
            .filter(|&k| outcomes[k].mask() & known != 0)
            .collect();
        match candidates.as_slice() {
            [] => {
                self.error
                    .get_or_insert_with(|| "inconsistent path condition".into());
                return 0;
            }
            &[k] => {
                self.record(&np, flipped, outcomes[k], None, Entailment::Implied);
                return k;
            }
            _ => {}
        }
        let text = np.smt(&self.names);
        let fingerprint = {
            let mut h = DefaultHasher::new();
            text.hash(&mut h);
            flipped.hash(&mut h);
            outcomes.len().hash(&mut h);
            h.finish()
        };
        let c = Comparison {
            p,
            ptext: p.smt(&self.names),
            np,
            flipped,
            outcomes,
            fingerprint,
        };
        if self.taken.len() < self.forced.len() {
            return self.replay(&c);
        }
        // The outcome the current model takes is feasible: no query.
        let model_k = self.model.as_ref().and_then(|m| {
            let b = sign_bit(&p.eval(m));
            candidates
                .iter()
                .copied()
                .find(|&k| outcomes[k].mask() & b != 0)
        });
        if let Some(k0) = model_k {
            if self.only_model_outcome(&c, k0, &candidates) {
                self.taken.push(Decision {
                    fingerprint,
                    outcome: k0 as u8,
                    entailment: Entailment::Implied,
                });
                self.keep(&c, outcomes[k0], Entailment::Implied);
                return k0;
            }
        }
        let feasible = self.feasible(&c, &candidates, model_k);
        self.branch(&c, feasible)
    }

    /// Replays the forced decision at this position of the path.
    fn replay(&mut self, c: &Comparison) -> usize {
        let forced = self.forced[self.taken.len()];
        let k = usize::from(forced.outcome);
        if forced.fingerprint != c.fingerprint || k >= c.outcomes.len() {
            self.error.get_or_insert_with(|| {
                "the program did not replay identically (non-deterministic decision)".into()
            });
        }
        let k = k.min(c.outcomes.len() - 1);
        self.taken.push(Decision {
            fingerprint: c.fingerprint,
            ..forced
        });
        self.keep(c, c.outcomes[k], forced.entailment);
        k
    }

    /// `true` when the outcomes the model does not take are all infeasible:
    /// one query on their union (when there are two or more of them and a
    /// sign condition covers exactly their signs) settles the usual case
    /// where the path condition decides the comparison.
    fn only_model_outcome(&mut self, c: &Comparison, k0: usize, candidates: &[usize]) -> bool {
        let others: Vec<usize> = candidates.iter().copied().filter(|&k| k != k0).collect();
        if others.len() < 2 {
            return false;
        }
        let Some(union) = union_rel(others.iter().map(|&k| c.outcomes[k])) else {
            return false;
        };
        self.queries += 1;
        let q = union.smt(&c.ptext);
        let extra = Atom {
            poly: c.p.clone(),
            rel: union,
        };
        match self.ask(&extra, &q, Model::NotNeeded).map(|(a, _)| a) {
            Ok(Sat::Unsat) => true,
            Ok(_) => false,
            Err(e) => {
                self.error.get_or_insert(e.0);
                false
            }
        }
    }

    /// The feasible outcomes among `candidates`, the model's first: each
    /// other one asked of the solver (an `unknown` answer counts as
    /// feasible, and is counted).
    fn feasible(
        &mut self,
        c: &Comparison,
        candidates: &[usize],
        model_k: Option<usize>,
    ) -> Vec<Feasible> {
        let mut feasible = Vec::new();
        if let Some(k0) = model_k {
            feasible.push(Feasible {
                outcome: k0,
                model: self.model.clone(),
            });
        }
        for (i, &k) in candidates.iter().enumerate() {
            if Some(k) == model_k {
                continue;
            }
            if model_k.is_none() && i + 1 == candidates.len() && feasible.is_empty() {
                // The path condition is satisfiable and the outcomes cover
                // every sign: the last one must be feasible.
                feasible.push(Feasible {
                    outcome: k,
                    model: None,
                });
                continue;
            }
            if let Some(model) = self.outcome_feasible(c, k) {
                feasible.push(Feasible { outcome: k, model });
            }
        }
        feasible
    }

    /// Asks whether outcome `k` is feasible on the path: `Some` with the
    /// solver's point (if any) when it is or cannot be excluded, `None`
    /// when it is infeasible.
    fn outcome_feasible(&mut self, c: &Comparison, k: usize) -> Option<Option<Vec<BigRational>>> {
        let q = c.outcomes[k].smt(&c.ptext);
        self.queries += 1;
        let extra = Atom {
            poly: c.p.clone(),
            rel: c.outcomes[k],
        };
        let answer = match self.ask(&extra, &q, Model::Wanted) {
            Ok((Sat::Unknown, _)) => self.check_reduced(Some(extra)),
            other => other,
        };
        match answer {
            Ok((Sat::Sat, m)) => Some(m),
            Ok((Sat::Unsat, _)) => None,
            Ok((Sat::Unknown, _)) => {
                self.unknown_answers += 1;
                Some(None)
            }
            Err(e) => {
                self.error.get_or_insert(e.0);
                Some(None)
            }
        }
    }

    /// Takes the first feasible outcome and queues the others as branches.
    fn branch(&mut self, c: &Comparison, feasible: Vec<Feasible>) -> usize {
        let mut feasible = feasible.into_iter();
        let Some(first) = feasible.next() else {
            self.error
                .get_or_insert_with(|| "no feasible outcome".into());
            return 0;
        };
        self.model = first.model;
        // The only feasible outcome: the path condition implies it.
        let entailment = if feasible.as_slice().is_empty() {
            Entailment::Implied
        } else {
            Entailment::Branched
        };
        for alt in feasible {
            let mut prefix = self.taken.clone();
            prefix.push(Decision {
                fingerprint: c.fingerprint,
                outcome: alt.outcome as u8,
                entailment: Entailment::Branched,
            });
            self.branches.push(Branch {
                prefix,
                model: alt.model,
            });
        }
        self.taken.push(Decision {
            fingerprint: c.fingerprint,
            outcome: first.outcome as u8,
            entailment,
        });
        self.keep(c, c.outcomes[first.outcome], entailment);
        first.outcome
    }
}
