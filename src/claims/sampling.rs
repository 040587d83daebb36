//! §2.1, "Discretisation of the macroscopic initial datum", checked exactly
//! on the shipped `[macro]` scenes for N = 2, 4, …, 256 and on random
//! macroscopic data admissible under `hyp:u0` ([`crate::generate::macro_datum`]).

use num_rational::BigRational;

use super::Violation;
use crate::generate::{macro_datum, SplitMix64};
use crate::quantile::{BlockVelocity, MacroDatum};
use crate::scalar::Scalar;
use crate::scene::{self, SceneKind};

type R = Result<(), Violation>;

/// The shipped scenes ([`scene::SHIPPED`]) checked, by name.
const SCENES: [&str; 3] = [
    "appendix-c-two-blocks",
    "riemann-compression",
    "riemann-expansion-affine",
];

/// Random macroscopic data ([`crate::generate::macro_datum`]) the §2.1
/// claims are also checked on, fewest blocks first (so that the first
/// witness found is a small one).
const RANDOM_DATA: u64 = 300;

/// A macroscopic datum as the `blocks` of a `[macro]` scene, for witnesses.
pub(super) fn render_blocks(datum: &MacroDatum) -> String {
    let blocks: Vec<String> = datum
        .blocks()
        .iter()
        .map(|b| {
            let velocity = match &b.velocity {
                BlockVelocity::Constant(c) => format!("\"{}\"", c.render()),
                BlockVelocity::Affine(a, v) => format!("[\"{}\", \"{}\"]", a.render(), v.render()),
            };
            format!(
                "{{ from = \"{}\", to = \"{}\", density = \"{}\", velocity = {velocity} }}",
                b.from.render(),
                b.to.render(),
                b.density.render()
            )
        })
        .collect();
    format!("blocks = [{}]", blocks.join(", "))
}

/// Every datum with its name and the particle numbers it is sampled at: the
/// shipped `[macro]` scenes at N = 2, 4, …, 256, then the random data at
/// N = 2 … 16, 32, 64.
fn data(id: &'static str) -> Result<Vec<(String, MacroDatum, Vec<usize>)>, Violation> {
    let mut out = Vec::new();
    for name in SCENES {
        let text = scene::shipped(name)
            .ok_or_else(|| Violation::new(id, format!("{name} is not a shipped scene")))?;
        let s = scene::parse(text).map_err(|e| Violation::new(id, format!("{name}: {e}")))?;
        let SceneKind::Macro { datum, .. } = s.kind else {
            return Err(Violation::new(id, format!("{name} is not a macro scene")));
        };
        out.push((name.to_string(), datum, vec![2, 4, 8, 16, 32, 64, 128, 256]));
    }
    let mut rng = SplitMix64::new(0x005E_ED21);
    let mut random: Vec<MacroDatum> = (0..RANDOM_DATA)
        .map(|_| macro_datum(&rng.bytes(40)))
        .collect();
    random.sort_by_key(|d| d.blocks().len());
    let ns: Vec<usize> = (2..=16).chain([32, 64]).collect();
    for datum in random {
        out.push((render_blocks(&datum), datum, ns.clone()));
    }
    Ok(out)
}

/// Runs `f` on the quantile sample `(X⁰(i/N), U⁰(i/N))` of every datum at
/// every N — the numbers §2.1 speaks of, admissible or not.
fn each_sample(
    id: &'static str,
    mut f: impl FnMut(&str, usize, &MacroDatum, &[BigRational], &[BigRational]) -> R,
) -> R {
    for (name, datum, ns) in data(id)? {
        for n in ns {
            let (x, u) = datum
                .quantiles(n)
                .map_err(|e| Violation::new(id, format!("{name}, N = {n}: {e}")))?;
            f(&name, n, &datum, &x, &u)?;
        }
    }
    Ok(())
}

/// `§2.1#mass-between-particles`: "By construction, one has
/// ∫_{x_i^0}^{x_{i+1}^0} ρ^0(x) dx = 1/N" and hence "x_{i+1}^0 − x_i^0 ≥ 1/N".
pub fn mass_between() -> R {
    const ID: &str = "thm:main#sampling-mass";
    each_sample(ID, |name, n, datum, x, _u| {
        let inv = BigRational::one() / BigRational::from_usize(n);
        for i in 0..n - 1 {
            let mass = datum.cdf(&x[i + 1]) - datum.cdf(&x[i]);
            let gap = x[i + 1].clone() - &x[i];
            if mass != inv || gap < inv {
                return Err(Violation::new(
                    ID,
                    format!(
                        "{name}, N = {n}, pair ({i}, {}): ∫ρ⁰ = {}, x[{}] − x[{i}] = {} (1/N = {})",
                        i + 1,
                        i + 1,
                        mass.render(),
                        gap.render(),
                        inv.render()
                    ),
                ));
            }
        }
        Ok(())
    })
}

/// `§2.1#contacts-equal-velocities`: "if two particles are in contact then
/// they have the same velocity" (from `hyp:u0`, `∂_x u⁰ = 0` in
/// `{ρ⁰ = 1}`): `u⁰_{i+1} = u⁰_i` whenever `x⁰_{i+1} − x⁰_i = 2r = 1/N`,
/// with `u⁰_i = U⁰(i/N)` as printed. `U⁰` is an `L²` class, so its value
/// at `i/N` is a choice: both one-sided readings are checked, the
/// left-continuous `U⁰(i/N−)` ([`MacroDatum::u0`]) and the
/// right-continuous `U⁰(i/N+)` ([`MacroDatum::u0_right`]), and the
/// statement is refuted only by a sample (one datum, one N) where both
/// readings put two touching particles at different velocities.
pub fn contacts_equal_velocities() -> R {
    const ID: &str = "thm:main#sampling-contacts";
    each_sample(ID, |name, n, datum, x, u| {
        let two_r = BigRational::one() / BigRational::from_usize(n);
        let right: Vec<BigRational> = (1..=n)
            .map(|i| datum.u0_right(&(BigRational::from_usize(i) * &two_r)))
            .collect();
        let first_failure = |v: &[BigRational]| {
            (0..n - 1).find(|&i| x[i + 1].clone() - &x[i] == two_r && v[i] != v[i + 1])
        };
        if let (Some(l), Some(r)) = (first_failure(u), first_failure(&right)) {
            return Err(Violation::new(
                ID,
                format!(
                    "{name}, N = {n}: with U⁰ left-continuous (u⁰_i = U⁰(i/N−)) pair ({l}, {}) touches with u = {} and {}; with U⁰ right-continuous (u⁰_i = U⁰(i/N+)) pair ({r}, {}) touches with u = {} and {}",
                    l + 1,
                    u[l].render(),
                    u[l + 1].render(),
                    r + 1,
                    right[r].render(),
                    right[r + 1].render()
                ),
            )
            .indices(&[l, l + 1, r, r + 1])
            .sides(
                "u⁰ of the touching pairs, left-continuous reading",
                format!("{}, {}", u[l].render(), u[l + 1].render()),
                "right-continuous reading",
                format!("{}, {}", right[r].render(), right[r + 1].render()),
            ));
        }
        Ok(())
    })
}

/// The corrected `§2.1#contacts-equal-velocities`: two particles in contact
/// bound an interval `(i/N, (i+1)/N)` of `{∂_w X⁰ = 1}`, on which `U⁰` is
/// constant by `hyp:u0`; sampled from inside that interval — `U⁰(i/N+)` and
/// `U⁰((i+1)/N−)`, the representative of `U⁰` that takes the congested
/// side's value at the ends of a congested stretch — the two velocities are
/// equal. (`U⁰` is only defined almost everywhere; the printed step
/// evaluates it at the end points, where it may jump.)
pub fn contacts_equal_velocities_inside() -> R {
    const ID: &str = "thm:main#sampling-contacts";
    each_sample(ID, |name, n, datum, x, _u| {
        let inv = BigRational::one() / BigRational::from_usize(n);
        for i in 0..n - 1 {
            if x[i + 1].clone() - &x[i] != inv {
                continue;
            }
            let w = BigRational::from_usize(i + 1) * &inv;
            let right_of_left = datum.u0_right(&w);
            let left_of_right = datum.u0(&(w.clone() + &inv));
            let middle = datum.u0(&(w + &inv / BigRational::from_i64(2)));
            if right_of_left != middle || left_of_right != middle {
                return Err(Violation::new(
                    ID,
                    format!(
                        "{name}, N = {n}: pair ({i}, {}) touches, but U⁰ is not constant inside: U⁰({}/N+) = {}, U⁰ at the midpoint = {}, U⁰({}/N−) = {}",
                        i + 1,
                        i + 1,
                        right_of_left.render(),
                        middle.render(),
                        i + 2,
                        left_of_right.render()
                    ),
                ));
            }
        }
        Ok(())
    })
}
