//! The Eulerian formulation: particle residuals, densities at most one, test functions.

use super::*;

/// The momentum-residual identity of `eulerian` against a direct exact
/// computation: `(1/N) Σ_i ∫ (d/dt φ(t, x_i)) u_i dt` over the collision-free
/// intervals plus `Σ_k Σ_i ([λ_i]_k/N) ∂_x φ(t_k, x_i)`; and the
/// complementarity pairing against the snapshots.
#[test]
fn particle_residual_identities() {
    for name in SCENES {
        let sc = load(name);
        let datum = datum_of(&sc);
        let t_end = sc.t_end.clone().unwrap();
        let c = Continuum::new(&datum);
        let (center, scale) = support_window(&c, &t_end);
        let tests = test_family(&t_end, &center, &scale);
        let n = 16usize;
        let nn = Q::from_integer(n.into());
        let traj = Trajectory::new(datum.sample(n).unwrap());
        let delta = q(1, 2);
        let fast = particle_momentum_residuals(&traj, &tests, &t_end).unwrap();
        let compl = particle_complementarity(&traj, &tests, &t_end, &delta);
        let mut times: Vec<Q> = vec![q(0, 1)];
        times.extend(
            traj.impulses()
                .iter()
                .map(|i| i.t.clone())
                .filter(|t| *t <= t_end),
        );
        times.push(t_end.clone());
        times.dedup();
        let pressure = PressureMeasure::new(&traj);
        for (k, f) in tests.iter().enumerate() {
            let mut direct = q(0, 1);
            for w in times.windows(2) {
                let (a, b) = (traj.at(&w[0]).unwrap(), traj.at(&w[1]).unwrap());
                for i in 0..n {
                    let xb = &a.positions[i] + (&w[1] - &w[0]) * &a.velocities[i];
                    direct += &a.velocities[i]
                        * (f.value(&w[1], &xb) - f.value(&w[0], &a.positions[i]))
                        / &nn;
                    assert_eq!(xb, b.positions[i]);
                }
            }
            let mut comp = q(0, 1);
            for j in 0..pressure.atoms() {
                let tk = pressure.time(j).unwrap().clone();
                if tk > t_end {
                    continue;
                }
                let p = pressure.weights(j).unwrap();
                let s = Snapshot::new(
                    &traj.at(&tk).unwrap(),
                    traj.data().velocities(),
                    delta.clone(),
                )
                .unwrap();
                for i in 1..n {
                    let dx = f.time_bump(&tk) * f.space(&s.x[i], 1);
                    direct += &p[i] / &nn * dx;
                    comp +=
                        &p[i] / &nn * (q(1, 1) - s.dw_x_tilde(i).recip()) * f.value(&tk, &s.x[i]);
                }
            }
            let tol = q(1, 1) / Q::from_integer(BigInt::from(1) << 200);
            assert!(
                (&fast.values[k] - &direct).abs() < tol,
                "{name}, φ {k}: {} vs {}",
                fast.values[k],
                direct
            );
            assert!((&compl.values[k] - &comp).abs() < tol, "{name}, φ {k}");
        }
        assert!(fast.rounding_bound < 1e-60);
        // The atoms of p_N = (Id, X_N)#P_N carry the whole pressure mass.
        let atoms = particle_pressure_atoms(&traj, &t_end);
        let mass = atoms.iter().fold(q(0, 1), |a, (_, _, m)| a + m);
        assert_eq!(mass, pressure.mass_until(&t_end));
    }
    let mut bad = test_family(&q(1, 1), &q(0, 1), &q(1, 1));
    bad[0].degree = 5;
    let traj = Trajectory::new(datum_of(&load("riemann-compression")).sample(8).unwrap());
    assert!(particle_momentum_residuals(&traj, &bad, &q(1, 1)).is_err());
}

/// `ρ ≤ 1` everywhere: the continuum and particle density maps on a grid,
/// and the continuum's Oleinik margin.
#[test]
fn densities_at_most_one() {
    for name in SCENES {
        let sc = load(name);
        let datum = datum_of(&sc);
        let t_end = sc.t_end.clone().unwrap();
        let c = Continuum::new(&datum);
        let (center, half) = support_window(&c, &t_end);
        let range = (&center - &half, &center + &half);
        let grid = continuum_density_grid(&c, &t_end, 9, (&range.0, &range.1), 200).unwrap();
        let traj = Trajectory::new(datum.sample(64).unwrap());
        let pgrid =
            particle_density_grid(&traj, &q(1, 1), &t_end, 9, (&range.0, &range.1), 200).unwrap();
        for g in [&grid, &pgrid] {
            assert_eq!(g.values.len(), 9);
            for row in &g.values {
                assert!(row.iter().all(|v| (0.0..=1.0).contains(v)), "{name}");
            }
            // The mass is 1: Σ ρ Δx ≈ 1 at every time.
            let dx = g.xs[1] - g.xs[0];
            for row in &g.values {
                let mass: f64 = row.iter().sum::<f64>() * dx;
                assert!((mass - 1.0).abs() < 0.15, "{name}: mass {mass}");
            }
        }
        for k in 1..=8 {
            let t = &t_end * q(k, 8);
            let p = c.profile(&t).unwrap();
            if let Some(e) = p.to_rational() {
                assert!(e.max_density() <= q(1, 1));
                assert!(oleinik_margin(&e, &t, &q(0, 1)).unwrap() < q(1, 1));
                // ρu = ρ·u, and the pressure potential vanishes where ρ < 1.
                for j in 0..=40 {
                    let x = &range.0 + (&range.1 - &range.0) * q(j, 40);
                    let rho = continuum_density(&e, &x);
                    let m = continuum_momentum(&e, &x);
                    match continuum_velocity(&e, &x) {
                        Some(u) => assert_eq!(m, &rho * u),
                        None => assert_eq!(m, q(0, 1)),
                    }
                    let lam = continuum_pressure_potential(&e, &x);
                    assert!(lam >= q(0, 1));
                    if rho < q(1, 1) {
                        assert_eq!(lam, q(0, 1), "(1 − ρ)p = 0: {name}, t = {t}, x = {x}");
                    }
                }
            }
        }
    }
}

/// The test functions themselves: compact support in time, `C³` bump.
#[test]
fn test_functions() {
    let f = TestFunction {
        t0: q(1, 4),
        t1: q(3, 4),
        center: q(0, 1),
        scale: q(1, 1),
        degree: 2,
    };
    assert_eq!(f.time_bump(&q(1, 4)), q(0, 1));
    assert_eq!(f.time_bump(&q(1, 8)), q(0, 1));
    assert_eq!(f.time_bump(&q(1, 2)), q(1, 1));
    assert_eq!(f.value(&q(1, 2), &q(3, 1)), q(9, 1));
    let h = q(1, 1000);
    let fd = (f.time_bump(&(q(1, 3) + &h)) - f.time_bump(&(q(1, 3) - &h))) / (q(2, 1) * &h);
    assert!((fd - f.time_bump_dt(&q(1, 3))).abs() < q(1, 1000));
}
