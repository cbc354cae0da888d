//! Rig recordings (`shared/data/RIG-FORMAT.md`): several sensors on one body, joined by
//! hinge and 2-DoF joints. Reading and writing `rig.json`, running one orientation
//! filter per sensor over a recording ([`run_rig`], with one place where a joint
//! estimator plugs in: [`JointStage`]), the format's score ([`score_rig`]) and joint
//! angles in the axes' convention ([`joint_angles`]).
//!
//! Shared by `replay --rig`, the simulator (`rigsim`, `simulate_rig`), the baseline
//! benchmark (`rig_baseline`) and the tests.

use crate::eval::Recording;
use crate::json::{self, Value};
use orient::{Filter, Quat, Sample, Vec3};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// One sensor of a rig.
#[derive(Clone, Debug, PartialEq)]
pub struct RigSensor {
    pub name: String,
    /// The CSV file, relative to the rig's folder.
    pub file: String,
    /// Sensor to segment, `v_segment = R(mounting) v_sensor` (unit; identity when absent).
    pub mounting: Quat,
}

/// The joint kinds of rig.json (`"hinge"`, `"2dof"`): the library's.
pub use orient::joints::JointKind;

/// One joint: sensor indices into [`RigSpec::sensors`], unit axes in the sensor frames.
#[derive(Clone, Debug, PartialEq)]
pub struct RigJoint {
    pub name: String,
    pub kind: JointKind,
    pub parent: usize,
    pub child: usize,
    pub axis_parent: Vec3,
    pub axis_child: Vec3,
}

/// The interval (seconds) in which every segment frame is the same level frame.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferencePose {
    pub start: f64,
    pub end: f64,
    pub note: String,
}

/// The contents of `rig.json`.
#[derive(Clone, Debug, PartialEq)]
pub struct RigSpec {
    pub rate_hz: f64,
    pub reference_pose: Option<ReferencePose>,
    pub sensors: Vec<RigSensor>,
    /// A tree: each child has one parent, no cycles (checked by [`RigSpec::parse`]).
    pub joints: Vec<RigJoint>,
}

fn quat_from(v: &Value, what: &str) -> Result<Quat, String> {
    let a = v.as_array().filter(|a| a.len() == 4).ok_or(format!("{what}: expected [w, x, y, z]"))?;
    let c: Vec<f64> =
        a.iter().map(|x| x.as_f64().ok_or(format!("{what}: not a number"))).collect::<Result<_, _>>()?;
    let q = Quat::new(c[0], c[1], c[2], c[3]);
    let n = q.norm();
    if !(n.is_finite() && n > 1e-6) {
        return Err(format!("{what}: not a rotation (norm {n})"));
    }
    Ok(q.scale(1.0 / n))
}

fn axis_from(v: &Value, what: &str) -> Result<Vec3, String> {
    let a = v.as_array().filter(|a| a.len() == 3).ok_or(format!("{what}: expected [x, y, z]"))?;
    let c: Vec<f64> =
        a.iter().map(|x| x.as_f64().ok_or(format!("{what}: not a number"))).collect::<Result<_, _>>()?;
    let v = Vec3::new(c[0], c[1], c[2]);
    let n = v.norm();
    if !(n.is_finite() && n > 1e-6) {
        return Err(format!("{what}: not an axis (norm {n})"));
    }
    Ok(v * (1.0 / n))
}

impl RigSpec {
    /// Reads `rig.json`; see [`RigSpec::parse`].
    pub fn read(path: &Path) -> Result<RigSpec, String> {
        let text =
            std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        RigSpec::parse(&text)
    }

    /// Parses and checks a description: unique sensor names, joints naming known
    /// sensors, a tree (no sensor its own parent, no child with two parents, no cycle),
    /// usable mountings and axes (normalised here).
    pub fn parse(text: &str) -> Result<RigSpec, String> {
        let v = json::parse(text).map_err(|e| e.to_string())?;
        let rate_hz = v.get("rate_hz").and_then(Value::as_f64).ok_or("rate_hz: a number is required")?;
        if rate_hz.is_nan() || rate_hz <= 0.0 {
            return Err(format!("rate_hz: must be positive, got {rate_hz}"));
        }
        let reference_pose = match v.get("reference_pose") {
            None | Some(Value::Null) => None,
            Some(r) => {
                let f = |k: &str| {
                    r.get(k)
                        .and_then(Value::as_f64)
                        .ok_or(format!("reference_pose.{k}: a number is required"))
                };
                let (start, end) = (f("start")?, f("end")?);
                if end <= start {
                    return Err(format!("reference_pose: end {end} is not after start {start}"));
                }
                let note = r.get("note").and_then(Value::as_str).unwrap_or("").to_string();
                Some(ReferencePose { start, end, note })
            }
        };
        let mut sensors: Vec<RigSensor> = Vec::new();
        for (i, s) in v
            .get("sensors")
            .and_then(Value::as_array)
            .ok_or("sensors: an array is required")?
            .iter()
            .enumerate()
        {
            let name = s
                .get("name")
                .and_then(Value::as_str)
                .ok_or(format!("sensors[{i}].name: a string is required"))?;
            if sensors.iter().any(|o| o.name == name) {
                return Err(format!("sensors[{i}]: the name '{name}' is used twice"));
            }
            let file = s
                .get("file")
                .and_then(Value::as_str)
                .ok_or(format!("sensors[{i}].file: a string is required"))?;
            let mounting = match s.get("mounting") {
                None | Some(Value::Null) => Quat::IDENTITY,
                Some(m) => quat_from(m, &format!("sensors[{i}].mounting"))?,
            };
            sensors.push(RigSensor { name: name.into(), file: file.into(), mounting });
        }
        if sensors.is_empty() {
            return Err("sensors: at least one sensor is required".into());
        }
        let mut joints: Vec<RigJoint> = Vec::new();
        let empty = Vec::new();
        let list = match v.get("joints") {
            None => &empty[..],
            Some(j) => j.as_array().ok_or("joints: an array is required")?,
        };
        for (i, j) in list.iter().enumerate() {
            let what = |k: &str| format!("joints[{i}].{k}");
            let name =
                j.get("name").and_then(Value::as_str).ok_or(what("name") + ": a string is required")?;
            let kind = match j.get("type").and_then(Value::as_str) {
                Some("hinge") => JointKind::Hinge,
                Some("2dof") => JointKind::TwoDof,
                other => return Err(format!("{}: 'hinge' or '2dof', got {other:?}", what("type"))),
            };
            let sensor = |k: &str| -> Result<usize, String> {
                let n = j.get(k).and_then(Value::as_str).ok_or(what(k) + ": a sensor name is required")?;
                sensors.iter().position(|s| s.name == n).ok_or(format!("{}: no sensor named '{n}'", what(k)))
            };
            let (parent, child) = (sensor("parent")?, sensor("child")?);
            if parent == child {
                return Err(format!("joints[{i}] ('{name}'): a sensor cannot be its own parent"));
            }
            if let Some(o) = joints.iter().find(|o| o.child == child) {
                return Err(format!(
                    "joints[{i}] ('{name}'): '{}' already has a parent (joint '{}')",
                    sensors[child].name, o.name
                ));
            }
            let axis = |k: &str| axis_from(j.get(k).ok_or(what(k) + ": an axis is required")?, &what(k));
            joints.push(RigJoint {
                name: name.into(),
                kind,
                parent,
                child,
                axis_parent: axis("axis_parent")?,
                axis_child: axis("axis_child")?,
            });
        }
        // A cycle: walking up from any sensor takes more steps than there are joints.
        for (start, first) in sensors.iter().enumerate() {
            let (mut s, mut steps) = (start, 0);
            while let Some(j) = joints.iter().find(|j| j.child == s) {
                s = j.parent;
                steps += 1;
                if steps > joints.len() {
                    return Err(format!("joints: a cycle through '{}'", first.name));
                }
            }
        }
        Ok(RigSpec { rate_hz, reference_pose, sensors, joints })
    }

    /// `rig.json` text for this description.
    pub fn to_json(&self) -> String {
        let q = |q: Quat| format!("[{}, {}, {}, {}]", q.w, q.x, q.y, q.z);
        let v = |v: Vec3| format!("[{}, {}, {}]", v.x, v.y, v.z);
        let mut s = format!("{{\n \"rate_hz\": {},\n", self.rate_hz);
        if let Some(r) = &self.reference_pose {
            s += &format!(
                " \"reference_pose\": {{\"start\": {}, \"end\": {}, \"note\": {}}},\n",
                r.start,
                r.end,
                json::quote(&r.note)
            );
        }
        s += " \"sensors\": [\n";
        let sensors: Vec<String> = self
            .sensors
            .iter()
            .map(|x| {
                format!(
                    "  {{\"name\": {}, \"file\": {}, \"mounting\": {}}}",
                    json::quote(&x.name),
                    json::quote(&x.file),
                    q(x.mounting)
                )
            })
            .collect();
        s += &sensors.join(",\n");
        s += "\n ],\n \"joints\": [\n";
        let joints: Vec<String> = self
            .joints
            .iter()
            .map(|j| {
                format!(
                    "  {{\"name\": {}, \"type\": \"{}\", \"parent\": {}, \"child\": {},\n   \"axis_parent\": {}, \"axis_child\": {}}}",
                    json::quote(&j.name),
                    j.kind.name(),
                    json::quote(&self.sensors[j.parent].name),
                    json::quote(&self.sensors[j.child].name),
                    v(j.axis_parent),
                    v(j.axis_child)
                )
            })
            .collect();
        s += &joints.join(",\n");
        s += "\n ]\n}\n";
        s
    }

    /// The index of the sensor named `name`.
    pub fn sensor(&self, name: &str) -> Option<usize> {
        self.sensors.iter().position(|s| s.name == name)
    }
}

/// A rig recording in memory: the description and one [`Recording`] per sensor, all with
/// the same rows.
#[derive(Clone, Debug)]
pub struct RigRecording {
    pub spec: RigSpec,
    pub sensors: Vec<Recording>,
}

impl RigRecording {
    /// Reads `rig.json` and every sensor's CSV (files relative to its folder); checks that
    /// all files have the same rows, each row's `t` within a quarter of the nominal period
    /// of the first file's (a `t` written with fewer digits in one file, as FORMAT.md's
    /// `%.7g`, is the same instant), and gives every sensor the first file's `t`.
    pub fn read(rig_json: &Path, with_mag: bool) -> Result<RigRecording, String> {
        let spec = RigSpec::read(rig_json)?;
        let dir = rig_json.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let mut sensors: Vec<Recording> = Vec::new();
        for s in &spec.sensors {
            let path = dir.join(&s.file);
            let mut rec = Recording::read(&path, with_mag).map_err(|e| format!("{}: {e}", path.display()))?;
            if let Some(first) = sensors.first() {
                if first.t.len() != rec.t.len() {
                    return Err(format!(
                        "{}: {} rows, the first sensor's file has {}",
                        path.display(),
                        rec.t.len(),
                        first.t.len()
                    ));
                }
                let within = 0.25 / spec.rate_hz;
                if let Some(i) = first.t.iter().zip(&rec.t).position(|(a, b)| (a - b).abs() > within) {
                    return Err(format!(
                        "{}: row {} (line {}) is at t = {}, the first sensor's at {} (more than a \
                         quarter of the nominal period apart)",
                        path.display(),
                        i,
                        i + 2,
                        rec.t[i],
                        first.t[i]
                    ));
                }
                // One instant per row: every sensor's steps are the first file's.
                rec.t.clone_from(&first.t);
            }
            sensors.push(rec);
        }
        Ok(RigRecording { spec, sensors })
    }

    /// Writes `rig.json` and the sensors' CSVs (the columns of FORMAT.md, truth and
    /// movement where present) into `dir`, creating it.
    pub fn write(&self, dir: &Path) -> std::io::Result<()> {
        use std::io::Write;
        std::fs::create_dir_all(dir)?;
        std::fs::write(dir.join("rig.json"), self.spec.to_json())?;
        for (s, rec) in self.spec.sensors.iter().zip(&self.sensors) {
            let mut w = std::io::BufWriter::new(std::fs::File::create(dir.join(&s.file))?);
            let truth = rec.has_truth();
            let mag = !rec.mag.is_empty();
            write!(w, "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z")?;
            if mag {
                write!(w, ",mag_x,mag_y,mag_z")?;
            }
            if truth {
                write!(w, ",quat_w,quat_x,quat_y,quat_z,movement")?;
            }
            writeln!(w)?;
            for i in 0..rec.len() {
                let (g, a) = (rec.gyro[i], rec.accel[i]);
                write!(
                    w,
                    "{},{:.7e},{:.7e},{:.7e},{:.7e},{:.7e},{:.7e}",
                    rec.t[i], g.x, g.y, g.z, a.x, a.y, a.z
                )?;
                if mag {
                    let m = rec.mag[i];
                    write!(w, ",{:.7e},{:.7e},{:.7e}", m.x, m.y, m.z)?;
                }
                if truth {
                    let q = rec.truth[i];
                    write!(w, ",{:.9},{:.9},{:.9},{:.9},{}", q.w, q.x, q.y, q.z, u8::from(rec.movement[i]))?;
                }
                writeln!(w)?;
            }
            w.flush()?;
        }
        Ok(())
    }

    pub fn rows(&self) -> usize {
        self.sensors[0].len()
    }

    pub fn t(&self) -> &[f64] {
        &self.sensors[0].t
    }
}

pub use orient::joints::twist_angle;

/// The yaw (rad) of an ENU orientation: the twist about the vertical.
pub fn yaw_of(q: Quat) -> f64 {
    twist_angle(q, Vec3::new(0.0, 0.0, 1.0))
}

/// A joint's angles (rad) from its two sensors' orientations (sensor to earth), zero when
/// the segments coincide (the reference pose: relative sensor orientation
/// `m_parent⁻¹ m_child`), positive by the right-hand rule about the given axes: a hinge
/// gives `(θ, NaN)`, the turn about its axis; a 2-DoF joint `(α, β)`, the turns about
/// `axis_parent` and then `axis_child` that make up the relative orientation (exactly
/// when the axes are true, nearest otherwise).
pub fn joint_angles(spec: &RigSpec, j: &RigJoint, q_parent: Quat, q_child: Quat) -> (f64, f64) {
    let (m_p, m_c) = (spec.sensors[j.parent].mounting, spec.sensors[j.child].mounting);
    let [a, b] = orient::joints::angles(j.kind, j.axis_parent, j.axis_child, m_p, m_c, q_parent, q_child);
    (a, b)
}

/// The error angle (rad) of one joint at one row: with `r = q_parent⁻¹ ⊗ q_child` for the
/// estimate and the truth, `2 acos |(r_est⁻¹ ⊗ r_true).w|`, computed with atan2.
pub fn joint_error(est_parent: Quat, est_child: Quat, true_parent: Quat, true_child: Quat) -> f64 {
    let r_est = est_parent.conj() * est_child;
    let r_true = true_parent.conj() * true_child;
    let e = r_est.conj() * r_true;
    2.0 * libm::atan2(e.vector().norm(), e.w.abs())
}

/// Every joint's error (rad) at every row: `[joint][row]`; NaN where an estimate or the
/// truth is not finite. `est[s]` and `truth[s]` are sensor `s`'s rows.
pub fn joint_errors(spec: &RigSpec, est: &[Vec<Quat>], truth: &[&[Quat]]) -> Vec<Vec<f64>> {
    spec.joints
        .iter()
        .map(|j| {
            (0..est[j.parent].len())
                .map(|i| {
                    let q = [est[j.parent][i], est[j.child][i], truth[j.parent][i], truth[j.child][i]];
                    if q.iter().all(|q| q.is_finite()) {
                        joint_error(q[0], q[1], q[2], q[3])
                    } else {
                        f64::NAN
                    }
                })
                .collect()
        })
        .collect()
}

/// The scores RIG-FORMAT.md defines, in degrees.
#[derive(Clone, Debug, PartialEq)]
pub struct RigScores {
    /// RMSE over all joints' rows with t ≥ [`SCORED_FROM`].
    pub all: f64,
    /// The worst joint's name and RMSE.
    pub worst: (String, f64),
    /// RMSE over all joints' rows in the last minute (and t ≥ [`SCORED_FROM`]).
    pub last_minute: f64,
    /// Each joint's RMSE, in [`RigSpec::joints`] order.
    pub joints: Vec<f64>,
    /// Rows scored, over all joints.
    pub rows: usize,
}

/// Rows before this time (s) are not scored.
pub const SCORED_FROM: f64 = 10.0;

/// Scores per-joint errors (rad, `[joint][row]`, NaN rows left out) by the rule of
/// RIG-FORMAT.md.
pub fn score_rig(spec: &RigSpec, t: &[f64], errors: &[Vec<f64>]) -> RigScores {
    let end = t.last().copied().unwrap_or(0.0);
    let (mut all, mut all_n, mut last, mut last_n) = (0.0, 0usize, 0.0, 0usize);
    let mut per = Vec::new();
    let mut rows = 0;
    for e in errors {
        let (mut s, mut n) = (0.0, 0usize);
        for (ti, x) in t.iter().zip(e) {
            if *ti < SCORED_FROM || !x.is_finite() {
                continue;
            }
            s += x * x;
            n += 1;
            if *ti >= end - 60.0 {
                last += x * x;
                last_n += 1;
            }
        }
        all += s;
        all_n += n;
        rows += n;
        per.push(if n == 0 { f64::NAN } else { (s / n as f64).sqrt().to_degrees() });
    }
    let rms = |s: f64, n: usize| if n == 0 { f64::NAN } else { (s / n as f64).sqrt().to_degrees() };
    let worst = per
        .iter()
        .enumerate()
        .filter(|(_, x)| x.is_finite())
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map_or((String::new(), f64::NAN), |(i, x)| (spec.joints[i].name.clone(), *x));
    RigScores { all: rms(all, all_n), worst, last_minute: rms(last, last_n), joints: per, rows }
}

/// One sensor's orientation filter in a rig run: one of orient's kinds, or VQF (`vqf-rs`,
/// its defaults) as the anchor the issue measures against.
pub enum SensorFilter {
    Orient(Box<Filter>),
    /// `started`: it has taken an accelerometer reading (before, `q` is no orientation).
    Vqf {
        f: Box<vqf_rs::VQF>,
        mag: bool,
        q: Quat,
        started: bool,
    },
}

impl SensorFilter {
    pub fn vqf(dt: f64, mag: bool) -> SensorFilter {
        SensorFilter::Vqf {
            f: Box::new(vqf_rs::VQF::new(dt, None, None, None)),
            mag,
            q: Quat::IDENTITY,
            started: false,
        }
    }

    /// Takes one sample; false when the filter rejected it. VQF takes a sample without
    /// an accelerometer or magnetometer reading as its steps for the readings there are
    /// (`update_gyr`, `update_acc`, `update_mag`, as `VQF::update` calls them), at its
    /// fixed period; one without a gyroscope reading is rejected.
    pub fn update(&mut self, s: &Sample) -> bool {
        match self {
            SensorFilter::Orient(f) => f.update(s).is_ok(),
            SensorFilter::Vqf { f, mag, q, started } => {
                let v = |v: Vec3| [v.x, v.y, v.z];
                let Some(g) = s.gyro else { return false };
                f.update_gyr(v(g));
                if let Some(a) = s.accel {
                    f.update_acc(v(a));
                    *started = true;
                }
                if let (true, Some(m)) = (*mag, s.mag) {
                    f.update_mag(v(m));
                }
                let e = if *mag { f.quat_9d() } else { f.quat_6d() };
                *q = Quat::new(e.0, e.1, e.2, e.3);
                true
            }
        }
    }

    /// Whether the filter learns its gyroscope bias in motion
    /// ([`Filter::learns_bias_in_motion`]; VQF's motion bias estimation does).
    pub fn learns_bias_in_motion(&self) -> bool {
        match self {
            SensorFilter::Orient(f) => f.learns_bias_in_motion(),
            SensorFilter::Vqf { .. } => true,
        }
    }

    /// The sensor's orientation (sensor to earth, ENU) before any heading alignment.
    pub fn sensor_quaternion(&self) -> Quat {
        match self {
            SensorFilter::Orient(f) => f.sensor_quaternion(),
            SensorFilter::Vqf { q, .. } => *q,
        }
    }
}

/// Where a joint estimator plugs into [`run_rig`]: called once per row after every
/// sensor's filter has taken that row's sample, with the row's samples and the sensors'
/// orientations (sensor to earth; from the reference pose's last row on, headings aligned
/// there when [`run_rig`] aligns them), which it may correct in place; what it leaves there is the run's output for the row.
pub trait JointStage {
    /// `learns[s]`: sensor `s`'s filter learns its gyroscope bias in motion
    /// ([`SensorFilter::learns_bias_in_motion`]).
    fn update(&mut self, row: usize, samples: &[Sample], learns: &[bool], sensors: &mut [Quat]);

    /// The headings were aligned at the reference pose's last row, `row`, before that
    /// row's [`JointStage::update`]. Not called when the alignment failed (a sensor
    /// without an orientation there).
    fn aligned(&mut self, _row: usize) {}
}

/// No joint estimation: every sensor alone.
pub struct Alone;

impl JointStage for Alone {
    fn update(&mut self, _: usize, _: &[Sample], _: &[bool], _: &mut [Quat]) {}
}

/// A rig run's output.
pub struct RigRun {
    /// `[sensor][row]`: each sensor's orientation after the joint stage.
    pub sensors: Vec<Vec<Quat>>,
    /// Samples a filter rejected, over all sensors.
    pub rejected: usize,
    /// Thread CPU time of the per-sample loop ([`crate::clock`]).
    pub elapsed: Duration,
    /// The row after which headings were aligned (the last row of the reference pose);
    /// `None` without a pose, without `align`, or when a sensor had no orientation there.
    pub aligned_at: Option<usize>,
    /// The sensors without an orientation at the pose's last row, when that left the
    /// headings unaligned.
    pub unaligned: Vec<usize>,
}

/// The last row inside the reference pose, if the recording has one and covers it.
pub fn reference_row(spec: &RigSpec, t: &[f64]) -> Option<usize> {
    let r = spec.reference_pose.as_ref()?;
    let i = t.partition_point(|x| *x < r.end);
    (i > 0 && t[i - 1] >= r.start).then(|| i - 1)
}

/// Runs `filters[s]` over sensor `s`'s samples, row by row. With `align` and a reference
/// pose, at its last row turns every sensor's heading so that all segments share the mean
/// heading (orient's kinds through [`Filter::align_rig_heading`], their mountings set from
/// the description; VQF by the same rotation about the vertical applied to its output):
/// the alignment a host makes once. Then `stage` sees each row.
pub fn run_rig(
    rec: &RigRecording,
    filters: &mut [SensorFilter],
    stage: &mut dyn JointStage,
    align: bool,
) -> RigRun {
    let spec = &rec.spec;
    let n = spec.sensors.len();
    assert_eq!(filters.len(), n, "one filter per sensor");
    for (f, s) in filters.iter_mut().zip(&spec.sensors) {
        if let SensorFilter::Orient(f) = f {
            f.set_mounting(s.mounting).expect("a normalised mounting");
        }
    }
    let samples: Vec<Vec<Sample>> = rec.sensors.iter().map(Recording::samples).collect();
    let rows = rec.rows();
    let align_row = if align { reference_row(spec, rec.t()) } else { None };
    let (mut aligned_at, mut unaligned) = (None, Vec::new());
    let mut out: Vec<Vec<Quat>> = (0..n).map(|_| Vec::with_capacity(rows)).collect();
    let mut offsets = vec![Quat::IDENTITY; n];
    let mut row_samples = vec![Sample { dt: 0.0, gyro: None, accel: None, mag: None }; n];
    let mut q = vec![Quat::IDENTITY; n];
    // A filter's settings do not change during a run.
    let learns: Vec<bool> = filters.iter().map(SensorFilter::learns_bias_in_motion).collect();
    let mut rejected = 0;
    let start = crate::clock::thread_cpu();
    for i in 0..rows {
        for ((f, sample), from) in filters.iter_mut().zip(row_samples.iter_mut()).zip(&samples) {
            *sample = from[i];
            if !f.update(sample) {
                rejected += 1;
            }
        }
        if Some(i) == align_row {
            match align_headings(spec, filters, &mut offsets) {
                Ok(()) => {
                    aligned_at = Some(i);
                    stage.aligned(i);
                }
                Err(sensors) => unaligned = sensors,
            }
        }
        for ((q, f), o) in q.iter_mut().zip(filters.iter()).zip(&offsets) {
            *q = *o * f.sensor_quaternion();
        }
        stage.update(i, &row_samples, &learns, &mut q);
        for (out, q) in out.iter_mut().zip(&q) {
            out.push(*q);
        }
    }
    RigRun {
        sensors: out,
        rejected,
        elapsed: crate::clock::thread_cpu().saturating_sub(start),
        aligned_at,
        unaligned,
    }
}

/// Gives every segment the mean heading of all segments (each segment's orientation is
/// its sensor's times the mounting's inverse); with nothing changed, the sensors that have
/// no orientation yet (no valid sample before the pose's last row).
fn align_headings(
    spec: &RigSpec,
    filters: &mut [SensorFilter],
    offsets: &mut [Quat],
) -> Result<(), Vec<usize>> {
    let none: Vec<usize> = (0..filters.len())
        .filter(|&s| match &filters[s] {
            SensorFilter::Orient(f) => !f.is_initialized(),
            SensorFilter::Vqf { started, .. } => !started,
        })
        .collect();
    if !none.is_empty() {
        return Err(none);
    }
    let segment = |f: &SensorFilter, s: usize| f.sensor_quaternion() * spec.sensors[s].mounting.conj();
    let (mut sin, mut cos) = (0.0, 0.0);
    for (s, f) in filters.iter().enumerate() {
        let y = yaw_of(segment(f, s));
        sin += libm::sin(y);
        cos += libm::cos(y);
    }
    let mean = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), libm::atan2(sin, cos));
    let mut orient: Vec<&mut Filter> = Vec::new();
    for (s, f) in filters.iter_mut().enumerate() {
        match f {
            SensorFilter::Orient(f) => orient.push(f),
            SensorFilter::Vqf { q, .. } => {
                let seg = *q * spec.sensors[s].mounting.conj();
                offsets[s] = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), yaw_of(mean * seg.conj()));
            }
        }
    }
    // Fails only for a filter without an orientation, checked above.
    let refs = vec![mean; orient.len()];
    if !orient.is_empty() {
        Filter::align_rig_heading(&mut orient, &refs).expect("every filter has an orientation");
    }
    Ok(())
}
