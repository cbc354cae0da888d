//! The heading uncertainty's model ((H1)-(H5)): its equations, and how it follows the
//! field's trust, the turning and rest.

use super::*;

/// (H1) alone, without noise or walk, is a bias error of σ_b integrated: σ_b t; (H3)
/// alone settles to σ_m whatever the sample rate; (H2) to σ_r likewise.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_heading_model_steps_its_equations() {
    let s = RobustSettings { gyro_noise: 0.0, bias_walk: 0.0, ..Default::default() };
    let mut p = HeadingVariance::start(&s);
    for _ in 0..1000 {
        p.gyro_step(DT, 0.0, &s);
    }
    let t = 1000.0 * DT;
    assert!((p.p_ee.sqrt() - s.bias_sigma * t).abs() < 1e-12 * t, "{p:?}");
    assert!((p.p_eb - s.bias_sigma * s.bias_sigma * t).abs() < 1e-15 * t);
    for dt in [1e-3, 1e-2, 0.1] {
        let k = lp_gain(dt, s.tau_mag);
        let mut h = HeadingVariance { p_ee: 1.0, p_eb: 0.0, p_bb: 1.0, innov: 0.0, evidence: 0.0 };
        for _ in 0..(100.0 * s.tau_mag / dt) as usize {
            h.heading_step(k, s.mag_heading_sigma);
            h.bias_step(lp_gain(dt, s.bias_tau_rest), s.bias_sigma_rest);
        }
        assert!((h.p_ee.sqrt() - s.mag_heading_sigma).abs() < 1e-9, "{dt} {h:?}");
        assert!((h.p_bb.sqrt() - s.bias_sigma_rest).abs() < 1e-9, "{dt} {h:?}");
    }
    // A first field (gain 1) sets σ_m at once; (H4) caps a heading that is anything.
    p.heading_step(1.0, s.mag_heading_sigma);
    assert_eq!((p.p_ee, p.p_eb), (s.mag_heading_sigma * s.mag_heading_sigma, 0.0));
    for _ in 0..100_000 {
        p.gyro_step(1.0, 0.0, &s);
    }
    assert_eq!(p.p_ee, HEADING_VAR_MAX);
    assert!(p.valid());
}

/// Simulated truth: a sensor turning about the vertical with a vertical gyro bias of
/// 0.3 °/s (within the default σ_b) and no rest. While a magnet in the room is
/// rejected the heading drifts as b t and the reported σ grows every step, covering
/// the error; once the field is trusted again σ falls back to its floor (σ_m and the
/// lag b τ_mag the unlearned bias leaves, also covered).
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_heading_uncertainty_grows_while_the_field_is_distrusted() {
    let s = RobustSettings { hard_iron_time: 0.0, ..Default::default() };
    let mut f = Robust::new(s);
    let (rate, bias) = (0.5, 0.3f64.to_radians());
    let up = Vec3::new(0.0, 0.0, 1.0);
    let truth = |t: f64| Quat::from_axis_angle(up, rate * t);
    let error = |f: &Robust, t: f64| wrap(heading(f.quaternion()) - heading(truth(t))).abs();
    let mut t = 0.0;
    let step = |f: &mut Robust, magnet: Vec3, t: &mut f64| {
        *t += DT;
        let q = truth(*t);
        let m = q.rotate_inverse(FIELD + magnet);
        f.update(DT, up * (rate + bias), Some(q.rotate_inverse(G)), Some(m)).unwrap();
    };
    for _ in 0..3000 {
        step(&mut f, Vec3::ZERO, &mut t);
    }
    let settled = f.heading_sigma();
    assert!(!f.mag_disturbed() && error(&f, t) < 2.0 * settled, "{} {settled}", error(&f, t));
    // Without a rest the floor is σ_m and the lag σ_b τ_mag of an unlearned bias
    // (nearly reached after 30 s, 3.3 τ_mag).
    let floor = s.mag_heading_sigma.hypot(s.bias_sigma * s.tau_mag);
    assert!((settled - floor).abs() < 0.05 * floor, "{settled} {floor}");
    let (mut last, start) = (settled, error(&f, t));
    // 15 s: a field that stays different for 20 s while turning is taken as the
    // place's (`new_field`).
    for _ in 0..1500 {
        step(&mut f, Vec3::new(30.0, 0.0, 0.0), &mut t);
        assert!(f.mag_disturbed());
        let sigma = f.heading_sigma();
        assert!(sigma > last, "{sigma} after {last}");
        assert!(error(&f, t) < 2.0 * sigma, "error {} sigma {sigma}", error(&f, t));
        last = sigma;
    }
    let drift = error(&f, t) - start;
    assert!(last > 1.5 * settled && drift > 0.9 * bias * 15.0, "{last} {settled} {drift}");
    for _ in 0..6000 {
        step(&mut f, Vec3::ZERO, &mut t);
        assert!(error(&f, t) < 2.0 * f.heading_sigma().max(settled));
    }
    assert!((f.heading_sigma() - settled).abs() < 0.05 * settled, "{} {settled}", f.heading_sigma());
}

/// (H1) and (H3)'s evidence: the same turning sensor reports a larger σ when the
/// field it uses is off the reference in norm and dip (a disturbance the tests let
/// through) than in a clean field, and when it turns faster; without the magnetometer
/// σ grows at every step, and a clean field brings it back to the clean floor.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_heading_uncertainty_follows_the_fields_deviation_and_the_turning() {
    let s = RobustSettings { hard_iron_time: 0.0, ..Default::default() };
    let up = Vec3::new(0.0, 0.0, 1.0);
    let settle = |rate: f64, disturbance: Vec3| {
        let mut f = Robust::new(s);
        let turning = move |t: f64| (Quat::from_axis_angle(up, rate * t), up * rate, Vec3::ZERO);
        // A rest teaches the bias (else its lag σ_b τ_mag hides the rest); 10 s clean
        // (the reference), then 30 s in the given field.
        let still = |_: f64| (Quat::IDENTITY, Vec3::ZERO, Vec3::ZERO);
        run(&mut f, 20.0, still, |_, q| Some(q.rotate_inverse(FIELD)));
        run(&mut f, 10.0, turning, |_, q| Some(q.rotate_inverse(FIELD)));
        run(
            &mut f,
            30.0,
            move |t| turning(t + 10.0),
            move |_, q| Some(q.rotate_inverse(FIELD + disturbance)),
        );
        f
    };
    let clean = settle(0.5, Vec3::ZERO);
    // Norm 6 % low and dip 6.9 deg shallower: within the tests (10 %, 10 deg).
    let off = settle(0.5, Vec3::new(3.0, 3.0, 5.0));
    assert!(!off.mag_disturbed());
    let (c, o) = (clean.heading_sigma(), off.heading_sigma());
    assert!(o > 1.15 * c, "deviation: {o} vs clean {c}");
    let fast = settle(3.0, Vec3::ZERO).heading_sigma();
    assert!(fast > 1.1 * c, "turning fast: {fast} vs {c}");
    // Without the magnetometer (6D) σ grows at every step; a clean field brings it back.
    let mut f = clean;
    let turning = |t: f64| (Quat::from_axis_angle(up, 0.5 * t), up * 0.5, Vec3::ZERO);
    let mut last = f.heading_sigma();
    for i in 0..1000 {
        let (q, w, _) = turning(40.0 + i as f64 * DT);
        f.update(DT, w, Some(q.rotate_inverse(G)), None).unwrap();
        assert!(f.heading_sigma() > last);
        last = f.heading_sigma();
    }
    assert!(last > 1.3 * c, "{last} {c}");
    // Back to the clean floor, which the bias walk since the rest has raised a little.
    run(&mut f, 60.0, move |t| turning(t + 50.0), |_, q| Some(q.rotate_inverse(FIELD)));
    assert!(f.heading_sigma() < 1.2 * c && f.heading_sigma() < 0.8 * last, "{} {c}", f.heading_sigma());
}

/// Every path that changes the heading or the settings moves the covariance with it:
/// the bias walk up to its cap, a host's orientation (exact), a gap re-acquired with
/// the magnetometer (σ_m) or without (anything), a larger σ_b (added) or a smaller
/// one (capped), a reference field replaced by a far one (anything, then averaged).
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_heading_covariance_follows_every_path() {
    let s = RobustSettings { gyro_noise: 0.0, ..Default::default() };
    let mut p = HeadingVariance {
        p_ee: 0.0,
        p_eb: 0.0,
        p_bb: s.bias_sigma_rest * s.bias_sigma_rest,
        innov: 0.0,
        evidence: 0.0,
    };
    let t = 100.0;
    p.gyro_step(t, 0.0, &s);
    let walked = s.bias_sigma_rest * s.bias_sigma_rest + s.bias_walk * s.bias_walk * t;
    assert!(walked < s.bias_sigma * s.bias_sigma && (p.p_bb - walked).abs() < 1e-18, "{p:?}");
    p.gyro_step(1e6, 0.0, &s);
    assert_eq!(p.p_bb, s.bias_sigma * s.bias_sigma);
    assert!(p.valid());

    let mut f = Robust::new(s);
    let up = Vec3::new(0.0, 0.0, 1.0);
    let turning = |t: f64| (Quat::from_axis_angle(up, 0.5 * t), up * 0.5, Vec3::ZERO);
    run(&mut f, 10.0, turning, |_, q| Some(q.rotate_inverse(FIELD)));
    let settled = f.heading_sigma();
    f.set_quaternion(f.quaternion());
    assert_eq!(f.heading_sigma(), 0.0);
    let (q, a) = (f.quaternion(), f.quaternion().rotate_inverse(G));
    let gap = |mag: Option<Vec3>| crate::filters::pipeline::estimator::Reacquisition {
        keep: q,
        with_mag: None,
        dt: 1.0,
        gyro: Vec3::ZERO,
        accel: a,
        mag,
        still: None,
    };
    assert!(f.reacquire(&gap(Some(q.rotate_inverse(FIELD)))));
    assert_eq!(f.heading_sigma(), s.mag_heading_sigma);
    assert!(!f.reacquire(&gap(None)));
    assert_eq!(f.heading_sigma() * f.heading_sigma(), HEADING_VAR_MAX);

    let p_bb = f.heading_var.p_bb;
    let wider = RobustSettings { bias_sigma: 2.0 * s.bias_sigma, ..s };
    f.heading_var.configure(&s, &wider);
    assert!((f.heading_var.p_bb - (p_bb + 3.0 * s.bias_sigma * s.bias_sigma)).abs() < 1e-18);
    let narrower = RobustSettings { bias_sigma: 0.1 * s.bias_sigma, ..s };
    f.heading_var.configure(&wider, &narrower);
    assert_eq!(f.heading_var.p_bb, narrower.bias_sigma * narrower.bias_sigma);
    assert!(f.heading_var.valid());

    // A far field (half as strong again) that stays while turning replaces the
    // reference after MAG_NEW_TIME: the heading learned from the old one is anything.
    let mut f = Robust::new(s);
    run(&mut f, 10.0, turning, |_, q| Some(q.rotate_inverse(FIELD)));
    let mut peak: f64 = 0.0;
    for i in 0..3000 {
        let t = 10.0 + i as f64 * DT;
        let (q, w, _) = turning(t);
        f.update(DT, w, Some(q.rotate_inverse(G)), Some(q.rotate_inverse(FIELD * 1.5))).unwrap();
        peak = peak.max(f.heading_sigma());
    }
    assert!(peak > 0.5 && f.heading_sigma() < 2.0 * settled, "{peak} {} {settled}", f.heading_sigma());
}

/// A rest teaches the bias, and the heading uncertainty then grows at σ_r, not σ_b.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_rest_slows_the_growth() {
    let s = RobustSettings::default();
    let grow = |rest: bool| {
        let mut f = Robust::new(s);
        let still = |_: f64| (Quat::IDENTITY, Vec3::ZERO, Vec3::ZERO);
        if rest {
            run(&mut f, 20.0, still, |_, _| None);
            assert!(f.at_rest());
        }
        let before = f.heading_sigma();
        let turning = |t: f64| {
            let w = Vec3::new(0.0, 0.0, 0.5);
            (Quat::from_axis_angle(w.normalized(), 0.5 * t), w, Vec3::ZERO)
        };
        run(&mut f, 30.0, turning, |_, _| None);
        f.heading_sigma() - before
    };
    let (with, without) = (grow(true), grow(false));
    assert!(with < 0.2 * without, "{with} {without}");
    assert!((without - s.bias_sigma * 30.0).abs() < 0.05 * without, "{without}");
}
