//! `prop:proj-micro`: the event-driven cluster merge and the one-shot
//! projection `x(t) = P_K(x⁰ + t u⁰)` agree exactly — positions, right
//! derivatives, multipliers, contact clusters — at every collision instant,
//! between collisions and long after the last one; on thousands of random
//! scenes (N up to 200), on scenes built to have simultaneous multi-cluster
//! collisions, and on N = 1.

use num_rational::BigRational;
use sticky::claims::micro::{check_trajectory, projection_formula};
use sticky::generate::{initial_data, Limits, SplitMix64};
use sticky::trajectory::Trajectory;
use sticky::{InitialData, Scalar};

fn q(n: i64, d: i64) -> BigRational {
    BigRational::from_i64(n) / BigRational::from_i64(d)
}

/// Scenes for the agreement run: sizes spread log-uniformly in 1..=200 so
/// that small degenerate scenes and large ones are both frequent.
fn random_scenes(count: u64, seed: u64) -> impl Iterator<Item = InitialData<BigRational>> {
    let mut rng = SplitMix64::new(seed);
    (0..count).map(move |_| {
        let max_n = 1 + (rng.next_u64() % 200) as usize;
        let max_n = (max_n * max_n).div_ceil(200); // skew towards small N
        let bytes = rng.bytes(8 * max_n + 8);
        initial_data(
            &bytes,
            Limits {
                max_n,
                ..Limits::default()
            },
        )
    })
}

#[test]
#[ignore = "campaign: 3,000 random scenes, about a minute; CI runs it (cargo test --release -- --ignored)"]
fn events_equal_projection_on_random_scenes() {
    let scenes = 3000;
    let mut checks = 0usize;
    let mut collisions = 0usize;
    let mut largest = 0usize;
    let mut simultaneous = 0usize;
    for data in random_scenes(scenes, 0x5EED) {
        largest = largest.max(data.n());
        let traj = Trajectory::new(data);
        collisions += traj.impulses().len();
        simultaneous += traj.impulses().iter().filter(|i| i.parts.len() > 2).count();
        // All instants for small N, a spread of 6 beyond.
        let limit = (traj.data().n() > 40).then_some(6);
        checks += check_trajectory(&traj, limit).unwrap_or_else(|v| panic!("{v}"));
    }
    assert_eq!(largest, 200);
    assert!(
        simultaneous > 100,
        "only {simultaneous} multi-cluster collisions generated"
    );
    eprintln!(
        "{scenes} scenes, {collisions} collisions ({simultaneous} of 3+ clusters), {checks} checks"
    );
}

#[test]
fn single_particle() {
    let data = InitialData::new(q(1, 2), vec![q(-3, 7)], vec![q(5, 3)]).unwrap();
    let traj = Trajectory::new(data);
    assert!(traj.impulses().is_empty());
    for t in [q(0, 1), q(1, 3), q(1000, 1)] {
        projection_formula(&traj, &t).unwrap();
        assert_eq!(traj.at(&t).unwrap().positions, vec![q(-3, 7) + t * q(5, 3)]);
    }
}

#[test]
fn four_clusters_meet_at_one_instant() {
    // 2r = 1; clusters of sizes 1, 2, 3, 1 with velocities 3, 1, 0, −2 all
    // reach the translated position 6 at t = 2.
    let shifted = [0, 4, 4, 6, 6, 6, 10];
    let u = [3, 1, 1, 0, 0, 0, -2];
    let x: Vec<_> = shifted
        .iter()
        .enumerate()
        .map(|(i, &s)| q(s + i as i64, 1))
        .collect();
    let u: Vec<_> = u.iter().map(|&v| q(v, 1)).collect();
    let traj = Trajectory::new(InitialData::new(q(1, 2), x, u).unwrap());
    assert_eq!(traj.impulses().len(), 1);
    let imp = &traj.impulses()[0];
    assert_eq!(imp.t, q(2, 1));
    assert_eq!(
        imp.parts.iter().map(|c| c.size).collect::<Vec<_>>(),
        vec![1, 2, 3, 1]
    );
    check_trajectory(&traj, None).unwrap();
}

#[test]
fn two_separate_simultaneous_collisions_are_two_events() {
    // Pairs (0,1) and (2,3) both collide at t = 1, far apart.
    let x = vec![q(0, 1), q(3, 1), q(10, 1), q(13, 1)];
    let u = vec![q(1, 1), q(-1, 1), q(1, 1), q(-1, 1)];
    let traj = Trajectory::new(InitialData::new(q(1, 2), x, u).unwrap());
    let events: Vec<_> = traj
        .impulses()
        .iter()
        .map(|i| (i.t.clone(), i.cluster.first, i.cluster.size))
        .collect();
    assert_eq!(events, vec![(q(1, 1), 0, 2), (q(1, 1), 2, 2)]);
    check_trajectory(&traj, None).unwrap();
}

#[test]
fn separating_contact_at_time_zero() {
    // Particles 1, 2 touch at t = 0 and separate; 2 then hits 3.
    let x = vec![q(0, 1), q(1, 1), q(3, 1)];
    let u = vec![q(0, 1), q(1, 1), q(0, 1)];
    let traj = Trajectory::new(InitialData::new(q(1, 2), x, u).unwrap());
    let s0 = traj.at(&q(0, 1)).unwrap();
    assert_eq!(s0.clusters.len(), 2, "contact cluster {{1,2}} at t = 0");
    assert_eq!(s0.velocities, vec![q(0, 1), q(1, 1), q(0, 1)]);
    assert_eq!(traj.impulses().len(), 1);
    assert_eq!(traj.impulses()[0].t, q(1, 1));
    check_trajectory(&traj, None).unwrap();
}

#[test]
fn already_touching_equal_velocities_stay_one_cluster() {
    let x = vec![q(0, 1), q(1, 1), q(2, 1)];
    let u = vec![q(2, 1), q(2, 1), q(2, 1)];
    let traj = Trajectory::new(InitialData::new(q(1, 2), x, u).unwrap());
    assert!(traj.impulses().is_empty());
    check_trajectory(&traj, None).unwrap();
}
