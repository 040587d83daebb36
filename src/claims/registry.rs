//! The list of claims: every statement of the paper a computer can test, and
//! the steps of their proofs, each with the paper's words (LaTeX simplified)
//! and its checker. Statuses are never written here: the ledger computes
//! them. A `correction` is attached to a claim once it has been found false
//! as printed; the corrected statement is then what the test engines require.

use super::domain::Domain;
use super::paper_domains as pd;
use super::{
    always, continuum, density, discrete, eulerian, inclusion, linf, micro, momentum, paper_radius,
    sampling, scaling, test_pressure,
};
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
        domain: Domain::EVERY_T,
        correction: None,
        identity: None,
    };
    let s3 = |id, statement, check: super::CaseCheck<S>| Claim {
        id,
        section: S3,
        statement,
        kind: Kind::Case(check),
        applies: paper_radius::<S>,
        domain: Domain::EVERY_T,
        correction: None,
        identity: None,
    };
    let fixed = |id, section, statement, check: fn() -> Result<(), super::Violation>| Claim {
        id,
        section,
        statement,
        kind: Kind::Formula(check),
        applies: always::<S>,
        domain: Domain::FIXED,
        correction: None,
        identity: None,
    };
    let scal = |id, section, statement, check: scaling::ScalingCheck| Claim {
        id,
        section,
        statement,
        kind: Kind::Scaling(check),
        applies: always::<S>,
        domain: Domain::FIXED,
        correction: None,
        identity: None,
    };
    let within = |mut c: Claim<S>, domain: Domain| {
        c.domain = domain;
        c
    };
    let identity = |mut c: Claim<S>, why| {
        c.identity = Some(why);
        c
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
        fixed("thm:main#sampling-mass", "§2.1 discretisation", "\"By construction, one has ∫_{x_i^0}^{x_{i+1}^0} ρ^0(x) dx = 1/N. Since ρ^0 ≤ 1, it follows that x_{i+1}^0 − x_i^0 ≥ 1/N\" (quantile sampling x⁰_i = X⁰(i/N); shipped macro scenes, N = 2, 4, …, 256, and 300 random macro data under hyp:u0, N = 2 … 16, 32, 64).", sampling::mass_between),
        corrected(
            within(fixed("thm:main#sampling-contacts", "§2.1 discretisation", "\"if two particles are in contact then they have the same velocity\": from ∂_w U⁰ = 0 a.e. in (i/N, (i+1)/N), \"u⁰_{i+1} = U⁰((i+1)/N) = U⁰(i/N) = u⁰_i\" (u⁰_i = U⁰(i/N), under hyp:u0; shipped macro scenes, N = 2, 4, …, 256, and 300 random macro data, N = 2 … 16, 32, 64).", sampling::contacts_equal_velocities), pd::SAMPLING),
            "U⁰ is constant on (i/N, (i+1)/N) when particles i and i+1 touch, so the velocities sampled from inside that interval, U⁰(i/N+) and U⁰((i+1)/N−), are equal; U⁰ itself may jump at the end points i/N, (i+1)/N (a velocity jump on the boundary of a congested block is allowed by hyp:u0), and there the printed step \"∂_w U⁰ = 0 a.e. ⇒ U⁰((i+1)/N) = U⁰(i/N)\" does not follow.",
            Kind::Formula(sampling::contacts_equal_velocities_inside),
            "The theorem survives: U⁰ is an L² class, and sampling it with the representative that takes the congested side's value at the ends of a congested stretch (which changes u⁰_N only at particles sampled exactly on a block boundary, at most one per boundary, so U⁰_N → U⁰ is unaffected) gives admissible data u⁰_N ∈ C_{x⁰_N}; as printed, u⁰_i = U⁰(i/N) can put two touching particles on a collision course at t = 0 (u⁰_N ∉ C_{x⁰_N}, and sticky refuses such a [macro] scene).",
        ),
        case("df:KN", S2, "K^N = {x ∈ R^N ; x_{i+1} − x_i ≥ 2r}: the trajectory stays admissible, x(t) ∈ K^N for all t ≥ 0.", micro::admissible),
        case("df:tKN", S2, "\"In these new coordinates [x̃ = (x_1, x_2 − 2r, …, x_N − 2r(N−1)), df:translat-x] the admissible configurations become K̃^N = {x̃ ∈ R^N; x̃_{i+1} − x̃_i ≥ 0, i = 1, …, N−1}, i.e. K̃^N is the cone of monotone (non-decreasing) vectors\" (checked pair by pair, y_{i+1} − y_i − 2r = ỹ_{i+1} − ỹ_i, so y ∈ K^N ⟺ ỹ ∈ K̃^N, and ỹ − x̃ = y − x, on x(t), the free flight x⁰ + t u⁰ and its projection, at every probe time).", micro::translated_cone),
        case("def:velcone#tangent-cone", S2, "\"For any configuration x ∈ K^N, it is not difficult to check that the admissible velocities coincide with the tangent cone to K_N at x: C_x^N = T_x K^N := … {θ(y − x); y ∈ K^N, θ ≥ 0}\" (… : the closure bar) (at x = x(t), every probe time, on the generators ±(1, …, 1), s_j = Σ_{k>j} e_k for contacts and ±s_j for pairs apart (a spread of 8 contacts and 8 pairs apart when there are more): each is in C_x and x + θ g ∈ K^N for some θ > 0; y − x ∈ C_x for y = x(s) at every probe time s and y = x⁰ + t u⁰ when in K^N; −s_j ∉ C_x and x − θ s_j ∉ K^N (θ = 1, 1/1000) across each contact).", micro::tangent_cone),
        case("df:normal-cone#polar", S2, "\"and the normal cone is the polar cone of the tangent cone: N_x K^N = (T_x K^N)°\" (at x = x(t), every probe time, pairs spread as for def:velcone#tangent-cone: for each contact, n_j = e_j − e_{j+1} has ⟨n_j, g⟩ ≤ 0 on all the generators of T_x K (by tail sums) and ⟨n_j, y − x⟩ ≤ 0 for the sampled y ∈ K^N (df:normal-cone); for each pair apart, and for (1, …, 1), a generator and a point y ∈ K^N with positive products; and x⁰ + t u⁰ − x(t) ∈ N_x K lies in the polar and is Σ μ_j n_j with μ ≥ 0 on the contacts only).", micro::polar_cone),
        corrected(
            within(case("df:H-micro#contacts-grow", S2, "\"the set of active constraints is non-decreasing in time … N_{x(s)}K^N ⊂ N_{x(t)}K^N for all s ≤ t\" (for x⁰ ∈ K^N, u⁰ ∈ C^N_{x⁰}).", micro::contacts_grow_printed), pd::SECTION2_EVERY_T),
            "Ω_{x(s)} ⊂ Ω_{x(t)} for 0 < s ≤ t, and from s = 0 when u⁰ ∈ H_{x⁰} (two particles touching at t = 0 with u⁰_{i+1} > u⁰_i separate at once).",
            Kind::Case(micro::contacts_grow_corrected),
            "Holds: the paper's main theorem assumes u⁰_{i+1} = u⁰_i on contacts (u⁰ ∈ H_{x⁰}), where the printed statement is true; only data in C_{x⁰} \\ H_{x⁰}, allowed by prop:proj-micro, break it at s = 0.",
        ),
        case("prop:proj-micro", S2, "\"there exists a unique solution x to (eq:micro-f0-lagr). It is given by the projection formula x(t) = P_{K^N}(x_0 + t u_0)\" — the event-driven sticky history equals the projection, exactly (positions, right-derivative velocities, multipliers, contact clusters).", micro::proj_micro),
        case("prop:proj-micro#u-in-H", S2, "\"u(t) ∈ H_{x(t)}^N for a.e. t ≥ 0\" (checked at every probe time t > 0, right derivatives).", micro::u_in_h),
        case("eq:proj-micro-u", S2, "u(t) = P_{H^N_{x(t)}}(u_0) (checked at every probe time t > 0, right derivatives).", micro::u_projection),
        case("eq:dyn-micro", S2, "u(t) = u_0 − N Σ_{i=1}^{N−1} λ_i(t)(e_i − e_{i+1}), λ_0(t) = λ_N(t) = 0, λ_i ≥ 0, and λ_i(t)(x_{i+1}(t) − x_i(t) − 2r) = 0 (the identity is tested, not used as a definition: λ(t) is the sum of the jumps of λ at the collisions up to t, from the event history's pre- and post-collision cluster velocities, and u(t) comes from the projection formula; the state's λ must equal it).", micro::dyn_micro),
        case("lem:proj-characterization", S2, "\"Let C ⊂ R^N be a closed convex set. Then, for every z ∈ R^N and y ∈ C, y = P_C(z) ⟺ z − y ∈ ∂I_C(y) = N_y C\" — for C = K^N (N_y K^N = {Σ μ_j (e_j − e_{j+1}) : μ_j ≥ 0, μ_j = 0 off the contacts of y}, μ_j the prefix sums of z − y), at every probe time: ⟹ for z = x⁰ + t u⁰ and y = P_K(z) (the crate's projection): y ∈ K^N, the prefix sums of z − y are ≥ 0, vanish at N and off the contacts of y; ⟸ for y = x(t) and z = y + Σ μ_j (e_j − e_{j+1}), μ_j = (j + k mod 3) on the contacts (k = 0, 1, 2): P_K(z) = y; and z − y ∉ N_y K^N ⟹ P_K(z) ≠ y for z − y = (1, …, 1), e_j − e_{j+1} across pairs apart, −(e_j − e_{j+1}) across contacts (a spread of 8 pairs).", micro::proj_characterization_k),
        case("lem:proj-characterization#H", S2, "The same lemma for C = H^N_{x(t)} (a subspace: N_w H = H^⊥ = span{e_j − e_{j+1} : j ∈ Ω_{x(t)}}), at every probe time t > 0: ⟹ for z = u⁰ and w = P_H(u⁰) (the crate's velocity projection): w ∈ H, the prefix sums of u⁰ − w vanish at N and off the contacts; ⟸ for w = u(t) and z = w + Σ μ_j (e_j − e_{j+1}), μ_j = (j + k mod 3) − 1 on the contacts (both signs): P_H(z) = w; and z − w ∉ H^⊥ ⟹ P_H(z) ≠ w for (1, …, 1) and e_j − e_{j+1} across pairs apart.", micro::proj_characterization_h),
        case("prop:proj-micro#orthogonality", S2, "(proof of prop:proj-micro) ⟨u(t) − u⁰, x̃(t)⟩ = Σ_i (u_i(t) − u⁰_i) x̃_i(t) = 0.", micro::orthogonality),
        case("lem:incl-HSN", S2, "H^N_{x(t)} ⊂ T_{x(t)}K^N ∩ [x⁰ + t u⁰ − x(t)]^⊥ for all t ≥ 0.", micro::incl_hsn),
        corrected(
            within(case("lem:incl-HSN#proof-second-inclusion", S2, "\"Let us now show the second inclusion H_{x̃(t)}^N ⊂ [x⁰ + t u⁰]^⊥.\"", micro::incl_hsn_printed), pd::SECTION2_EVERY_T),
            "H^N_{x(t)} ⊂ [x⁰ + t u⁰ − x(t)]^⊥ (the lemma's own statement; the proof then shows exactly this).",
            Kind::Case(micro::incl_hsn),
            "Holds: a typo (− x(t) dropped); the proof's computation is for x⁰ + t u⁰ − x(t).",
        ),
        case("prop:proj-velo-micro#step1", S2, "Step 1: ⟨u⁰ − u(t), u(t)⟩ ≥ 0.", micro::velo_step1),
        corrected(
            within(case("eq:w-Hs-perp", S2, "\"We also know by the previous lemma that ⟨x⁰ + t u⁰, w⟩ = 0\" for w ∈ H^N_{x(t)}.", micro::w_hs_perp), pd::SECTION2_AE_T),
            "⟨x⁰ + t u⁰ − x(t), w⟩ = 0 for w ∈ H^N_{x(t)} (lem:incl-HSN).",
            Kind::Case(micro::incl_hsn),
            "Holds: Step 2 uses the identity only through ⟨x⁰ + t u⁰ − x(t), ·⟩, whose vanishing on H is lem:incl-HSN.",
        ),
        case("eq:ineg-projortho", S2, "⟨u⁰ − u(t), y(t) − x(t)⟩ ≤ 0 for all y ∈ K^N (checked exactly on the generators of the tangent cone T_{x(t)}K^N).", micro::ineg_projortho),
        corrected(
            within(case("eq:proj-u-micro", S2, "Writing Ω^N_{x(t)} = ∪_k J_k(t), J_k = ⟦j_k, j_k + L_k⟧: u_i(t) = u⁰_i if i ∉ Ω^N_{x(t)}, and u_i(t) = (1/L_k) Σ_{l=1}^{L_k} u⁰_{j_k+l} if i ∈ J_k (read literally: J_k are runs of contact indices, i a particle index).", micro::proj_u_micro_literal), pd::SECTION2_AE_T),
            "u_i(t) = (1/|C|) Σ_{j ∈ C} u⁰_j where C is the contact cluster of particle i (a run of contacts ⟦j_k, j_k + L_k⟧ joins the L_k + 2 particles j_k … j_k + L_k + 1).",
            Kind::Case(micro::u_projection),
            "Holds: the lemma's first sentence (u(t) is the orthogonal projection of u⁰ onto H) is right; only the explicit index formula is off (0/0 for a single contact, a particle left out of the mean).",
        ),
        corrected(
            within(case("prop:bound-micro#position-contraction", S2, "\"From the projection formula we obtain ‖x(t)‖ ≤ ‖x⁰ + t u⁰‖\" (contraction of P_{K^N}).", micro::position_contraction), pd::SECTION2_EVERY_T),
            "P_{K^N} is non-expansive, not a contraction towards 0 (0 ∉ K^N for N ≥ 2): ‖x(t) − P_K(0)‖ ≤ ‖x⁰ + t u⁰ − P_K(0)‖, with ‖P_K(0)‖² = (2r)²(N² − 1)/12, so ‖x(t)‖ ≤ ‖x⁰‖ + T‖u⁰‖ + 2r√((N²−1)/12).",
            Kind::Case(micro::position_nonexpansive),
            "Holds: with 2r = 1/N the extra term is ≤ 1/√12, independent of N, so the bound of prop:bound-micro stands with C(T, ‖x⁰‖, ‖u⁰‖) + 1/√12.",
        ),
        case("prop:bound-micro#velocity-bound", S2, "‖u(t)‖ ≤ ‖u⁰‖.", micro::velocity_bound),
        corrected(
            within(case("prop:bound-micro#multiplier-relation", S2, "\"using the relation N(λ_i(t) − λ_{i−1}(t)) = u_i(t) − u⁰_i\" (proofs of prop:bound-micro and prop:Linf-micro).", micro::multiplier_relation_printed), pd::SECTION2_AE_T),
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
        case("prop:micro-pressure", S2, "p_i = dλ_i/dt satisfies (x_{i+1} − x_i − 2r)p_i = 0 and p_i ≥ 0 (checked at every collision instant — a spread of 40 when there are more — on the jumps [λ_i] of λ across it; the sum of the jumps when Σ of the merged cluster sizes ≤ 20,000): every jump is ≥ 0, the pair (i, i+1) is in contact (zero gap) after every instant where λ_i jumps, and λ(t) is the sum of its jumps. λ_i may jump at an instant where another pair collides (N = 3, x⁰ = (0, 1/3, 2), u⁰ = (1, 1, 0), r = 1/6: at t = 4/3 the pair (1, 2) collides and λ[0] jumps 0 → 1/9, pair (0, 1) being already in contact; indices from 0); what is checked is the contact at the jump, not which pair caused it.", micro::micro_pressure),
        corrected(
            within(case("prop:proj-micro#uniqueness-identity", S2, "For two solutions with the same u⁰: (N²/2) d/dt ‖x¹ − x²‖² = −⟨ξ¹ − ξ², x¹ − x²⟩.", micro::uniqueness_identity_printed), pd::SECTION2_AE_T),
            "(N/2) d/dt ‖x¹ − x²‖² = −⟨ξ¹ − ξ², x¹ − x²⟩ ≤ 0 (‖·‖² = (1/N)⟨·,·⟩).",
            Kind::Case(micro::uniqueness_identity_corrected),
            "Holds: only the sign of the derivative is used; uniqueness follows.",
        ),
        corrected(
            within(case("app:KKT", APPA, "The KKT conditions \"yield the existence of multipliers λ_i(t) ≥ 0 such that x(t) − (x⁰ + t u⁰) + N Σ_{i=1}^{N−1} λ_i(t)(e_i − e_{i+1}) = 0, λ_i(t)(x_{i+1}(t) − x_i(t) − 2r) = 0. This provides directly the multipliers and the Signorini condition introduced in the main text.\"", micro::kkt_printed), pd::SECTION2_AE_T),
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
            within(s3("eq:PDE-Lagr-N-1#complementarity", "(∂_w X̃_N − 1) Λ_N = 0: on ((i−1)/N, i/N], (N(x_i − x_{i−1}) − 1) λ_i = 0.", discrete::lagr_n1_printed), pd::SECTION3_AE_TW),
            "With df:LN re-indexed, Λ_N := λ_{i−1} on ((i−1)/N, i/N] (so P_N = ∂_t Λ_N := p_{i−1}; Λ̃_N is unchanged), λ_{i−1} and the slope N(x_i − x_{i−1}) belong to the same pair (i−1, i) and (∂_w X̃_N − 1) Λ_N = 0 holds as printed. This one re-indexing makes three printed statements exact at once, and this checker checks all three: eq:PDE-Lagr-N-1#complementarity, lem:discPDE2#exclusion ((∂_w X̃_N − 1) P_N = 0 at every collision) and eq:diffLambda_N's equality |Λ̃_N − Λ_N| = |N(λ_i − λ_{i−1})(w − (i−1)/N)|.",
            Kind::Case(discrete::reindexed),
            "Holds after the re-indexing: it leaves eq:PDE-Lagr-N-1's first line (which involves only Λ̃_N), Λ_N ≥ 0, the L² and L^∞ bounds on Λ_N (the same values, λ_0 = 0 in place of λ_N = 0) and the limit Λ unchanged; prop:cvg1's passage to the limit in the exclusion relation, which starts from (∂_w X̃_N − 1)Λ_N = 0, then starts from a true identity.",
        ),
        s3("lem:discPDE2", "∂_t X_N = U_N, ∂_t U_N + ∂_w P̃_N = 0, ∂_w X̃_N ≥ 1, P_N ≥ 0 in D'((0,T)×(0,1)) (eq:PDE-Lagr-N-2) — in discrete form, at every collision instant t_k (a spread of 40): u_i(t_k) − u_i(t_k⁻) = −N([λ_i] − [λ_{i−1}]) for i = 1 … N with [λ_0] = [λ_N] = 0 and [λ_i] ≥ 0 (velocities from the projection formula, jumps [λ] from the event history), x(t_k) − x(s) = (t_k − s)u(s) since the previous instant (and after the last one), N(x_{i+1} − x_i) ≥ 1.", momentum::disc_pde2),
        corrected(
            within(s3("lem:discPDE2#exclusion", "(∂_w X̃_N − 1) P_N = 0, P_N ≥ 0 (P_N = ∂_t Λ_N, piecewise constant in w).", discrete::disc_pde2_printed), pd::SECTION3_PRESSURE),
            "(∂_w X̃_N − 1) P_N = 0 with P_N := p_{i−1} on ((i−1)/N, i/N] (the re-indexing of eq:PDE-Lagr-N-1#complementarity), i.e. the jump of λ_i occurs with N(x_{i+1} − x_i) = 1.",
            Kind::Case(discrete::reindexed),
            "Holds after the re-indexing stated once under eq:PDE-Lagr-N-1#complementarity (same checker).",
        ),
        s3("prop:Linf-micro", "\"Assume ... x⁰_N − x⁰_0 + sup_i |u⁰_i| ≤ C'_0 [cond:Linfty] ... Then, the following BV estimate holds: sup_{t ∈ [0,T]} ∫_0^1 |∂_w X̃_N(t,w)| dw ≤ C' [eq:BV_XN] ... Without loss of generality, we may assume x⁰_0 = 0 ... ‖X_N‖_{L^∞((0,T)×(0,1))} + ‖X̃_N‖_{L^∞((0,T)×(0,1))} ≤ C', and ‖Λ_N‖_{L^∞((0,T)×(0,1))} + ‖Λ̃_N‖_{L^∞((0,T)×(0,1))} ≤ C', for some positive constant C' = C'(T, C'_0)\" — per trajectory, with the constants of the proof: C'_0 the smallest constant of cond:Linfty (x⁰_0 = x⁰_1 − 1/N − δ, δ = 1), positions measured from x⁰_0, T = each probe time: sup|u(t)| ≤ sup|u⁰|; x_N − x_0 ≤ (x⁰_N − x⁰_0) + 2T sup|u⁰| ≤ (1 + 2T)C'_0; ‖X_N‖_∞ + ‖X̃_N‖_∞ ≤ 2(T sup|u⁰| + (x⁰_N − x⁰_0) + 2T sup|u⁰|) ≤ 2(1 + 3T)C'_0; ‖Λ_N‖_∞ + ‖Λ̃_N‖_∞ ≤ 4 sup|u⁰| ≤ 4C'_0.", linf::linf_micro),
        scal("cond:Linfty", S3, concat!("prop:Linf-micro's hypothesis \"x⁰_N − x⁰_0 + sup_i |u⁰_i| ≤ C'_0 with C'_0 > 0 independent of N\" (eq. cond:Linfty), which \"follows from the compact support of the initial density ρ⁰, which ensures that the discrete initial configurations remain uniformly confined\" — measured as the smallest C'_0 of the quantile sample at each N (artificial particle x⁰_0 = x⁰_1 − 1/N − δ, δ = 1, as prop:Linf-micro's checker uses it)", run_on!()), scaling::cond_linfty),
        corrected(
            within(s3("prop:pressure-bound#exclusion", "(proof) \"Since (∂_w X̃_N − 1) P̃_N = 0, we may replace ∂_w X̃_N by 1 on the support of P̃_N\" (P̃_N piecewise affine).", discrete::pressure_bound_exclusion_printed), pd::SECTION3_PRESSURE),
            "No re-indexing rescues this step: on [(i−1)/N, i/N], P̃_N interpolates p_{i−1} and p_i, carried by the pairs (i−1, i) and (i, i+1), and a continuous piecewise-affine P̃_N cannot vanish on an interval whose pair is apart while its end values are the pressures of the neighbouring pairs. The bound itself follows from the pair-indexed pressure: testing eq:micro-2nd-ID with φ_i = (x_N − x_0) i/N − x_i (the proof's test function at the nodes) and summing by parts, at every collision (1/N) Σ_i [u_i] φ_i = Σ_i [λ_i](φ_{i+1} − φ_i) = ((x_N − x_0) − 1)/N · Σ_i [λ_i] ≥ (δ/N) Σ_i [λ_i] (the exclusion is exact for the pair (i, i+1)), and (1/N) Σ_i [λ_i] is the mass of both P_N and P̃_N (trapezoid rule, p_0 = p_N = 0).",
            Kind::Case(momentum::pressure_bound_by_parts),
            "prop:pressure-bound holds by this other argument (the summation by parts above, checked exactly at every collision: it sees the sign and the scale of λ); the printed step is wrong. The same wrong step is reused in the proof of prop:2ndorder-LagrPDE, \"0 = ⟨P̃_N, (∂_w X̃_N − 1)Ψ⟩\", false as printed for the same reason (the counterexample above). That conclusion survives through the paper's own previous item: with the re-indexed P_N := p_{i−1} the exclusion (∂_w X̃_N − 1) P_N = 0 is exact, so ⟨P̃_N, (∂_w X̃_N − 1)Ψ⟩ = −⟨R¹_N, Ψ⟩ with R¹_N = (∂_w X̃_N − 1)(P_N − P̃_N), which the paper shows tends to 0; the final item then needs → 0 instead of = 0. That limit is not checked by the ledger.",
        ),
        corrected(
            within(s3("prop:pressure-bound#test-function", "(proof) φ(t,w) = ((x_N(t) − x_0(t))w − X̃_N(t,w))ϕ(t): \"Observe that at the boundaries φ(t,0) = φ(t,1) = 0\" (with the normalisation x⁰_0 = 0 of prop:Linf-micro; checked at every probe time t > 0, any ϕ ≥ 0 with ϕ(t) > 0).", test_pressure::test_function_boundary), pd::PRESSURE_TEST_FUNCTION),
            "φ(t,0) = φ(t,1) = −x_0(t)ϕ(t), and x_0(t) = ∫_0^t u_1 moves; the integration by parts in w needs only P̃_N(t,0) = p_0 = 0 and P̃_N(t,1) = p_N = 0, so the tested identity holds with this φ (its checker, eq:test-pressure-bound's correction, is run here).",
            Kind::Case(test_pressure::test_identity_corrected),
            "Holds: the boundary terms vanish because the pressure does; (x_0(t) + (x_N − x_0)w − X̃_N)ϕ, which does vanish at both ends, has the same ∂_w φ and changes the right side by −(∫U_N dw)∫(x_0ϕ)' dt = 0 (the mean velocity is conserved).",
        ),
        corrected(
            within(s3("eq:test-pressure-bound", "\"Using (eq:PDE-Lagr-N-2), we obtain ∫_0^T∫_0^1 ((x_N(t) − x_0(t)) − ∂_w X̃_N(t,w))ϕ(t) P̃_N(w,dt) dw = −∫_0^T∫_0^1 ((U_N(t,0) − U_N(t,1))w − Ũ_N(t,w)) U_N(t,w) ϕ(t) dw dt − ∫_0^T∫_0^1 U_N(t,w)((x_N(t) − x_0(t))w − X̃_N(t,w)) ϕ'(t) dw dt. By the previously established bounds on U_N and X̃_N, the right-hand side is uniformly bounded. Hence … |∫_0^T∫_0^1 ((x_N(t) − x_0(t)) − ∂_w X̃_N(t,w))ϕ(t) P̃_N(dt,w) dw| ≤ C(‖U_N‖_{L^∞_{t,w}}² + ‖U_N‖_{L²_tL²_w}² + ‖X̃_N‖_{L²_tL²_w}²)\" — the identity checked exactly per trajectory (δ = 1, U_N(t,0) read as u_0 = u_1, the artificial particle moving with particle 1, U_N(t,1) = u_N) for ϕ = (t − a)²(b − t)² on [a, b] covering the collisions (up to 400 instants) and on [a, c] ending between the first two.", test_pressure::test_identity_printed), pd::PRESSURE_IDENTITY),
            "The identity holds with (u_N(t) − u_0(t))w in place of (U_N(t,0) − U_N(t,1))w — the ∂_t φ computed just before in the proof — exactly, and it gives |left side| ≤ 2‖ϕ‖_{L¹} sup_t ‖U_N‖²_∞ + ‖ϕ'‖_{L¹} sup_t ‖U_N(t)‖_∞ ((x_N − x_0) + max(|x_0|, |x_N|)) (checked), bounded independently of N by prop:Linf-micro: the bound needs the L^∞ bounds (the spread x_N − x_0 enters through (x_N − x_0)w), not only the L² norms listed.",
            Kind::Case(test_pressure::test_identity_corrected),
            "Holds: a sign slip in one factor; the proof only uses that the right side is bounded, which the corrected identity gives with C depending on ϕ through ‖ϕ‖_{L¹} ≤ T and ‖ϕ'‖_{L¹} (= 2 max ϕ for ϕ increasing then decreasing, enough for the total mass since P̃_N ≥ 0).",
        ),
        corrected(
            within(s3("prop:2ndorder-LagrPDE#exclusion-pairing", "(proof of prop:2ndorder-LagrPDE) \"Now, for Ψ ∈ C_c^1((0,T)×(0,1)), we have 0 = ⟨P̃_N,(∂_w X̃_N − 1)Ψ⟩\" — at every collision instant (P̃_N is a Dirac mass in time there, weights the jumps [λ_i]; a spread of 40 collisions when more), for Ψ = 1: Σ_i (N(x_i − x_{i−1}) − 1)([λ_{i−1}] + [λ_i])/(2N), δ = 1 (every term is ≥ 0, so this Ψ is the sharpest).", discrete::pairing_printed), pd::EXCLUSION_PAIRING),
            "With the re-indexed P_N := p_{i−1} on ((i−1)/N, i/N] (the pressure of the pair whose gap is that cell's, as in eq:PDE-Lagr-N-1#complementarity's correction), ⟨P_N, (∂_w X̃_N − 1)Ψ⟩ = 0 exactly, hence ⟨P̃_N, (∂_w X̃_N − 1)Ψ⟩ = −⟨R¹_N, Ψ⟩ with R¹_N = (∂_w X̃_N − 1)(P_N − P̃_N), the term the proof's previous item shows tends to 0 in D': the step holds with → 0 in place of = 0 (checked: the re-indexed pairing is 0 and the printed one equals −⟨R¹_N, 1⟩ at every collision; the limit R¹_N → 0 is the paper's previous item, not measured by the ledger).",
            Kind::Case(discrete::pairing_reindexed),
            "The proposition survives: T¹_N + T²_N → 0 instead of = 0 leaves the limit (∂_w X − 1)P = 0 unchanged. The same wrong exclusion is prop:pressure-bound#exclusion's.",
        ),
        s3("prop:pressure-bound#gap-delta", "(x_N(t) − x_0(t)) − 1 ≥ 2r(N − 1) + (2r + δ) − 1 = δ.", discrete::gap_delta),
        s3("prop:cvg1#XN-L1", "∫_0^1 |X̃_N(t,w) − X_N(t,w)| dw = (1/2N) Σ_{i=0}^{N−1} (x_{i+1}(t) − x_i(t)) = (1/2N)(x_N(t) − x_0(t)).", discrete::xn_l1),
        corrected(
            within(s3("eq:diffLambda_N", "For w ∈ ((i−1)/N, i/N]: |Λ̃_N(t,w) − Λ_N(t,w)| = |N(λ_i(t) − λ_{i−1}(t))(w − (i−1)/N)| ≤ |λ_i(t) − λ_{i−1}(t)| ≤ C'/N.", discrete::diff_lambda_printed), pd::SECTION3_AE_TW),
            "|Λ̃_N − Λ_N| = |λ_i − λ_{i−1}| · |1 − N(w − (i−1)/N)| ≤ |λ_i − λ_{i−1}| ≤ 2 sup|u⁰|/N.",
            Kind::Case(discrete::diff_lambda_corrected),
            "Holds: the bound, which is all that is used, is right; and with the re-indexing Λ_N := λ_{i−1} of eq:PDE-Lagr-N-1#complementarity the printed equality itself is exact (checked there).",
        ),
        corrected(
            within(s3("prop:2ndorder-LagrPDE#UN-L1", "∫_0^1 |Ũ_N(t,w) − U_N(t,w)| dw = (1/2N) Σ_{i=1}^N |u_i(t) − u_{i−1}(t)| = (1/2N)|u_N(t) − u_0(t)| ≤ C/N.", discrete::un_l1_printed), pd::SECTION3_AE_TW),
            "(1/2N) Σ |u_i − u_{i−1}| ≤ TV(u⁰)/(2N): the total variation of u(t) never exceeds that of u⁰ (cluster means create no variation); TV(u⁰) is bounded when U⁰ ∈ BV.",
            Kind::Case(discrete::un_l1_corrected),
            "Holds if U⁰ has bounded variation (or for t ≥ α by pwUN-L1); the second equality is true only for monotone u.",
        ),
        s3("eq:Oleinik-tUN", "∂_w Ũ_N < ∂_w X̃_N / t: t(u_i − u_{i−1}) < x_i − x_{i−1}, i = 1 … N (artificial particle included), t > 0.", discrete::oleinik_tun),
        s3("pwUN-L1", "(proof) ‖∂_w Ũ_N(t)‖_{L¹} ≤ (2/t)(x_N(t) − x_0(t)) − (Ũ_N(t,1) − Ũ_N(t,0)).", discrete::pw_un_l1),
        s3("eq:BV_XN", "(proof) ∫_0^1 |∂_w X̃_N(t,w)| dw = x_N(t) − x_0(t) ≤ (x_N(0) − x_0(0)) + T(sup_{[0,T]}|u_N| + sup_{[0,T]}|u_1|).", discrete::bv_xn),
        // -- scaling claims across N on random macroscopic data (issue 14, macro) --
        scal("prop:pressure-bound", S3, concat!("‖P̃_N‖_{M(0,T; L¹(0,1))} ≤ C with C independent of N: the total variation Σ_{t_k ≤ T} (1/N) Σ_i |[λ_i]_{t_k}| of the pressure measure (sign-aware: a negative jump, P̃_N ≱ 0, is reported)", run_on!()), scaling::pressure_mass),
        scal("prop:L2-micro", S3, concat!("\"‖X_N‖_{L^∞(0,T;L²(0,1))} + ‖X̃_N‖_{L^∞(0,T;L²(0,1))} + ‖∂_t X_N‖_{L^∞(0,T;L²(0,1))} + ‖∂_t X̃_N‖_{L^∞(0,T;L²(0,1))} + ‖Λ_N‖_{L^∞(0,T;L²(0,1))} + ‖Λ̃_N‖_{L^∞(0,T;L²(0,1))} + ‖∂_w Λ̃_N‖_{L^∞(0,T;L²(0,1))} ≤ C\" independent of N — all seven measured, as sup_t of the sum of their squares (exact: constant and affine interpolations cell by cell, x_0 = x_1 − 1/N − δ with δ = 1, u_0 = u_1, λ_0 = 0, ∂_w Λ̃_N = N(λ_i − λ_{i−1})), bounded iff the sum of the norms is", run_on!()), scaling::l2_bounds),
        scal("prop:2ndorder-LagrPDE#PN-minus-tPN", S3, concat!("(proof of prop:2ndorder-LagrPDE) \"⟨P_N − P̃_N, Ψ⟩ = −∫_0^T∫_0^1 (Λ_N(t,w) − Λ̃_N(t,w)) ∂_t Ψ(t,w) dw dt. Hence, using (eq:diffLambda_N) |⟨P_N − P̃_N, Ψ⟩| ≤ (C/N)‖∂_t Ψ‖_{L¹(0,T; L^∞(0,1))}\" — for Ψ = ψ(t)w (against Ψ = ψ(t) the pairing is exactly 0, since ∫(Λ_N − Λ̃_N) dw = (λ_N − λ_0)/(2N) = 0), the constant C ≥ N sup_t |∫_0^1 (Λ_N − Λ̃_N)(t,w) w dw| measured across N and required bounded (exact: Σ_i (λ_i − λ_{i−1})((i−1)/(2N²) + 1/(6N²))). The proof's next step, the bound on ∂_w X̃_N used for compactness (bounded in W^{1,∞}(α,T; L¹(0,1)), i.e. ∫|∂_w X̃_N| = x_N − x_0 and ∫|∂_t ∂_w X̃_N| = ‖∂_w Ũ_N‖_{L¹} bounded), is eq:BV_XN and pwUN-L1#independent-of-N", run_on!()), scaling::pn_minus_tpn),
        scal("pwUN-L1#independent-of-N", S3, concat!("sup_{t ∈ [α,T]} ‖∂_w Ũ_N(t)‖_{L¹(0,1)} ≤ C_α independent of N (α = T/2; only the data on which it is not 0 count, the ledger note gives their number: the two shipped scenes are one cluster by T/2)", run_on!()), scaling::tv_u),
        scal("eq:bound-UN-Linf", S3, concat!("\"‖U_N‖_{L^∞((0,T)×(0,1))} + ‖Ũ_N‖_{L^∞((0,T)×(0,1))} ≤ C\" (= 2 sup_t max_i |u_i(t)|)", run_on!()), scaling::bound_un_linf),
        scal("thm:main#discretisation", "§2.1 discretisation", concat!("(i) \"X⁰_N → X⁰, … strongly in L²(0,1)\" for the quantile sampling x⁰_i = X⁰(i/N) (MacroDatum::quantiles), ‖X⁰_N − X⁰‖²_{L²} exact against X⁰ as the continuum profile at t = 0", run_on!()), scaling::discretisation),
        scal("thm:main#discretisation-U", "§2.1 discretisation", concat!("(i) \"U⁰_N → U⁰ strongly in L²(0,1)\" for the printed sampling u⁰_i = U⁰(i/N) (MacroDatum::quantiles), ‖U⁰_N − U⁰‖²_{L²} exact against U⁰ as the continuum profile at t = 0", run_on!()), scaling::discretisation_u),
        corrected(
            scal("prop:cvg1", S3, concat!("\"there exists X ∈ W^{1,∞}((0,T)×(0,1)) … such that, up to the extraction of a subsequence, X̃_N → X strongly in C([0,T]×[0,1])\" (the first-order limit is unique, so the whole sequence is measured; here at t = 0: sup_{w ∈ [0,1]} |X̃_N(0,w) − X⁰(w)|, exact, on the whole [0, 1], the artificial particle's cell [0, 1/N] included)", run_on!()), scaling::cvg1_uniform),
            "X̃_N, X_N → X strongly in C([0,T]; L¹(0,1)) and Λ_N ⇀* Λ: measured as sup_t ‖X_N(t) − X(t)‖²_{L²} → 0 and max_φ |∫_0^1 (Λ_N(t) − Λ(t))φ| → 0 for φ ∈ {1, w}, at t = T/4, T/2, 3T/4, T, against the exact continuum solution (data whose continuum profile is rational at those times), on the same data and N. Uniform convergence on [0, T] × [0, 1] fails for every datum: X̃_N(t, 0) = x_0(t) = x_1(t) − 1/N − δ (df:x0) while X(t, 0) = lim x_1, so |X̃_N(t,0) − X(t,0)| → δ > 0 (one congested block, ρ⁰ = 1 on [0, 1], u⁰ = 0: |X̃_N(0,0) − X⁰(0)| = δ for every N); uniform convergence holds on [ε, 1] for every ε > 0 only without vacuum, since X(t,·) jumps wherever ρ(t) has vacuum inside its support (X⁰ jumps by the width of a gap between blocks, and X̃_N(0,·) is continuous), and X ∈ W^{1,∞} likewise.",
            Kind::Scaling(scaling::cvg1_measured),
            "The theorem survives: the passage to the limit in eq:PDE-Lagr-N-1 uses the strong convergence in C([0,T]; L¹(0,1)) and the weak-* limits, not uniform convergence; X ∈ L^∞(0,T; BV(0,1)) with ∂_t X ∈ L^∞ instead of W^{1,∞}. Witness (the ledger's): appendix-c-two-blocks, sup_{w ∈ [0,1]} |X̃_N(0,w) − X⁰(w)| does not decay (δ = 1 at w = 0 from the artificial particle, and the gap η = 1/4 between the two congested blocks inside).",
        ),
        fixed("eq:Lagr-1", S3, "\"∂_t X = U⁰ − ∂_w Λ, ∂_w X ≥ 1, (∂_w X − 1)Λ = 0, Λ ≥ 0 a.e., Λ(t,0) = Λ(t,1) = 0\" — checked exactly on the continuum solution X = P_K(X⁰ + tU⁰) (limit::continuum, ∂_t X its right derivative U) of the 18 macroscopic data of the scaling claims at t = T/4, T/2, 3T/4, T, on the profiles that are rational there (segment by segment: a quadratic Λ is ≥ 0 on an interval iff at its ends and vertex). What is a definition and what is tested: limit::continuum builds U as the plateau means of U⁰ and Λ as ∫_0^w (U⁰ − U) (0 off the plateaus), so ∂_t X = U⁰ − ∂_w Λ (with ∂_t X read as U), Λ(t,0) = 0 and (∂_w X − 1)Λ = 0 hold by construction and their checks only guard the code; ∂_w X ≥ 1 is the projection's; Λ ≥ 0 on every plateau and Λ(t,1) = 0 are consequences of the pooling, tested. The construction itself is tested independently: by prop:cvg1's correction, the particles' X_N and Λ_N (from their own λ_i) converge to this X and this Λ as N grows (‖X_N − X‖²_{L²} → 0, ⟨Λ_N − Λ, φ⟩ → 0 for φ ∈ {1, w}, same data and times), and by eq:Lagr-1#particle-multiplier, pointwise at the nodes (max_i |λ_i(t) − Λ(t, i/N)| → 0).", continuum::lagr1),
        scal("eq:Lagr-1#particle-multiplier", S3, concat!("The multiplier Λ of eq:Lagr-1 (\"∂_t X = U⁰ − ∂_w Λ … Λ ≥ 0 a.e., Λ(t,0) = Λ(t,1) = 0\") is the limit of the particles' multipliers, checked against a construction independent of the continuum solver: Λ_N(t, i/N) = λ_i(t) (df:LN) from the event history's λ (λ_i = (1/N)Σ_{j ≤ i}(u⁰_j − u_j(t)), eq:dyn-micro, λ_N from the same sum), against the continuum Λ(t, i/N) built by limit::continuum from plateau means of U⁰ (the definitions listed under eq:Lagr-1) — max_i |λ_i(t) − Λ(t, i/N)| over the nodes i = 1 … N, maximised over t = T/4, T/2, 3T/4, T (rational profiles), exact, must tend to 0. Unlike prop:cvg1's correction (two weak moments), a wrong plateau, a Λ built from the wrong mean, or a particle λ off by one pair shows at a node", run_on!()), scaling::lagr1_particle_multiplier),
        fixed("eq:PDE-Lagr-2", S3, "\"∂_t U + ∂_w P = 0 in D', … P ≥ 0 in D'\" with P = ∂_t Λ — checked exactly between consecutive times t₀ < t₁ of {T/4, T/2, 3T/4, T} on the continuum solution of the same 18 data (rational profiles): Λ(t₁) − Λ(t₀) ≥ 0 on [0, 1] and U(t₁) − U(t₀) = −∂_w(Λ(t₁) − Λ(t₀)) on the common refinement. The momentum equation follows from the definition ∂_w Λ = U⁰ − U (see eq:Lagr-1) and its check only guards the code; P ≥ 0, i.e. Λ non-decreasing in time at every w, is tested; the independent comparisons with the particles' λ are prop:cvg1's correction (weak moments) and eq:Lagr-1#particle-multiplier (at the nodes i/N, where Λ(t₁) − Λ(t₀) is then the limit of the particles' λ_i(t₁) − λ_i(t₀) ≥ 0, the sum of non-negative jumps checked by prop:micro-pressure).", continuum::pde_lagr2),
        fixed("eq:Oleinik-Lagr", S3, "\"∂_w U < ∂_w X / t in D'((0,T) × (0,1))\" — checked exactly on the continuum solution of the same 18 data at t = T/4 … T (rational profiles): strictly, t ∂_w U < ∂_w X, on every affine piece, and t [U] ≤ [X] at every jump (equality happens: a velocity jump upwards between touching blocks opens a vacuum with [X] = t[U]).", continuum::oleinik_lagr),
        s3("lem:density", "(= lem:density-app) \"Let X ∈ W^{1,∞}((0,T)×(0,1)) be such that, for a.e. t ∈ (0,T), the map w ↦ X(t,w) is nondecreasing and satisfies ∂_w X(t,w) ≥ 1 … ρ(t,·) := X(t,·)#L¹_(0,1). Then the following properties hold: [(i), lem:density] the curve t ↦ ρ(t) belongs to AC([0,T]; P_2(R)). [(ii), lem:density] There exists a bounded Borel function, still denoted by ρ, such that ρ(dt,dx) = ρ(t,x) dt dx, 0 ≤ ρ(t,x) ≤ 1\" — for the particle interpolation X̃_N (artificial particle x_0 = x_1 − 1/N − δ, δ = 1), at every probe time: the hypothesis ∂_w X̃_N = N(x_i − x_{i−1}) ≥ 1 on every cell; (ii) ρ̃_N = 1/(N(x_i − x_{i−1})) on (x_{i−1}, x_i) (limit::eulerian::particle_density) is in [0, 1], gives each cell the mass 1/N of its w-interval (so it is the density of X̃_N#L¹) and is 0 off [x_0, x_N]; (i) between consecutive probe times s < t, the proof's coupling bound W_2(ρ̃_N(s), ρ̃_N(t))² ≤ ∫_0^1 |X̃_N(t,w) − X̃_N(s,w)|² dw ≤ (t − s)² ‖∂_t X̃_N‖²_{L^∞((s,t)×(0,1))}, exactly, and the proof's steps in order: (1) at every node w = i/N (the artificial particle included) |X̃_N(t,w) − X̃_N(s,w)| ≤ (t − s)‖∂_t X̃_N‖_∞ (the Lipschitz step, squares compared), (2) on every cell, with g, h the displacements of its two nodes, (g² + gh + h²)/3 ≤ (t − s)²‖∂_t X̃_N‖²_∞ (N times the cell's exact integral), (3) their mean, the integral (in 1D the monotone coupling is optimal: X̃_N(t,·), non-decreasing and pushing L¹ to ρ̃_N, is the quantile function of ρ̃_N(t), so the first inequality is an equality; the integral is exact on the grid i/N; ‖∂_t X̃_N‖_∞ = max_i |u_i(τ)| over τ = s and the collision instants in (s,t)).", density::density),
        fixed("lem:density#continuum", S3, "lem:density (ii) for the exact continuum solution X = P_K(X⁰ + tU⁰) (limit::continuum) of the 18 macroscopic data of the scaling claims at t = T/4, T/2, 3T/4, T (rational profiles): the hypothesis ∂_w X ≥ 1 on every segment, ρ = 1/∂_w X ∈ [0, 1] on the image of each segment (limit::eulerian::continuum_density), carrying the mass of its w-interval, and ρ = 0 in the vacuum between images.", density::density_continuum),
        identity(
            s3("prop:eulerian-formulation#mass", "Proposition \"Eulerian formulation\" (unlabelled; §3.4): \"(ρ, ρu, p) is a distributional solution of the constrained Euler system (eq:macro-euler)\", mass equation — \"Differentiating under the integral sign … −∫_0^T∫_0^1 (∂_tφ(t,X(t,w)) + U(t,w)∂_xφ(t,X(t,w))) dw dt\" — for the particles (ρ = X_N#L¹, u = u_i at x_i): the weak residual R_mass^N(φ) = (1/N) Σ_i ∫_0^T (∂_tφ + u_i ∂_xφ)(t, x_i(t)) dt is exactly 0 for φ = B(t)(x − x⁰_1)^m, B the C³ bump of limit::eulerian::TestFunction on [0, T] and on [T/4, 3T/4] (T the last probe time), m = 2, 3 — integrated exactly as a polynomial in t on each interval between collision instants, from the positions and right-derivative velocities of the state at its left end.", eulerian::mass),
            "R_mass^N(φ) = (1/N) Σ_i ∫_0^T d/dt φ(t, x_i(t)) dt with B vanishing at 0 and T: zero for any path whose velocity is its derivative, whatever the dynamics (the checker only sees a velocity that is not the derivative of the positions). It tests the consistency of the recorded history, not the paper; the same holds for the interpolated density ρ̃_N = X̃_N#L¹ transported by Ũ_N (∂_t X̃_N = Ũ_N). The pairing of ρ̃_N with the paper's velocity U_N, whose residual is not identically 0, is prop:eulerian-formulation#mass-interpolated.",
        ),
        scal("prop:eulerian-formulation#mass-interpolated", S3, concat!("Proposition \"Eulerian formulation\" (unlabelled; §3.4), mass equation, \"Using the definition of ρ as a push-forward … Differentiating under the integral sign\", at finite N for the interpolated density ρ̃_N = X̃_N(t)#L¹ (lem:density's, the Eulerian density of eq:PDE-Lagr-N-1's X̃_N) with the momentum m̃_N = X̃_N(t)#(U_N L¹), U_N the velocity of df:UN and eq:PDE-Lagr-N (∂_t X_N = U_N): the weak residual R_N(φ) = ∫∫ ρ̃_N ∂_tφ + m̃_N ∂_xφ dx dt tends to 0. What is an identity and what is tested: the push-forward argument makes the residual of (Y#L¹, Y#(∂_t Y L¹)) exactly 0 for any Y Lipschitz in t, so with Ũ_N = ∂_t X̃_N in place of U_N it is 0 whatever the dynamics (and prop:eulerian-formulation#mass is that identity for X_N); what remains is R_N(φ) = ∫_0^T∫_0^1 (U_N − Ũ_N) ∂_xφ(t, X̃_N) dw dt, a sum over the pairs apart of (1/N)(u_i − u_{i−1}) ∫ B(t) ∫_0^1 (1 − s) Q'(x_{i−1} + s(x_i − x_{i−1})) ds dt, not 0 whenever a pair apart has distinct velocities and → 0 only if the velocity jumps stay summable (the total variation of pwUN-L1, prop:2ndorder-LagrPDE#UN-L1's ‖Ũ_N − U_N‖_{L¹} ≤ C/N). Computed exactly (limit::eulerian::interpolated_mass_residuals: one polynomial piece in t per pair apart between the collisions of its two clusters, integrated against the bump; cross-checked against the Eulerian double integral by quadrature in a unit test), measured as max_φ |R_N(φ)| over the 12 test functions φ = B(t)((x − c)/L)^m of prop:eulerian-formulation#momentum, each value plus its dyadic accumulation bound (pieces · 2⁻²⁵⁷), for N ≤ 512 only (its cost grows with the collision times' denominators: 27 s for one datum at N = 4096)", run_on!()), scaling::eulerian_mass_interpolated),
        scal("prop:eulerian-formulation#momentum", S3, concat!("Proposition \"Eulerian formulation\" (unlabelled; §3.4): \"(ρ, ρu, p) is a distributional solution of the constrained Euler system (eq:macro-euler)\", momentum equation, for the particles: the weak residual R_mom^N(φ) = ∫∫(∂_tφ + u∂_xφ)ρu + ⟨p, ∂_xφ⟩ of ρ̃_N, ρ_N u_N, p_N = (Id, X_N)#P_N tends to 0 (it is O(1/N): the exact identity R_mom^N(φ) = Σ_k B(t_k) Σ_i [λ_i]_k (Q'(x_i)/N − (Q(x_{i+1}) − Q(x_i))) of limit::eulerian, summed by power sums), measured as max_φ |R_mom^N(φ)| over the 12 test functions φ = B(t)((x − c)/L)^m of limit::eulerian::test_family (windows [0,T], [0,T/2], [T/4,3T/4], [T/2,T], m = 2, 3, 4, c and L covering the motion), each value plus its dyadic accumulation bound (terms · 2⁻²⁵⁷)", run_on!()), scaling::eulerian_momentum),
        fixed("prop:eulerian-formulation#oleinik", S3, "Proposition \"Eulerian formulation\": (ρ, ρu, p) satisfies \"an Oleinik inequality ∂_x u < 1/t in the sense of distributions\" — on the exact continuum solution of the 18 macroscopic data at t = T/4 … T (rational profiles), u(t,x) = U(t,W(t,x)): t ∂_x u = t ∂_w U/∂_w X < 1 on the image of every segment (the support of ρ), and t [U]/[X] ≤ 1 across every vacuum gap (u interpolated linearly through the gap; equality happens where a vacuum opens at t = 0 between touching blocks, u = x/t there, as for eq:Oleinik-Lagr), by limit::eulerian::oleinik_margin; a velocity jumping upwards with no gap fails.", eulerian::oleinik),
        // -- end of the scaling block --
        case("app:uniqueness#monotone-inclusion", APPC, "Proposition \"Monotone inclusion and uniqueness for (eq:Lagr-1)\" (unlabelled; app:uniqueness): \"ξ := ∂_w Λ. Then, for a.e. t ∈ (0,T), one has ξ(t) ∈ ∂I_K(X(t)) … Equivalently, ∂_t X(t) + ∂I_K(X(t)) ∋ U⁰. As a consequence, (eq:Lagr-1) admits at most one solution\" (proof: ∫ ∂_wΛ (Y − X) = −∫ Λ ∂_w(Y − X) ≤ 0; for two solutions (1/2) d/dt ‖X¹ − X²‖² = −∫(ξ¹ − ξ²)(X¹ − X²) ≤ 0) — its discrete analogue on the particles, at every probe time: ξ = N(λ_i − λ_{i−1}) from the multipliers (λ_0 = λ_N = 0) equals u⁰ − u(t); ⟨ξ, y − x(t)⟩ ≤ 0 with the proof's summation by parts ⟨ξ, y − x⟩ = −N Σ λ_i((y_{i+1} − y_i) − (x_{i+1} − x_i)), each term ≥ 0, on 3 pseudo-random y ∈ K^N (some gaps exactly 2r) and on the generators of T_{x(t)}K^N; and for second solutions with the same u⁰ and x⁰ translated by 1, with its slack halved, with its gaps widened: ⟨ξ¹ − ξ², x¹ − x²⟩ ≥ 0 at every probe and collision time of either history, and ‖x¹(t) − x²(t)‖ non-increasing on [0, T] (on each interval between consecutive such times, d/dt‖x¹ − x²‖² is affine and is checked ≤ 0 at both ends). Unlike eq:ineg-projortho (u⁰ − u on the generators) and prop:proj-micro#uniqueness-identity (one second datum, the derivative at the probe times), ξ is read from λ and the contraction is checked on the whole interval.", inclusion::monotone_inclusion),
        fixed("app:uniqueness#free-collision", APPC, "The collision occurs at t* = η/2, at which point X^f(t*, w) = w + η/2.", appendix_c::free_collision),
        corrected(
            within(fixed("app:uniqueness#sticky-pressure", APPC, "P¹(t,w) = [w 1_{[0,1/2)}(w) − (1 − w) 1_{[1/2,1]}(w)] δ_{t=t*}, with U¹ = 0, X¹ = w + η/2 for t ≥ t*, solves eq:PDE-Lagr-2 (∂_t U + ∂_w P = 0, P ≥ 0).", super::weak_pressure::sticky_pressure_printed), pd::APPENDIX_C_PRESSURE),
            "P¹ = [w 1_{[0,1/2)} + (1 − w) 1_{[1/2,1]}] δ_{t=t*} (≥ 0, continuous, vanishing at w = 0, 1); it is exactly the limit of the particles: the jump of λ_i at t* is P¹(i/N).",
            Kind::Formula(appendix_c::sticky_pressure_corrected),
            "Holds: the sticky continuation is a solution with the corrected pressure; the non-uniqueness argument is unaffected.",
        ),
        fixed("app:uniqueness#rebound-pressure", APPC, "U²(t,w) = 2w − 1, X² = (w + η/2) + (t − t*)U², P² = [(2w − w²) 1_{[0,1/2)} − (w² − 1) 1_{[1/2,1]}] δ_{t=t*} solves eq:PDE-Lagr-2.", appendix_c::rebound_pressure),
        fixed("app:uniqueness#projection-selects-sticky", APPC, "\"A natural way to restore uniqueness is to supplement eq:PDE-Lagr-2 with a projection principle on the velocity … U(t) = P_{H_{X(t)}}(U⁰)\" (eq:velocity-projection): of the two continuations only the sticky one satisfies it (and X = P_K(X⁰ + tU⁰)).", appendix_c::projection_selects_sticky),
        fixed("app:uniqueness#particle-limit", APPC, "The projection principle \"can be seen as the macroscopic counterpart of the sticky blocks dynamics\": the quantile-sampled particles converge to the sticky continuation and not to the rebound (‖X_N − X²‖² within 1/N of (t − t*)²/3), checked at η = 1/4, t = 1, N = 8 … 512. The exact value ‖X_N − X¹‖² = 1/(3N²) (checked) is for the project's sampling x⁰_i = X⁰(i/N) with the left-continuous quantile X⁰(w) = inf{x : F(x) ≥ w} (MacroDatum::x0, the sampling of every macro scene): the particle at w = 1/2 is the last of the left block, at x = 1/2. With the paper's right-continuous X⁰ = w + η 1_{w ≥ 1/2}, U⁰ = 1 − 2·1_{w ≥ 1/2}, that particle belongs to the right block and the value differs (7/(48N²) by the audit of issue 29, not recomputed here); both tend to 0, which is all the claim uses.", appendix_c::sticky_is_particle_limit),
        fixed("app:uniqueness#sticky-pressure-is-continuum", APPC, "\"The pressure P is uniquely recovered from the momentum equation and the boundary condition\" P(t,0) = P(t,1) = 0: for the sticky continuation it is the jump at t* of the continuum multiplier Λ (∂_t X = U⁰ − ∂_w Λ), i.e. the corrected P¹.", appendix_c::sticky_pressure_is_continuum),
        fixed("app:uniqueness#rebound-oleinik", APPC, "∂_w U² = 2, ∂_w X²(t,w) = 1 + 2(t − t*), and for η < 1, ∂_w U² ≤ ∂_w X²/t for all t > t* (eq:Oleinik-Lagr).", appendix_c::rebound_oleinik),
    ]
}
