//! §3.1: the interpolation identities and the time derivatives.

use super::*;

/// The interpolation identities of §3.1, exactly, on every shipped scene
/// with N = 32 at every probe time.
#[test]
fn interpolation_identities() {
    for name in SCENES {
        let datum = datum_of(&load(name));
        let n = 32usize;
        let nn = Q::from_integer(n.into());
        let traj = Trajectory::new(datum.sample(n).unwrap());
        let delta = q(1, 3);
        let interp = Interpolations::new(&traj, &delta);
        for t in probe_times(&traj) {
            let s = interp.at(&t).unwrap();
            // The artificial particle (df:x0).
            assert_eq!(&s.x[1] - &s.x[0], nn.recip() + &delta);
            for i in 1..=n {
                let a = Q::from_integer((i - 1).into()) / &nn;
                let b = Q::from_integer(i.into()) / &nn;
                let m = (&a + &b) / q(2, 1);
                // df:XN, df:UN, df:LN: constant on ((i−1)/N, i/N].
                assert_eq!(s.x_n(&b).unwrap(), s.x[i]);
                assert_eq!(s.x_n(&m).unwrap(), s.x[i]);
                assert_eq!(s.u_n(&m).unwrap(), s.u[i]);
                assert_eq!(s.lambda_n(&m).unwrap(), s.lambda[i]);
                // X̃_N interpolates x_{i−1} … x_i; ∂_w X̃_N = N(x_i − x_{i−1}) ≥ 1.
                assert_eq!(s.x_tilde(&a).unwrap(), s.x[i - 1]);
                assert_eq!(s.x_tilde(&b).unwrap(), s.x[i]);
                let slope = (s.x_tilde(&b).unwrap() - s.x_tilde(&m).unwrap()) / (&b - &m);
                assert_eq!(slope, s.dw_x_tilde(i));
                assert!(slope >= q(1, 1), "∂_w X̃_N < 1 at {name}, t = {t}, i = {i}");
                // eq:PDE-Lagr-N-1: ∂_t X_N = U⁰_N − ∂_w Λ̃_N on each cell.
                assert_eq!(s.u[i], &s.u0[i] - s.dw_lambda_tilde(i));
                // Corrected eq:diffLambda_N: |Λ̃_N − Λ_N| ≤ |λ_i − λ_{i−1}|.
                let d = (s.lambda_tilde(&m).unwrap() - s.lambda_n(&m).unwrap()).abs();
                assert!(d <= (&s.lambda[i] - &s.lambda[i - 1]).abs());
            }
            // λ_0 = λ_N = 0.
            assert_eq!(s.lambda[0], q(0, 1));
            assert_eq!(s.lambda[n], q(0, 1));
            // prop:cvg1: ∫|X̃_N − X_N| = (x_N − x_0)/(2N), by Simpson on each
            // cell (exact: |X̃_N − x_i| is affine on the cell).
            let mut simpson = q(0, 1);
            for i in 1..=n {
                let a = Q::from_integer((i - 1).into()) / &nn;
                let b = Q::from_integer(i.into()) / &nn;
                let m = (&a + &b) / q(2, 1);
                let f = |w: &Q| (s.x_tilde(w).unwrap() - &s.x[i]).abs();
                simpson += (f(&a) + q(4, 1) * f(&m) + f(&b)) / (q(6, 1) * &nn);
            }
            assert_eq!(simpson, (&s.x[n] - &s.x[0]) / (q(2, 1) * &nn));
            assert_eq!(s.l1_x_tilde_minus_x_n(), simpson);
            assert_eq!(s.bv_x(), &s.x[n] - &s.x[0]);
            // ∫|Ũ_N − U_N| = (1/2N) Σ|u_i − u_{i−1}| (the printed
            // (1/2N)|u_N − u_0| holds only for monotone u).
            let mut su = q(0, 1);
            for i in 1..=n {
                let a = Q::from_integer((i - 1).into()) / &nn;
                let b = Q::from_integer(i.into()) / &nn;
                let m = (&a + &b) / q(2, 1);
                let f = |w: &Q| (s.u_tilde(w).unwrap() - &s.u[i]).abs();
                su += (f(&a) + q(4, 1) * f(&m) + f(&b)) / (q(6, 1) * &nn);
            }
            assert_eq!(su, s.l1_u_tilde_minus_u_n());
            // ρ̃_N ≤ 1, and the discrete Oleinik inequality (eq:Oleinik-tUN).
            assert!(s.max_density() <= q(1, 1));
            if t > q(0, 1) {
                assert!(s.oleinik_margin() < q(1, 1));
            }
            assert!(s.x_n(&q(-1, 1)).is_err());
            assert!(s.x_tilde(&q(2, 1)).is_err());
        }
    }
}

/// `∂_t X_N = U_N` between collisions, and `∂_t U_N + ∂_w P̃_N = 0` at
/// each collision (`lem:discPDE2`), with `P_N = ∂_t Λ_N` (`df:PN`).
#[test]
fn time_derivatives_and_pressure_atoms() {
    for name in SCENES {
        let datum = datum_of(&load(name));
        let n = 32usize;
        let nn = Q::from_integer(n.into());
        let traj = Trajectory::new(datum.sample(n).unwrap());
        let delta = q(1, 1);
        let interp = Interpolations::new(&traj, &delta);
        let pressure = interp.pressure();
        let mut times: Vec<Q> = vec![q(0, 1)];
        times.extend(traj.impulses().iter().map(|i| i.t.clone()));
        times.dedup();
        for w in times.windows(2) {
            // Between collisions: X_N(t₂) − X_N(t₁) = (t₂ − t₁) U_N(t₁).
            let (t1, t2) = (
                &w[0] + (&w[1] - &w[0]) / q(4, 1),
                &w[0] + q(3, 4) * (&w[1] - &w[0]),
            );
            let (s1, s2) = (interp.at(&t1).unwrap(), interp.at(&t2).unwrap());
            for i in 0..=n {
                assert_eq!(&s2.x[i] - &s1.x[i], (&t2 - &t1) * &s1.u[i], "{name}");
            }
        }
        let mut lambda = vec![q(0, 1); n + 1];
        for k in 0..pressure.atoms() {
            let tk = pressure.time(k).unwrap().clone();
            let before_t = times
                .iter()
                .rev()
                .find(|s| **s < tk)
                .map(|s| (s + &tk) / q(2, 1))
                .unwrap_or_else(|| q(0, 1));
            let before = interp.at(&before_t).unwrap();
            let after = interp.at(&tk).unwrap();
            let p = pressure.weights(k).unwrap();
            assert_eq!(p[0], q(0, 1));
            assert_eq!(p[n], q(0, 1));
            for i in 1..=n {
                // [u_i] = −N(p_i − p_{i−1}) = −∂_w P̃_N on cell i.
                assert_eq!(
                    &after.u[i] - &before.u[i],
                    -(&p[i] - &p[i - 1]) * &nn,
                    "{name}"
                );
                assert!(p[i] >= q(0, 1), "P_N ≥ 0 (prop:micro-pressure)");
                let m = (Q::from_integer((2 * i - 1).into())) / (q(2, 1) * &nn);
                assert_eq!(pressure.p_n(k, &m).unwrap(), p[i]);
                assert_eq!(
                    pressure.p_tilde(k, &m).unwrap(),
                    (&p[i] + &p[i - 1]) / q(2, 1)
                );
            }
            // ∫ P̃_N(t_k) = (1/N) Σ p_i.
            let sum = p.iter().fold(q(0, 1), |a, b| a + b) / &nn;
            assert_eq!(pressure.mass(k).unwrap(), sum);
            // Λ_N = Σ of the atoms up to t (λ_i only jumps at collisions).
            for (l, pi) in lambda.iter_mut().zip(&p) {
                *l += pi;
            }
            if pressure.time(k + 1) != Some(&tk) {
                assert_eq!(after.lambda[..n], lambda[..n], "{name} at t = {tk}");
            }
        }
        let end = times.last().cloned().unwrap() + q(1, 1);
        assert_eq!(
            pressure.mass_until(&end),
            interp.at(&end).unwrap().lambda_integral()
        );
    }
}
