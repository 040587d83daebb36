//! The domain of a claim: what its statement quantifies over, as the paper
//! states it — the times (`for all t`, `t > 0`, `for a.e. t`, an integral
//! in `t`), the number of particles (`N > 1`, `thm:main`: "Let N > 1"), the
//! class of test functions, and the hypotheses on the datum (`u⁰ ∈ C_{x⁰}`,
//! `prop:proj-micro`; `u⁰ ∈ H_{x⁰}`, the hypothesis `hyp:u0` of
//! `thm:main` on sampled data). A counterexample counts only inside it: the
//! ledger's shrinker ([`super::ledger`]) asks [`Domain::admits`] of every
//! candidate witness, so a witness at a collision instant, at `t = 0`, with
//! `N = 1` or with a datum outside the hypotheses is refused.

use crate::cluster::contact_clusters;
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

/// How a statement quantifies over the time `t`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InTime {
    /// "for all t ≥ 0": any probe time, collision instants included.
    Every,
    /// "for all t > 0": any probe time but `t = 0`.
    Positive,
    /// "for a.e. t ≥ 0" (a derivative, or an identity between functions
    /// of `t` defined up to a null set): a witness time lies strictly
    /// between two collision instants and the failure is shown at two
    /// times of that open interval.
    AlmostEvery,
    /// A measure in `t` (the pressure, a sum of Dirac masses at the
    /// collision instants) or an integral in `t`: collision instants are
    /// where it lives.
    Measure,
    /// No time (a fixed formula, a datum at `t = 0`).
    None,
}

/// The class of test functions a statement quantifies over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TestFunctions {
    /// The statement has no test function.
    None,
    /// `Ψ ∈ C¹_c((0,T)×(0,1))`: the ledger uses an explicit polynomial
    /// bump `((t − t₀)(t₁ − t))²((w − a)(b − w))²` on `[t₀,t₁]×[a,b]`,
    /// `0 < t₀ < t₁ < T`, `0 < a < b < 1`, extended by 0 (it is `C¹`).
    SmoothCompact,
    /// `ϕ ∈ C¹_c(0,T)`, `ϕ ≥ 0` (a test function in `t` only).
    SmoothInTime,
}

/// How a statement quantifies over the Lagrangian variable `w`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InW {
    /// No `w`, or an identity at given nodes.
    None,
    /// "for a.e. w" (`L¹`/`L^∞` functions of `w`): a failure is shown on
    /// a set of positive measure (two points of one open cell where both
    /// sides are continuous, or an integral).
    AlmostEvery,
}

/// The hypothesis on the datum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Datum {
    /// `x⁰ ∈ K^N`, `u⁰ ∈ C_{x⁰}` (`prop:proj-micro`): every datum the
    /// crate accepts.
    InC,
    /// `u⁰ ∈ H_{x⁰}`: equal velocities across every contact at `t = 0`
    /// (`hyp:u0` sampled, section 3 and `thm:main`).
    InH,
}

/// What a statement quantifies over, with the paper's `\label` and words.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Domain {
    /// The `\label` whose text states the domain.
    pub label: &'static str,
    /// The paper's words that fix it (LaTeX simplified).
    pub text: &'static str,
    /// The quantifier over `t`.
    pub time: InTime,
    /// The least `N` (2 where the paper says `N > 1`).
    pub min_n: usize,
    /// The class of test functions.
    pub test_functions: TestFunctions,
    /// The quantifier over `w`.
    pub w: InW,
    /// The hypothesis on the datum.
    pub datum: Datum,
}

/// Why a candidate witness lies outside its statement's domain.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum Refusal {
    /// `N` is below the statement's least `N`.
    TooFewParticles {
        /// The witness's `N`.
        n: usize,
        /// The least `N` of the domain.
        min_n: usize,
    },
    /// The datum breaks the statement's hypothesis (`u⁰ ∉ H_{x⁰}`).
    DatumOutside,
    /// A witness time of an a.e.-in-`t` or a `t > 0` statement is not
    /// positive.
    NotPositive(String),
    /// An a.e.-in-`t` statement's witness time is a collision instant.
    AtCollision(String),
    /// An a.e.-in-`t` statement's failure is shown at fewer than two
    /// times, or at two times of different open intervals.
    NotTwoTimesOfOneInterval,
    /// A measure-in-`t` statement's failure is shown at times that end
    /// (at `shown`) before the last collision instant (`last`): the
    /// measure, Dirac masses at the collisions, is not all shown.
    HistoryCut {
        /// The latest witness time.
        shown: String,
        /// The last collision instant.
        last: String,
    },
}

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Refusal::TooFewParticles { n, min_n } => {
                write!(f, "N = {n} but the statement assumes N ≥ {min_n}")
            }
            Refusal::DatumOutside => f.write_str("the datum is outside the hypothesis u⁰ ∈ H_x⁰"),
            Refusal::NotPositive(t) => write!(f, "t = {t} is not > 0"),
            Refusal::AtCollision(t) => write!(f, "t = {t} is a collision instant"),
            Refusal::NotTwoTimesOfOneInterval => f.write_str(
                "the failure is not shown at two times of one open interval between collisions",
            ),
            Refusal::HistoryCut { shown, last } => write!(
                f,
                "a measure in t is shown up to t = {shown}, before the last collision at t = {last}"
            ),
        }
    }
}

impl Domain {
    /// "for all t ≥ 0", any N ≥ 1, any datum in `C_{x⁰}`: the default of a
    /// per-case claim whose statement sets nothing narrower (the label is
    /// the claim's own).
    pub const EVERY_T: Domain = Domain {
        label: "prop:proj-micro",
        text: "Let x_0 ∈ K^N and u_0 ∈ C^N_{x_0} … x(t) = P_{K^N}(x_0 + t u_0), t ≥ 0",
        time: InTime::Every,
        min_n: 1,
        test_functions: TestFunctions::None,
        w: InW::None,
        datum: Datum::InC,
    };
    /// A fixed formula or a scaling check (no time, no particle datum of
    /// its own).
    pub const FIXED: Domain = Domain {
        label: "thm:main",
        text: "Let N > 1 … (a formula printed in the paper, checked once)",
        time: InTime::None,
        min_n: 1,
        test_functions: TestFunctions::None,
        w: InW::None,
        datum: Datum::InC,
    };

    /// Whether a datum of `N = n` particles with trajectory `traj` meets the
    /// domain's hypotheses on `N` and on the datum.
    pub fn admits_datum<S: Scalar>(&self, traj: &Trajectory<S>) -> Result<(), Refusal> {
        let data = traj.data();
        if data.n() < self.min_n {
            return Err(Refusal::TooFewParticles {
                n: data.n(),
                min_n: self.min_n,
            });
        }
        if self.datum == Datum::InH && !in_h(data.positions(), data.velocities(), &data.two_r()) {
            return Err(Refusal::DatumOutside);
        }
        Ok(())
    }

    /// Whether `times` (where the failure is shown) are admissible
    /// witness times for this domain on `traj`: for an a.e.-in-`t`
    /// statement, two distinct positive times of one open interval between
    /// consecutive collision instants (or after the last); for a measure in
    /// `t`, times reaching the last collision instant (none: the checker's
    /// own probe times, its measure read over the whole history);
    /// otherwise any.
    pub fn admits_times<S: Scalar>(
        &self,
        traj: &Trajectory<S>,
        times: &[S],
    ) -> Result<(), Refusal> {
        for t in times {
            self.admits_time(traj, t)?;
        }
        if self.time == InTime::Measure {
            let shown = times.iter().max_by(|a, b| a.total_cmp(b));
            return match (shown, traj.last_collision()) {
                (Some(shown), Some(last)) if shown < last => Err(Refusal::HistoryCut {
                    shown: shown.render(),
                    last: last.render(),
                }),
                _ => Ok(()),
            };
        }
        if self.time != InTime::AlmostEvery {
            return Ok(());
        }
        let [a, b] = times else {
            return Err(Refusal::NotTwoTimesOfOneInterval);
        };
        if a == b || interval_of(traj, a) != interval_of(traj, b) {
            return Err(Refusal::NotTwoTimesOfOneInterval);
        }
        Ok(())
    }

    /// Whether one time is admissible for this domain on `traj`: `t > 0`
    /// for a statement "for t > 0" or "for a.e. t", and not a collision
    /// instant for the latter; otherwise any.
    pub fn admits_time<S: Scalar>(&self, traj: &Trajectory<S>, t: &S) -> Result<(), Refusal> {
        if !matches!(self.time, InTime::AlmostEvery | InTime::Positive) {
            return Ok(());
        }
        if t.total_cmp(&S::zero()).is_le() {
            return Err(Refusal::NotPositive(t.render()));
        }
        if self.time == InTime::AlmostEvery && traj.impulses().iter().any(|imp| imp.t == *t) {
            return Err(Refusal::AtCollision(t.render()));
        }
        Ok(())
    }

    /// Both [`Domain::admits_datum`] and [`Domain::admits_times`].
    pub fn admits<S: Scalar>(&self, traj: &Trajectory<S>, times: &[S]) -> Result<(), Refusal> {
        self.admits_datum(traj)?;
        self.admits_times(traj, times)
    }
}

/// `u⁰ ∈ H_{x⁰}`: `u⁰` constant on every contact cluster of `x⁰`.
fn in_h<S: Scalar>(x: &[S], u: &[S], two_r: &S) -> bool {
    contact_clusters(x, two_r)
        .iter()
        .all(|c| u[c.range()].windows(2).all(|p| p[0] == p[1]))
}

/// The distinct collision instants of `traj`, increasing.
pub fn collision_instants<S: Scalar>(traj: &Trajectory<S>) -> Vec<S> {
    let mut out: Vec<S> = Vec::new();
    for imp in traj.impulses() {
        if out.last() != Some(&imp.t) {
            out.push(imp.t.clone());
        }
    }
    out
}

/// The open interval between consecutive collision instants containing
/// `t`: `(lo, hi)`, `hi = None` after the last one.
pub fn interval_of<S: Scalar>(traj: &Trajectory<S>, t: &S) -> (S, Option<S>) {
    let instants = collision_instants(traj);
    let mut lo = S::zero();
    for c in instants {
        if c > *t {
            return (lo, Some(c));
        }
        lo = c;
    }
    (lo, None)
}

/// One open interval of times between collisions and two times inside it,
/// at a third and two thirds (or `lo + 1`, `lo + 2` after the last
/// collision): where an a.e.-in-`t` statement is checked.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OpenInterval<S> {
    /// The left end: 0 or a collision instant.
    pub lo: S,
    /// The right end: the next collision instant, `None` after the last.
    pub hi: Option<S>,
    /// Two times strictly inside, increasing.
    pub times: [S; 2],
}

/// The open intervals of `(0, ∞)` cut by the collision instants of `traj`,
/// each with its two probe times.
pub fn open_intervals<S: Scalar>(traj: &Trajectory<S>) -> Vec<OpenInterval<S>> {
    let mut out = Vec::new();
    let mut lo = S::zero();
    let third = S::one() / S::from_i64(3);
    for c in collision_instants(traj) {
        if c > lo {
            let len = c.clone() - &lo;
            let a = lo.clone() + &(len.clone() * &third);
            let b = lo.clone() + &(len * &third * &S::from_i64(2));
            out.push(OpenInterval {
                lo: lo.clone(),
                hi: Some(c.clone()),
                times: [a, b],
            });
        }
        lo = c;
    }
    let (a, b) = (lo.clone() + &S::one(), lo.clone() + &S::from_i64(2));
    out.push(OpenInterval {
        lo,
        hi: None,
        times: [a, b],
    });
    debug_assert!(out.iter().all(|iv| iv.times[0] < iv.times[1]));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::initial::InitialData;
    use crate::rational::ratio as q;

    /// A measure in `t` is shown over the whole history: times ending
    /// before the last collision (here the only one, at `t = 3/2`) are
    /// refused, times reaching it and the checker's own times are not.
    #[test]
    fn a_measure_is_shown_up_to_the_last_collision() {
        let data = InitialData::with_paper_radius(vec![q(0, 1), q(2, 1)], vec![q(1, 1), q(0, 1)]);
        let traj = Trajectory::new(data.unwrap());
        assert_eq!(traj.last_collision(), Some(&q(3, 2)));
        let measure = Domain {
            time: InTime::Measure,
            ..Domain::EVERY_T
        };
        assert_eq!(
            measure.admits_times(&traj, &[q(0, 1)]),
            Err(Refusal::HistoryCut {
                shown: "0".into(),
                last: "3/2".into()
            })
        );
        assert_eq!(measure.admits_times(&traj, &[q(3, 2)]), Ok(()));
        assert_eq!(measure.admits_times(&traj, &[q(1, 1), q(2, 1)]), Ok(()));
        assert_eq!(measure.admits_times(&traj, &[]), Ok(()));
        assert_eq!(Domain::EVERY_T.admits_times(&traj, &[q(0, 1)]), Ok(()));
    }
}
