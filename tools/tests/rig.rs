//! The rig simulator's truth is self-consistent, the rig description reads what it
//! writes, and `replay --rig` scores what a direct computation of RIG-FORMAT.md's rule
//! gives on its own output files.

use orient::{Quat, Vec3};
use orient_tools::rig::{joint_angles, JointKind, RigRecording, RigSpec};
use orient_tools::rigsim::{bias_drift_arg, exp, log, SimConfig, SimRig, Simulation};
use std::path::PathBuf;
use std::process::Command;

fn short(seed: u64, seconds: f64, rate: f64) -> SimConfig {
    SimConfig { duration_s: seconds, rate_hz: rate, ..SimConfig::preset("60hz-vigorous", seed).unwrap() }
}

fn angle(a: Vec3, b: Vec3) -> f64 {
    libm::atan2(a.cross(b).norm(), a.dot(b))
}

/// The true axes in the segment frames (the description's mountings are the true ones
/// when no mounting error is configured).
fn segment_axes(sim: &SimRig, j: usize) -> (Vec3, Vec3) {
    let spec = &sim.recording.spec;
    let joint = &spec.joints[j];
    let (ap, ac) = sim.true_axes[j];
    (spec.sensors[joint.parent].mounting.rotate(ap), spec.sensors[joint.child].mounting.rotate(ac))
}

#[test]
fn joint_constraints_hold_in_the_truth_up_to_the_laxity() {
    let c = short(3, 60.0, 100.0);
    let sim = Simulation::new(c.clone()).run();
    let spec = &sim.recording.spec;
    assert_eq!((spec.sensors.len(), spec.joints.len()), (9, 8));
    for (j, joint) in spec.joints.iter().enumerate() {
        let (ap, ac) = segment_axes(&sim, j);
        let (p, ch) = (&sim.segment_truth[joint.parent], &sim.segment_truth[joint.child]);
        let mut worst: f64 = 0.0;
        for (qp, qc) in p.iter().zip(ch) {
            let off = match joint.kind {
                // Both ends of a hinge's axis are one earth vector.
                JointKind::Hinge => angle(qp.rotate(ap), qc.rotate(ac)),
                // A 2-DoF joint keeps its axes perpendicular.
                JointKind::TwoDof => {
                    (angle(qp.rotate(ap), qc.rotate(ac)) - std::f64::consts::FRAC_PI_2).abs()
                }
            };
            worst = worst.max(off.to_degrees());
        }
        let bound = match joint.kind {
            JointKind::Hinge => c.laxity_deg * 2f64.sqrt(),
            JointKind::TwoDof => c.laxity_deg + c.axial_play_deg,
        };
        assert!(worst <= bound + 1e-9, "{}: {worst:.3} deg off the constraint, bound {bound}", joint.name);
        // The laxity is there, not zero.
        assert!(worst > 0.3 * c.laxity_deg, "{}: only {worst:.3} deg of laxity", joint.name);
    }
}

#[test]
fn fingers_flex_through_their_range_and_the_angles_read_back() {
    let c = short(5, 90.0, 100.0);
    let sim = Simulation::new(c.clone()).run();
    let spec = &sim.recording.spec;
    let wobble = 2.0 * 3f64.sqrt() * c.wobble_deg;
    for joint in spec.joints.iter().filter(|j| j.kind == JointKind::Hinge) {
        let (p, ch) = (&sim.recording.sensors[joint.parent].truth, &sim.recording.sensors[joint.child].truth);
        let a: Vec<f64> =
            p.iter().zip(ch).map(|(p, c)| joint_angles(spec, joint, *p, *c).0.to_degrees()).collect();
        // Zero at the reference pose.
        assert!(a[..400].iter().all(|x| x.abs() < 1e-6), "{}: {:?}", joint.name, &a[..3]);
        let (lo, hi) = a.iter().fold((f64::MAX, f64::MIN), |(l, h), x| (l.min(*x), h.max(*x)));
        // PIP flexion 0..90 deg (vigorous: 15 % wider), seen through laxity and wobble.
        let slack = c.laxity_deg + wobble;
        assert!(lo >= -slack && hi <= 90.0 * 1.15 + slack, "{}: {lo:.1}..{hi:.1}", joint.name);
        assert!(hi > 45.0, "{}: flexes only to {hi:.1} deg", joint.name);
    }
}

#[test]
fn the_reference_pose_is_level_and_the_mountings_give_the_segments() {
    let sim = Simulation::new(short(7, 12.0, 100.0)).run();
    let spec = &sim.recording.spec;
    let end = spec.reference_pose.as_ref().unwrap().end;
    let up = Vec3::new(0.0, 0.0, 1.0);
    let first = sim.segment_truth[0][0];
    for (s, sensor) in spec.sensors.iter().enumerate() {
        for (i, t) in sim.recording.t().iter().enumerate().filter(|(_, t)| **t < end) {
            let seg = sim.segment_truth[s][i];
            assert!(angle(seg.rotate(up), up) < 1e-12, "{} not level at t = {t}", sensor.name);
            assert!(seg.angle_to(first) < 1e-12, "{} turned from the hand at t = {t}", sensor.name);
            let from_sensor = sim.recording.sensors[s].truth[i] * sensor.mounting.conj();
            assert!(
                from_sensor.angle_to(seg) < 1e-12,
                "{}: sensor times mounting⁻¹ is not the segment",
                sensor.name
            );
            // Still: the accelerometer reads gravity in the sensor frame, within noise.
            let f = sim.recording.sensors[s].accel[i];
            assert!((f - sim.recording.sensors[s].truth[i].rotate_inverse(up * 9.81)).norm() < 0.3);
        }
        // Mountings are not identity.
        assert!(sensor.mounting.angle_to(Quat::IDENTITY) > 1e-3, "{}", sensor.name);
    }
    // And then the body moves.
    let last = sim.recording.rows() - 1;
    assert!(sim.segment_truth[0][last].angle_to(first) > 1e-3);
}

#[test]
fn the_gyroscope_integrates_to_the_truth_within_noise() {
    let c = short(11, 60.0, 60.0);
    let sim = Simulation::new(c.clone()).run();
    let dt = 1.0 / c.rate_hz;
    let window = c.rate_hz as usize; // 1 s
    let mut worst_unbiased: f64 = 0.0;
    let mut still = 0;
    let mut largest: f64 = 0.0;
    for (s, rec) in sim.recording.sensors.iter().enumerate() {
        for start in (0..rec.len() - window).step_by(window) {
            let mut q = rec.truth[start];
            let mut raw = q;
            for i in start + 1..=start + window {
                q = (q * exp((rec.gyro[i] - sim.bias[s][i]) * dt)).normalized();
                raw = (raw * exp(rec.gyro[i] * dt)).normalized();
            }
            let truth = rec.truth[start + window];
            worst_unbiased = worst_unbiased.max(q.angle_to(truth).to_degrees());
            // The bias is there, up to its bound: over 1 s still it turns the estimate
            // by its size (in motion the body frame turns the error about).
            let b = sim.bias[s][start].norm().to_degrees();
            let per_axis = sim.bias[s][start].max_abs().to_degrees();
            assert!(per_axis <= c.bias_deg_s && b > 0.05 * c.bias_deg_s, "bias {b} deg/s");
            largest = largest.max(per_axis);
            if sim.activity[start..=start + window].iter().all(|a| *a == 0.0) {
                still += 1;
                let drift = raw.angle_to(truth).to_degrees();
                assert!((drift - b).abs() < 0.1 * b, "sensor {s}: {drift:.3} deg in 1 s, bias {b:.3} deg/s");
            }
        }
    }
    // White noise of σ per axis over n steps: an angle of about σ·dt·√(3n) (here
    // 0.1 deg/s → 0.02 deg); five times that is the bound.
    let expected = c.gyro_noise.to_degrees() * dt * (3.0 * window as f64).sqrt();
    // Some sensor comes near the bound.
    assert!(largest > 0.5 * c.bias_deg_s, "largest bias {largest} deg/s");
    assert!(still >= 4 * sim.recording.sensors.len(), "{still} still windows");
    assert!(worst_unbiased < 5.0 * expected, "{worst_unbiased:.4} deg after 1 s, noise alone {expected:.4}");
    assert!(log(exp(Vec3::new(0.3, -0.2, 0.1))).norm() - Vec3::new(0.3, -0.2, 0.1).norm() < 1e-15);
}

/// Scale and axis errors: the reading less the bias is `(I + E) ω` plus the same noise,
/// `E`'s entries within their bounds and some near them; everything else about the
/// recording is the same as without them.
#[test]
fn gyroscope_scale_errors_are_within_their_bounds() {
    let plain = Simulation::new(short(12, 20.0, 60.0)).run();
    let scaled = Simulation::new(SimConfig { gyro_scale_pct: 2.0, ..short(12, 20.0, 60.0) }).run();
    let dt = 1.0 / 60.0;
    let mut largest: f64 = 0.0;
    for (s, (a, b)) in plain.recording.sensors.iter().zip(&scaled.recording.sensors).enumerate() {
        assert_eq!(a.truth, b.truth);
        assert_eq!(a.accel, b.accel);
        for i in 1..a.len() {
            // ω of the interval, as the simulator takes it; E ω is what scaling added.
            let omega = log(a.truth[i - 1].conj() * a.truth[i]) * (1.0 / dt);
            let added = b.gyro[i] - a.gyro[i];
            assert_eq!(plain.bias[s][i], scaled.bias[s][i]);
            // |(E ω)_i| ≤ |(0.02, 0.01, 0.01)| |ω| per component.
            assert!(added.max_abs() <= 0.0245 * omega.norm() + 1e-12, "{added:?} {omega:?}");
            if omega.norm() > 1.0 {
                largest = largest.max(added.norm() / omega.norm());
            }
        }
    }
    assert!(largest > 0.01, "{largest}");
}

/// `bias_drift`: 0 keeps each sensor's bias constant, a share d moves it by at most d of
/// the bound around a centre within 1 - d of it, and the motion is the same whatever d
/// is; `--bias-drift` takes 0 to 1 and nothing else.
#[test]
fn the_bias_drifts_by_the_share_it_is_given() {
    let base = short(5, 120.0, 60.0);
    let bound = base.bias_deg_s.to_radians();
    let (steady, drifting) = (
        Simulation::new(SimConfig { bias_drift: 0.0, ..base.clone() }).run(),
        Simulation::new(SimConfig { bias_drift: 0.5, ..base }).run(),
    );
    let mut moved: f64 = 0.0;
    for (s, (a, b)) in steady.bias.iter().zip(&drifting.bias).enumerate() {
        assert_eq!(steady.recording.sensors[s].truth, drifting.recording.sensors[s].truth);
        assert!(a.iter().all(|x| *x == a[0]), "sensor {s}: a steady bias moved");
        for x in b {
            assert!(x.max_abs() <= bound + 1e-15, "sensor {s}: {x:?} beyond the bound");
            moved = moved.max((*x - b[0]).max_abs());
        }
    }
    // Over two minutes some axis moves by a good part of its 0.5 of the bound.
    assert!(moved > 0.05 * bound && moved <= bound, "largest move {moved} rad/s");
    for ok in ["0", "0.2", "1"] {
        assert!(bias_drift_arg(ok).is_ok(), "{ok}");
    }
    for bad in ["-0.1", "1.5", "NaN", "inf", "x"] {
        assert!(bias_drift_arg(bad).is_err(), "{bad}");
    }
}

#[test]
fn rig_json_reads_what_it_writes_and_refuses_what_is_not_a_tree() {
    let sim = Simulation::new(short(2, 1.0, 60.0)).run();
    let spec = &sim.recording.spec;
    let back = RigSpec::parse(&spec.to_json()).unwrap();
    assert_eq!(back.sensors.len(), spec.sensors.len());
    for (a, b) in back.sensors.iter().zip(&spec.sensors) {
        assert_eq!((a.name.as_str(), a.file.as_str()), (b.name.as_str(), b.file.as_str()));
        assert!(a.mounting.angle_to(b.mounting) < 1e-12);
    }
    for (a, b) in back.joints.iter().zip(&spec.joints) {
        assert_eq!((a.kind, a.parent, a.child), (b.kind, b.parent, b.child));
        assert!(
            (a.axis_parent - b.axis_parent).norm() < 1e-12 && (a.axis_child - b.axis_child).norm() < 1e-12
        );
    }
    let rig = |joints: &str| {
        format!(
            "{{\"rate_hz\": 100, \"sensors\": [{{\"name\": \"a\", \"file\": \"a.csv\"}}, \
             {{\"name\": \"b\", \"file\": \"b.csv\"}}, {{\"name\": \"c\", \"file\": \"c.csv\"}}], \"joints\": [{joints}]}}"
        )
    };
    let j = |p: &str, c: &str, axis: &str| {
        format!("{{\"name\": \"{p}{c}\", \"type\": \"hinge\", \"parent\": \"{p}\", \"child\": \"{c}\", \"axis_parent\": {axis}, \"axis_child\": [0, 1, 0]}}")
    };
    let y = "[0, 1, 0]";
    assert!(RigSpec::parse(&rig(&[j("a", "b", y), j("b", "c", y)].join(","))).is_ok());
    for (bad, why) in [
        (j("a", "a", y), "its own parent"),
        ([j("a", "c", y), j("b", "c", y)].join(","), "already has a parent"),
        ([j("b", "c", y), j("c", "b", y)].join(","), "cycle"),
        (j("a", "x", y), "no sensor named"),
        (j("a", "b", "[0, 0, 0]"), "not an axis"),
    ] {
        let e = RigSpec::parse(&rig(&bad)).unwrap_err();
        assert!(e.contains(why), "{why}: {e}");
    }
}

/// RIG-FORMAT.md's rule, written out here independently of `orient_tools::rig`.
fn direct_scores(
    spec: &RigSpec,
    t: &[f64],
    est: &[Vec<[f64; 4]>],
    truth: &[Vec<[f64; 4]>],
) -> (f64, f64, f64) {
    let mul = |a: [f64; 4], b: [f64; 4]| {
        [
            a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
            a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
            a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
        ]
    };
    let inv = |a: [f64; 4]| {
        let n = a.iter().map(|x| x * x).sum::<f64>();
        [a[0] / n, -a[1] / n, -a[2] / n, -a[3] / n]
    };
    let end = t[t.len() - 1];
    let (mut all, mut n, mut last, mut m, mut worst) = (0.0, 0.0, 0.0, 0.0, 0.0f64);
    for j in &spec.joints {
        let (mut s, mut k) = (0.0, 0.0);
        for i in (0..t.len()).filter(|i| t[*i] >= 10.0) {
            let r_est = mul(inv(est[j.parent][i]), est[j.child][i]);
            let r_true = mul(inv(truth[j.parent][i]), truth[j.child][i]);
            let e = mul(inv(r_est), r_true);
            let w = e[0] / e.iter().map(|x| x * x).sum::<f64>().sqrt();
            let a = 2.0 * w.abs().min(1.0).acos();
            s += a * a;
            k += 1.0;
            if t[i] >= end - 60.0 {
                last += a * a;
                m += 1.0;
            }
        }
        all += s;
        n += k;
        worst = worst.max((s / k).sqrt());
    }
    ((all / n).sqrt().to_degrees(), worst.to_degrees(), (last / m).sqrt().to_degrees())
}

fn read_quats(path: &std::path::Path, cols: [&str; 4]) -> (Vec<f64>, Vec<[f64; 4]>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at = |c: &str| head.iter().position(|h| *h == c).unwrap();
    let (ti, qi) = (at("t"), cols.map(at));
    let mut t = Vec::new();
    let mut q = Vec::new();
    for l in lines {
        let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
        t.push(v[ti]);
        q.push(qi.map(|i| v[i]));
    }
    (t, q)
}

#[test]
fn replay_rig_scores_what_a_direct_computation_gives() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("rig-replay-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let sim = Simulation::new(SimConfig { duration_s: 80.0, ..SimConfig::preset("100hz", 4).unwrap() }).run();
    sim.recording.write(&dir.join("in")).unwrap();
    // What was written reads back as what was simulated.
    let back = RigRecording::read(&dir.join("in/rig.json"), true).unwrap();
    assert_eq!(back.rows(), sim.recording.rows());
    let out = Command::new(env!("CARGO_BIN_EXE_replay"))
        .args(["--rig", dir.join("in/rig.json").to_str().unwrap(), "--out-dir"])
        .arg(dir.join("out"))
        .args(["--no-mag", "--kind", "robust"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    // "rig RMSE [deg]: all joints A  worst W (name)  last minute L ..."
    let line = stdout.lines().find(|l| l.starts_with("rig RMSE")).unwrap_or_else(|| panic!("{stdout}"));
    let num = |after: &str| -> f64 {
        let rest = &line[line.find(after).unwrap() + after.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    let printed = (num("all joints"), num("worst"), num("last minute"));

    let spec = &back.spec;
    let q = ["quat_w", "quat_x", "quat_y", "quat_z"];
    let mut est = Vec::new();
    let mut truth = Vec::new();
    let mut t = Vec::new();
    for s in &spec.sensors {
        let (te, e) = read_quats(&dir.join("out").join(format!("{}.csv", s.name)), q);
        let (tt, g) = read_quats(&dir.join("in").join(&s.file), q);
        assert_eq!(te.len(), tt.len(), "{}: one output row per input row", s.name);
        assert!(te.iter().zip(&tt).all(|(a, b)| (a - b).abs() < 1e-9));
        est.push(e);
        truth.push(g);
        t = tt;
    }
    let direct = direct_scores(spec, &t, &est, &truth);
    for (p, d) in [printed.0, printed.1, printed.2].iter().zip([direct.0, direct.1, direct.2]) {
        assert!((p - d).abs() <= 0.006, "printed {printed:?}, direct {direct:?}");
    }
    // The last minute is not the whole run here (80 s, scored from 10 s).
    assert!((direct.0 - direct.2).abs() > 1e-6);
    let joints = std::fs::read_to_string(dir.join("out/joints.csv")).unwrap();
    assert_eq!(joints.lines().count(), t.len() + 1);
    assert!(joints.lines().next().unwrap().contains("index_mcp_1,index_mcp_2,index_pip"));
    // The default is the joints; --no-joints every sensor alone, further apart.
    assert!(stdout.contains("robust 6D (joints)"), "{stdout}");
    // Each sensor's estimate as replay writes it into OUT/NAME with `extra`, and stdout.
    let replay = |name: &str, extra: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_replay"))
            .args(["--rig", dir.join("in/rig.json").to_str().unwrap(), "--out-dir"])
            .arg(dir.join(name))
            .arg("--no-mag")
            .args(extra)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let est: Vec<_> = spec
            .sensors
            .iter()
            .map(|s| read_quats(&dir.join(name).join(format!("{}.csv", s.name)), q).1)
            .collect();
        (String::from_utf8_lossy(&o.stdout).into_owned(), est)
    };
    let (alone, est) = replay("alone", &["--no-joints"]);
    assert!(alone.contains("robust 6D (every sensor alone)"), "{alone}");
    let apart = direct_scores(spec, &t, &est, &truth);
    assert!(direct.0 < 0.5 * apart.0, "joints {direct:?}, alone {apart:?}");
    // --joint-set reaches the joints: a parameter set to its default changes no bit of
    // the output, set to another value it changes the estimates.
    let (_, same) = replay("same", &["--joint-set", "gate=3"]);
    let (_, other) = replay("other", &["--joint-set", "gate=1"]);
    let (_, joints) = replay("joints", &[]);
    assert!(same == joints && other != joints);
    // Without the alignment the joints start with the headings unknown: heading_std0 π.
    let (_, unaligned) = replay("unaligned", &["--no-align"]);
    let (_, pi) = replay("pi", &["--no-align", "--joint-set", "heading_std0=3.141592653589793"]);
    let (_, one) = replay("one", &["--no-align", "--joint-set", "heading_std0=0.017453292519943295"]);
    assert!(unaligned == pi && unaligned != one);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn replay_rig_refuses_bad_descriptions_and_arguments_with_status_2() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("rig-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,9.81\n0.01,0,0,0,0,0,9.81\n";
    for f in ["a.csv", "b.csv"] {
        std::fs::write(dir.join(f), csv).unwrap();
    }
    std::fs::write(dir.join("short.csv"), &csv[..csv.rfind("0.01").unwrap()]).unwrap();
    let rig = |joints: &str, b_file: &str| {
        format!(
            "{{\"rate_hz\": 100, \"sensors\": [{{\"name\": \"a\", \"file\": \"a.csv\"}}, \
             {{\"name\": \"b\", \"file\": \"{b_file}\"}}], \"joints\": [{joints}]}}"
        )
    };
    let hinge = |p: &str, c: &str| {
        format!("{{\"name\": \"j{p}{c}\", \"type\": \"hinge\", \"parent\": \"{p}\", \"child\": \"{c}\", \"axis_parent\": [0, 1, 0], \"axis_child\": [0, 1, 0]}}")
    };
    let run = |json: &str, extra: &[&str]| {
        let path = dir.join("rig.json");
        std::fs::write(&path, json).unwrap();
        Command::new(env!("CARGO_BIN_EXE_replay"))
            .args(["--rig", path.to_str().unwrap(), "--no-mag"])
            .args(extra)
            .output()
            .unwrap()
    };
    let out = dir.join("out");
    let out = out.to_str().unwrap();
    // A good one first: no truth, nothing to score, status 0, one row per input row.
    let o = run(&rig(&hinge("a", "b"), "b.csv"), &["--out-dir", out]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("nothing to score"));
    assert_eq!(std::fs::read_to_string(dir.join("out/b.csv")).unwrap().lines().count(), 3);
    for (json, extra, needle) in [
        (rig(&[hinge("a", "b"), hinge("b", "a")].join(","), "b.csv"), vec!["--out-dir", out], "cycle"),
        (rig(&hinge("a", "b"), "short.csv"), vec!["--out-dir", out], "rows"),
        (rig(&hinge("a", "b"), "b.csv"), vec![], "--out-dir"),
        (rig(&hinge("a", "b"), "b.csv"), vec!["--out-dir", out, "--kind", "kalman"], "unknown kind"),
        (rig(&hinge("a", "b"), "b.csv"), vec!["--out-dir", out, "--svg", "x.svg"], "no truth"),
        (
            rig(&hinge("a", "b"), "b.csv"),
            vec!["--out-dir", out, "--joint-set", "beta=1"],
            "no joint parameter",
        ),
        (rig(&hinge("a", "b"), "b.csv"), vec!["--out-dir", out, "--joint-set", "gate=0"], "outside [0.1"),
        (rig(&hinge("a", "b"), "b.csv"), vec!["--out-dir", out, "--joint-set", "gate"], "KEY=VALUE"),
    ] {
        let o = run(&json, &extra);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{needle}: {err}");
        assert!(err.contains(needle), "{needle}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// What RIG-FORMAT.md allows and replay once misread (a review against the format): a
/// reference pose later in the recording, a sensor without readings in the pose, a sensor
/// named `joints`, truth in some files only, `t` written with fewer digits in one file, a
/// magnetometer at half the rate (NaN cells).
#[test]
fn replay_rig_takes_what_the_format_allows() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("rig-format-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let sim = Simulation::new(SimConfig { duration_s: 40.0, ..SimConfig::preset("100hz", 4).unwrap() }).run();
    sim.recording.write(&dir.join("in")).unwrap();
    let rig_json = std::fs::read_to_string(dir.join("in/rig.json")).unwrap();
    let q = ["quat_w", "quat_x", "quat_y", "quat_z"];
    let names: Vec<String> = sim.recording.spec.sensors.iter().map(|s| s.name.clone()).collect();
    // A variant: rig.json and each sensor's CSV as `edit` leaves them.
    let variant = |name: &str, json: &str, edit: &dyn Fn(&str, usize, &str) -> String| {
        let d = dir.join(name);
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("rig.json"), json).unwrap();
        for s in &names {
            let text = std::fs::read_to_string(dir.join("in").join(format!("{s}.csv"))).unwrap();
            let lines: Vec<String> = text.lines().enumerate().map(|(i, l)| edit(s, i, l)).collect();
            std::fs::write(d.join(format!("{s}.csv")), lines.join("\n") + "\n").unwrap();
        }
        d.join("rig.json")
    };
    let replay = |rig: &std::path::Path, out: &str, extra: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_replay"))
            .args(["--rig", rig.to_str().unwrap(), "--out-dir"])
            .arg(dir.join(out))
            .args(extra)
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(o.status.success(), "{stdout}{}", String::from_utf8_lossy(&o.stderr));
        let est: Vec<_> = names
            .iter()
            .map(|s| dir.join(out).join(format!("{s}.csv")))
            .filter(|p| p.exists())
            .map(|p| read_quats(&p, q).1)
            .collect();
        (stdout, est)
    };
    let same = |_: &str, _: usize, l: &str| l.to_string();
    let pose = "\"reference_pose\": {\"start\": 0, \"end\": 5, \"note\": \"hand level, fingers straight\"},";
    assert!(rig_json.contains(pose));
    let no_pose = variant("no-pose", &rig_json.replace(pose, ""), &same);
    let (_, unknown) = replay(&no_pose, "out-no-pose", &[]);
    let at = |t: f64| (t * 100.0).round() as usize;

    // A pose later in the recording: the rows before its last run as without a pose
    // (the joints find the headings from the motion), then the headings are aligned and
    // the joints start over. Before, those rows had no joints at all.
    let later =
        rig_json.replace(pose, &pose.replace("\"start\": 0, \"end\": 5", "\"start\": 20, \"end\": 25"));
    let (stdout, est) = replay(&variant("later", &later, &same), "out-later", &[]);
    assert!(stdout.contains("aligned at t = 24.99"), "{stdout}");
    let last = at(24.99);
    assert!(est.iter().zip(&unknown).all(|(e, u)| e[..last] == u[..last] && e[last..] != u[last..]));

    // A sensor without readings until after the pose: nothing can be aligned; replay says
    // which, and the run is the one without a pose, bit for bit.
    let late = |s: &str, i: usize, l: &str| {
        if s == "index_middle" && (1..=at(6.0)).contains(&i) {
            let mut cells: Vec<String> = l.split(',').map(str::to_string).collect();
            for c in &mut cells[1..10] {
                *c = "NaN".into();
            }
            cells.join(",")
        } else {
            l.to_string()
        }
    };
    let (stdout, est) = replay(&variant("late", &rig_json, &late), "out-late", &[]);
    assert!(
        stdout.contains("not aligned: at the reference pose's last row (t = 4.99) index_middle had"),
        "{stdout}"
    );
    let (_, without) =
        replay(&variant("late-no-pose", &rig_json.replace(pose, ""), &late), "out-late-np", &[]);
    assert!(est == without);
    // So with VQF, which has no orientation before its first accelerometer reading.
    let (stdout, _) = replay(&dir.join("late/rig.json"), "out-late-vqf", &["--kind", "vqf"]);
    assert!(stdout.contains("(t = 4.99) index_middle had no orientation yet"), "{stdout}");

    // With the pose at the start, the rows from its last on are those of joints started
    // there (what replay ran before the joints ran from the first row).
    {
        use orient::{Config, Filter, Kind};
        use orient_tools::joints::{JointParams, Joints};
        use orient_tools::rig::{reference_row, run_rig, SensorFilter};
        let rec = RigRecording::read(&dir.join("in/rig.json"), false).unwrap();
        let last = reference_row(&rec.spec, rec.t()).unwrap();
        let run = |stage: &mut Joints| {
            let mut config = Config::new(Kind::Robust).unwrap();
            config.for_joints();
            let mut f: Vec<SensorFilter> = (0..names.len())
                .map(|_| SensorFilter::Orient(Box::new(Filter::new(&config).unwrap())))
                .collect();
            run_rig(&rec, &mut f, stage, true).sensors
        };
        let unknown = JointParams { heading_std0: std::f64::consts::PI, ..JointParams::default() };
        let started = run(&mut Joints::new(&rec.spec, last, JointParams::default()));
        let restarted = run(&mut Joints::until_aligned(&rec.spec, unknown, JointParams::default()));
        assert!(started
            .iter()
            .zip(&restarted)
            .all(|(a, b)| a[last..] == b[last..] && a[..last] != b[..last]));
        let (_, est) = replay(&dir.join("in/rig.json"), "out-in", &[]);
        let restarted: Vec<Vec<[f64; 4]>> =
            restarted.iter().map(|s| s.iter().map(|q| [q.w, q.x, q.y, q.z]).collect()).collect();
        assert!(est.iter().zip(&restarted).all(|(a, b)| a.iter().zip(b).all(|(x, y)| (0..4).all(|k| (x
            [k]
            - y[k])
            .abs()
            < 1e-15))));
    }

    // A sensor named `joints`: its estimate is OUT/joints.csv, the angles go beside it.
    let renamed = rig_json
        .replace("\"name\": \"hand\"", "\"name\": \"joints\"")
        .replace("\"parent\": \"hand\"", "\"parent\": \"joints\"");
    let r = variant("renamed", &renamed, &same);
    let (stdout, _) = replay(&r, "out-renamed", &[]);
    assert!(stdout.contains("joint angles: joints_angles.csv"), "{stdout}");
    let (_, joints) = read_quats(&dir.join("out-renamed/joints.csv"), q);
    let (_, mut all) = replay(&dir.join("in/rig.json"), "out-all", &[]);
    assert_eq!(joints, all.remove(0));
    let angles = std::fs::read_to_string(dir.join("out-renamed/joints_angles.csv")).unwrap();
    assert!(angles.starts_with("t,index_mcp_1,index_mcp_2,index_pip,"));

    // Truth in all files but one: the joints whose two sensors have it are scored, as
    // with truth everywhere; the others are named.
    let full = replay(&dir.join("in/rig.json"), "out-full", &[]).0;
    let drop_truth = |s: &str, _: usize, l: &str| {
        if s == "little_middle" {
            l.split(',').take(10).collect::<Vec<_>>().join(",")
        } else {
            l.to_string()
        }
    };
    let (part, _) = replay(&variant("part", &rig_json, &drop_truth), "out-part", &[]);
    assert!(part.contains("no truth in little_middle: not scored: little_pip"), "{part}");
    let joint_line =
        |out: &str, j: &str| out.lines().find(|l| l.trim_start().starts_with(j)).unwrap().to_string();
    assert!(joint_line(&part, "little_pip").ends_with("not scored"), "{part}");
    for j in ["index_mcp", "index_pip", "little_mcp"] {
        assert_eq!(joint_line(&part, j), joint_line(&full, j));
    }

    // `t` in one file within a quarter of the period of the first file's: the same rows.
    let shifted = |by: f64| {
        move |s: &str, i: usize, l: &str| {
            if s != "ring_middle" || i == 0 {
                return l.to_string();
            }
            let (t, rest) = l.split_once(',').unwrap();
            format!("{},{rest}", t.parse::<f64>().unwrap() + by)
        }
    };
    let (_, est) = replay(&variant("close", &rig_json, &shifted(0.0024)), "out-close", &[]);
    assert!(est == replay(&dir.join("in/rig.json"), "out-again", &[]).1);
    let far = variant("far", &rig_json, &shifted(0.0026));
    let o = Command::new(env!("CARGO_BIN_EXE_replay"))
        .args(["--rig", far.to_str().unwrap(), "--out-dir"])
        .arg(dir.join("out-far"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("a quarter of the nominal period"));

    // A magnetometer at half the rate (NaN on every other row): every gyroscope row is
    // taken, each sensor alone in 9D, none rejected.
    let half = |_: &str, i: usize, l: &str| {
        if i % 2 == 1 {
            let mut cells: Vec<&str> = l.split(',').collect();
            cells[7..10].fill("NaN");
            cells.join(",")
        } else {
            l.to_string()
        }
    };
    let (stdout, _) = replay(&variant("half", &rig_json, &half), "out-half", &["--no-joints"]);
    assert!(stdout.contains("robust 9D") && stdout.contains(" 0 rejected"), "{stdout}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The library's joints (orient::joints) on simulated gloves, 6D, seeds the defaults were
/// not chosen on: the child segments stay with their parents where every sensor alone
/// drifts apart. Two minutes per case, the filters under joints with the settings for
/// joints: over seeds 7-12 the joints scored 0.40 to 1.32 deg (every sensor alone, the
/// defaults, 2.57 to 5.90), and 1.08 to 2.06 with biases to 3 deg/s (alone 9.7 to 24.9;
/// measured with the robust kind's rest time constant at 2 s, its default then),
/// so 1.6 deg (2.5 with those biases) and half of alone fail only on a change of
/// behaviour (the 10-minute figures against the target: `rig_joints`).
#[test]
fn joints_hold_a_6d_glove_together() {
    use orient::{Config, Filter, Kind};
    use orient_tools::joints::{JointParams, Joints};
    use orient_tools::rig::{joint_errors, reference_row, run_rig, score_rig, Alone, SensorFilter};
    let cases =
        [("100hz", 7, 1.6), ("60hz-vigorous", 8, 1.6), ("axes-5deg-off", 9, 1.6), ("bias-3dps", 10, 2.5)];
    for (case, seed, bound) in cases {
        let config = SimConfig { duration_s: 120.0, ..SimConfig::preset(case, seed).unwrap() };
        let mut sim = Simulation::new(config).run();
        for s in &mut sim.recording.sensors {
            s.mag.clear();
        }
        let rec = &sim.recording;
        let truth: Vec<&[Quat]> = rec.sensors.iter().map(|r| r.truth.as_slice()).collect();
        // Every sensor alone with the defaults, under joints with the settings for joints.
        let robust = |under_joints: bool| -> Vec<SensorFilter> {
            let mut config = Config::new(Kind::Robust).unwrap();
            if under_joints {
                config.for_joints();
            }
            (0..rec.spec.sensors.len())
                .map(|_| SensorFilter::Orient(Box::new(Filter::new(&config).unwrap())))
                .collect()
        };
        let start = reference_row(&rec.spec, rec.t()).expect("a reference pose");
        let alone = run_rig(rec, &mut robust(false), &mut Alone, true);
        let mut stage = Joints::new(&rec.spec, start, JointParams::default());
        let joints = run_rig(rec, &mut robust(true), &mut stage, true);
        let score = |run: &orient_tools::rig::RigRun| {
            score_rig(&rec.spec, rec.t(), &joint_errors(&rec.spec, &run.sensors, &truth))
        };
        let (a, j) = (score(&alone), score(&joints));
        assert!(j.all < bound && j.all < 0.5 * a.all, "{case} seed {seed}: joints {j:?}, alone {a:?}");
        // Two minutes of real estimates save and load into a fresh rig.
        let mut blob = vec![0u8; stage.joints.state_size()];
        stage.joints.save(&mut blob).unwrap();
        let mut fresh = Joints::new(&rec.spec, start, JointParams::default());
        fresh.joints.load(&blob).unwrap();
        assert_eq!(format!("{:?}", fresh.joints), format!("{:?}", stage.joints));
        // Every rating in [0, 1], every angle of a hinge finite.
        for (k, spec) in rec.spec.joints.iter().enumerate() {
            let r = stage.joints.rating(k);
            assert!((0.0..=1.0).contains(&r), "{r}");
            assert!(stage.joints.angles(k)[0].is_finite(), "{}", spec.name);
        }
    }
}
