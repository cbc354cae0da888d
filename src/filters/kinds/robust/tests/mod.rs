use super::*;

mod heading_uncertainty;

const G: Vec3 = Vec3::new(0.0, 0.0, 9.81);
/// An earth field in ENU (µT): north and down, dip about 63°.
const FIELD: Vec3 = Vec3::new(0.0, 20.0, -40.0);
const DT: f64 = 0.01;

/// Wraps an angle into (-π, π].
fn wrap(a: f64) -> f64 {
    use core::f64::consts::{PI, TAU};
    if a > PI {
        a - TAU
    } else if a <= -PI {
        a + TAU
    } else {
        a
    }
}

/// The readable heading step of [`Turn`]: δ itself, `atan2` and `sincos`.
fn readable_heading_step(delta: f64, k: f64, f_e: Vec3) -> Turn {
    let target = libm::atan2(f_e.x, f_e.y);
    let delta = wrap(delta + k * wrap(target - delta));
    let (s, c) = libm::sincos(0.5 * delta);
    Turn { c, s }
}

/// [`Turn::corrected`] against the readable step, from random headings, fields and
/// gains: fields near the turned north (the series), anywhere (libm), and the first
/// sample's gain 1 (a turn of up to π). The pairs agree as rotations within 4 ulp
/// (`c ≥ 0` leaves the sign free only at δ = ±π) and the error within 4 ulp of π.
#[test]
#[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
fn turn_is_the_readable_heading_step() {
    use core::f64::consts::PI;
    let mut u = crate::math::test_uniform(97);
    let mut series = 0;
    for i in 0..40000 {
        let delta = if i % 97 == 0 { PI } else { PI * u() };
        let (s, c) = libm::sincos(0.5 * delta);
        let turn = Turn { c, s };
        // The field's azimuth: within 1/4 rad of the turned north, or anywhere.
        let azimuth = if i % 2 == 0 { delta + u() / 4.0 } else { PI * u() };
        let (h, z) = (20.0 + 30.0 * u(), 40.0 * u());
        let f_e = Vec3::new(h * libm::sin(azimuth), h * libm::cos(azimuth), z);
        let k = match i % 4 {
            0 => 1.0,
            1 => 0.5 * (u() + 1.0),
            _ => 10f64.powf(-5.0 + 4.0 * 0.5 * (u() + 1.0)),
        };
        let e = turn.error(f_e);
        let want_e = wrap(libm::atan2(f_e.x, f_e.y) - delta);
        let de = (e - want_e).abs();
        assert!(de.min(2.0 * PI - de) <= 4.0 * f64::EPSILON * PI, "{delta} {f_e:?}: {e} vs {want_e}");
        series += usize::from(4.0 * libm::tan(e).abs() < 0.99 && e.abs() < 1.0);
        let got = turn.corrected(k, f_e);
        let want = readable_heading_step(delta, k, f_e);
        let apart = |a: Turn, b: Turn| (a.c - b.c).abs().max((a.s - b.s).abs());
        let d = apart(got, want).min(apart(got, Turn { c: -want.c, s: -want.s }));
        assert!(d <= 4.0 * f64::EPSILON, "{delta} {f_e:?} {k}: {got:?} vs {want:?}");
        assert!(got.valid(), "{got:?}");
    }
    assert!(series > 15000, "{series} steps took the series");
}

/// [`Turn::times`] gives the general Hamilton product's bits.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_turn_product_is_the_hamilton_product() {
    let mut u = crate::math::test_uniform(6);
    for _ in 0..1000 {
        let (s, c) = libm::sincos(3.0 * u());
        let turn = Turn { c: c.abs(), s };
        let q = Quat::new(u(), u(), u(), u()).normalized();
        let (got, want) = (turn.times(q), turn.quat() * q);
        assert_eq!(
            [got.w, got.x, got.y, got.z].map(f64::to_bits),
            [want.w, want.x, want.y, want.z].map(f64::to_bits),
            "{turn:?} {q:?}"
        );
    }
}

/// A compensated field larger than any reading (readings near the bound, a hard-iron
/// offset opposite to them, the widest norm test) is used, and the reference norm's
/// low-pass stays within what `valid` accepts: the state still saves and loads.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_large_compensated_field_keeps_the_reference_valid() {
    use crate::filters::state::holds::MAG_NORM_MAX;
    use crate::filters::MAX_MAG;
    let settings = RobustSettings { mag_norm_th: 10.0, ..RobustSettings::default() };
    let mut f = Robust::new(settings);
    let m = Vec3::new(0.0, 0.99 * MAX_MAG, -0.99 * MAX_MAG);
    (f.mag_count, f.ref_norm, f.ref_dip) = (5, 0.9 * MAG_NORM_MAX, dip(m));
    (f.hard_iron_on, f.hard_iron) = (true, m * -1.0);
    assert!(f.valid());
    assert!(f.correct_heading(DT, m, Quat::IDENTITY), "the compensated field 2m is used");
    assert_eq!(f.ref_norm, MAG_NORM_MAX);
    assert!(f.valid(), "{f:?}");
}

/// A state loaded with its three output factors at `holds::unit`'s limit (|·|² =
/// 1 ± 0.99e-9) stays one `valid` accepts through gyroscope-only steps,
/// which leave q_inc and q_δ as loaded and multiply them into the output without a
/// normalisation: its blob still loads.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn factors_at_the_unit_limit_leave_a_valid_output() {
    for e in [0.99e-9f64, -0.99e-9] {
        let k = (1.0 + e).sqrt();
        let mut f = Robust::new(RobustSettings::default());
        let q_inc = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.1);
        let (s, c) = libm::sincos(0.4);
        (f.q_inc, f.turn) = (q_inc.scale(k), Turn { c: c * k, s: s * k });
        f.q_gyr = Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), 0.2).scale(k);
        f.q = f.turn.times(f.q_inc * f.q_gyr);
        assert!(f.valid(), "{e}: loaded state {f:?}");
        for _ in 0..100 {
            f.update(DT, Vec3::new(0.1, -0.2, 0.3), None, None).unwrap();
            assert!(f.valid(), "{e}: {f:?}");
        }
        // Past what `holds::unit` allows a single quaternion: the case this covers.
        assert!((f.q.norm_squared() - 1.0).abs() > 1.5e-9, "{e}: {}", f.q.norm_squared() - 1.0);
    }
}

/// A million small corrections keep the pair unit to rounding: each step's Newton
/// normalisation takes out what the products add.
#[test]
#[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
fn the_turn_stays_unit() {
    let mut u = crate::math::test_uniform(5);
    let mut turn = Turn::IDENTITY;
    let mut worst = 0.0f64;
    for _ in 0..1_000_000 {
        let f_e = Vec3::new(20.0 * u(), 20.0 + u(), -40.0);
        turn = turn.corrected(0.01 * (u() + 1.0), f_e);
        worst = worst.max((turn.c * turn.c + turn.s * turn.s - 1.0).abs());
    }
    assert!(worst <= 4.0 * f64::EPSILON, "{worst:e}");
}

fn filter(settings: RobustSettings, q: Quat) -> Robust {
    let mut f = Robust::new(settings);
    f.set_quaternion(q);
    f
}

/// Feeds `seconds` of samples of the true orientation `q(t)` with rate `w(t)`.
fn run(
    f: &mut Robust,
    seconds: f64,
    mut truth: impl FnMut(f64) -> (Quat, Vec3, Vec3),
    mag: impl Fn(f64, Quat) -> Option<Vec3>,
) {
    let n = (seconds / DT).round() as usize;
    for i in 0..n {
        let t = i as f64 * DT;
        let (q, w, lin) = truth(t);
        let accel = q.rotate_inverse(G + lin);
        f.update(DT, w, Some(accel), mag(t, q)).unwrap();
    }
}

fn heading(q: Quat) -> f64 {
    q.to_euler().yaw
}

fn inclination(est: Quat, truth: Quat) -> f64 {
    let up = Vec3::new(0.0, 0.0, 1.0);
    let a = est.rotate_inverse(up);
    let b = truth.rotate_inverse(up);
    libm::atan2(a.cross(b).norm(), a.dot(b))
}

/// [`to_up`] is `Quat::from_two_vectors(a, UP)` bit for bit (zeros compared by value)
/// over random directions, including near and at half a turn.
#[test]
#[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
fn to_up_is_from_two_vectors_to_up() {
    let mut u = crate::math::test_uniform(23);
    for i in 0..20000 {
        let a = match i {
            0 => Vec3::new(0.0, 0.0, -9.81),
            1 => Vec3::new(1e-7, 0.0, -9.81),
            2 => Vec3::new(0.0, 0.0, 3.0),
            _ => Vec3::new(u(), u(), u()) * (10.0 * (u() + 1.0)),
        };
        let (got, want) = (to_up(a), Quat::from_two_vectors(a, UP));
        for (x, y) in [(got.w, want.w), (got.x, want.x), (got.y, want.y), (got.z, want.z)] {
            assert!(x == y, "{a:?}: {got:?} vs {want:?}");
        }
    }
}

/// A magnitude at the ends or in the middle of `[0, bound)`, of either sign when
/// `signed`: what the randomised tests below put in states, settings and samples.
fn extreme(u: &mut dyn FnMut() -> f64, bound: f64, signed: bool) -> f64 {
    let r = 0.5 * (u() + 1.0);
    let x = match (4.0 * (u() + 1.0)) as usize {
        0 => 0.0,
        1 => f64::MIN_POSITIVE,
        2 => bound * (1.0 - 1e-9),
        3 => bound * 0.999,
        4 => bound * r,
        5 => bound * 10f64.powf(-15.0 * r),
        6 => bound * 10f64.powf(-300.0 * r),
        _ => bound * 1e-6 * r,
    };
    if signed && u() < 0.0 {
        -x
    } else {
        x
    }
}

/// Writes a value at the ends of its range into every field a snapshot holds, in the
/// codec's order: `bounds[i]` is the i-th number's bound, negative for one that is
/// never negative.
struct Forge<'a, U: FnMut() -> f64> {
    u: &'a mut U,
    bounds: &'a [f64],
    i: usize,
}

impl<U: FnMut() -> f64> Codec for Forge<'_, U> {
    fn u64(&mut self, v: &mut u64) {
        // Only `mag_count` (bools are below).
        *v = [0, 1, 1000, u32::MAX as u64][(2.0 * ((self.u)() + 1.0)) as usize];
    }
    fn f64(&mut self, v: &mut f64) {
        let b = self.bounds[self.i];
        *v = extreme(self.u, b.abs(), b > 0.0);
        self.i += 1;
    }
    fn bool(&mut self, v: &mut bool) {
        *v = (self.u)() < 0.0;
    }
    fn fail(&mut self) {
        unreachable!()
    }
}

/// The argument at [`Robust::update`], tried: states at the ends of what `valid`
/// accepts (every field forged, then the quaternions, the low-passes' coefficients and
/// the covariances made consistent), settings at the ends of their ranges, and
/// samples at the ends of the runner's bounds (dt from 1e-9 to 1e6 s, each component
/// under its bound, squared norms from `f64::MIN_POSITIVE`), stepped 20 times from each
/// of 4,000 states: every number of the state stays finite after every step.
#[test]
#[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
fn no_accepted_sample_makes_the_step_non_finite() {
    use crate::filters::params::{Settings, MAX_PARAMS};
    use crate::filters::{MAX_ACCEL, MAX_DT, MAX_GYRO, MAX_MAG, MIN_DT};
    use core::f64::consts::PI;
    let mut u = crate::math::test_uniform(31);
    let (rate, acc, mag) = (10.0 * MAX_GYRO, 10.0 * MAX_ACCEL, 10.0 * MAX_MAG);
    let norm = 3f64.sqrt() * MAX_MAG;
    #[rustfmt::skip]
    let bounds = [
        1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, // q_gyr, q_inc, q_δ, q
        rate, rate, rate, // bias
        1.0, 1.0, 1.0, 1.0, 1.0, 1.0, acc, acc, acc, 1e12, 1e12, 1e12, -1e6, // low-pass
        rate, rate, rate, acc, acc, acc, acc, acc, acc, acc, acc, acc, -1e300, // rest detector
        -norm, PI, mag, mag, mag, -(2.0 * mag) * (2.0 * mag), -1e300, mag, mag, mag, // magnetic
        -MAG_CONFIRM_TIME, -norm, PI, -1e300, // reference confirmation, candidate
        1.0, 1.0, 1.0, // heading covariance
        PI, -PI * PI, // innovation low-pass and evidence (H5)
        // The motion bias filter: four low-passes, its covariance, the window's sums.
        1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1e12, 1e12, 1e12, -1e6,
        1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1e12, 1e12, 1e12, -1e6,
        1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1e12, 1e12, 1e12, -1e6,
        1.0, 1.0, 1.0, 1.0, 1.0, 1.0, rate, rate, rate, 1e12, 1e12, 1e12, -1e6,
        rate * rate, rate * rate, rate * rate, rate * rate, rate * rate, rate * rate, rate * rate,
        rate * rate, rate * rate,
        16.0, 16.0, 16.0, -8e6, -1e300, -1e6, -8e6,
    ];
    let unit = |u: &mut dyn FnMut() -> f64| Quat::new(u(), u(), u(), u()).normalized();
    let reading = |u: &mut dyn FnMut() -> f64, bound: f64| loop {
        let mut c = || extreme(&mut *u, bound, true);
        let v = Vec3::new(c(), c(), c());
        if v.norm_squared() >= f64::MIN_POSITIVE {
            return v;
        }
    };
    for case in 0..4000 {
        let mut slots = [0.0; MAX_PARAMS];
        RobustSettings::default().write_slots(&mut slots);
        for p in PARAMS {
            let r = 0.5 * (u() + 1.0);
            slots[p.id as usize] = match (5.0 * r) as usize {
                0 => p.min,
                1 => p.max,
                2 if p.zero_off => 0.0,
                3 if p.min > 0.0 => p.min * (p.max / p.min).powf(0.5 * (u() + 1.0)),
                _ => p.default,
            };
        }
        let settings = RobustSettings::from_slots(&slots);
        let mut f = Robust::new(settings);
        f.codec(&mut Forge { u: &mut u, bounds: &bounds, i: 0 });
        (f.q_gyr, f.q_inc, f.q) = (unit(&mut u), unit(&mut u), unit(&mut u));
        let (s, c) = libm::sincos(PI * u());
        f.turn = Turn { c: c.abs(), s };
        let dt0 = MIN_DT * (MAX_DT / MIN_DT).powf(0.5 * (u() + 1.0));
        f.acc_lp.coefficients(dt0, settings.tau_acc);
        f.motion.make_consistent(dt0, settings.tau_acc, &mut u);
        let h = &mut f.heading_var;
        h.p_ee = extreme(&mut u, HEADING_VAR_MAX, false);
        h.p_bb = extreme(&mut u, rate * rate, false);
        h.p_eb = (h.p_ee * h.p_bb).sqrt() * (0.5 * (u() + 1.0));
        assert!(f.valid(), "case {case}: forged state not valid: {f:?}");
        for _ in 0..20 {
            let dt = match (4.0 * (u() + 1.0)) as usize {
                0 => MIN_DT,
                1 => MAX_DT,
                _ => MIN_DT * (MAX_DT / MIN_DT).powf(0.5 * (u() + 1.0)),
            };
            let gyro = Vec3::new(
                extreme(&mut u, MAX_GYRO, true),
                extreme(&mut u, MAX_GYRO, true),
                extreme(&mut u, MAX_GYRO, true),
            );
            let accel = (u() < 0.6).then(|| reading(&mut u, MAX_ACCEL));
            let m = (u() < 0.6).then(|| reading(&mut u, MAX_MAG));
            let before = f.clone();
            f.step(dt, gyro, accel, m);
            let mut check = Finite(true);
            f.codec(&mut check);
            assert!(check.0, "case {case}: dt {dt}, {gyro:?}, {accel:?}, {m:?} from {before:?} gave {f:?}");
        }
    }
}

/// A codec that finds whether every number is finite.
struct Finite(bool);

impl Codec for Finite {
    fn u64(&mut self, _: &mut u64) {}
    fn f64(&mut self, v: &mut f64) {
        self.0 &= v.is_finite();
    }
    fn fail(&mut self) {}
}

/// Readings beyond the runner's bounds that leave the orientation finite, driven into
/// the core directly: NaN, overflowing and infinite magnetometer readings while the
/// field is disturbed. The hard-iron estimate starts over, and good samples then leave
/// a state `valid` accepts (a NaN kept in the estimate would fail it).
#[test]
#[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
fn an_absurd_magnetometer_reading_leaves_no_nan_behind() {
    let still = |_: f64| (Quat::IDENTITY, Vec3::ZERO, Vec3::ZERO);
    let mut f = filter(RobustSettings::default(), Quat::IDENTITY);
    run(&mut f, 2.0, still, |_, q| Some(q.rotate_inverse(FIELD)));
    for bad in
        [Vec3::new(f64::NAN, 0.0, 0.0), Vec3::new(1e200, 1e200, 1e200), Vec3::new(f64::INFINITY, 0.0, 1.0)]
    {
        run(&mut f, 0.5, still, |_, q| Some(q.rotate_inverse(FIELD * 3.0)));
        for _ in 0..3 {
            assert!(f.update(DT, Vec3::ZERO, Some(G), Some(bad)).is_some());
        }
        run(&mut f, 0.5, still, |_, q| Some(q.rotate_inverse(FIELD * 3.0)));
        run(&mut f, 0.5, still, |_, q| Some(q.rotate_inverse(FIELD)));
        assert!(f.valid(), "{bad:?}: {f:?}");
    }
}

/// The guard: readings beyond the runner's bounds that do make the step non-finite
/// return `None`, keep the orientation from before the step, the settings and the
/// bias, and good samples then bring the filter back.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_non_finite_step_starts_over_from_the_orientation_before_it() {
    let q = Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalized(), 0.7);
    let mut f = filter(RobustSettings::default(), q);
    f.bias = Vec3::new(0.01, -0.02, 0.005);
    assert!(f.update(DT, Vec3::new(f64::NAN, 0.0, 0.0), Some(q.rotate_inverse(G)), None).is_none());
    assert_eq!(f.quaternion(), q);
    assert_eq!(f.bias(), Vec3::new(0.01, -0.02, 0.005));
    assert_eq!(f.settings, RobustSettings::default());
    assert_eq!(f.heading_sigma(), HEADING_VAR_MAX.sqrt());
    let mut good = f.clone();
    good.restart(q);
    assert_eq!(f, good);
    // Still at q, with the gyroscope reading the bias.
    let (a, m) = (q.rotate_inverse(G), q.rotate_inverse(FIELD));
    for _ in 0..500 {
        let step = f.update(DT, Vec3::new(0.01, -0.02, 0.005), Some(a), Some(m));
        assert!(step.is_some_and(|s| s.used_accel && s.used_mag));
    }
    assert!(inclination(f.quaternion(), q) < 1e-3);
    assert!(f.heading_sigma() < 0.1);
    assert!(f.valid());
}

/// The series for `exp(−x) (cos x, sin x)` against libm's `exp` and `sincos`, term
/// for term of the readable form, over its range (x from 1e-9 to 1/32, log-uniform,
/// and the ends): each within 2⁻⁵¹ (relative for `E S`); past the range it declines.
/// Against 200-bit arithmetic (mpmath, same x) the series is the closer of the two:
/// at most 0.27 and 0.73 units of 2⁻⁵² relative, the libm form 0.73 and 1.13, so the
/// bound is their two errors.
#[test]
#[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
fn the_low_pass_coefficient_series_is_the_libm_form() {
    let mut u = crate::math::test_uniform(31);
    let (mut worst_c, mut worst_s) = (0.0f64, 0.0f64);
    for i in 0..20000 {
        let x = match i {
            0 => f64::MIN_POSITIVE,
            1 => 1.0 / 32.0 - f64::EPSILON / 32.0,
            _ => 10f64.powf(-9.0 + (9.0 - 32f64.log10()) * 0.5 * (u() + 1.0)),
        };
        let (sc, ss) = exp_turn_series(x).expect("within the series' range");
        let (lc, ls) = exp_turn(x);
        worst_c = worst_c.max((sc - lc).abs());
        worst_s = worst_s.max((ss - ls).abs() / ls);
    }
    assert!(
        worst_c <= 2.0 * f64::EPSILON && worst_s <= 2.0 * f64::EPSILON,
        "E C {worst_c:e}, E S {worst_s:e}"
    );
    assert_eq!(exp_turn_series(1.0 / 32.0), None);
    assert_eq!(exp_turn_series(-1e-3), None);
    assert_eq!(exp_turn_series(f64::NAN), None);
}

/// A state holding libm's coefficients for its dt and τ (a snapshot written before
/// the series) is valid; coefficients 1e-12 away from their dt and τ's are not.
#[test]
fn coefficients_from_before_the_series_stay_valid() {
    let mut f = Butterworth::default();
    f.settle(Vec3::new(0.1, -0.2, 9.8));
    let mut differ = 0;
    for (dt, tau) in [(0.0035, 3.0), (0.01, 0.5), (0.004, 0.13), (0.0071, 1.7), (0.02, 0.9)] {
        f.coefficients(dt, tau);
        assert!(f.valid());
        // The coefficients exactly as the code before the series computed them.
        let e = libm::exp(-dt / tau);
        let (s, c) = libm::sincos(dt / tau);
        let old = Butterworth {
            ee: e * (c + s),
            ev: e * s * tau,
            ve: -2.0 * e * s / tau,
            vv: e * (c - s),
            ..f.clone()
        };
        assert!(old.valid(), "dt {dt}, tau {tau}");
        differ += usize::from(old != f);
        assert!(!Butterworth { ev: f.ev * (1.0 + 1e-12), ..f.clone() }.valid());
        assert!(!Butterworth { vv: f.vv * (1.0 - 1e-12), ..f.clone() }.valid());
    }
    assert!(differ > 0, "libm's coefficients were the series' in every case");
}

/// One step is the flow of `ÿ = ω² (x − y) − 2ζω ẏ` (ζ = 1/√2, ω = √2/τ) over dt with
/// the input held: against a fine fourth-order Runge-Kutta integration of that
/// equation, over steps of mixed lengths.
#[test]
#[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
fn the_low_pass_steps_its_differential_equation_exactly() {
    let (zeta, tau) = (core::f64::consts::FRAC_1_SQRT_2, 0.8);
    let omega = core::f64::consts::SQRT_2 / tau;
    let deriv = |x: f64, y: f64, v: f64| (v, omega * omega * (x - y) - 2.0 * zeta * omega * v);
    let (mut y, mut v) = (0.0, 0.0);
    let mut f = Butterworth::default();
    f.settle(Vec3::ZERO);
    for i in 0..300 {
        let dt = [0.01, 0.003, 0.25, 1.7][i % 4];
        let x = (i as f64 * 0.37).sin() + 1.0;
        let n = 2000;
        let h = dt / n as f64;
        for _ in 0..n {
            let k1 = deriv(x, y, v);
            let k2 = deriv(x, y + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
            let k3 = deriv(x, y + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
            let k4 = deriv(x, y + h * k3.0, v + h * k3.1);
            y += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            v += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
        let got = f.filter(dt, tau, Vec3::new(x, 0.0, 0.0)).x;
        assert!((got - y).abs() < 1e-10, "step {i} (dt {dt}): {got} vs {y}");
    }
}

/// A steady input passes unchanged whatever the steps, and a step response stays
/// bounded for every τ in the parameter's range at any dt and any mix of dt.
#[test]
#[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
fn the_low_pass_is_stable_for_every_dt_and_tau() {
    let spec = PARAMS.iter().find(|p| p.id == id::ROBUST_TAU_ACC).unwrap();
    let mut taus = vec![spec.min, spec.max, spec.default];
    let mut t = spec.min;
    while t < spec.max {
        taus.push(t);
        t *= 1.37;
    }
    let v = Vec3::new(0.3, -9.0, 2.0);
    for &tau in &taus {
        for dt in [1e-9, 1e-4, 0.001, 0.0123, 0.1, 0.7, 3.0, 100.0] {
            let mut f = Butterworth::default();
            f.settle(v);
            for k in 0..50 {
                let y = f.filter(if k % 3 == 0 { dt } else { 0.01 }, tau, v);
                assert!((y - v).norm() < 1e-7 * v.norm(), "tau {tau}, dt {dt}: {y:?}");
            }
            // A unit step: a Butterworth overshoots by about 4 %.
            let mut f = Butterworth::default();
            f.settle(Vec3::ZERO);
            for k in 0..2000 {
                let y = f.filter(if k % 5 == 0 { 0.01 } else { dt }, tau, Vec3::new(1.0, 0.0, 0.0)).x;
                assert!(y.is_finite() && y.abs() < 1.05, "tau {tau}, dt {dt}: {y}");
            }
        }
    }
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn learns_the_bias_at_rest() {
    let bias = Vec3::new(0.01, -0.02, 0.015);
    let q = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.3);
    let mut f = filter(RobustSettings::default(), q);
    run(&mut f, 20.0, |_| (q, bias, Vec3::ZERO), |_, q| Some(q.rotate_inverse(FIELD)));
    assert!(f.at_rest());
    assert!((f.bias() - bias).norm() < 1e-5, "{:?}", f.bias());
    // Heading drifted before the bias was learned; the tilt did not.
    assert!(inclination(f.quaternion(), q) < 1e-3);
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_slow_turn_is_not_rest() {
    // 1 deg/s about a horizontal axis: under rest_gyro, but the accelerometer tilts.
    let w = Vec3::new(0.0175, 0.0, 0.0);
    let mut f = filter(RobustSettings::default(), Quat::IDENTITY);
    let mut seen_rest = false;
    for i in 0..3000 {
        let q = rotation_of(w, i as f64 * DT);
        f.update(DT, w, Some(q.rotate_inverse(G)), None).unwrap();
        seen_rest |= f.at_rest();
    }
    assert!(!seen_rest);
    assert!(f.bias().norm() < 1e-3, "{:?}", f.bias());
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn rejects_zero_mean_linear_acceleration() {
    // 4 m/s² along east at 1 Hz: an accelerometer-only tilt swings by about 22°.
    let q = Quat::from_axis_angle(Vec3::new(0.3, 1.0, 0.2), 0.5);
    let mut f = filter(RobustSettings::default(), q);
    let mut worst: f64 = 0.0;
    for i in 0..2000 {
        let t = i as f64 * DT;
        let lin = Vec3::new(4.0 * libm::sin(core::f64::consts::TAU * t), 0.0, 0.0);
        f.update(DT, Vec3::ZERO, Some(q.rotate_inverse(G + lin)), None).unwrap();
        // The first tau_acc averages the readings so far (a mean over 2.5 periods
        // still carries 0.5 m/s² of the acceleration, 3°); the low-pass, started from
        // that mean, has shed it by 2 tau_acc.
        if t >= 2.0 * RobustSettings::default().tau_acc {
            worst = worst.max(inclination(f.quaternion(), q));
        }
    }
    assert!(worst.to_degrees() < 1.5, "{}", worst.to_degrees());
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn holds_heading_through_a_disturbance_and_resumes_without_a_jump() {
    let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.7);
    let settings = RobustSettings { hard_iron_time: 0.0, ..Default::default() };
    let mut f = filter(settings, q);
    let clean = |_: f64, q: Quat| Some(q.rotate_inverse(FIELD));
    run(&mut f, 5.0, |_| (q, Vec3::ZERO, Vec3::ZERO), clean);
    let before = heading(f.quaternion());
    // A magnet in the room: 30 µT more along east, fixed in the earth frame.
    let magnet = |_: f64, q: Quat| Some(q.rotate_inverse(FIELD + Vec3::new(30.0, 0.0, 0.0)));
    run(&mut f, 10.0, |_| (q, Vec3::ZERO, Vec3::ZERO), magnet);
    assert!(f.mag_disturbed());
    assert!((heading(f.quaternion()) - before).abs() < 1e-9);
    let mut steps = Vec::new();
    for _ in 0..500 {
        let h = heading(f.quaternion());
        run(&mut f, DT, |_| (q, Vec3::ZERO, Vec3::ZERO), clean);
        steps.push((heading(f.quaternion()) - h).abs());
    }
    assert!(!f.mag_disturbed());
    assert!(steps.iter().all(|s| *s < 1e-3), "largest step {:?}", steps.iter().cloned().fold(0.0, f64::max));
    assert!((heading(f.quaternion()) - 0.7).abs() < 1e-3);
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn compensates_a_magnet_attached_to_the_sensor() {
    let hard = Vec3::new(25.0, -10.0, 15.0);
    let w = Vec3::new(0.0, 0.0, 0.5);
    let q0 = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.2);
    let mut f = filter(RobustSettings::default(), q0);
    let truth = |t: f64| {
        let q = q0 * rotation_of(w, t);
        (q, w, Vec3::ZERO)
    };
    // Clean, then the magnet: the raw field fails the norm test from then on.
    let mag = |t: f64, q: Quat| Some(q.rotate_inverse(FIELD) + if t >= 5.0 { hard } else { Vec3::ZERO });
    run(&mut f, 30.0, truth, mag);
    let h = f.hard_iron().expect("compensation on");
    assert!((h - hard).norm() < 0.5, "{h:?}");
    assert!(!f.mag_disturbed());
    assert!(f.quaternion().angle_to(truth(30.0).0) < 0.01);
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn estimates_bias_in_motion_from_the_inclination_correction() {
    let bias = Vec3::new(0.01, -0.008, 0.0);
    let settings = RobustSettings::default();
    let mut f = filter(settings, Quat::IDENTITY);
    let mut q = Quat::IDENTITY;
    for i in 0..60_000 {
        let t = i as f64 * DT;
        let w = Vec3::new(0.4 * libm::sin(0.3 * t), 0.4 * libm::cos(0.2 * t), 0.3);
        q = q * rotation_of(w, DT);
        f.update(DT, w + bias, Some(q.rotate_inverse(G)), None).unwrap();
    }
    assert!(!f.at_rest());
    // Rotation about all axes makes every component observable from gravity.
    assert!((f.bias() - bias).norm() < 1e-3, "{:?}", f.bias());
}

/// `bias_walk` is the motion bias filter's process noise: a bias that drifts while the
/// sensor turns is followed the closer the larger it is, and not at all at 0.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_bias_walk_sets_how_closely_a_drifting_bias_is_followed() {
    // 0.3 deg/s of drift per minute on x, a constant on y.
    let bias = |t: f64| Vec3::new(0.002 + 0.3f64.to_radians() * t / 60.0, -0.004, 0.0);
    let error = |walk: f64| {
        let settings = RobustSettings { bias_walk: walk, ..Default::default() };
        let mut f = filter(settings, Quat::IDENTITY);
        let mut q = Quat::IDENTITY;
        let n = 18_000;
        for i in 0..n {
            let t = i as f64 * DT;
            let w = Vec3::new(0.4 * libm::sin(0.3 * t), 0.4 * libm::cos(0.2 * t), 0.3);
            q = q * rotation_of(w, DT);
            f.update(DT, w + bias(t), Some(q.rotate_inverse(G)), None).unwrap();
        }
        assert!(!f.at_rest());
        (f.bias(), (f.bias() - bias(n as f64 * DT)).norm())
    };
    let default = RobustSettings::default().bias_walk;
    let ((none, e0), (_, e1), (_, e3)) = (error(0.0), error(default), error(3.0 * default));
    assert_eq!(none, Vec3::ZERO);
    // A walk whose square underflows is no walk either (and leaves everything finite).
    assert_eq!(error(1e-200).0, Vec3::ZERO);
    assert!(e3 < 0.8 * e1 && e1 < 0.8 * e0, "errors at 0, 1x and 3x the default: {e0:e} {e1:e} {e3:e}");
}

/// The motion bias filter measures a rate: the drift each correction removes over the
/// time since the last one. A gyroscope at four times the accelerometer's rate must give
/// the same learning as one accelerometer reading per gyroscope reading (counting only
/// the samples with a reading, the filter read four times the rate and learnt with four
/// times the gain).
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_bias_in_motion_is_learnt_alike_with_fewer_accelerometer_readings() {
    let bias = Vec3::new(0.01, -0.008, 0.0);
    let learnt = |every: usize| {
        let mut f = filter(RobustSettings::default(), Quat::IDENTITY);
        let mut q = Quat::IDENTITY;
        for i in 0..6_000 {
            let t = i as f64 * DT;
            let w = Vec3::new(0.4 * libm::sin(0.3 * t), 0.4 * libm::cos(0.2 * t), 0.3);
            q = q * rotation_of(w, DT);
            let a = (i % every == 0).then(|| q.rotate_inverse(G));
            f.update(DT, w + bias, a, None).unwrap();
        }
        f.bias()
    };
    let (all, quarter) = (learnt(1), learnt(4));
    // Halfway there after 60 s, the same way.
    assert!((all - bias).norm() < 0.6 * bias.norm(), "{all:?}");
    assert!((quarter - all).norm() < 0.1 * bias.norm(), "every sample {all:?}, every 4th {quarter:?}");
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn butterworth_has_unit_gain_and_settles() {
    let mut b = Butterworth::default();
    let x = Vec3::new(1.0, -2.0, 3.0);
    b.settle(x);
    for _ in 0..10 {
        assert!((b.filter(0.01, 2.5, x) - x).norm() < 1e-12);
    }
    // A step from zero reaches 1 - 1/e within about tau, never overshooting 5 %.
    let mut b = Butterworth::default();
    b.settle(Vec3::ZERO);
    let mut y = Vec3::ZERO;
    let mut peak: f64 = 0.0;
    for _ in 0..2000 {
        y = b.filter(0.01, 2.5, x);
        peak = peak.max(y.x);
    }
    assert!((y - x).norm() < 2e-3 && peak < 1.05, "{y:?} {peak}");
}
