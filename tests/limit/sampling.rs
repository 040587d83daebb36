//! Quantile sampling and its hypotheses.

use super::*;

#[test]
fn sampling_hypotheses() {
    for name in SCENES {
        let datum = datum_of(&load(name));
        assert!(check_datum(&datum).holds(), "{name}");
        let mut last = None;
        for n in [16usize, 32, 64] {
            let r = check_sampling(&datum, n).unwrap();
            assert!(
                r.checks.holds(),
                "{name}, N = {n}: {:?}",
                r.checks.failures()
            );
            // thm:main (i): X⁰_N → X⁰ and U⁰_N → U⁰ in L².
            if let Some((x0, u0)) = last {
                assert!(r.x0_l2_squared < x0);
                assert!(r.u0_l2_squared <= u0);
            }
            last = Some((r.x0_l2_squared.clone(), r.u0_l2_squared.clone()));
        }
    }
    let c = |v: i64| BlockVelocity::Constant(q(v, 1));
    let block = |from: Q, to: Q, density: Q, velocity| Block {
        from,
        to,
        density,
        velocity,
    };
    // Two touching congested blocks separating: MacroDatum::new accepts it,
    // hyp:u0 and thm:main (i)'s contact condition fail.
    let touching = MacroDatum::new(vec![
        block(q(0, 1), q(1, 2), q(1, 1), c(0)),
        block(q(1, 2), q(1, 1), q(1, 1), c(1)),
    ])
    .unwrap();
    let r = check_datum(&touching);
    assert_eq!(r.failures().len(), 1);
    assert_eq!(r.failures()[0].hypothesis, Hypothesis::HypU0);
    let s = check_sampling(&touching, 8).unwrap();
    assert_eq!(
        s.checks.failures()[0].hypothesis,
        Hypothesis::ContactVelocities
    );
    assert!(s.checks.failures()[0]
        .detail
        .contains("particles 3 and 4 (indices from 0)"));
    // Raw blocks: each failure named.
    let bad = vec![
        block(q(0, 1), q(1, 2), q(3, 2), c(0)),
        block(
            q(1, 4),
            q(1, 1),
            q(1, 2),
            BlockVelocity::Affine(q(0, 1), q(1, 1)),
        ),
    ];
    let r = check_blocks(&bad);
    let failed: Vec<Hypothesis> = r.failures().iter().map(|c| c.hypothesis).collect();
    assert_eq!(
        failed,
        vec![
            Hypothesis::WellFormed,
            Hypothesis::DensityAtMostOne,
            Hypothesis::Probability
        ]
    );
    let congested_affine = vec![block(
        q(0, 1),
        q(1, 1),
        q(1, 1),
        BlockVelocity::Affine(q(0, 1), q(1, 1)),
    )];
    assert_eq!(
        check_blocks(&congested_affine).failures()[0].hypothesis,
        Hypothesis::HypU0
    );
    assert!(check_sampling(&touching, 0).is_err());
}
