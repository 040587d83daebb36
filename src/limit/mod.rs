//! The hydrodynamic limit `N → ∞` (paper §3, `thm:main` (iii), and
//! Appendix C), computed exactly where the data allow it.
//!
//! * [`sampling`] — the hypotheses of `thm:main` on a `[macro]` datum and of
//!   part (i) on its quantile sampling, each reported separately;
//! * [`interpolation`] — `X_N`, `U_N`, `Λ_N`, `X̃_N`, `Ũ_N`, `Λ̃_N`, `P̃_N`
//!   (with the artificial particle of `df:x0`) as functions of `(t, w)`,
//!   and `P_N` as a measure in time (§3.1, `ssec:interpol1`);
//! * [`continuum`] — the exact continuum solution `X(t) = P_K(X⁰ + tU⁰)`,
//!   `U(t) = P_{H_{X(t)}}(U⁰)` (`eq:velocity-projection`) and the
//!   multiplier `Λ` whose time derivative is the pressure, by the greatest
//!   convex minorant; numbers are rationals or quadratic surds ([`surd`]);
//! * [`eulerian`] — `ρ`, `ρu`, the pressure potential, density maps, the
//!   weak residuals of `eq:macro-euler`, `(1 − ρ)p` and the Oleinik
//!   inequality, for the particles and the continuum;
//! * [`poly`] — exact polynomials in one variable (product, derivative,
//!   integral), shared by Appendix C and the claims;
//! * [`converge`](mod@converge) — the convergence study across N (exact engine, then
//!   `f64`), fitted rates (its CSV files are written by the report layer);
//! * [`appendix_c`] — the two-block example with its sticky and rebound
//!   continuations, checked exactly as printed, and the ledger-ready checks
//!   that the projection principle selects the sticky one, which is the
//!   particle limit.
//!
//! Entry points for the command line: [`converge::converge`] (or
//! [`converge::converge_with_progress`]) with [`converge::ConvergeOptions`],
//! [`converge::ConvergenceReport::summary`] (and, in the report layer,
//! `report::converge::write_csv`);
//! [`eulerian::continuum_density_grid`] and
//! [`eulerian::particle_density_grid`] for heat maps;
//! [`eulerian::particle_pressure_atoms`] for pressure pictures.

pub mod appendix_c;
pub mod continuum;
pub mod converge;
pub mod eulerian;
pub mod interpolation;
pub mod poly;
pub mod sampling;
pub mod surd;

pub use converge::{converge, ConvergeOptions, ConvergenceReport};
