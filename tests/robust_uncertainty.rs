//! Issue 40: the robust kind's heading uncertainty covers its heading error at the stated
//! rate (95 % within 2 sigma) after accepted glitches, gaps, a host's attitude and a
//! magnet the disturbance tests let through, not only on BROAD's ordinary motion.
//!
//! Each scenario: 30 s still or turning slowly about the vertical with the magnetometer
//! (the estimate settled, the bias learned at rest), then the event, then 60 s more of the
//! same motion. Over those 60 s, the fraction of samples whose heading error is within 2
//! sigma must be at least 95 %; it is printed split at the first sample from which the
//! error stays under 2 deg. The exception is a magnet that passes the disturbance tests
//! beside a still sensor: 95 % over the first τ_mag (9 s) only, the transition in which
//! the innovation shows it (measured: 22-27 % over the 60 s, the estimate 19° off).

mod common;

use common::sim::{Noise, FIELD, G};
use orient::{Config, Filter, Kind, Quat, Sample, Vec3};

const DT: f64 = 0.01;
const UP: Vec3 = Vec3::new(0.0, 0.0, 1.0);

/// The true attitude at time t: a fixed tilt, then a heading that turns at `rate`.
fn truth(t: f64, rate: f64) -> Quat {
    let tilt = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.3);
    Quat::from_axis_angle(UP, 0.5 + rate * t) * tilt
}

/// One sample at `q` with the gyroscope reading `gyro` and the earth-frame field `field`.
fn at(q: Quat, dt: f64, gyro: Vec3, field: Vec3, rng: &mut Noise) -> Sample {
    Sample {
        dt,
        gyro: Some(gyro + rng.vec(0.005)),
        accel: Some(q.rotate_inverse(Vec3::new(0.0, 0.0, G)) + rng.vec(0.05)),
        mag: Some(q.rotate_inverse(field) + rng.vec(0.3)),
    }
}

/// |heading error| (rad): the rotation about the vertical between estimate and truth.
fn heading_error(est: Quat, truth: Quat) -> f64 {
    let e = (est.normalized() * truth.normalized().conj()).normalized();
    2.0 * e.z.abs().atan2(e.w.abs())
}

/// A room-fixed magnet near the desk: 7 µT east, which turns the field's azimuth by 19°
/// while its norm changes by 1.2 % and its dip by 1.3° (within the 10 % and 10° tests).
const MAGNET: Vec3 = Vec3::new(7.0, 0.0, 0.0);

#[derive(Clone, Copy, Debug)]
enum Event {
    /// One gyroscope sample at 9999 rad/s about a tilted axis (the sensor did not move).
    Glitch1,
    /// 100 such samples.
    Glitch100,
    /// 100 samples of alternating sign.
    GlitchAlternating,
    /// dt = 5 s while the sensor turned by 2 rad unseen, the gyroscope reading after it
    /// the rate before, with the gap policy off (`gap_dt` = 0: the step is integrated).
    Gap,
    /// The same gap with the gap policy on (the default: re-acquisition from the
    /// accelerometer and the magnetometer).
    GapReacquired,
    /// The host sets the attitude 150° off in heading.
    SetAttitude,
    /// A magnet in the room that passes the disturbance tests appears and stays.
    Magnet,
}

struct Outcome {
    /// Within 2 sigma over the first τ_mag = 9 s after the event.
    first: (usize, usize),
    until: (usize, usize),
    after: (usize, usize),
    end_error: f64,
    end_sigma: f64,
}

impl Outcome {
    fn coverage(&self) -> f64 {
        (self.until.0 + self.after.0) as f64 / (self.until.1 + self.after.1) as f64
    }
}

fn scenario(event: Event, rate: f64) -> Outcome {
    let mut config = Config::new(Kind::Robust).unwrap();
    if matches!(event, Event::Gap) {
        config.set("gap_dt", 0.0).unwrap().unwrap();
    }
    let mut f = Filter::new(&config).unwrap();
    let mut rng = Noise(0x40_11 ^ (event as u64) << 8 ^ (rate * 1000.0) as u64);
    let mut t = 0.0;
    // The body rate of a turn about the vertical (the tilt is fixed).
    let w = truth(0.0, rate).rotate_inverse(UP * rate);
    // The still or turning sensor in the room's field (plus the magnet once it is there).
    let mut field = FIELD;
    let mut offset = 0.0; // heading the truth gained without the gyroscope seeing it
    let step = |f: &mut Filter, t: &mut f64, field: Vec3, offset: f64, rng: &mut Noise| {
        *t += DT;
        let q = Quat::from_axis_angle(UP, offset) * truth(*t, rate);
        f.update(&at(q, DT, w, field, rng)).unwrap();
        q
    };
    for _ in 0..3000 {
        step(&mut f, &mut t, field, offset, &mut rng);
    }
    let here = |t: f64, offset: f64| Quat::from_axis_angle(UP, offset) * truth(t, rate);
    let glitch = Vec3::new(1.0, 2.0, 3.0) * (9999.0 / 14f64.sqrt());
    match event {
        Event::Glitch1 | Event::Glitch100 | Event::GlitchAlternating => {
            let n = if matches!(event, Event::Glitch1) { 1 } else { 100 };
            for i in 0..n {
                let sign = if matches!(event, Event::GlitchAlternating) && i % 2 == 1 { -1.0 } else { 1.0 };
                t += DT;
                f.update(&at(here(t, offset), DT, glitch * sign, field, &mut rng)).unwrap();
            }
        }
        Event::Gap | Event::GapReacquired => {
            t += 5.0;
            offset += 2.0;
            f.update(&at(here(t, offset), 5.0, w, field, &mut rng)).unwrap();
        }
        Event::SetAttitude => {
            f.set_quaternion(Quat::from_axis_angle(UP, 150f64.to_radians()) * here(t, offset)).unwrap();
        }
        Event::Magnet => field = FIELD + MAGNET,
    }
    let mut out = Outcome { first: (0, 0), until: (0, 0), after: (0, 0), end_error: 0.0, end_sigma: 0.0 };
    let mut rows = Vec::new();
    for _ in 0..6000 {
        let q = step(&mut f, &mut t, field, offset, &mut rng);
        let (e, sigma) = (heading_error(f.quaternion(), q), f.uncertainty().heading.unwrap());
        rows.push((e, sigma));
    }
    // The error stays under 2° from `settled` on.
    let settled = rows.iter().rposition(|r| r.0 >= 2f64.to_radians()).map_or(0, |i| i + 1);
    for (i, (e, sigma)) in rows.iter().enumerate() {
        let part = if i < settled { &mut out.until } else { &mut out.after };
        part.0 += usize::from(*e <= 2.0 * sigma);
        part.1 += 1;
        if i < 900 {
            out.first.0 += usize::from(*e <= 2.0 * sigma);
            out.first.1 += 1;
        }
    }
    (out.end_error, out.end_sigma) = *rows.last().unwrap();
    out
}

#[test]
#[cfg_attr(miri, ignore = "long loops")]
fn the_heading_uncertainty_covers_the_error_after_glitches_gaps_set_attitude_and_a_magnet() {
    let mut failures = Vec::new();
    for event in [
        Event::Glitch1,
        Event::Glitch100,
        Event::GlitchAlternating,
        Event::Gap,
        Event::GapReacquired,
        Event::SetAttitude,
        Event::Magnet,
    ] {
        for rate in [0.0, 0.1] {
            let o = scenario(event, rate);
            let pct = |(a, n): (usize, usize)| if n == 0 { f64::NAN } else { 100.0 * a as f64 / n as f64 };
            let line = format!(
                "{event:?} at {rate} rad/s: within 2 sigma {:.1} % ({:.1} % of {} samples until the error \
                 stays under 2 deg, {:.1} % of {} after); at 60 s error {:.2} deg, sigma {:.2} deg",
                100.0 * o.coverage(),
                pct(o.until),
                o.until.1,
                pct(o.after),
                o.after.1,
                o.end_error.to_degrees(),
                o.end_sigma.to_degrees()
            );
            println!("{line}");
            // The magnet is the documented exception (src/filters/robust.rs, "What the
            // evidence cannot see"): once the estimate has turned to the magnet's north
            // no innovation is left; the transition, the first τ_mag, is covered.
            let first = o.first.0 as f64 / o.first.1 as f64;
            let covered = if matches!(event, Event::Magnet) { first } else { o.coverage() };
            if covered < 0.95 {
                failures.push(format!("{line} (first 9 s: {:.1} %)", 100.0 * first));
            }
        }
    }
    assert!(failures.is_empty(), "{} failures:\n{}", failures.len(), failures.join("\n"));
}
