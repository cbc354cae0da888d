//! Recordings and scoring: read the recording CSV of `shared/data/FORMAT.md`, turn it into
//! samples, and score estimates against optical ground truth with BROAD's rule.
//!
//! Not used by the filters; the replay and benchmark tools and the tests share it.

use core::fmt;
use orient::filters::Sample;
use orient::math::{Quat, Vec3};
use std::path::Path;

/// A recording: IMU samples, optionally with ground truth and BROAD's movement mask.
#[derive(Clone, Debug, Default)]
pub struct Recording {
    /// Time of each row, seconds, strictly increasing.
    pub t: Vec<f64>,
    pub gyro: Vec<Vec3>,
    pub accel: Vec<Vec3>,
    /// Empty when the file has no magnetometer columns or they were not asked for.
    pub mag: Vec<Vec3>,
    /// Ground truth `q_ES` in ENU (NaN where not tracked); empty when absent.
    pub truth: Vec<Quat>,
    /// BROAD's movement mask (rows that count in the error); empty when absent.
    pub movement: Vec<bool>,
}

/// Why a CSV could not be read: the 1-based line, the column name, and what was wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct CsvError {
    pub line: usize,
    pub column: String,
    pub message: String,
}

impl fmt::Display for CsvError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.column.is_empty() {
            write!(f, "line {}: {}", self.line, self.message)
        } else {
            write!(f, "line {}, column '{}': {}", self.line, self.column, self.message)
        }
    }
}

impl std::error::Error for CsvError {}

const IMU_COLUMNS: [&str; 7] = ["t", "gyr_x", "gyr_y", "gyr_z", "acc_x", "acc_y", "acc_z"];
const MAG_COLUMNS: [&str; 3] = ["mag_x", "mag_y", "mag_z"];
const TRUTH_COLUMNS: [&str; 4] = ["quat_w", "quat_x", "quat_y", "quat_z"];

impl Recording {
    /// Reads a recording from a file; see [`Recording::parse`].
    pub fn read(path: &Path, with_mag: bool) -> Result<Recording, CsvError> {
        let text = std::fs::read_to_string(path).map_err(|e| CsvError {
            line: 0,
            column: String::new(),
            message: format!("cannot read {}: {e}", path.display()),
        })?;
        Recording::parse(&text, with_mag)
    }

    /// Parses CSV text: a header row naming the columns (any order, extra columns
    /// ignored), then one row per sample. Needs `t`, `gyr_*`, `acc_*`, and `mag_*` when
    /// `with_mag`; reads `quat_*` and `movement` when present. `NaN` is accepted in any
    /// numeric cell.
    pub fn parse(text: &str, with_mag: bool) -> Result<Recording, CsvError> {
        let mut lines = text.lines().enumerate();
        let (_, header) = lines.next().ok_or(CsvError {
            line: 1,
            column: String::new(),
            message: "empty file: expected a header row".into(),
        })?;
        let names: Vec<&str> = header.split(',').map(str::trim).collect();
        let find = |name: &str| names.iter().position(|n| *n == name);
        let require = |name: &str| {
            find(name).ok_or_else(|| CsvError {
                line: 1,
                column: name.into(),
                message: "missing column".into(),
            })
        };
        let imu: Vec<usize> = IMU_COLUMNS.iter().map(|n| require(n)).collect::<Result<_, _>>()?;
        let mag: Option<Vec<usize>> = if with_mag {
            Some(MAG_COLUMNS.iter().map(|n| require(n)).collect::<Result<_, _>>()?)
        } else {
            None
        };
        let truth: Option<Vec<usize>> = TRUTH_COLUMNS.iter().map(|n| find(n)).collect();
        let movement = find("movement");

        let mut rec = Recording::default();
        let mut cells: Vec<&str> = Vec::with_capacity(names.len());
        for (index, line) in lines {
            let line_no = index + 1;
            if line.trim().is_empty() {
                continue;
            }
            cells.clear();
            cells.extend(line.split(',').map(str::trim));
            let cell = |col: usize| -> Result<f64, CsvError> {
                let err =
                    |message: String| CsvError { line: line_no, column: names[col].to_string(), message };
                let text = cells.get(col).ok_or_else(|| err("missing cell".into()))?;
                text.parse::<f64>().map_err(|_| err(format!("not a number: '{text}'")))
            };
            let v = |cols: &[usize]| -> Result<Vec3, CsvError> {
                Ok(Vec3::new(cell(cols[0])?, cell(cols[1])?, cell(cols[2])?))
            };
            let t = cell(imu[0])?;
            if !t.is_finite() {
                return Err(CsvError {
                    line: line_no,
                    column: "t".into(),
                    message: format!("time must be finite, got {t}"),
                });
            }
            if let Some(&prev) = rec.t.last() {
                if t <= prev {
                    return Err(CsvError {
                        line: line_no,
                        column: "t".into(),
                        message: format!("time must increase: {t} after {prev}"),
                    });
                }
            }
            rec.t.push(t);
            rec.gyro.push(v(&imu[1..4])?);
            rec.accel.push(v(&imu[4..7])?);
            if let Some(m) = &mag {
                rec.mag.push(v(m)?);
            }
            if let Some(q) = &truth {
                rec.truth.push(Quat::new(cell(q[0])?, cell(q[1])?, cell(q[2])?, cell(q[3])?));
            }
            if let Some(col) = movement {
                rec.movement.push(cell(col)? == 1.0);
            }
        }
        if rec.t.is_empty() {
            return Err(CsvError { line: 2, column: String::new(), message: "no data rows".into() });
        }
        Ok(rec)
    }

    pub fn len(&self) -> usize {
        self.t.len()
    }

    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// True when the recording has ground truth and a movement mask to score against.
    pub fn has_truth(&self) -> bool {
        !self.truth.is_empty() && !self.movement.is_empty()
    }

    /// The samples, `dt` from consecutive `t` (the first row takes the second row's dt).
    /// Magnetometer readings are included when the recording has them. A reading with a
    /// `NaN` cell (FORMAT.md's missing value) is left out of its sample, and the rest of
    /// the sample kept: a magnetometer at half the rate still leaves every gyroscope row.
    pub fn samples(&self) -> Vec<Sample> {
        (0..self.len())
            .map(|i| {
                let dt = match i {
                    0 if self.len() > 1 => self.t[1] - self.t[0],
                    0 => 0.01,
                    _ => self.t[i] - self.t[i - 1],
                };
                let present = |v: Vec3| (!v.x.is_nan() && !v.y.is_nan() && !v.z.is_nan()).then_some(v);
                Sample {
                    dt,
                    gyro: present(self.gyro[i]),
                    accel: present(self.accel[i]),
                    mag: self.mag.get(i).copied().and_then(present),
                }
            })
            .collect()
    }
}

/// The `.csv` files in `dir`, sorted by name.
pub fn csv_files(dir: &Path) -> std::io::Result<Vec<std::path::PathBuf>> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.extension().is_some_and(|x| x == "csv") {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}

/// A recording at 1/`k` of its rate: every `k`-th row, with the gyroscope averaged
/// (dt-weighted) over the `k` rows that end there, the other readings, truth and mask of
/// that row, and dt the sum of the `k` steps. Returns the truth and mask as a
/// [`Recording`] (other fields empty) and the samples.
pub fn decimate(rec: &Recording, samples: &[Sample], k: usize) -> (Recording, Vec<Sample>) {
    let mut out = Recording::default();
    let mut kept = Vec::new();
    for end in (k.max(1) - 1..samples.len()).step_by(k.max(1)) {
        let rows = &samples[end + 1 - k.max(1)..=end];
        let dt: f64 = rows.iter().map(|s| s.dt).sum();
        let gyro = rows.iter().try_fold(Vec3::ZERO, |a, s| s.gyro.map(|g| a + g * (s.dt / dt)));
        kept.push(Sample { dt, gyro, ..samples[end] });
        if let (Some(t), Some(m)) = (rec.truth.get(end), rec.movement.get(end)) {
            out.truth.push(*t);
            out.movement.push(*m);
        }
    }
    (out, kept)
}

/// RMSE in degrees over the scored samples.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Scores {
    pub total: f64,
    pub heading: f64,
    pub inclination: f64,
    /// How many samples were scored.
    pub count: usize,
}

/// BROAD's error angles (radians) between an estimate and the truth, both ENU `q_ES`:
/// `e = q_est ⊗ q_truth*`, total `2 acos|e.w|`, heading `2 atan2(|e.z|, |e.w|)`,
/// inclination `2 acos √(e.w² + e.z²)`.
pub fn error_angles(est: Quat, truth: Quat) -> (f64, f64, f64) {
    let e = (est.normalized() * truth.normalized().conj()).normalized();
    let total = 2.0 * libm::acos(e.w.abs().clamp(0.0, 1.0));
    let heading = 2.0 * libm::atan2(e.z.abs(), e.w.abs());
    let inclination = 2.0 * libm::acos((e.w * e.w + e.z * e.z).sqrt().clamp(0.0, 1.0));
    (total, heading, inclination)
}

/// BROAD's score (FORMAT.md "Scoring"): RMSE of each angle over rows with
/// `movement == 1`, rows whose truth is NaN left out, in degrees.
pub fn score(est: &[Quat], truth: &[Quat], movement: &[bool]) -> Scores {
    let (mut t2, mut h2, mut i2, mut n) = (0.0, 0.0, 0.0, 0usize);
    for ((q, g), m) in est.iter().zip(truth).zip(movement) {
        if !*m || !g.is_finite() || !q.is_finite() {
            continue;
        }
        let (t, h, i) = error_angles(*q, *g);
        t2 += t * t;
        h2 += h * h;
        i2 += i * i;
        n += 1;
    }
    let rms = |s: f64| if n == 0 { f64::NAN } else { (s / n as f64).sqrt().to_degrees() };
    Scores { total: rms(t2), heading: rms(h2), inclination: rms(i2), count: n }
}

/// For a filter without magnetometer: removes one constant heading offset (the circular
/// mean of the heading error over the scored rows, FORMAT.md "6D with heading removed")
/// from every estimate. Returns the offset in radians.
pub fn remove_heading_offset(est: &mut [Quat], truth: &[Quat], movement: &[bool]) -> f64 {
    let (mut s, mut c) = (0.0, 0.0);
    for ((q, g), m) in est.iter().zip(truth).zip(movement) {
        if !*m || !g.is_finite() || !q.is_finite() {
            continue;
        }
        let e = q.normalized() * g.normalized().conj();
        let psi = 2.0 * libm::atan2(e.z, e.w);
        s += libm::sin(psi);
        c += libm::cos(psi);
    }
    let delta = libm::atan2(s, c);
    let fix = Quat::new(libm::cos(-delta / 2.0), 0.0, 0.0, libm::sin(-delta / 2.0));
    for q in est.iter_mut() {
        *q = fix * *q;
    }
    delta
}

/// BROAD's groups among the 14 shared trials (FORMAT.md "Scoring", trials.json): the
/// folds of the leave-one-group-out cross-validations (robust_cv, robust_sigma).
pub const GROUPS: [(&str, &[u32]); 7] = [
    ("rotation", &[1, 3, 6]),
    ("translation", &[11, 15, 21]),
    ("breaks", &[8]),
    ("tapping", &[24, 25]),
    ("vibration", &[26]),
    ("stationary magnet", &[28, 30]),
    ("attached magnet", &[32, 34]),
];

#[cfg(test)]
mod tests {
    use super::*;

    const CSV: &str = "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z,quat_w,quat_x,quat_y,quat_z,movement,extra\n\
        0,0,0,0,0,0,9.81,0,20,-40,1,0,0,0,0,x\n\
        0.01,0.1,0,0,0,0,9.81,0,20,-40,NaN,NaN,NaN,NaN,1,y\n";

    #[test]
    fn parses_columns_by_name_and_accepts_nan() {
        let r = Recording::parse(CSV, true).unwrap();
        assert_eq!(r.len(), 2);
        assert_eq!(r.gyro[1], Vec3::new(0.1, 0.0, 0.0));
        assert_eq!(r.mag[0], Vec3::new(0.0, 20.0, -40.0));
        assert!(r.truth[1].w.is_nan());
        assert_eq!(r.movement, vec![false, true]);
        let s = r.samples();
        assert_eq!(s[0].dt, 0.01);
        assert_eq!(s[1].dt, 0.01);
    }

    #[test]
    fn decimation_averages_the_gyroscope_over_each_interval() {
        let rec = Recording {
            truth: vec![Quat::IDENTITY; 4],
            movement: vec![false, true, false, true],
            ..Recording::default()
        };
        let s = |g: f64, dt: f64| Sample { dt, gyro: Some(Vec3::new(g, 0.0, 0.0)), accel: None, mag: None };
        let samples = [s(1.0, 0.01), s(3.0, 0.03), s(5.0, 0.01), s(5.0, 0.01)];
        let (r, d) = decimate(&rec, &samples, 2);
        assert_eq!(d.len(), 2);
        assert_eq!((d[0].dt, d[0].gyro.unwrap().x), (0.04, 2.5));
        assert_eq!(r.movement, vec![true, true]);
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let missing = Recording::parse("t,gyr_x\n0,1\n", false).unwrap_err();
        assert_eq!((missing.line, missing.column.as_str()), (1, "gyr_y"));
        let bad = CSV.replace("0.01,0.1", "0.01,abc");
        let e = Recording::parse(&bad, true).unwrap_err();
        assert_eq!((e.line, e.column.as_str()), (3, "gyr_x"));
        let back = CSV.replace("0.01,0.1", "0,0.1");
        let e = Recording::parse(&back, true).unwrap_err();
        assert_eq!((e.line, e.column.as_str()), (3, "t"));
        // Without --no-mag the magnetometer columns are needed.
        let e = Recording::parse("t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,1\n", true).unwrap_err();
        assert_eq!(e.column, "mag_x");
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn score_of_a_known_heading_error() {
        let truth = vec![Quat::IDENTITY; 4];
        let yaw = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 10f64.to_radians());
        let tilt = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 4f64.to_radians());
        let est = vec![yaw, yaw, tilt, Quat::IDENTITY];
        let s = score(&est, &truth, &[true, true, true, false]);
        assert_eq!(s.count, 3);
        let expect_total = ((100.0 + 100.0 + 16.0) / 3.0f64).sqrt();
        assert!((s.total - expect_total).abs() < 1e-9, "{s:?}");
        assert!((s.heading - (200.0 / 3.0f64).sqrt()).abs() < 1e-9);
        assert!((s.inclination - (16.0 / 3.0f64).sqrt()).abs() < 1e-9);
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn heading_offset_removal_recovers_a_constant_offset() {
        let truth: Vec<Quat> =
            (0..50).map(|i| Quat::from_axis_angle(Vec3::new(0.3, 0.1, 1.0), i as f64 * 0.05)).collect();
        let offset = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.7);
        let mut est: Vec<Quat> = truth.iter().map(|q| offset * *q).collect();
        let mask = vec![true; 50];
        let delta = remove_heading_offset(&mut est, &truth, &mask);
        assert!((delta - 0.7).abs() < 1e-12);
        assert!(score(&est, &truth, &mask).total < 1e-6);
    }
}
