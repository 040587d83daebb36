//! The list of claims: every statement of the paper a computer can test, and
//! the steps of their proofs, each with the paper's words (LaTeX simplified)
//! and its checker. Statuses are never written here: the ledger computes
//! them. A `correction` is attached to a claim once it has been found false
//! as printed; the corrected statement is then what the test engines require.

use super::{always, continuum, discrete, micro, paper_radius, sampling, scaling};
use super::{Claim, Correction, Kind};
use crate::limit::appendix_c;
use crate::scalar::Scalar;

/// What every scaling claim runs on (see [`super::macro_data`]).
macro_rules! run_on {
    () => {
        " (run exactly on 18 macroscopic data — the shipped scenes appendix-c-two-blocks and riemann-compression and 16 random [macro] data admissible under hyp:u0 (generate::macro_datum, fixed seed), T = 1 — at N = 4, 8, …, 4096 (ledger budget), histories by the integer event merge; sup_t over t = 0, T/4, T/2, 3T/4, T; the verdict compares the late values with the early ones, see claims::scaling)."
    };
}

const S2: &str = "§2 microscopic dynamics";
const S3: &str = "§3 hydrodynamic limit (discrete form)";
const APPA: &str = "Appendix A (KKT)";
const APPC: &str = "Appendix C (uniqueness)";

/// Every claim, in the order of the paper.
pub fn registry<S: Scalar>() -> Vec<Claim<S>> {
    let case = |id, section, statement, check: super::CaseCheck<S>| Claim {
        id,
        section,
        statement,
        kind: Kind::Case(check),
        applies: always::<S>,
        correction: None,
    };
    let s3 = |id, statement, check: super::CaseCheck<S>| Claim {
        id,
        section: S3,
        statement,
        kind: Kind::Case(check),
        applies: paper_radius::<S>,
        correction: None,
    };
    let fixed = |id, section, statement, check: fn() -> Result<(), super::Violation>| Claim {
        id,
        section,
        statement,
        kind: Kind::Formula(check),
        applies: always::<S>,
        correction: None,
    };
    let scal = |id, section, statement, check: scaling::ScalingCheck| Claim {
        id,
        section,
        statement,
        kind: Kind::Scaling(check),
        applies: always::<S>,
        correction: None,
    };
    let corrected = |mut c: Claim<S>, statement, check: Kind<S>, conclusion| {
        c.correction = Some(Correction {
            statement,
            check,
            conclusion,
        });
        c
    };
    vec![
        fixed("thm:main#sampling-mass", "§2.1 discretisation", "\"By construction, one has ∫_{x_i^0}^{x_{i+1}^0} ρ^0(x) dx = 1/N. Since ρ^0 ≤ 1, it follows that x_{i+1}^0 − x_i^0 ≥ 1/N\" (quantile sampling x⁰_i = X⁰(i/N); shipped macro scenes, N = 2 … 256, and 300 random macro data under hyp:u0, N = 2 … 16, 32, 64).", sampling::mass_between),
        corrected(
            fixed("thm:main#sampling-contacts", "§2.1 discretisation", "\"if two particles are in contact then they have the same velocity\": from ∂_w U⁰ = 0 a.e. in (i/N, (i+1)/N), \"u⁰_{i+1} = U⁰((i+1)/N) = U⁰(i/N) = u⁰_i\" (u⁰_i = U⁰(i/N), under hyp:u0; shipped macro scenes, N = 2 … 256, and 300 random macro data, N = 2 … 16, 32, 64).", sampling::contacts_equal_velocities),
            "U⁰ is constant on (i/N, (i+1)/N) when particles i and i+1 touch, so the velocities sampled from inside that interval, U⁰(i/N+) and U⁰((i+1)/N−), are equal; U⁰ itself may jump at the end points i/N, (i+1)/N (a velocity jump on the boundary of a congested block is allowed by hyp:u0), and there the printed step \"∂_w U⁰ = 0 a.e. ⇒ U⁰((i+1)/N) = U⁰(i/N)\" does not follow.",
            Kind::Formula(sampling::contacts_equal_velocities_inside),
            "The theorem survives: U⁰ is an L² class, and sampling it with the representative that takes the congested side's value at the ends of a congested stretch (which changes u⁰_N only at particles sampled exactly on a block boundary, at most one per boundary, so U⁰_N → U⁰ is unaffected) gives admissible data u⁰_N ∈ C_{x⁰_N}; as printed, u⁰_i = U⁰(i/N) can put two touching particles on a collision course at t = 0 (u⁰_N ∉ C_{x⁰_N}, and sticky refuses such a [macro] scene).",
        ),
        case("df:KN", S2, "K^N = {x ∈ R^N ; x_{i+1} − x_i ≥ 2r}: the trajectory stays admissible, x(t) ∈ K^N for all t ≥ 0.", micro::admissible),
        corrected(
            case("df:H-micro#contacts-grow", S2, "\"the set of active constraints is non-decreasing in time … N_{x(s)}K^N ⊂ N_{x(t)}K^N for all s ≤ t\" (for x⁰ ∈ K^N, u⁰ ∈ C^N_{x⁰}).", micro::contacts_grow_printed),
            "Ω_{x(s)} ⊂ Ω_{x(t)} for 0 < s ≤ t, and from s = 0 when u⁰ ∈ H_{x⁰} (two particles touching at t = 0 with u⁰_{i+1} > u⁰_i separate at once).",
            Kind::Case(micro::contacts_grow_corrected),
            "Holds: the paper's main theorem assumes u⁰_{i+1} = u⁰_i on contacts (u⁰ ∈ H_{x⁰}), where the printed statement is true; only data in C_{x⁰} \\ H_{x⁰}, allowed by prop:proj-micro, break it at s = 0.",
        ),
        case("prop:proj-micro", S2, "\"there exists a unique solution x to (eq:micro-f0-lagr). It is given by the projection formula x(t) = P_{K^N}(x_0 + t u_0)\" — the event-driven sticky history equals the projection, exactly (positions, right-derivative velocities, multipliers, contact clusters).", micro::proj_micro),
        case("prop:proj-micro#u-in-H", S2, "\"u(t) ∈ H^N_{x(t)} for a.e. t ≥ 0\" (checked at every probe time t > 0, right derivatives).", micro::u_in_h),
        case("eq:proj-micro-u", S2, "u(t) = P_{H^N_{x(t)}}(u_0) (checked at every probe time t > 0, right derivatives).", micro::u_projection),
        case("eq:dyn-micro", S2, "u(t) = u_0 − N Σ_{i=1}^{N−1} λ_i(t)(e_i − e_{i+1}), λ_0(t) = λ_N(t) = 0, λ_i ≥ 0, and λ_i(t)(x_{i+1}(t) − x_i(t) − 2r) = 0.", micro::dyn_micro),
        case("prop:proj-micro#orthogonality", S2, "(proof of prop:proj-micro) ⟨u(t) − u⁰, x̃(t)⟩ = Σ_i (u_i(t) − u⁰_i) x̃_i(t) = 0.", micro::orthogonality),
        case("lem:incl-HSN", S2, "H^N_{x(t)} ⊂ T_{x(t)}K^N ∩ [x⁰ + t u⁰ − x(t)]^⊥ for all t ≥ 0.", micro::incl_hsn),
        corrected(
            case("lem:incl-HSN#proof-second-inclusion", S2, "\"Let us now show the second inclusion H^N_{x̃(t)} ⊂ [x⁰ + t u⁰]^⊥.\"", micro::incl_hsn_printed),
            "H^N_{x(t)} ⊂ [x⁰ + t u⁰ − x(t)]^⊥ (the lemma's own statement; the proof then shows exactly this).",
            Kind::Case(micro::incl_hsn),
            "Holds: a typo (− x(t) dropped); the proof's computation is for x⁰ + t u⁰ − x(t).",
        ),
        case("prop:proj-velo-micro#step1", S2, "Step 1: ⟨u⁰ − u(t), u(t)⟩ ≥ 0.", micro::velo_step1),
        corrected(
            case("eq:w-Hs-perp", S2, "\"We also know by the previous lemma that ⟨x⁰ + t u⁰, w⟩ = 0\" for w ∈ H^N_{x(t)}.", micro::w_hs_perp),
            "⟨x⁰ + t u⁰ − x(t), w⟩ = 0 for w ∈ H^N_{x(t)} (lem:incl-HSN).",
            Kind::Case(micro::incl_hsn),
            "Holds: Step 2 uses the identity only through ⟨x⁰ + t u⁰ − x(t), ·⟩, whose vanishing on H is lem:incl-HSN.",
        ),
        case("eq:ineg-projortho", S2, "⟨u⁰ − u(t), y(t) − x(t)⟩ ≤ 0 for all y ∈ K^N (checked exactly on the generators of the tangent cone T_{x(t)}K^N).", micro::ineg_projortho),
        corrected(
            case("eq:proj-u-micro", S2, "Writing Ω^N_{x(t)} = ∪_k J_k(t), J_k = ⟦j_k, j_k + L_k⟧: u_i(t) = u⁰_i if i ∉ Ω^N_{x(t)}, and u_i(t) = (1/L_k) Σ_{l=1}^{L_k} u⁰_{j_k+l} if i ∈ J_k (read literally: J_k are runs of contact indices, i a particle index).", micro::proj_u_micro_literal),
            "u_i(t) = (1/|C|) Σ_{j ∈ C} u⁰_j where C is the contact cluster of particle i (a run of contacts ⟦j_k, j_k + L_k⟧ joins the L_k + 2 particles j_k … j_k + L_k + 1).",
            Kind::Case(micro::u_projection),
            "Holds: the lemma's first sentence (u(t) is the orthogonal projection of u⁰ onto H) is right; only the explicit index formula is off (0/0 for a single contact, a particle left out of the mean).",
        ),
        corrected(
            case("prop:bound-micro#position-contraction", S2, "\"From the projection formula we obtain ‖x(t)‖ ≤ ‖x⁰ + t u⁰‖\" (contraction of P_{K^N}).", micro::position_contraction),
            "P_{K^N} is non-expansive, not a contraction towards 0 (0 ∉ K^N for N ≥ 2): ‖x(t) − P_K(0)‖ ≤ ‖x⁰ + t u⁰ − P_K(0)‖, with ‖P_K(0)‖² = (2r)²(N² − 1)/12, so ‖x(t)‖ ≤ ‖x⁰‖ + T‖u⁰‖ + 2r√((N²−1)/12).",
            Kind::Case(micro::position_nonexpansive),
            "Holds: with 2r = 1/N the extra term is ≤ 1/√12, independent of N, so the bound of prop:bound-micro stands with C(T, ‖x⁰‖, ‖u⁰‖) + 1/√12.",
        ),
        case("prop:bound-micro#velocity-bound", S2, "‖u(t)‖ ≤ ‖u⁰‖.", micro::velocity_bound),
        corrected(
            case("prop:bound-micro#multiplier-relation", S2, "\"using the relation N(λ_i(t) − λ_{i−1}(t)) = u_i(t) − u⁰_i\" (proofs of prop:bound-micro and prop:Linf-micro).", micro::multiplier_relation_printed),
            "N(λ_i(t) − λ_{i−1}(t)) = u⁰_i − u_i(t) (the sign of eq:dyn-micro).",
            Kind::Case(micro::multiplier_relation_corrected),
            "Holds: only absolute values of the relation are used afterwards.",
        ),
        case("prop:bound-micro#delta-lambda", S2, "‖ΔL(t)‖² = Σ_i (1/N)(λ_i − λ_{i−1})² = Σ_i (1/N³)(u_i(t) − u⁰_i)² ≤ (4/N²)‖u⁰‖².", micro::delta_lambda),
        case("prop:bound-micro#lambda-cauchy-schwarz", S2, "|λ_i(t)| ≤ N‖ΔL(t)‖ and ‖L(t)‖² ≤ N²‖ΔL(t)‖² ≤ 4‖u⁰‖².", micro::lambda_cs),
        case("eq:sup-micro-u-L#velocity-and-increments", S2, "sup_t [sup_i |u_i(t)| + sup_i |N(λ_i(t) − λ_{i−1}(t))|] ≤ C' (for fixed N: sup|u| ≤ sup|u⁰| and sup|NΔλ| ≤ 2 sup|u⁰|).", micro::sup_u_and_increments),
        corrected(
            scal("eq:sup-micro-u-L#N-lambda", S2, concat!("sup_{t ∈ [0,T]} sup_i N|λ_i(t)| ≤ C' for some C' independent of N (under sup_i |u⁰_i| ≤ C'_0).", run_on!()), scaling::n_lambda),
            "sup_{t ∈ [0,T]} sup_i |λ_i(t)| ≤ 2 sup_i |u⁰_i| (λ_i = (1/N) Σ_{j ≤ i}(u⁰_j − u_j)), independent of N; N|λ_i| itself can grow like N.",
            Kind::Scaling(scaling::lambda_sup),
            "Holds for what is used later: prop:Linf-micro and eq:diffLambda_N need |λ_i| ≤ C' and |λ_i − λ_{i−1}| ≤ C'/N, both true; the factor N on λ_i is too much.",
        ),
        case("prop:Oleinik", S2, "(u_i(t) − u_{i−1}(t))/(x_i(t) − x_{i−1}(t)) < 1/t for all t > 0 (i = 2 … N).", micro::oleinik),
        case("prop:Oleinik#backward-characteristics", S2, "If i − 1 and i are not in contact at t: x_ℓ = x_{i−1}(t) − t u_{i−1}(t) ≤ x_{i−1}(0) and x_r = x_i(t) − t u_i(t) ≥ x_i(0).", micro::oleinik_characteristics),
        case("eq:semigroup", S2, "x(t) = P_{K^N}(x(s) + (t − s)u(s)) for 0 ≤ s < t.", micro::semigroup),
        case("eq:projortho-sg", S2, "u(t) = P_{H^N_{x(t)}}(u(s)) for 0 ≤ s < t.", micro::projortho_sg),
        case("prop:micro-pressure", S2, "p_i = dλ_i/dt satisfies (x_{i+1} − x_i − 2r)p_i = 0 and p_i ≥ 0: λ_i jumps only at collisions of the pair (i, i+1), by a non-negative amount, and λ(t) is the sum of its jumps.", micro::micro_pressure),
        corrected(
            case("prop:proj-micro#uniqueness-identity", S2, "For two solutions with the same u⁰: (N²/2) d/dt ‖x¹ − x²‖² = −⟨ξ¹ − ξ², x¹ − x²⟩.", micro::uniqueness_identity_printed),
            "(N/2) d/dt ‖x¹ − x²‖² = −⟨ξ¹ − ξ², x¹ − x²⟩ ≤ 0 (‖·‖² = (1/N)⟨·,·⟩).",
            Kind::Case(micro::uniqueness_identity_corrected),
            "Holds: only the sign of the derivative is used; uniqueness follows.",
        ),
        corrected(
            case("app:KKT", APPA, "The KKT conditions \"yield the existence of multipliers λ_i(t) ≥ 0 such that x(t) − (x⁰ + t u⁰) + N Σ λ_i(t)(e_i − e_{i+1}) = 0, λ_i(t)(x_{i+1} − x_i − 2r) = 0. This provides directly the multipliers and the Signorini condition introduced in the main text.\"", micro::kkt_printed),
            "The KKT multipliers μ(t) of the position projection satisfy x(t) − (x⁰ + t u⁰) + N Σ μ_i(t)(e_i − e_{i+1}) = 0, μ ≥ 0, μ_i(x_{i+1} − x_i − 2r) = 0, and μ(t) = ∫_0^t λ(s) ds: they are the time integral of the main text's λ, not λ.",
            Kind::Case(micro::kkt_corrected),
            "Holds: Appendix A gives existence of (other) multipliers; the main text's λ are obtained from the velocity projection, as the paper itself does in prop:proj-micro.",
        ),
        {
            let mut c = s3("eq:PDE-Lagr-N-1", "∂_t X_N = U⁰_N − ∂_w Λ̃_N, ∂_w X̃_N ≥ 1, Λ_N ≥ 0 (with 2r = 1/N and the artificial particle x_0 = x_1 − 1/N − δ).", discrete::lagr_n1);
            c.applies = paper_radius::<S>;
            c
        },
        corrected(
            s3("eq:PDE-Lagr-N-1#complementarity", "(∂_w X̃_N − 1) Λ_N = 0: on ((i−1)/N, i/N], (N(x_i − x_{i−1}) − 1) λ_i = 0.", discrete::lagr_n1_printed),
            "(∂_w X̃_N(t, w + 1/N) − 1) Λ_N(t, w) = 0, i.e. (N(x_{i+1} − x_i) − 1) λ_i = 0: λ_i is carried by the pair (i, i+1), whose slope lives on the next interval (equivalently, define Λ_N = λ_{i−1} on ((i−1)/N, i/N]).",
            Kind::Case(discrete::lagr_n1_corrected),
            "Holds after the index shift: Λ_N and its shifted version differ by at most sup|λ_i − λ_{i−1}| ≤ C'/N (eq:diffLambda_N), so the limit (∂_w X − 1)Λ = 0 of prop:cvg1 is unaffected.",
        ),
        corrected(
            s3("lem:discPDE2#exclusion", "(∂_w X̃_N − 1) P_N = 0, P_N ≥ 0 (P_N = ∂_t Λ_N, piecewise constant in w).", discrete::disc_pde2_printed),
            "(∂_w X̃_N(t, w + 1/N) − 1) P_N(t, w) = 0, i.e. the jump of λ_i occurs with N(x_{i+1} − x_i) = 1 (prop:micro-pressure).",
            Kind::Case(micro::micro_pressure),
            "Holds after the same index shift as eq:PDE-Lagr-N-1.",
        ),
        corrected(
            s3("prop:pressure-bound#exclusion", "(proof) \"Since (∂_w X̃_N − 1) P̃_N = 0, we may replace ∂_w X̃_N by 1 on the support of P̃_N\" (P̃_N piecewise affine).", discrete::pressure_bound_exclusion_printed),
            "P̃_N on [(i−1)/N, i/N] interpolates p_{i−1} and p_i, carried by the pairs (i−1, i) and (i, i+1); the product vanishes only for the index-shifted interpolation (prop:micro-pressure).",
            Kind::Case(micro::micro_pressure),
            "Open: the bound ∫∫ P̃_N ≤ C/δ is measured separately (prop:pressure-bound, across N); the step as written needs the index shift and a control of the boundary terms it creates.",
        ),
        s3("prop:pressure-bound#gap-delta", "(x_N(t) − x_0(t)) − 1 ≥ 2r(N − 1) + (2r + δ) − 1 = δ.", discrete::gap_delta),
        s3("prop:cvg1#XN-L1", "∫_0^1 |X̃_N(t,w) − X_N(t,w)| dw = (1/2N) Σ_{i=0}^{N−1} (x_{i+1}(t) − x_i(t)) = (1/2N)(x_N(t) − x_0(t)).", discrete::xn_l1),
        corrected(
            s3("eq:diffLambda_N", "For w ∈ ((i−1)/N, i/N]: |Λ̃_N(t,w) − Λ_N(t,w)| = |N(λ_i(t) − λ_{i−1}(t))(w − (i−1)/N)| ≤ |λ_i(t) − λ_{i−1}(t)| ≤ C'/N.", discrete::diff_lambda_printed),
            "|Λ̃_N − Λ_N| = |λ_i − λ_{i−1}| · |1 − N(w − (i−1)/N)| ≤ |λ_i − λ_{i−1}| ≤ 2 sup|u⁰|/N.",
            Kind::Case(discrete::diff_lambda_corrected),
            "Holds: the bound, which is all that is used, is right.",
        ),
        corrected(
            s3("prop:2ndorder-LagrPDE#UN-L1", "∫_0^1 |Ũ_N(t,w) − U_N(t,w)| dw = (1/2N) Σ_{i=1}^N |u_i(t) − u_{i−1}(t)| = (1/2N)|u_N(t) − u_0(t)| ≤ C/N.", discrete::un_l1_printed),
            "(1/2N) Σ |u_i − u_{i−1}| ≤ TV(u⁰)/(2N): the total variation of u(t) never exceeds that of u⁰ (cluster means create no variation); TV(u⁰) is bounded when U⁰ ∈ BV.",
            Kind::Case(discrete::un_l1_corrected),
            "Holds if U⁰ has bounded variation (or for t ≥ α by pwUN-L1); the second equality is true only for monotone u.",
        ),
        s3("eq:Oleinik-tUN", "∂_w Ũ_N < ∂_w X̃_N / t: t(u_i − u_{i−1}) < x_i − x_{i−1}, i = 1 … N (artificial particle included), t > 0.", discrete::oleinik_tun),
        s3("pwUN-L1", "(proof) ‖∂_w Ũ_N(t)‖_{L¹} ≤ (2/t)(x_N(t) − x_0(t)) − (Ũ_N(t,1) − Ũ_N(t,0)).", discrete::pw_un_l1),
        s3("eq:BV_XN", "(proof) ∫_0^1 |∂_w X̃_N(t,w)| dw = x_N(t) − x_0(t) ≤ (x_N(0) − x_0(0)) + T(sup_{[0,T]}|u_N| + sup_{[0,T]}|u_1|).", discrete::bv_xn),
        // -- scaling claims across N on random macroscopic data (issue 14, macro) --
        scal("prop:pressure-bound", S3, concat!("‖P̃_N‖_{M(0,T; L¹(0,1))} ≤ C with C independent of N: the total variation Σ_{t_k ≤ T} (1/N) Σ_i |[λ_i]_{t_k}| of the pressure measure (sign-aware: a negative jump, P̃_N ≱ 0, is reported)", run_on!()), scaling::pressure_mass),
        scal("prop:L2-micro", S3, concat!("‖X_N‖ + ‖∂_t X_N‖ + ‖Λ_N‖ in L^∞(0,T; L²(0,1)) ≤ C independent of N", run_on!()), scaling::l2_bounds),
        scal("pwUN-L1#independent-of-N", S3, concat!("sup_{t ∈ [α,T]} ‖∂_w Ũ_N(t)‖_{L¹(0,1)} ≤ C_α independent of N (α = T/2; only the data on which it is not 0 count, the ledger note gives their number: the two shipped scenes are one cluster by T/2)", run_on!()), scaling::tv_u),
        scal("eq:bound-UN-Linf", S3, concat!("\"‖U_N‖_{L^∞((0,T)×(0,1))} + ‖Ũ_N‖_{L^∞((0,T)×(0,1))} ≤ C\" (= 2 sup_t max_i |u_i(t)|)", run_on!()), scaling::bound_un_linf),
        scal("thm:main#discretisation", "§2.1 discretisation", concat!("(i) \"X⁰_N → X⁰ strongly in L²(0,1)\" for the quantile sampling x⁰_i = X⁰(i/N) (MacroDatum::quantiles), ‖X⁰_N − X⁰‖²_{L²} exact against X⁰ as the continuum profile at t = 0", run_on!()), scaling::discretisation),
        scal("thm:main#discretisation-U", "§2.1 discretisation", concat!("(i) \"U⁰_N → U⁰ strongly in L²(0,1)\" for the printed sampling u⁰_i = U⁰(i/N) (MacroDatum::quantiles), ‖U⁰_N − U⁰‖²_{L²} exact against U⁰ as the continuum profile at t = 0", run_on!()), scaling::discretisation_u),
        corrected(
            scal("prop:cvg1", S3, concat!("\"there exists X ∈ W^{1,∞}((0,T)×(0,1)) … such that, up to the extraction of a subsequence, X̃_N → X strongly in C([0,T]×[0,1])\" (the first-order limit is unique, so the whole sequence is measured; here at t = 0: sup_{w ∈ [1/N,1]} |X̃_N(0,w) − X⁰(w)|, exact)", run_on!()), scaling::cvg1_uniform),
            "X̃_N, X_N → X strongly in C([0,T]; L¹(0,1)) and Λ_N ⇀* Λ: measured as sup_t ‖X_N(t) − X(t)‖²_{L²} → 0 and max_φ |∫_0^1 (Λ_N(t) − Λ(t))φ| → 0 for φ ∈ {1, w}, at t = T/4, T/2, 3T/4, T, against the exact continuum solution (data whose continuum profile is rational at those times), on the same data and N. X(t,·) jumps wherever ρ(t) has vacuum inside its support (X⁰ jumps by the width of a gap between blocks, and X̃_N(0,·) is continuous), so the uniform convergence and X ∈ W^{1,∞} hold only without vacuum.",
            Kind::Scaling(scaling::cvg1_measured),
            "The theorem survives: the passage to the limit in eq:PDE-Lagr-N-1 uses the strong convergence in C([0,T]; L¹(0,1)) and the weak-* limits, not uniform convergence; X ∈ L^∞(0,T; BV(0,1)) with ∂_t X ∈ L^∞ instead of W^{1,∞}. Witness: appendix-c-two-blocks (gap η = 1/4 between two congested blocks): sup_w |X̃_N(0,w) − X⁰(w)| = 1/4 for every N = 4 … 4096.",
        ),
        fixed("eq:Lagr-1", S3, "\"∂_t X = U⁰ − ∂_w Λ, ∂_w X ≥ 1, (∂_w X − 1)Λ = 0, Λ ≥ 0 a.e., Λ(t,0) = Λ(t,1) = 0\" — checked exactly on the continuum solution X = P_K(X⁰ + tU⁰) (limit::continuum, ∂_t X its right derivative U) of the 18 macroscopic data of the scaling claims at t = T/4, T/2, 3T/4, T, on the profiles that are rational there (segment by segment: a quadratic Λ is ≥ 0 on an interval iff at its ends and vertex).", continuum::lagr1),
        fixed("eq:PDE-Lagr-2", S3, "\"∂_t U + ∂_w P = 0 in D', … P ≥ 0 in D'\" with P = ∂_t Λ — checked exactly between consecutive times t₀ < t₁ of {T/4, T/2, 3T/4, T} on the continuum solution of the same 18 data (rational profiles): Λ(t₁) − Λ(t₀) ≥ 0 on [0, 1] and U(t₁) − U(t₀) = −∂_w(Λ(t₁) − Λ(t₀)) on the common refinement.", continuum::pde_lagr2),
        fixed("eq:Oleinik-Lagr", S3, "\"∂_w U < ∂_w X / t in D'((0,T) × (0,1))\" — checked exactly on the continuum solution of the same 18 data at t = T/4 … T (rational profiles): strictly, t ∂_w U < ∂_w X, on every affine piece, and t [U] ≤ [X] at every jump (equality happens: a velocity jump upwards between touching blocks opens a vacuum with [X] = t[U]).", continuum::oleinik_lagr),
        // -- end of the scaling block --
        fixed("app:uniqueness#free-collision", APPC, "The collision occurs at t* = η/2, at which point X^f(t*, w) = w + η/2.", appendix_c::free_collision),
        corrected(
            fixed("app:uniqueness#sticky-pressure", APPC, "P¹(t,w) = [w 1_{[0,1/2)}(w) − (1 − w) 1_{[1/2,1]}(w)] δ_{t=t*}, with U¹ = 0, X¹ = w + η/2 for t ≥ t*, solves eq:PDE-Lagr-2 (∂_t U + ∂_w P = 0, P ≥ 0).", appendix_c::sticky_pressure_printed),
            "P¹ = [w 1_{[0,1/2)} + (1 − w) 1_{[1/2,1]}] δ_{t=t*} (≥ 0, continuous, vanishing at w = 0, 1); it is exactly the limit of the particles: the jump of λ_i at t* is P¹(i/N).",
            Kind::Formula(appendix_c::sticky_pressure_corrected),
            "Holds: the sticky continuation is a solution with the corrected pressure; the non-uniqueness argument is unaffected.",
        ),
        fixed("app:uniqueness#rebound-pressure", APPC, "U²(t,w) = 2w − 1, X² = (w + η/2) + (t − t*)U², P² = [(2w − w²) 1_{[0,1/2)} − (w² − 1) 1_{[1/2,1]}] δ_{t=t*} solves eq:PDE-Lagr-2.", appendix_c::rebound_pressure),
        fixed("app:uniqueness#projection-selects-sticky", APPC, "\"A natural way to restore uniqueness is to supplement eq:PDE-Lagr-2 with a projection principle on the velocity … U(t) = P_{H_{X(t)}}(U⁰)\" (eq:velocity-projection): of the two continuations only the sticky one satisfies it (and X = P_K(X⁰ + tU⁰)).", appendix_c::projection_selects_sticky),
        fixed("app:uniqueness#particle-limit", APPC, "The projection principle \"can be seen as the macroscopic counterpart of the sticky blocks dynamics\": the quantile-sampled particles converge to the sticky continuation (‖X_N − X¹‖² = 1/(3N²)) and not to the rebound (‖X_N − X²‖ → (t − t*)/√3).", appendix_c::sticky_is_particle_limit),
        fixed("app:uniqueness#sticky-pressure-is-continuum", APPC, "\"The pressure P is uniquely recovered from the momentum equation and the boundary condition\" P(t,0) = P(t,1) = 0: for the sticky continuation it is the jump at t* of the continuum multiplier Λ (∂_t X = U⁰ − ∂_w Λ), i.e. the corrected P¹.", appendix_c::sticky_pressure_is_continuum),
        fixed("app:uniqueness#rebound-oleinik", APPC, "∂_w U² = 2, ∂_w X²(t,w) = 1 + 2(t − t*), and for η < 1, ∂_w U² ≤ ∂_w X²/t for all t > t* (eq:Oleinik-Lagr).", appendix_c::rebound_oleinik),
        Claim {
            id: "lem:proj-characterization",
            section: S2,
            statement: "y = P_C(z) ⟺ z − y ∈ N_y C for closed convex C.",
            kind: Kind::NotCheckable("classical (omitted in the paper); for C = K^N it is exercised by eq:ineg-projortho and app:KKT (corrected), which check z − P_K(z) ∈ N_{P_K(z)}K^N exactly"),
            applies: always::<S>,
            correction: None,
        },
    ]
}
