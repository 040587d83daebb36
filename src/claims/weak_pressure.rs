//! `app:uniqueness#sticky-pressure` in the sense the paper states it:
//! "P ≥ 0" for a measure `P = P¹(w) δ_{t = t*}` means `⟨P, Ψ⟩ ≥ 0` for
//! every non-negative `Ψ ∈ C¹_c((0,T)×(0,1))`. A value of `P¹` at one point
//! (`w = 1/2`, a null set) says nothing; the pairing with a bump does.

use num_rational::BigRational;

use super::bump::Bump;
use super::Violation;
use crate::limit::appendix_c::{Continuation, Printing, TwoBlocks};
use crate::rational::render_exact;

/// `app:uniqueness#sticky-pressure`, as printed: `P¹ = [w 1_{[0,1/2)} −
/// (1 − w) 1_{[1/2,1]}] δ_{t = t*}` paired with `Ψ(t,w) = ϕ(t)ψ(w)`, `ψ`
/// the bump `((w − 1/2)(1 − w))²` on `[1/2, 1]` and `ϕ ≥ 0` any bump with
/// `ϕ(t*) > 0`: `⟨P¹, Ψ⟩ = ϕ(t*) ∫ P¹ψ dw` must be `≥ 0`.
pub fn sticky_pressure_printed() -> Result<(), Violation> {
    const ID: &str = "app:uniqueness#sticky-pressure";
    let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
    let tb = TwoBlocks::new(q(1, 4)).map_err(|e| Violation::new(ID, e.to_string()))?;
    let weight = tb.pressure_weight(Continuation::Sticky, Printing::AsPrinted);
    // The printed P¹ on [1/2, 1] is its `right` piece; ψ vanishes off it.
    let psi = Bump::new(q(1, 2), q(1, 1));
    let pairing = psi.integral_times(&weight.right);
    if pairing < q(0, 1) {
        let test = format!(
            "Ψ(t,w) = ϕ(t)ψ(w), ψ(w) = {}, ϕ ≥ 0 a bump in t with ϕ(t*) = 1 (t* = {})",
            psi.describe("w"),
            render_exact(&tb.t_star())
        );
        return Err(Violation::new(
            ID,
            format!(
                "P¹ as printed: ⟨P¹, Ψ⟩ = ∫ P¹ ψ dw = {} < 0 for {test} (P¹ = −(1 − w) < 0 on all of [1/2, 1), a set of positive measure): P ≥ 0 fails",
                render_exact(&pairing)
            ),
        )
        .test_function(test)
        .sides("⟨P¹, Ψ⟩", render_exact(&pairing), "0 (≤)", "0"));
    }
    Ok(())
}
