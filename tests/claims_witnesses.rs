//! The ledger's witnesses lie in their statements' domains (issue 35):
//! a witness at a collision instant is refused, every per-case erratum's
//! witness replays from its `witness_data` alone (parsed back from the JSON
//! of `sticky claims --json`) with the generic `BigRational` engine, and a
//! tampered witness does not.

use num_rational::BigRational;
use sticky::claims::domain::{Domain, Refusal};
use sticky::claims::ledger::{self, failure_in_domain, Budget, Status};
use sticky::claims::witness::{ReplayError, WitnessData, WitnessScene};
use sticky::claims::{registry, Case, Claim, Kind, Violation};
use sticky::initial::InitialData;
use sticky::trajectory::Trajectory;

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(n.into(), d.into())
}

/// The witness shared by ten errata before issue 35: N = 2, r = 1/4,
/// x⁰ = (0, 3/2), u⁰ = (−8, −9); its only collision is at t = 1.
fn old_shared_witness() -> Trajectory<BigRational> {
    let data = InitialData::new(q(1, 4), vec![q(0, 1), q(3, 2)], vec![q(-8, 1), q(-9, 1)]).unwrap();
    Trajectory::new(data)
}

fn claim(id: &str) -> Claim<BigRational> {
    registry::<BigRational>()
        .into_iter()
        .find(|c| c.id == id)
        .unwrap_or_else(|| panic!("{id} is in the registry"))
}

/// A mutant checker that fails exactly at the collision instants among its
/// probe times (and nowhere else): what the old `t = 1` witnesses were.
fn fails_at_collisions(case: &Case<BigRational>) -> Result<(), Violation> {
    let instants: Vec<&BigRational> = case.traj.impulses().iter().map(|i| &i.t).collect();
    match case.times.iter().find(|t| instants.contains(t)) {
        Some(t) => Err(Violation::new("mutant", format!("t = {t}")).at(t.to_string())),
        None => Ok(()),
    }
}

#[test]
fn a_witness_at_a_collision_instant_is_refused() {
    let traj = old_shared_witness();
    let kkt = claim("app:KKT");
    // The old witness time, alone or with a second time.
    assert_eq!(
        kkt.domain.admits(&traj, &[q(1, 1)]),
        Err(Refusal::AtCollision("1".into()))
    );
    assert_eq!(
        kkt.domain.admits(&traj, &[q(1, 1), q(3, 2)]),
        Err(Refusal::AtCollision("1".into()))
    );
    assert_eq!(
        kkt.domain.admits(&traj, &[q(0, 1), q(1, 2)]),
        Err(Refusal::NotPositive("0".into()))
    );
    // One time, or two times on either side of the collision: refused.
    assert_eq!(
        kkt.domain.admits(&traj, &[q(3, 2)]),
        Err(Refusal::NotTwoTimesOfOneInterval)
    );
    assert_eq!(
        kkt.domain.admits(&traj, &[q(1, 2), q(3, 2)]),
        Err(Refusal::NotTwoTimesOfOneInterval)
    );
    assert_eq!(kkt.domain.admits(&traj, &[q(3, 2), q(2, 1)]), Ok(()));
    // The shrinker's test: a checker failing only at collision instants
    // finds nothing inside an a.e.-in-t domain, and finds the collision
    // under "every t" (so the refusal is the domain's doing).
    let case = Case::new(traj.data().clone(), None);
    assert!(failure_in_domain(fails_at_collisions, &case, &kkt.domain).is_none());
    let every = failure_in_domain(fails_at_collisions, &case, &Domain::EVERY_T)
        .expect("the mutant fails at t = 1 under every t");
    assert_eq!(every.violations[0].detail.t.as_deref(), Some("1"));
    // N = 1 is refused where the paper assumes N > 1.
    let one = Trajectory::new(InitialData::new(q(1, 4), vec![q(0, 1)], vec![q(1, 1)]).unwrap());
    assert_eq!(
        claim("eq:w-Hs-perp")
            .domain
            .admits(&one, &[q(1, 1), q(2, 1)]),
        Err(Refusal::TooFewParticles { n: 1, min_n: 2 })
    );
}

/// The witness data of `id` as the JSON of `sticky claims --json` carries
/// it, parsed back.
fn witness_from_json(entry: &ledger::Entry) -> WitnessData {
    let text = ledger::json(std::slice::from_ref(entry));
    let value: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
    serde_json::from_value(value[0]["witness_data"].clone()).expect("a witness_data object")
}

#[test]
fn every_per_case_erratum_replays_from_its_witness_data() {
    let mut replayed = 0;
    for claim in registry::<BigRational>() {
        let (Kind::Case(check), Some(_)) = (&claim.kind, &claim.correction) else {
            continue;
        };
        let entry = ledger::run_claim(&claim, Budget::default());
        assert_eq!(entry.outcome.status, Status::Counterexample, "{}", claim.id);
        let wd = witness_from_json(&entry);
        let WitnessScene::Particles { .. } = &wd.scene else {
            panic!("{}: a particle witness", claim.id);
        };
        assert!(wd.scene_n() >= claim.domain.min_n, "{}", claim.id);
        wd.replay(&claim.domain, *check)
            .unwrap_or_else(|e| panic!("{}: {e:?}", claim.id));
        // Mutants of the object: the witness times moved onto a collision
        // instant (when there is one) and a velocity changed.
        if let (Some(iv), [_, _]) = (&wd.interval, wd.times.as_slice()) {
            if let Some(hi) = &iv.hi {
                let mut at = wd.clone();
                at.times[1] = hi.clone();
                assert!(
                    matches!(
                        at.replay(&claim.domain, *check),
                        Err(ReplayError::Outside(_))
                    ),
                    "{}: a witness time at a collision instant is refused",
                    claim.id
                );
            }
        }
        // Another datum: every particle at rest and the last one moved
        // right by 1 (still admissible). At rest most statements hold; one
        // read at t = 0 alone (lem:incl-HSN's step) still fails, with
        // other values. Either way the recorded witness is not replayed.
        let mut other = wd.clone();
        if let WitnessScene::Particles {
            positions,
            velocities,
            ..
        } = &mut other.scene
        {
            velocities.iter_mut().for_each(|v| *v = "0".into());
            let last = positions.last_mut().expect("N ≥ 1");
            let moved = sticky::rational::parse_exact(last).expect("an exact number") + q(1, 1);
            *last = sticky::rational::render_exact(&moved);
        }
        assert!(
            matches!(
                other.replay(&claim.domain, *check),
                Err(ReplayError::Holds(_) | ReplayError::OtherValues(_))
            ),
            "{}: another datum must not replay the recorded witness",
            claim.id
        );
        replayed += 1;
    }
    assert!(replayed >= 10, "only {replayed} per-case errata replayed");
}
