//! The recommended kind on simulated protocols with exact truth (tests/common/magnetic.rs):
//! attached magnets of any size, a start inside a magnet's field, a gyro bias drifting
//! past 2 °/s, hand-held motion at 256 Hz. VQF (`vqf-rs`, defaults) runs beside it on the
//! same samples; its figures are printed, and asserted against where robust is ahead.

mod common;

use common::magnetic;
use common::sim::Run;
use orient::{Config, Filter, Kind, Quat, Vec3};
use orient_tools::eval::error_angles;

/// Robust's estimates and bias estimates, one per sample.
fn robust(run: &Run) -> (Vec<Quat>, Vec<Vec3>) {
    let mut f = Filter::new(&Config::new(Kind::Robust).unwrap()).unwrap();
    let mut q = Vec::new();
    let mut b = Vec::new();
    for s in &run.samples {
        f.update(s).unwrap();
        q.push(f.quaternion());
        b.push(f.diagnostics().gyro_bias);
    }
    (q, b)
}

fn vqf(run: &Run) -> (Vec<Quat>, Vec<Vec3>) {
    let mut f = vqf_rs::VQF::new(run.samples[0].dt, None, None, None);
    let v = |v: Vec3| [v.x, v.y, v.z];
    let mut q = Vec::new();
    let mut b = Vec::new();
    for s in &run.samples {
        f.update(v(s.gyro.unwrap()), v(s.accel.unwrap()), s.mag.map(v));
        let e = f.quat_9d();
        q.push(Quat::new(e.0, e.1, e.2, e.3));
        let (bias, _) = f.bias_estimate();
        b.push(Vec3::new(bias[0], bias[1], bias[2]));
    }
    (q, b)
}

/// RMS (degrees) of (total, heading) error over samples with t in [from, to).
fn rmse(run: &Run, est: &[Quat], from: f64, to: f64) -> (f64, f64) {
    let (mut t2, mut h2, mut n) = (0.0, 0.0, 0.0);
    for ((q, g), t) in est.iter().zip(&run.truth).zip(&run.t) {
        if *t >= from && *t < to {
            let (tot, head, _) = error_angles(*q, *g);
            t2 += tot * tot;
            h2 += head * head;
            n += 1.0;
        }
    }
    ((t2 / n).sqrt().to_degrees(), (h2 / n).sqrt().to_degrees())
}

/// Largest heading error (degrees) over samples with t ≥ from.
fn worst_heading(run: &Run, est: &[Quat], from: f64) -> f64 {
    est.iter()
        .zip(&run.truth)
        .zip(&run.t)
        .filter(|(_, t)| **t >= from)
        .map(|((q, g), _)| error_angles(*q, *g).1.to_degrees())
        .fold(0.0, f64::max)
}

/// Seconds after `from` until the heading error stays below `deg` for good.
fn recovery(run: &Run, est: &[Quat], from: f64, deg: f64) -> f64 {
    let mut last_bad = from;
    for ((q, g), t) in est.iter().zip(&run.truth).zip(&run.t) {
        if *t >= from && error_angles(*q, *g).1.to_degrees() >= deg {
            last_bad = *t;
        }
    }
    last_bad - from
}

#[test]
#[cfg_attr(miri, ignore = "long simulated runs: too slow under Miri")]
fn an_attached_magnet_of_any_size_never_turns_the_heading() {
    // From 5 µT (a tenth of the field: the raw field still passes the norm test at most
    // orientations) to 200 µT (four times the field). Measured total 1.43 / 1.40 / 2.26
    // / 0.80 (VQF 2.04 / 3.15 / 7.34 / 10.79); before issue 19, 15 and 40 µT gave 2.65
    // and 2.75.
    let mut failures = Vec::new();
    for size in [5.0, 15.0, 40.0, 200.0] {
        let offset = Vec3::new(0.6, -0.48, 0.64) * size;
        let run = magnetic::attached_magnet(offset);
        let (q, _) = robust(&run);
        let (qv, _) = vqf(&run);
        let (total, heading) = rmse(&run, &q, 20.0, 120.0);
        let worst = worst_heading(&run, &q, 20.0);
        let (vt, vh) = rmse(&run, &qv, 20.0, 120.0);
        println!(
            "magnet {size} uT: robust total {total:.2} heading {heading:.2} worst {worst:.2} | VQF total {vt:.2} heading {vh:.2} worst {:.2}",
            worst_heading(&run, &qv, 20.0)
        );
        if !(total < 2.5 && worst < 10.0 && total < vt) {
            failures.push(format!("{size} uT: total {total:.2} (VQF {vt:.2}), worst heading {worst:.2}"));
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}

#[test]
#[cfg_attr(miri, ignore = "long simulated runs: too slow under Miri")]
fn a_start_inside_a_magnets_field_is_recovered_from() {
    let run = magnetic::start_in_disturbance();
    let (q, _) = robust(&run);
    let (qv, _) = vqf(&run);
    let (head_before, _) = (error_angles(q[2999], run.truth[2999]).1.to_degrees(), 0);
    let r = recovery(&run, &q, 30.0, 5.0);
    let rv = recovery(&run, &qv, 30.0, 5.0);
    let (total, _) = rmse(&run, &q, 60.0, 90.0);
    let (vt, _) = rmse(&run, &qv, 60.0, 90.0);
    println!(
        "heading error at 30 s {head_before:.1} deg; within 5 deg for good after {r:.1} s (VQF {rv:.1} s); \
         total RMSE 60-90 s {total:.2} (VQF {vt:.2})"
    );
    // Started in the magnet's field the heading is 45 deg off; leaving it, the earth's
    // field is consistent while the sensor turns and replaces the reference.
    assert!(head_before > 30.0, "{head_before}");
    assert!(r < 12.0, "recovered after {r:.1} s");
    assert!(total < 2.0, "{total:.2}");
}

#[test]
#[cfg_attr(miri, ignore = "long simulated runs: too slow under Miri")]
fn a_bias_drifting_past_two_degrees_per_second_is_tracked() {
    let run = magnetic::drifting_bias();
    let (q, b) = robust(&run);
    let (qv, bv) = vqf(&run);
    let bias_rms = |b: &[Vec3]| {
        let (mut s, mut n) = (0.0, 0.0);
        for (e, t) in b.iter().zip(&run.t) {
            if *t >= 150.0 {
                s += (*e - magnetic::drift(*t)).norm_squared();
                n += 1.0;
            }
        }
        (s / n).sqrt().to_degrees()
    };
    let (be, bve) = (bias_rms(&b), bias_rms(&bv));
    let (total, _) = rmse(&run, &q, 150.0, 300.0);
    let (vt, _) = rmse(&run, &qv, 150.0, 300.0);
    println!("bias error RMS 150-300 s: robust {be:.3} deg/s, VQF {bve:.3}; total RMSE robust {total:.2}, VQF {vt:.2}");
    // The true bias passes 2 deg/s per axis at 150 s (3.5 deg/s in norm).
    assert!(be < 0.5 && be < bve, "bias error {be:.3} deg/s (VQF {bve:.3})");
    assert!(total < 2.0 && total < vt, "total {total:.2} (VQF {vt:.2})");
}

#[test]
#[cfg_attr(miri, ignore = "long simulated runs: too slow under Miri")]
fn hand_held_at_256_hz() {
    let run = magnetic::hand_held(256.0);
    let (q, _) = robust(&run);
    let (qv, _) = vqf(&run);
    let (total, heading) = rmse(&run, &q, 5.0, 65.0);
    let (vt, vh) = rmse(&run, &qv, 5.0, 65.0);
    println!("hand-held 256 Hz: robust total {total:.2} heading {heading:.2}; VQF {vt:.2} {vh:.2}");
    assert!(total < 1.5, "{total:.2}");
}

#[test]
#[cfg_attr(miri, ignore = "long simulated runs: too slow under Miri")]
fn started_in_motion_it_settles_quickly() {
    // Hand-held from the first sample (no rest), 100 Hz: the first accelerometer reading
    // carries up to 2.9 m/s² of linear acceleration.
    let run = common::sim::simulate(Quat::IDENTITY, 40.0, 100.0, magnetic::NOISE, |t| {
        magnetic::hand_held_moment(t, 0.0)
    });
    let settle = |est: &[Quat]| {
        // Seconds until the total error is below 3° and stays there for 5 s.
        let mut since = None;
        for (i, (q, g)) in est.iter().zip(&run.truth).enumerate() {
            let bad = error_angles(*q, *g).0.to_degrees() >= 3.0;
            match (bad, since) {
                (true, _) => since = None,
                (false, None) => since = Some(i),
                (false, Some(s)) if i - s >= 500 => return run.t[s],
                _ => {}
            }
        }
        f64::INFINITY
    };
    let (q, _) = robust(&run);
    let (qv, _) = vqf(&run);
    let (r, v) = (settle(&q), settle(&qv));
    println!("started in motion: robust settles in {r:.2} s, VQF {v:.2} s");
    // Measured 10.8 s against VQF's 11.9: both average the heading from readings seen
    // through the first seconds' tilt error. Two alternatives measured and not taken,
    // since on 80 starts in motion on BROAD (tools/src/bin/robust_cv.rs --starts) they were
    // slower: restarting that average once the accelerometer low-pass has settled (6.6 s
    // here, BROAD 6.9 s against 5.3), and settling the low-pass on the first reading
    // instead of averaging (3.1 s here, where the first reading happens to carry little
    // acceleration; BROAD 10.9 s).
    assert!(r < 12.0 && r < v, "robust {r:.2} s, VQF {v:.2} s");
}
