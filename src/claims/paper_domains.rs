//! The domains of the claims whose statement is narrower than "for all
//! `t ≥ 0`, every datum" ([`Domain::EVERY_T`]): each with the `\label`
//! whose text fixes it and those words. The registry attaches them; the
//! ledger's shrinker accepts only witnesses inside them.

use super::domain::{Datum, Domain, InTime, InW, TestFunctions};

/// `thm:main`: "Let N > 1, and consider N particles of identical radius
/// r > 0 such that 2r = 1/N"; section 2 opens with "N > 1 solid
/// particles". Every time, `N ≥ 2`.
pub const SECTION2_EVERY_T: Domain = Domain {
    label: "thm:main",
    text: "Let N > 1, and consider N particles of identical radius r > 0 … (section 2: \"N > 1 solid particles\"); lem:incl-HSN: \"for all t ≥ 0\"",
    time: InTime::Every,
    min_n: 2,
    test_functions: TestFunctions::None,
    w: InW::None,
    datum: Datum::InC,
};

/// `prop:proj-micro`: "x is Lipschitz continuous and therefore
/// differentiable for almost every t ≥ 0. Denoting u(t) := ẋ(t), one has
/// u(t) ∈ H for a.e. t ≥ 0"; `prop:proj-velo-micro`: "for almost all
/// t ≥ 0, we can define u(t) = ẋ(t)": statements about `u(t)`, `λ(t)` or
/// a derivative in `t`, with `N > 1`.
pub const SECTION2_AE_T: Domain = Domain {
    label: "prop:proj-micro",
    text: "x is Lipschitz continuous and therefore differentiable for almost every t ≥ 0. Denoting u(t) := ẋ(t), one has u(t) ∈ H^N_{x(t)} for a.e. t ≥ 0 (and N > 1, thm:main)",
    time: InTime::AlmostEvery,
    min_n: 2,
    test_functions: TestFunctions::None,
    w: InW::None,
    datum: Datum::InC,
};

/// `eq:PDE-Lagr-N-1` and the estimates of section 3: "The interpolated
/// quantities satisfy the following system in the sense of distributions
/// on (0,T)×(0,1)", for the sampled data of `thm:main` (`N ≥ 2`,
/// `u⁰ ∈ H_{x⁰}` by `hyp:u0`): a.e. `(t, w)`.
pub const SECTION3_AE_TW: Domain = Domain {
    label: "eq:PDE-Lagr-N-1",
    text: "The interpolated quantities satisfy the following system in the sense of distributions on (0,T)×(0,1) (for a given integer N ≥ 2, x⁰_i := X⁰(i/N); hyp:u0: ∂_x u⁰ = 0 in {ρ⁰ = 1})",
    time: InTime::AlmostEvery,
    min_n: 2,
    test_functions: TestFunctions::None,
    w: InW::AlmostEvery,
    datum: Datum::InH,
};

/// `lem:discPDE2`, `prop:pressure-bound`: the pressure `P_N = ∂_t Λ_N` is
/// a measure in `t` (Dirac masses at the collision instants), with `N ≥ 2`
/// and sampled data.
pub const SECTION3_PRESSURE: Domain = Domain {
    label: "prop:pressure-bound",
    text: "The interpolated pressure P̃_N satisfies the uniform estimate ‖P̃_N‖_{M(0,T; L¹(0,1))} ≤ C (a measure in t; N ≥ 2, x⁰_i := X⁰(i/N), hyp:u0)",
    time: InTime::Measure,
    min_n: 2,
    test_functions: TestFunctions::None,
    w: InW::None,
    datum: Datum::InH,
};

/// `prop:pressure-bound` (proof): "We test Equation eq:PDE-Lagr-N-2
/// against the test function φ(t,w) = ((x_N(t) − x_0(t))w − X̃_N(t,w)) ϕ(t),
/// ϕ ∈ C¹_c((0,T)), ϕ ≥ 0. Observe that at the boundaries φ(t,0) = φ(t,1)
/// = 0": every `t` where `ϕ(t) > 0`, so `t > 0`.
pub const PRESSURE_TEST_FUNCTION: Domain = Domain {
    label: "prop:pressure-bound",
    text: "We test Equation eq:PDE-Lagr-N-2 against the test function φ(t,w) = ((x_N(t) − x_0(t))w − X̃_N(t,w)) ϕ(t), ϕ ∈ C¹_c((0,T)), ϕ ≥ 0. Observe that at the boundaries φ(t,0) = φ(t,1) = 0 (N ≥ 2, hyp:u0)",
    time: InTime::Positive,
    min_n: 2,
    test_functions: TestFunctions::SmoothInTime,
    w: InW::None,
    datum: Datum::InH,
};

/// `prop:pressure-bound` (proof), the identity after testing: an integral
/// in `t` against `ϕ ∈ C¹_c((0,T))`.
pub const PRESSURE_IDENTITY: Domain = Domain {
    label: "eq:test-pressure-bound",
    text: "φ(t,w) = ((x_N(t) − x_0(t))w − X̃_N(t,w)) ϕ(t), ϕ ∈ C¹_c((0,T)), ϕ ≥ 0 (the identity is an integral in t; N ≥ 2, hyp:u0)",
    time: InTime::Measure,
    min_n: 2,
    test_functions: TestFunctions::SmoothInTime,
    w: InW::None,
    datum: Datum::InH,
};

/// `prop:2ndorder-LagrPDE` (proof): "Now, for Ψ ∈ C¹_c((0,T)×(0,1)), we
/// have 0 = ⟨P̃_N, (∂_w X̃_N − 1)Ψ⟩".
pub const EXCLUSION_PAIRING: Domain = Domain {
    label: "prop:2ndorder-LagrPDE",
    text: "Now, for Ψ ∈ C¹_c((0,T)×(0,1)), we have 0 = ⟨P̃_N, (∂_w X̃_N − 1)Ψ⟩ (N ≥ 2, hyp:u0)",
    time: InTime::Measure,
    min_n: 2,
    test_functions: TestFunctions::SmoothCompact,
    w: InW::AlmostEvery,
    datum: Datum::InH,
};

/// `app:uniqueness`: `P¹` solves `eq:PDE-Lagr-2` (`P ≥ 0` in `D'`): a
/// measure, tested against non-negative `C¹_c` functions.
pub const APPENDIX_C_PRESSURE: Domain = Domain {
    label: "eq:PDE-Lagr-2",
    text: "∂_t U + ∂_w P = 0 in D', … P ≥ 0 in D' (P¹ = [w 1_{[0,1/2)} − (1 − w) 1_{[1/2,1]}] δ_{t=t*}, tested against non-negative Ψ ∈ C¹_c)",
    time: InTime::Measure,
    min_n: 1,
    test_functions: TestFunctions::SmoothCompact,
    w: InW::AlmostEvery,
    datum: Datum::InC,
};

/// `thm:main` (§2.1): the sampled datum `u⁰_i = U⁰(i/N)` of an `L²` class
/// `U⁰`: a pointwise value is a choice of representative, so the ledger
/// checks both one-sided readings.
pub const SAMPLING: Domain = Domain {
    label: "thm:main",
    text: "For a given integer N ≥ 2 … x⁰_i := X⁰(i/N) … u⁰_i = U⁰(i/N) (U⁰ ∈ L², hyp:u0: ∂_x u⁰ = 0 in {ρ⁰ = 1})",
    time: InTime::None,
    min_n: 2,
    test_functions: TestFunctions::None,
    w: InW::AlmostEvery,
    datum: Datum::InH,
};
