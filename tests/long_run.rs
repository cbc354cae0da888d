//! Every filter over a simulated 24 hours at 100 Hz, held still, slowly turning, and
//! turning with a gap in the data every 200 s; and an hour at 1 kHz with gaps: no
//! rejected sample, no NaN, |q| within 1e-12 of 1 at every sample, bounded error.
//! (Native only: 8.6 million samples per kind and scenario are minutes under qemu.)

mod common;

use common::sim::{inclination_error, Noise, FIELD, G};
use orient::filters::complementary::rotation_of;
use orient::{Config, Filter, Kind, Quat, Sample, Vec3};

const DAY: f64 = 24.0 * 3600.0;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Motion {
    Still,
    /// About 0.02 rad/s about a slowly wandering axis for 50 s of every minute, still
    /// for the other 10 (hand-held use has pauses, and the complementary filter corrects
    /// only at rest, by design).
    Turning,
    /// Turning, and every 200 s a gap of 0.5-9.5 s in the data (dropped packets): the
    /// body keeps turning, and the first sample after the gap carries the missing time
    /// in its dt. Errors are scored from 3 s after each gap on.
    TurningWithGaps,
}

/// A kind, its scenario and rate, and what [`run`] returns.
type Outcome = (Kind, Motion, f64, (f64, f64, f64, f64));

/// Runs one kind at `rate` Hz for `seconds`. Returns the worst inclination and total
/// errors (degrees) after the first minute, the inclination RMS over the last hour, and
/// the error of the final gyro bias estimate (rad/s; NaN for a kind without one).
fn run(kind: Kind, motion: Motion, rate: f64, seconds: f64) -> (f64, f64, f64, f64) {
    let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
    let mut q = Quat::from_axis_angle(Vec3::new(0.3, -0.2, 1.0), 0.4);
    let mut rng = Noise(0x1234_5678_9abc_def1);
    let bias = Vec3::new(0.003, -0.002, 0.001);
    let dt = 1.0 / rate;
    let n = (seconds * rate) as usize;
    let every = (rate / 100.0) as usize;
    let (mut worst_incl, mut worst_total): (f64, f64) = (0.0, 0.0);
    let (mut last_hour, mut last_hour_n) = (0.0, 0usize);
    let mut carried = 0.0;
    for i in 0..n {
        let t = i as f64 * dt;
        let omega = if motion != Motion::Still && t > 60.0 && t % 60.0 < 50.0 {
            Vec3::new((t / 3000.0).sin(), (t / 5000.0).cos(), 0.5) * 0.02
        } else {
            Vec3::ZERO
        };
        q = (q * rotation_of(omega, dt)).normalized();
        // Gap k (from 200 s on) lasts 0.5 + (k mod 10) s.
        let (since, length) = (t % 200.0, 0.5 + ((t / 200.0) as usize % 10) as f64);
        let gaps = motion == Motion::TurningWithGaps && t > 200.0;
        if gaps && since < length {
            carried += dt;
            continue;
        }
        let s = Sample {
            dt: dt + carried,
            gyro: Some(omega + bias + rng.vec(0.002)),
            accel: Some(q.rotate_inverse(Vec3::new(0.0, 0.0, G)) + rng.vec(0.03)),
            mag: Some(q.rotate_inverse(FIELD) + rng.vec(0.3)),
        };
        carried = 0.0;
        f.update(&s).unwrap_or_else(|e| panic!("{kind:?} sample {i}: {e}"));
        let est = f.quaternion();
        assert!(
            est.is_finite() && (est.norm() - 1.0).abs() <= 1e-12,
            "{kind:?} sample {i}: |q| = {}",
            est.norm()
        );
        let settled = !gaps || since > length + 3.0;
        if t > 60.0 && i % every == 0 && settled {
            let incl = inclination_error(est, q).to_degrees();
            worst_incl = worst_incl.max(incl);
            worst_total = worst_total.max(est.angle_to(q).to_degrees());
            if t > seconds - 3600.0 {
                last_hour += incl * incl;
                last_hour_n += 1;
            }
        }
    }
    let bias_error = (f.diagnostics().gyro_bias - bias).norm();
    (worst_incl, worst_total, (last_hour / last_hour_n.max(1) as f64).sqrt(), bias_error)
}

#[test]
fn every_kind_survives_a_day_still_and_turning() {
    if common::native::cross() {
        eprintln!("skipped under emulation: 86 million updates");
        return;
    }
    let kinds = Kind::ALL;
    let scenarios = [
        (Motion::Still, 100.0, DAY),
        (Motion::Turning, 100.0, DAY),
        (Motion::TurningWithGaps, 100.0, DAY),
        (Motion::TurningWithGaps, 1000.0, 3600.0),
    ];
    let results: Vec<Outcome> = std::thread::scope(|s| {
        let jobs: Vec<_> = kinds
            .iter()
            .flat_map(|k| scenarios.map(|sc| (*k, sc)))
            .map(|(k, (motion, rate, seconds))| {
                s.spawn(move || (k, motion, rate, run(k, motion, rate, seconds)))
            })
            .collect();
        jobs.into_iter().map(|j| j.join().unwrap()).collect()
    });
    for (kind, motion, rate, (incl, total, last, bias)) in &results {
        println!(
            "{kind:?} {motion:?} {rate} Hz: worst inclination {incl:.3}°, total {total:.3}°, last-hour inclination RMS {last:.3}°, bias error {bias:.5} rad/s"
        );
    }
    for (kind, motion, _, (incl, total, _, bias)) in results {
        // GMVDK's regression over static runs must find the bias (0.0037 rad/s), not the
        // slow turn; so must the robust filter's rest and motion estimates.
        if matches!(kind, Kind::Gmvdk | Kind::Robust) {
            assert!(bias < 0.001, "{kind:?} {motion:?}: bias error {bias} rad/s");
        }
        let turning = motion != Motion::Still;
        // Bounds a few tenths above the measured worst over the day (the robust kind's
        // 0.63 / 1.59 turning: its rest time constant, 1 s, learns the start of the slow
        // turn as bias for a moment before the tilt test ends the rest; with the earlier
        // tilt test 0.87 / 1.86, and at 0.5 s it exceeded both). Mahony (Ki = 0 by
        // default) carries a steady offset of about |bias|/Kp; the complementary filter
        // has no heading reference (its heading drifts with the start-up bias residual),
        // so only its inclination is bounded.
        let (max_incl, max_total) = match kind {
            Kind::Mahony => (1.2, 4.5),
            Kind::Complementary => (1.0, f64::INFINITY),
            _ => (1.0, 2.0),
        };
        assert!(incl < max_incl, "{kind:?} turning={turning}: inclination {incl}");
        assert!(total < max_total, "{kind:?} turning={turning}: total {total}");
    }
}
