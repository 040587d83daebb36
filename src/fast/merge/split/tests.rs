//! Tests of the split merge: cuts tile the line and rebuild the whole history.

use super::*;
use crate::fast::scaling::{scale_i128, Scaled};
use crate::generate::{initial_data, Limits, SplitMix64};

/// Equal histories; instants compared as fractions (a half may keep
/// another unreduced pair for the same time).
fn same(a: &History, b: &History) -> Result<(), String> {
    if a.instants.len() != b.instants.len() {
        return Err(format!(
            "{} instants against {}",
            a.instants.len(),
            b.instants.len()
        ));
    }
    for (k, (p, q)) in a.instants.iter().zip(&b.instants).enumerate() {
        if Time::new(p.0, p.1).cmp_exact(&Time::new(q.0, q.1)) != Ordering::Equal {
            return Err(format!("instant {k}: {p:?} against {q:?}"));
        }
    }
    if a.impulses != b.impulses {
        return Err("impulses differ".into());
    }
    if a.parts != b.parts {
        return Err("parts differ".into());
    }
    if a.join != b.join {
        return Err(format!("join {:?} against {:?}", a.join, b.join));
    }
    Ok(())
}

/// `count` random scenes of 2 to 61 particles, scaled, with their
/// index `k`: denominators up to `1 + k % dens` and speeds up to
/// `1 + k % speeds`, small, for many equal times, chains of
/// simultaneous meetings and contacts.
fn small_scenes(
    seed: u64,
    count: usize,
    dens: usize,
    speeds: usize,
) -> impl Iterator<Item = (usize, Scaled)> {
    let mut rng = SplitMix64::new(seed);
    (0..count).filter_map(move |k| {
        let data = initial_data(
            &rng.bytes(400),
            Limits {
                max_n: 2 + k % 60,
                max_den: 1 + (k % dens) as u32,
                max_speed: 1 + (k % speeds) as u32,
            },
        );
        Some((k, scale_i128(&data)?))
    })
}

#[test]
fn every_cut_gives_the_whole_history() {
    let mut cuts = 0;
    let mut runs = 0;
    for (k, s) in small_scenes(77, 300, 4, 5) {
        let whole = History::from_joins(run::<i128, i128>(&s.x, &s.u));
        for m in 1..s.x.len() {
            if cut(&s.x, &s.u, m) != Some(m) {
                continue;
            }
            // Combined on one thread and on two; and with every piece
            // of at least 4 particles cut again, down to the middle, on
            // one thread and on two (the pieces shared out).
            let split = run_halves::<i128, i128>(&s.x, &s.u, m, Cores::One, usize::MAX);
            let two = run_halves::<i128, i128>(&s.x, &s.u, m, Cores::Two, usize::MAX);
            let parts = run_halves::<i128, i128>(&s.x, &s.u, m, Cores::One, 4);
            let shared = run_halves::<i128, i128>(&s.x, &s.u, m, Cores::Two, 4);
            for (how, h) in [
                ("one thread", &split),
                ("two", &two),
                ("parts", &parts),
                ("parts on two threads", &shared),
            ] {
                if let Err(e) = same(&History::from_joins(h.clone()), &whole) {
                    panic!(
                        "scene {k}, cut {m}, {how}: {e}\nx = {:?}\nu = {:?}",
                        s.x, s.u
                    );
                }
            }
            cuts += 1;
            runs += usize::from(split.join[m - 1] != JOIN_NEVER);
        }
    }
    // The run across the cut formed often enough to be tested.
    assert!(cuts > 2000 && runs > 500, "{cuts} cuts, {runs} runs");
}

/// The tree of cuts: every piece of at least `part_min` particles with
/// a legal cut is cut (at the first legal cut from its middle), the
/// others run whole; halves come before their piece, tile it, and are
/// lower; the whole is last.
#[test]
fn the_pieces_tile_the_line() {
    for (k, s) in small_scenes(9, 200, 3, 4) {
        let n = s.x.len();
        let Some(m) = cut(&s.x, &s.u, n / 2) else {
            continue;
        };
        let part_min = 2 + k % 5;
        let mut pieces = Vec::new();
        plan(&s.x, &s.u, 0..n, Some(m), part_min, &mut pieces);
        assert_eq!(pieces.last().map(|p| p.range.clone()), Some(0..n));
        for (i, p) in pieces.iter().enumerate() {
            let (lo, hi) = (p.range.start, p.range.end);
            let want = match i + 1 == pieces.len() {
                true => Some(m),
                false if hi - lo >= part_min => {
                    cut(&s.x[lo..hi], &s.u[lo..hi], (hi - lo) / 2).map(|c| lo + c)
                }
                false => None,
            };
            assert_eq!(p.cut.map(|c| c.at), want, "piece {i} of {pieces:?}");
            match p.cut {
                None => assert_eq!(p.height, 0),
                Some(Split {
                    at: c,
                    left: l,
                    right: r,
                }) => {
                    assert!(l < i && r < i);
                    assert_eq!(
                        (pieces[l].range.clone(), pieces[r].range.clone()),
                        (lo..c, c..hi)
                    );
                    let h = pieces[l].height.max(pieces[r].height);
                    assert_eq!(p.height, h + 1);
                }
            }
        }
    }
}

#[test]
fn two_threads_above_the_threshold() {
    // Past SPLIT_MIN `run_split` takes two threads; the history is the
    // one-thread history all the same.
    let mut rng = SplitMix64::new(4);
    let data = initial_data(
        &rng.bytes(1 << 20),
        Limits {
            max_n: 3 * SPLIT_MIN,
            max_den: 3,
            max_speed: 4,
        },
    );
    let s = scale_i128(&data).expect("small data");
    assert!(s.x.len() >= SPLIT_MIN && cut(&s.x, &s.u, s.x.len() / 2).is_some());
    let split = run_split::<i128, i128>(&s.x, &s.u);
    let whole = History::from_joins(run::<i128, i128>(&s.x, &s.u));
    same(&split, &whole).unwrap();
    assert!(whole.impulses.len() > SPLIT_MIN / 2);
}
