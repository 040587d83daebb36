//! §2.1, "Discretisation of the macroscopic initial datum", checked exactly
//! on the shipped `[macro]` scenes for N = 2, 4, …, 256.

use num_rational::BigRational;

use super::Violation;
use crate::quantile::MacroDatum;
use crate::scalar::Scalar;
use crate::scene::{self, SceneKind};

type R = Result<(), Violation>;

/// The shipped scenes ([`scene::SHIPPED`]) checked, by name.
const SCENES: [&str; 3] = [
    "appendix-c-two-blocks",
    "riemann-compression",
    "riemann-expansion-affine",
];

fn each_sample(
    id: &'static str,
    mut f: impl FnMut(&str, usize, &MacroDatum, &crate::InitialData<BigRational>) -> R,
) -> R {
    for name in SCENES {
        let text = scene::shipped(name)
            .ok_or_else(|| Violation::new(id, format!("{name} is not a shipped scene")))?;
        let s = scene::parse(text).map_err(|e| Violation::new(id, format!("{name}: {e}")))?;
        let SceneKind::Macro { datum, .. } = s.kind else {
            return Err(Violation::new(id, format!("{name} is not a macro scene")));
        };
        let mut n = 2;
        while n <= 256 {
            let data = datum
                .sample(n)
                .map_err(|e| Violation::new(id, format!("{name}, N = {n}: {e}")))?;
            f(name, n, &datum, &data)?;
            n *= 2;
        }
    }
    Ok(())
}

/// `§2.1#mass-between-particles`: "By construction, one has
/// ∫_{x_i^0}^{x_{i+1}^0} ρ^0(x) dx = 1/N" and hence "x_{i+1}^0 − x_i^0 ≥ 1/N".
pub fn mass_between() -> R {
    const ID: &str = "thm:main#sampling-mass";
    each_sample(ID, |name, n, datum, data| {
        let inv = BigRational::one() / BigRational::from_usize(n);
        let x = data.positions();
        for i in 0..n - 1 {
            let mass = datum.cdf(&x[i + 1]) - datum.cdf(&x[i]);
            let gap = x[i + 1].clone() - &x[i];
            if mass != inv || gap < inv {
                return Err(Violation::new(
                    ID,
                    format!(
                        "{name}, N = {n}, i = {}: ∫ρ⁰ = {}, x_{{i+1}} − x_i = {} (1/N = {})",
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
/// `{ρ⁰ = 1}`): `u⁰_{i+1} = u⁰_i` whenever `x⁰_{i+1} − x⁰_i = 2r = 1/N`.
pub fn contacts_equal_velocities() -> R {
    const ID: &str = "thm:main#sampling-contacts";
    each_sample(ID, |name, n, _datum, data| {
        let two_r = data.two_r();
        let (x, u) = (data.positions(), data.velocities());
        for i in 0..n - 1 {
            if x[i + 1].clone() - &x[i] == two_r && u[i] != u[i + 1] {
                return Err(Violation::new(
                    ID,
                    format!(
                        "{name}, N = {n}: particles {} and {} touch with u = {} and {}",
                        i + 1,
                        i + 2,
                        u[i].render(),
                        u[i + 1].render()
                    ),
                ));
            }
        }
        Ok(())
    })
}
