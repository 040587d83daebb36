//! The exact continuum solution: the isotonic regression and the particle limit.

use super::*;

/// A tiny deterministic generator (no dependency).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        self.0 >> 33
    }
    fn pick<T: Clone>(&mut self, v: &[T]) -> T {
        v[(self.next() % v.len() as u64) as usize].clone()
    }
}

/// A random datum satisfying `thm:main` (touching congested blocks share
/// their velocity).
fn random_datum(rng: &mut Lcg) -> MacroDatum {
    let b = 1 + (rng.next() % 4) as usize;
    let weights: Vec<i64> = (0..b).map(|_| 1 + (rng.next() % 4) as i64).collect();
    let total: i64 = weights.iter().sum();
    let mut blocks: Vec<Block> = Vec::new();
    let mut x = q(0, 1);
    for wgt in weights {
        let density = rng.pick(&[q(1, 1), q(1, 2), q(1, 3), q(2, 3), q(3, 4), q(1, 1)]);
        let gap = if blocks.is_empty() {
            q(0, 1)
        } else {
            rng.pick(&[q(0, 1), q(1, 8), q(1, 3), q(1, 2)])
        };
        x += gap.clone();
        let width = q(wgt, total) / &density;
        let v = |rng: &mut Lcg| q(rng.next() as i64 % 5 - 2, 2);
        let mut velocity = if density < q(1, 1) && rng.next() % 2 == 0 {
            BlockVelocity::Affine(v(rng), v(rng))
        } else {
            BlockVelocity::Constant(v(rng))
        };
        if let Some(prev) = blocks.last() {
            if gap == q(0, 1) && density == q(1, 1) && prev.density == q(1, 1) {
                velocity = BlockVelocity::Constant(prev.velocity_at(&prev.to));
            }
        }
        blocks.push(Block {
            from: x.clone(),
            to: &x + &width,
            density,
            velocity,
        });
        x += width;
    }
    MacroDatum::new(blocks).unwrap()
}

/// `f(t, w) = X⁰ + tU⁰ − w` as a profile (one segment per block), built
/// from `MacroDatum::x0`/`u0` alone (independently of the solver).
fn free_profile(datum: &MacroDatum, t: &Q) -> Profile<Q> {
    let breaks = datum.mass_breakpoints();
    let mut segments = Vec::new();
    for k in 0..datum.blocks().len() {
        let (a, b) = (breaks[k].clone(), breaks[k + 1].clone());
        let (p1, p2) = (&a + (&b - &a) / q(4, 1), &a + q(3, 4) * (&b - &a));
        let f = |w: &Q| datum.x0(w) + t * datum.u0(w) - w;
        let slope = (f(&p2) - f(&p1)) / (&p2 - &p1);
        let c = f(&p1) - &slope * &p1;
        segments.push(Segment {
            w0: a,
            w1: b,
            block: k,
            plateau: None,
            x: [c, slope],
            u: [q(0, 1), q(0, 1)],
            lambda: [q(0, 1), q(0, 1), q(0, 1)],
        });
    }
    Profile {
        t: t.clone(),
        segments,
        plateaus: vec![],
    }
}

/// `X(t) − w` of the solver, as a profile in f64.
fn shifted(p: &Profile<Surd>) -> Profile<f64> {
    let (mut f, _) = p.to_f64();
    for s in &mut f.segments {
        s.x[1] -= 1.0;
    }
    f
}

/// The solver's isotonic regression `f* = X(t) − w` against the discrete
/// isotonic regression of the cell averages `f_M` of `f`: since `P_C` is
/// 1-Lipschitz in `L²`, `‖P_C(f_M) − f*‖ ≤ ‖f_M − f‖` must hold — an
/// independent check of the exact GCM construction, on random data with
/// gaps, affine velocities, compressions (negative slopes) and congested
/// blocks. Also: `ρ ≤ 1`, `Λ ≥ 0`, `Λ` non-decreasing in time (`P ≥ 0`),
/// plateaus only grow, `Λ = 0` off the plateaus.
#[test]
fn continuum_is_the_isotonic_regression() {
    let mut rng = Lcg(20_240_607);
    let m = 256usize;
    let mm = Q::from_integer(m.into());
    for case in 0..40 {
        let datum = random_datum(&mut rng);
        let c = Continuum::new(&datum);
        let mut prev: Option<Profile<Surd>> = None;
        for t in [q(0, 1), q(1, 7), q(1, 2), q(1, 1), q(5, 2)] {
            let p = c.profile(&t).unwrap();
            // The cell averages of f (exact) and their discrete isotonic regression.
            let f = free_profile(&datum, &t);
            let mut avg = Vec::with_capacity(m);
            for i in 0..m {
                let (a, b) = (
                    Q::from_integer(i.into()) / &mm,
                    Q::from_integer((i + 1).into()) / &mm,
                );
                let mut integral = q(0, 1);
                for s in &f.segments {
                    let lo = if s.w0 > a { s.w0.clone() } else { a.clone() };
                    let hi = if s.w1 < b { s.w1.clone() } else { b.clone() };
                    if hi > lo {
                        let v = |w: &Q| &s.x[0] + &s.x[1] * w;
                        integral += (&hi - &lo) * (v(&lo) + v(&hi)) / q(2, 1);
                    }
                }
                avg.push(integral * &mm);
            }
            let iso = isotonic(&avg);
            let rhs = x_l2_squared(&avg, &f).to_f64_lossy();
            let iso_f: Vec<f64> = iso.iter().map(|v| v.to_f64_lossy()).collect();
            let lhs = x_l2_squared(&iso_f, &shifted(&p));
            assert!(
                lhs.sqrt() <= rhs.sqrt() + 1e-9,
                "case {case}, t = {t}: ‖iso(f_M) − f*‖ = {} > ‖f_M − f‖ = {}",
                lhs.sqrt(),
                rhs.sqrt()
            );
            let (pf, bound) = p.to_f64();
            assert!(bound < 1e-14);
            assert!(pf.max_density() <= 1.0 + 1e-12, "ρ ≤ 1 (lem:density)");
            // Λ ≥ 0 on the plateaus, = 0 off them, non-decreasing in t.
            for k in 0..=64 {
                let w = q(k, 64);
                let l = p.lambda_exact(&w).unwrap();
                assert_ne!(
                    l.signum(),
                    Ordering::Less,
                    "Λ < 0: case {case}, t = {t}, w = {w}"
                );
                if let Some(pp) = &prev {
                    let l0 = pp.lambda_exact(&w).unwrap();
                    assert_ne!(
                        l.cmp_exact(&l0),
                        Ordering::Less,
                        "Λ decreases in time (P < 0): case {case}, t = {t}, w = {w}"
                    );
                }
            }
            for s in p.segments.iter().filter(|s| s.plateau.is_none()) {
                assert!(s.lambda.iter().all(|c| c.signum() == Ordering::Equal));
            }
            // Plateaus only grow: each earlier plateau lies inside a later one.
            if let (Some(pp), false) = (&prev, t == q(0, 1)) {
                if pp.t > q(0, 1) {
                    for old in &pp.plateaus {
                        assert!(
                            p.plateaus.iter().any(|new| {
                                new.w0.cmp_exact(&old.w0) != Ordering::Greater
                                    && new.w1.cmp_exact(&old.w1) != Ordering::Less
                            }),
                            "a plateau shrank: case {case}, t = {t}"
                        );
                    }
                }
            }
            prev = Some(p);
        }
    }
}

/// The continuum against the particle trend: on every shipped scene
/// `‖X_N(t) − X(t)‖_{L²}` halves when N doubles (rate ≥ 0.8 × the measured
/// 1.0) at an off-grid time, and the exact profile is rational exactly for
/// the density-1 and symmetric scenes.
#[test]
fn continuum_is_the_particle_limit() {
    for (name, rational) in [
        ("appendix-c-two-blocks", true),
        ("riemann-compression", true),
        ("riemann-expansion-affine", false),
    ] {
        let sc = load(name);
        let datum = datum_of(&sc);
        let t = sc.t_end.clone().unwrap() * q(5, 7);
        let p = Continuum::new(&datum).profile(&t).unwrap();
        assert_eq!(p.is_rational(), rational, "{name}");
        let (pf, _) = p.to_f64();
        let mut last: Option<(usize, f64)> = None;
        for n in [64usize, 256, 1024] {
            let traj = Trajectory::new(datum.sample(n).unwrap());
            let s = traj.at(&t).unwrap();
            let x: Vec<f64> = s.positions.iter().map(|v| v.to_f64_lossy()).collect();
            let u: Vec<f64> = s.velocities.iter().map(|v| v.to_f64_lossy()).collect();
            let d = x_l2_squared(&x, &pf).sqrt();
            if let Some((n0, d0)) = last {
                let rate = -(d / d0).ln() / ((n as f64) / (n0 as f64)).ln();
                assert!(rate >= 0.8, "{name}: rate {rate} between N = {n0} and {n}");
            }
            assert!(
                u_l1(&u, &pf) < 4.0 / n as f64,
                "{name}: ‖U_N − U‖_L¹ at N = {n}"
            );
            last = Some((n, d));
        }
    }
}
