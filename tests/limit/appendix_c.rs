//! Appendix C: the ledger checks and the appendix as printed.

use super::*;

#[test]
fn appendix_c_ledger_checks() {
    projection_selects_sticky().unwrap();
    sticky_is_particle_limit().unwrap();
    sticky_pressure_is_continuum().unwrap();
}

/// The printed formulas, claim by claim, for several η.
#[test]
fn appendix_c_as_printed() {
    for eta in [q(1, 4), q(1, 2), q(3, 4), q(1, 1), q(3, 2)] {
        let f = all_findings(&eta).unwrap();
        let status = |c: Continuation, p: Printing, claim: &str| {
            f.iter()
                .find(|x| x.continuation == c && x.printing == p && x.claim == claim)
                .unwrap()
                .holds
        };
        use Continuation::{Rebound, Sticky};
        use Printing::{AsPrinted, Corrected};
        // P¹ as printed: wrong slope and sign on [1/2, 1] (and a jump at 1/2).
        assert!(!status(
            Sticky,
            AsPrinted,
            "eq:PDE-Lagr-2 (∂_t U + ∂_w P = 0)"
        ));
        assert!(!status(Sticky, AsPrinted, "eq:PDE-Lagr-2 (P ≥ 0)"));
        assert!(status(Sticky, AsPrinted, "eq:velocity-projection"));
        // Corrected P¹: everything holds.
        assert!(f
            .iter()
            .filter(|x| x.continuation == Sticky && x.printing == Corrected)
            .all(|x| x.holds));
        // The rebound solves eq:PDE-Lagr-2 with P ≥ 0 and complementarity …
        for claim in [
            "eq:PDE-Lagr-2 (∂_t X = U)",
            "eq:PDE-Lagr-2 (∂_t U + ∂_w P = 0)",
            "eq:PDE-Lagr-2 (∂_w X ≥ 1)",
            "eq:PDE-Lagr-2 (P ≥ 0)",
            "eq:PDE-Lagr-2 ((∂_w X − 1) P = 0)",
        ] {
            assert!(status(Rebound, AsPrinted, claim), "{claim}");
        }
        // … and Oleinik exactly when η < 1, as the appendix says …
        assert_eq!(
            status(Rebound, AsPrinted, "eq:Oleinik-Lagr"),
            eta < q(1, 1),
            "η = {eta}"
        );
        // … but not the projection principle nor the first-order system.
        assert!(!status(Rebound, AsPrinted, "eq:velocity-projection"));
        assert!(!status(Rebound, AsPrinted, "eq:Lagr-1"));
        assert!(!status(
            Rebound,
            AsPrinted,
            "eq:Lagr-1 (X(t) = P_K(X⁰ + tU⁰))"
        ));
    }
    assert!(TwoBlocks::new(q(0, 1)).is_err());
    // The particle distances: ‖X_N − X¹‖ → 0, ‖X_N − X²‖ → (t − t*)/√3.
    let tb = TwoBlocks::new(q(1, 2)).unwrap();
    let d = tb.particle_distances(&[8, 64, 512], &q(2, 1)).unwrap();
    for (n, d1, d2) in d {
        let nn = Q::from_integer(n.into());
        assert_eq!(d1, (q(3, 1) * &nn * &nn).recip());
        let limit = q(7, 4) * q(7, 4) / q(3, 1);
        assert!((d2 - limit).abs() < nn.recip());
    }
}
