//! Every case checker of the claims registry can fail: each one (and each
//! correction) must reject at least one hand-written mutant of the engines'
//! output, on a case where it accepts the true output.
//!
//! A checker that no mutant can fail proves nothing when it passes (issue 14:
//! "Checkers that cannot fail, or barely"). cargo-mutants (docs/mutants.md)
//! mutates the engines' code and runs the tests; it is too slow to run every
//! claim checker against every code mutant, so this test corrupts the
//! computed output directly, the way plausible bugs of the engines would:
//!
//! * **state mutants** — a [`Tamper`] applied by [`Case::state`] (and
//!   [`Case::history_state`]) to every state the checkers read: `λ` with its
//!   sign flipped, not divided by N, shifted by one index; velocities that are
//!   the cluster mean leaving out one particle, the unprojected `u⁰`, the left
//!   derivative; positions left in translated coordinates, lagging (free
//!   flight at `t/2`), or not projected at all; a contact cluster split in two;
//! * **history mutants** — a [`Trajectory`] rebuilt with
//!   [`Trajectory::from_parts`] from tampered records: a collision dropped from
//!   the impulses only, or from the whole history (a contact never made), the
//!   velocity after a collision averaged over the parts without their sizes,
//!   and the parts' velocities listed in reverse order.
//!
//! A checker *kills* a mutant when, on some case it applies to, it accepts the
//! true case and rejects the mutated one. The registry is iterated, not a
//! list: a claim added later is held to the same rule. A checker that kills
//! nothing is a failure of this test (it either cannot fail, or reads the
//! engines' output by a way the hook does not reach: read states through
//! `Case::state`); a mutant that no checker kills is a failure too.

use num_rational::BigRational;
use sticky::claims::{registry, Case, Kind, Tamper};
use sticky::cluster::{runs, Cluster};
use sticky::contact::{multipliers, Impulse};
use sticky::generate::{initial_data, Limits, SplitMix64};
use sticky::initial::shift;
use sticky::projection::{free_flight, state_at};
use sticky::state::State;
use sticky::trajectory::Trajectory;
use sticky::{InitialData, Scalar};

type Q = BigRational;

/// How a mutant corrupts a case.
enum Apply {
    /// Every state read through the case.
    State(Tamper<Q>),
    /// The recorded history (`None`: nothing to corrupt in this case).
    History(fn(&Trajectory<Q>) -> Option<Trajectory<Q>>),
}

struct Mutant {
    name: &'static str,
    apply: Apply,
}

// ---- state mutants -------------------------------------------------------

/// `λ` recomputed from the (mutated) velocities, as the engines do.
fn relambda(data: &InitialData<Q>, s: &mut State<Q>) {
    s.multipliers = multipliers(data.velocities(), &s.velocities).0;
}

fn lambda_sign(_: &InitialData<Q>, s: &mut State<Q>) {
    for l in &mut s.multipliers {
        *l = -l.clone();
    }
}

fn lambda_not_divided_by_n(data: &InitialData<Q>, s: &mut State<Q>) {
    let n = Q::from_usize(data.n());
    for l in &mut s.multipliers {
        *l = l.clone() * &n;
    }
}

/// `λ_i ← λ_{i+1}` (an off-by-one in the pair index), `λ_{N−1} ← 0`.
fn lambda_shifted(_: &InitialData<Q>, s: &mut State<Q>) {
    if !s.multipliers.is_empty() {
        s.multipliers.remove(0);
        s.multipliers.push(Q::zero());
    }
}

/// On every contact cluster of two or more particles, the mean of `u⁰` over
/// the cluster without its last particle.
fn mean_leaves_one_out(data: &InitialData<Q>, s: &mut State<Q>) {
    let u0 = data.velocities();
    for c in &s.clusters {
        if c.size >= 2 {
            let k = c.size - 1;
            let sum = u0[c.first..c.first + k]
                .iter()
                .fold(Q::zero(), |a, v| a + v);
            let mean = sum / Q::from_usize(k);
            for u in &mut s.velocities[c.range()] {
                *u = mean.clone();
            }
        }
    }
    relambda(data, s);
}

/// On every contact cluster of two or more particles, the sum of `u⁰` over
/// the cluster instead of its mean (the division by the size forgotten).
fn velocity_cluster_sum(data: &InitialData<Q>, s: &mut State<Q>) {
    let u0 = data.velocities();
    for c in &s.clusters {
        if c.size >= 2 {
            let sum = u0[c.range()].iter().fold(Q::zero(), |a, v| a + v);
            for u in &mut s.velocities[c.range()] {
                *u = sum.clone();
            }
        }
    }
    relambda(data, s);
}

/// The velocity not projected: `u(t) = u⁰`.
fn velocity_unprojected(data: &InitialData<Q>, s: &mut State<Q>) {
    s.velocities = data.velocities().to_vec();
    relambda(data, s);
}

/// The left derivative (pre-collision velocity): the clusters joined
/// strictly before `t`, not at `t`.
fn velocity_left_derivative(data: &InitialData<Q>, s: &mut State<Q>) {
    let traj = Trajectory::new(data.clone());
    let before = runs(data.n(), |j| {
        traj.join_times()[j]
            .as_ref()
            .is_some_and(|jt| jt.total_cmp(&s.t).is_lt())
    });
    s.velocities = sticky::cluster::project_h(data.velocities(), &before);
    relambda(data, s);
}

/// Positions left in translated coordinates `x̃_i = x_i − 2r(i−1)`.
fn positions_untranslated(data: &InitialData<Q>, s: &mut State<Q>) {
    s.positions = shift(&s.positions, &data.two_r());
}

/// Positions of the time `t/2` (the free flight scaled wrongly).
fn positions_lag(data: &InitialData<Q>, s: &mut State<Q>) {
    let half = s.t.clone() / Q::from_i64(2);
    if let Ok(h) = state_at(data, &half) {
        s.positions = h.positions;
    }
}

/// Positions not projected: `x(t) = x⁰ + t u⁰`.
fn positions_free_flight(data: &InitialData<Q>, s: &mut State<Q>) {
    s.positions = free_flight(data, &s.t);
}

/// The first contact cluster of two or more particles reported as two.
fn cluster_split(_: &InitialData<Q>, s: &mut State<Q>) {
    if let Some(k) = s.clusters.iter().position(|c| c.size >= 2) {
        let c = s.clusters[k];
        s.clusters[k] = Cluster {
            first: c.first,
            size: 1,
        };
        s.clusters.insert(
            k + 1,
            Cluster {
                first: c.first + 1,
                size: c.size - 1,
            },
        );
    }
}

// ---- history mutants -----------------------------------------------------

fn rebuild(
    traj: &Trajectory<Q>,
    join_time: Vec<Option<Q>>,
    impulses: Vec<Impulse<Q>>,
) -> Trajectory<Q> {
    Trajectory::from_parts(traj.data().clone(), join_time, impulses)
}

/// The last collision missing from the impulses (the pressure record), the
/// history otherwise intact.
fn impulse_dropped(traj: &Trajectory<Q>) -> Option<Trajectory<Q>> {
    let mut imps = traj.impulses().to_vec();
    imps.pop()?;
    Some(rebuild(traj, traj.join_times().to_vec(), imps))
}

/// The last collision never happens: its contact is missing from the
/// history (join time) and from the impulses.
fn contact_dropped(traj: &Trajectory<Q>) -> Option<Trajectory<Q>> {
    let mut imps = traj.impulses().to_vec();
    let last = imps.pop()?;
    let mut join = traj.join_times().to_vec();
    for p in &last.parts[..last.parts.len() - 1] {
        join[p.end() - 1] = None;
    }
    Some(rebuild(traj, join, imps))
}

/// The velocity after a collision taken as the plain mean of the parts'
/// velocities, forgetting their sizes.
fn impulse_velocity_unweighted(traj: &Trajectory<Q>) -> Option<Trajectory<Q>> {
    let mut changed = false;
    let imps = traj
        .impulses()
        .iter()
        .map(|imp| {
            let sum = imp.part_velocities.iter().fold(Q::zero(), |a, v| a + v);
            let v = sum / Q::from_usize(imp.parts.len());
            changed |= v != imp.velocity;
            Impulse {
                velocity: v,
                ..imp.clone()
            }
        })
        .collect();
    changed.then(|| rebuild(traj, traj.join_times().to_vec(), imps))
}

/// A collision recorded that never happened: particles 1 and 2, never
/// joined, reported as merging at the last probe time (the record of an
/// invalidated candidate, say).
fn impulse_phantom(traj: &Trajectory<Q>) -> Option<Trajectory<Q>> {
    let data = traj.data();
    if data.n() < 2 || traj.join_times()[0].is_some() {
        return None;
    }
    let u0 = data.velocities();
    let t = sticky::trajectory::probe_times(traj, Some(10)).pop()?;
    let mut imps = traj.impulses().to_vec();
    imps.push(Impulse {
        t,
        cluster: Cluster { first: 0, size: 2 },
        parts: vec![Cluster { first: 0, size: 1 }, Cluster { first: 1, size: 1 }],
        part_velocities: vec![u0[0].clone(), u0[1].clone()],
        velocity: (u0[0].clone() + &u0[1]) / Q::from_i64(2),
        n: data.n(),
    });
    Some(rebuild(traj, traj.join_times().to_vec(), imps))
}

/// The parts' velocities listed right to left.
fn impulse_parts_reversed(traj: &Trajectory<Q>) -> Option<Trajectory<Q>> {
    let mut changed = false;
    let imps = traj
        .impulses()
        .iter()
        .map(|imp| {
            let mut pv = imp.part_velocities.clone();
            pv.reverse();
            changed |= pv != imp.part_velocities;
            Impulse {
                part_velocities: pv,
                ..imp.clone()
            }
        })
        .collect();
    changed.then(|| rebuild(traj, traj.join_times().to_vec(), imps))
}

fn mutants() -> Vec<Mutant> {
    let state = |name, f: Tamper<Q>| Mutant {
        name,
        apply: Apply::State(f),
    };
    let history = |name, f: fn(&Trajectory<Q>) -> Option<Trajectory<Q>>| Mutant {
        name,
        apply: Apply::History(f),
    };
    vec![
        state("lambda-sign", lambda_sign),
        state("lambda-not-divided-by-N", lambda_not_divided_by_n),
        state("lambda-shifted", lambda_shifted),
        state("velocity-mean-leaves-one-out", mean_leaves_one_out),
        state("velocity-cluster-sum", velocity_cluster_sum),
        state("velocity-unprojected", velocity_unprojected),
        state("velocity-left-derivative", velocity_left_derivative),
        state("positions-untranslated", positions_untranslated),
        state("positions-lag", positions_lag),
        state("positions-free-flight", positions_free_flight),
        state("cluster-split", cluster_split),
        history("impulse-dropped", impulse_dropped),
        history("contact-dropped", contact_dropped),
        history("impulse-velocity-unweighted", impulse_velocity_unweighted),
        history("impulse-parts-reversed", impulse_parts_reversed),
        history("impulse-phantom", impulse_phantom),
    ]
}

fn mutate(case: &Case<Q>, m: &Mutant) -> Option<Case<Q>> {
    match m.apply {
        Apply::State(f) => Some(case.clone().tampered(f)),
        Apply::History(f) => f(&case.traj).map(|t| Case::with_times(t, case.times.clone())),
    }
}

fn q(n: i64, d: i64) -> Q {
    Q::from_i64(n) / Q::from_i64(d)
}

fn scene(radius: Q, x: &[Q], u: &[Q]) -> Case<Q> {
    Case::new(
        InitialData::new(radius, x.to_vec(), u.to_vec()).expect("admissible"),
        Some(10),
    )
}

/// Random admissible cases (contacts, separating contacts, simultaneous
/// collisions), half of them with the paper's radius `2r = 1/N`, and a few
/// degenerate data on which some statements found false as printed happen
/// to hold (so that their checkers, too, have a true case to accept).
fn cases() -> Vec<Case<Q>> {
    let mut rng = SplitMix64::new(0x0DD5);
    let (zero, one) = (Q::zero(), Q::one());
    let mut out = vec![
        // One cluster of three at rest, centred at 0: ⟨x⁰ + t u⁰, w⟩ = 0 on H.
        scene(
            q(1, 2),
            &[-one.clone(), zero.clone(), one.clone()],
            &[zero.clone(), zero.clone(), zero.clone()],
        ),
        // One cluster of three moving rigidly, nothing else: eq:proj-u-micro
        // as printed holds (L_k = 1, equal velocities).
        scene(
            q(1, 2),
            &[zero.clone(), one.clone(), q(2, 1)],
            &[one.clone(), one.clone(), one.clone()],
        ),
        // Two particles moving apart: no contact, no collision ever.
        scene(
            q(1, 4),
            &[zero.clone(), one.clone()],
            &[-one.clone(), one.clone()],
        ),
    ];
    out.extend((0..48).map(|k| {
        let mut b = rng.bytes(128);
        if k % 2 == 0 {
            b[0] &= !0b11; // radius code 0: 2r = 1/N
        }
        let limits = Limits {
            max_n: 2 + k % 11,
            max_den: 6,
            max_speed: 8,
        };
        Case::new(initial_data(&b, limits), Some(10))
    }));
    out
}

type Checker = (
    String,
    fn(&Case<Q>) -> Result<(), sticky::claims::Violation>,
    fn(&Case<Q>) -> bool,
);

/// Every case checker of the registry, and every case correction.
fn checkers() -> Vec<Checker> {
    let mut out: Vec<Checker> = Vec::new();
    for claim in registry::<Q>() {
        if let Kind::Case(check) = claim.kind {
            out.push((claim.id.to_string(), check, claim.applies));
        }
        if let Some(c) = claim.correction {
            if let Kind::Case(check) = c.check {
                out.push((format!("{} (correction)", claim.id), check, claim.applies));
            }
        }
    }
    out
}

/// Checkers that no mutant of the engines' output can fail, each with the
/// reason. Nothing else may be added here without one.
const NO_ENGINE_MUTANT: [(&str, &str); 3] = [
    (
        "df:tKN",
        "a statement about the change of coordinates x ↦ x̃ (df:translat-x), true of every vector whatever the engine computes; its checker tests the translation map, and the unit test of claims::micro::cones shows it fails on a wrong one",
    ),
    (
        "eq:test-pressure-bound",
        "false as printed (a sign slip; counterexample in the ledger); no case of this battery satisfies the printed identity, so there is no true case to mutate; the correction rejects 9 of the mutants",
    ),
    (
        "prop:pressure-bound#test-function",
        "false as printed (φ(t,0) = φ(t,1) = −x_0(t)ϕ(t) ≠ 0; counterexample in the ledger); it holds only when the artificial particle sits at 0, which no case here has; the correction rejects 9 of the mutants",
    ),
];

#[test]
fn every_checker_rejects_a_mutant() {
    let cases = cases();
    let mutants = mutants();
    let checkers = checkers();
    assert!(checkers.len() > 20, "the registry lost its case checkers");
    // The mutated cases, computed once: mutated[m][c].
    let mutated: Vec<Vec<Option<Case<Q>>>> = mutants
        .iter()
        .map(|m| cases.iter().map(|c| mutate(c, m)).collect())
        .collect();
    let mut kills = vec![vec![false; mutants.len()]; checkers.len()];
    for (k, (_, check, applies)) in checkers.iter().enumerate() {
        for (ci, case) in cases.iter().enumerate() {
            if !applies(case) || check(case).is_err() {
                continue;
            }
            for (m, row) in mutated.iter().enumerate() {
                if kills[k][m] {
                    continue;
                }
                if let Some(mc) = &row[ci] {
                    kills[k][m] = check(mc).is_err();
                }
            }
        }
    }
    // The matrix, for the report (docs/mutants.md).
    eprintln!(
        "kill matrix (x = the checker rejects the mutant on some case it accepts unmutated):"
    );
    for (m, mutant) in mutants.iter().enumerate() {
        eprintln!("  m{m:<2} {}", mutant.name);
    }
    for (k, (id, _, _)) in checkers.iter().enumerate() {
        let row: String = (0..mutants.len())
            .map(|m| if kills[k][m] { 'x' } else { '.' })
            .collect();
        let count = kills[k].iter().filter(|&&x| x).count();
        eprintln!("  {row}  {count:>2}  {id}");
    }
    let blind: Vec<&str> = checkers
        .iter()
        .zip(&kills)
        .filter(|(_, row)| !row.iter().any(|&x| x))
        .map(|((id, _, _), _)| id.as_str())
        .filter(|id| !NO_ENGINE_MUTANT.iter().any(|(e, _)| e == id))
        .collect();
    let unseen: Vec<&str> = mutants
        .iter()
        .enumerate()
        .filter(|(m, _)| !kills.iter().any(|row| row[*m]))
        .map(|(_, mu)| mu.name)
        .collect();
    assert!(
        blind.is_empty(),
        "checkers that reject no mutant (they cannot fail on these engines' bugs, or read the state around Case::state): {blind:?}"
    );
    assert!(
        unseen.is_empty(),
        "mutants that no checker rejects: {unseen:?}"
    );
}

/// The hook changes nothing on a real case: the tampered-free case reads the
/// engines' states, and the two engines agree.
#[test]
fn untampered_states_are_the_engines() {
    for case in cases().iter().take(8) {
        for t in &case.times {
            assert_eq!(case.state(t).unwrap(), state_at(case.data(), t).unwrap());
            assert_eq!(case.history_state(t).unwrap(), case.traj.at(t).unwrap());
        }
    }
}

// ---- the index convention of the violation texts ---------------------------

/// The integer that starts `s` (an optional `-` or `−`, then digits), and
/// the rest of `s` after it.
fn leading_int(s: &str) -> Option<(i64, &str)> {
    let (sign, rest) = match s.strip_prefix('-').or_else(|| s.strip_prefix('−')) {
        Some(r) => (-1, r),
        None => (1, s),
    };
    let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    let k: i64 = rest[..digits].parse().ok()?;
    Some((sign * k, &rest[digits..]))
}

/// What in a ledger text breaks the convention of `claims::ledger::NUMBERING`
/// for a case of `n` particles: a bracket index `x[k]`, `particle [k]`,
/// `particles [a..b]` outside `−1 … N−1` (−1 is the artificial particle `x_0`
/// of section 3, or the end multiplier `λ_0`), a `pair (a, b)` or
/// `contact (a, b)` that is not two neighbours among `−1 … N−1`, or — unless
/// the text says "paper's numbering" — a 1-based form: `x_1`, `u⁰_2`, `λ_1`,
/// `particle 3`, `pair 2`, `i = 1`.
fn index_problems(text: &str, n: usize) -> Vec<String> {
    let n = n as i64;
    let in_range = |k: i64| (-1..n).contains(&k);
    let mut out = Vec::new();
    let mut prev: Option<char> = None;
    for (at, c) in text.char_indices() {
        let rest = &text[at + c.len_utf8()..];
        let before = &text[..at];
        if c == '[' {
            let named = prev.is_some_and(|p| p.is_alphabetic() || "⁰\u{303}".contains(p))
                || before.ends_with("particle ")
                || before.ends_with("particles ");
            if let Some((k, tail)) = leading_int(rest).filter(|_| named) {
                let last = match tail.strip_prefix("..").and_then(leading_int) {
                    Some((b, t)) if t.starts_with(']') => Some(b),
                    _ if tail.starts_with(']') => Some(k),
                    _ => None,
                };
                if let Some(b) = last {
                    if !in_range(k) || !in_range(b) {
                        out.push(format!("index [{k}] or [{b}] outside −1…{}", n - 1));
                    }
                }
            }
        }
        if c == '(' && (before.ends_with("pair ") || before.ends_with("contact ")) {
            if let Some((a, tail)) = leading_int(rest) {
                if let Some((b, _)) = tail.strip_prefix(", ").and_then(leading_int) {
                    if b != a + 1 || !in_range(a) || !in_range(b) {
                        out.push(format!(
                            "pair ({a}, {b}) is not two neighbours of −1…{}",
                            n - 1
                        ));
                    }
                }
            }
        }
        if !text.contains("paper's numbering") {
            let digit_next = rest.starts_with(|d: char| d.is_ascii_digit());
            let subscript = c == '_' && prev.is_some_and(|p| "xuλμpeysnξ⁰\u{303}".contains(p));
            let word_start = prev.is_none_or(|p| p == ' ' || p == '(' || p == ',');
            let word = ["particle ", "particles ", "pair ", "i = ", "j = "]
                .iter()
                .filter(|_| word_start)
                .any(|w| {
                    text[at..].starts_with(w)
                        && text[at + w.len()..].starts_with(|d: char| d.is_ascii_digit())
                });
            if (subscript && digit_next) || word {
                let show: String = text[at..].chars().take(12).collect();
                out.push(format!("1-based form `{show}`"));
            }
        }
        prev = Some(c);
    }
    out
}

#[test]
fn index_scanner_sees_1_based_forms() {
    assert!(index_problems("pair (0, 1) touches, x[1] − x[0] = 1/2, λ[−1] = 0", 2).is_empty());
    assert!(index_problems("x[0] − x[-1] = 2", 1).is_empty());
    assert!(index_problems("particles [0..2] ∈ H, u⁰[2] = 1, w ∈ (0/N, 1/N]", 3).is_empty());
    assert!(index_problems("particle [0] (i = 1 in the paper's numbering): u_i", 1).is_empty());
    assert!(index_problems("Σ [u_i] φ_i = 0, u_i = 2", 1).is_empty());
    for bad in [
        "pair (1, 2) touches",
        "pair (0, 2)",
        "x[2] − x[1]",
        "particles [1..2]",
        "λ[−2] = 0",
        "particles 1 and 2 touch",
        "(i = 1)",
        "u⁰_1 = -8",
        "t = 1, i = 1: N(λ_i − λ_{i−1})",
        "λ_1 jumps",
    ] {
        assert!(!index_problems(bad, 2).is_empty(), "{bad:?} passed");
    }
}

/// Every violation text the case checkers write — on the battery's cases and
/// on every mutant of them — indexes particles from 0
/// (`claims::ledger::NUMBERING`): no index at or beyond N, no paper
/// subscript unless the text says so. A checker put back to `i + 1` names
/// `x[N]` or `pair (N−1, N)` on the cases whose violation is at the last
/// particle, among them every violation at N = 2.
#[test]
fn violation_texts_index_from_0() {
    let cases = cases();
    let mutants = mutants();
    let mut seen = 0usize;
    let mut bad = Vec::new();
    for (id, check, applies) in checkers() {
        // N ≤ 6: where an index put back to `i + 1` runs past N − 1 most
        // often, and a third of the battery's time.
        for case in cases.iter().filter(|c| c.n() <= 6 && applies(c)) {
            let variants =
                std::iter::once(Some(case.clone())).chain(mutants.iter().map(|m| mutate(case, m)));
            for v in variants.flatten() {
                if let Err(violation) = check(&v) {
                    seen += 1;
                    for p in index_problems(&violation.witness, v.n()) {
                        bad.push(format!(
                            "{id} (N = {}): {p} in {:?}",
                            v.n(),
                            violation.witness
                        ));
                    }
                }
            }
        }
    }
    assert!(
        seen > 1000,
        "only {seen} violation texts: the battery lost its mutants"
    );
    assert!(
        bad.is_empty(),
        "{} texts break the 0-based convention, e.g.:\n{}",
        bad.len(),
        bad.iter().take(12).cloned().collect::<Vec<_>>().join("\n")
    );
}
