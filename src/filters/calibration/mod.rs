//! Sensor calibration (issue 20): inertial models for the gyroscope and accelerometer,
//! a magnetic model, applied in every kind before the update; a magnetometer
//! calibration estimator (an ellipsoid fit fed sample by sample); a gyroscope offset
//! estimate from a still period.
//!
//! An inertial model is `calibrated = M (raw - offset)`, with `M` the misalignment times
//! the sensitivity (x-io Fusion's `FusionCalibrationInertial`, its matrices multiplied);
//! the magnetic model is `calibrated = S (raw - h)`, `S` the soft-iron matrix and `h` the
//! hard-iron offset (Fusion's `FusionCalibrationMagnetic`, MATLAB `magcal`'s `A` and
//! `b`, with `S = Aᵀ` for its row vectors).

use crate::filters::error::Error;
use crate::filters::error::Field;
use crate::filters::pipeline::filter::Filter;
use crate::filters::pipeline::sample::Sample;
use crate::filters::pipeline::sample::SampleView;
use crate::filters::state::Codec;
use crate::math::Vec3;
use nalgebra::{Matrix3, SMatrix, SVector};

/// `calibrated = matrix (raw - offset)`; `matrix` is row-major.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Model {
    pub matrix: [[f64; 3]; 3],
    pub offset: Vec3,
}

impl Model {
    pub const IDENTITY: Model =
        Model { matrix: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], offset: Vec3::ZERO };

    #[inline]
    pub fn apply(&self, v: Vec3) -> Vec3 {
        let d = v - self.offset;
        let m = &self.matrix;
        Vec3::new(
            m[0][0] * d.x + m[0][1] * d.y + m[0][2] * d.z,
            m[1][0] * d.x + m[1][1] * d.y + m[1][2] * d.z,
            m[2][0] * d.x + m[2][1] * d.y + m[2][2] * d.z,
        )
    }

    /// A model the filter can use: one that maps the sensor's plausible readings
    /// ([`PLAUSIBLE_GYRO`], [`PLAUSIBLE_GRAVITY`], [`PLAUSIBLE_FIELD`]) to readings every
    /// update accepts, so that no accepted model leaves every sample refused. In order:
    /// - NonFinite for a NaN or infinite entry;
    /// - ZeroVector for a matrix that is singular whatever its scale:
    ///   `|det M| ≤ 10⁻¹² (‖M‖_F/√3)³`, computed on `M` divided by its largest entry (so
    ///   that no scale overflows or underflows);
    /// - TooLarge for an offset with a component at or beyond the sensor's physical bound
    ///   (no reading lies there);
    /// - gyroscope: TooLarge unless every reading of at most [`PLAUSIBLE_GYRO`] (a still
    ///   sensor's 0 among them) calibrates with each component under
    ///   [`MAX_GYRO`](crate::filters::pipeline::sample::MAX_GYRO);
    /// - accelerometer: a reading of standard gravity ([`PLAUSIBLE_GRAVITY`]) in any
    ///   direction must calibrate with each component under [`MAX_ACCEL`](crate::filters::pipeline::sample::MAX_ACCEL)
    ///   (else TooLarge) and to a nonzero vector, `|calibrated|² ≥ f64::MIN_POSITIVE` (the
    ///   zero threshold of every reading; else ZeroVector);
    /// - magnetometer (any unit): the earth's field at any strength of
    ///   [`PLAUSIBLE_FIELD`] (gauss to nanotesla) in any direction, read with the hard-iron
    ///   offset added, must calibrate with each component under [`MAX_MAG`](crate::filters::pipeline::sample::MAX_MAG)
    ///   (else TooLarge) and to a nonzero vector (else ZeroVector).
    ///
    /// Over the readings `r = c + ρ u` around a centre `c` (0, or the offset for the
    /// magnetometer), `ρ ≤ hi`, component `i` of `M (r − offset)` reaches at most
    /// `hi ‖Mᵢ‖ + |Mᵢ (c − offset)|` (row `Mᵢ`; exact), and the norm is at least
    /// `σ_min(M) · min |r − offset|`, with `σ_min(M) ≥ 1/‖M⁻¹‖_F` (a bound that may
    /// refuse a model whose least calibrated reading is a few times above zero).
    pub(crate) fn check(&self, field: Field) -> Result<(), Error> {
        let finite = self.matrix.iter().flatten().all(|x| x.is_finite()) && self.offset.is_finite();
        if !finite {
            return Err(Error::NonFinite(field));
        }
        let big = self.matrix.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        if big == 0.0 {
            return Err(Error::ZeroVector(field));
        }
        let m = self.matrix.map(|row| row.map(|x| x / big));
        // Cofactors: adj(m)ᵀ, so that det = m₀ · cof₀ and m⁻¹ = adj(m) / det.
        let cof = [
            [
                m[1][1] * m[2][2] - m[1][2] * m[2][1],
                m[1][2] * m[2][0] - m[1][0] * m[2][2],
                m[1][0] * m[2][1] - m[1][1] * m[2][0],
            ],
            [
                m[0][2] * m[2][1] - m[0][1] * m[2][2],
                m[0][0] * m[2][2] - m[0][2] * m[2][0],
                m[0][1] * m[2][0] - m[0][0] * m[2][1],
            ],
            [
                m[0][1] * m[1][2] - m[0][2] * m[1][1],
                m[0][2] * m[1][0] - m[0][0] * m[1][2],
                m[0][0] * m[1][1] - m[0][1] * m[1][0],
            ],
        ];
        let det = m[0][0] * cof[0][0] + m[0][1] * cof[0][1] + m[0][2] * cof[0][2];
        // ‖M‖_F²/3 ≥ 1/3 after the division: no underflow.
        let mean_square = m.iter().flatten().map(|x| x * x).sum::<f64>() / 3.0;
        if det.abs() <= 1e-12 * mean_square * mean_square.sqrt() {
            return Err(Error::ZeroVector(field));
        }
        let (bound, (centre, lo, hi)) = match field {
            Field::Gyro => (crate::filters::pipeline::sample::MAX_GYRO, (Vec3::ZERO, 0.0, PLAUSIBLE_GYRO)),
            Field::Accel => (
                crate::filters::pipeline::sample::MAX_ACCEL,
                (Vec3::ZERO, PLAUSIBLE_GRAVITY, PLAUSIBLE_GRAVITY),
            ),
            _ => (
                crate::filters::pipeline::sample::MAX_MAG,
                (self.offset, PLAUSIBLE_FIELD.0, PLAUSIBLE_FIELD.1),
            ),
        };
        if self.offset.max_abs() >= bound {
            return Err(Error::TooLarge(field));
        }
        // Largest component over |r − centre| ≤ hi: ρ‖Mᵢ‖ + |Mᵢ (centre − offset)|, each
        // factor of big taken last (an overflow gives ∞, refused).
        let d = centre - self.offset;
        let reach = m.iter().fold(0.0f64, |w, row| {
            let r = Vec3::new(row[0], row[1], row[2]);
            w.max(hi * r.norm() + r.dot(d).abs())
        });
        // NaN cannot arise (finite factors; an overflow is ∞), but would be refused too.
        if (reach * big).is_nan() || reach * big >= bound {
            return Err(Error::TooLarge(field));
        }
        if lo > 0.0 {
            // |M (r − offset)| ≥ σ_min(M) |r − offset| ≥ σ_min(M) · min |r − offset|, with
            // σ_min(M) ≥ big |det m| / ‖adj m‖_F.
            let adj = cof.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
            let sigma = det.abs() / adj * big;
            // The readings are `centre + ρ u`, ρ in [lo, hi]: the nearest to the offset.
            let dist = d.norm();
            let nearest = if dist < lo {
                lo - dist
            } else if dist > hi {
                dist - hi
            } else {
                0.0
            };
            let least = sigma * nearest;
            if least.is_nan() || least * least < f64::MIN_POSITIVE {
                return Err(Error::ZeroVector(field));
            }
        }
        Ok(())
    }
}

/// The gyroscope readings a model must map within the physical bound (rad/s): every
/// reading of at most 1 rad/s, a still sensor's 0 among them.
pub const PLAUSIBLE_GYRO: f64 = 1.0;
/// The accelerometer reading a model must map to a usable vector in every direction
/// (m/s²): standard gravity.
pub const PLAUSIBLE_GRAVITY: f64 = 9.80665;
/// The strengths of the earth's field a magnetometer model must map to usable vectors,
/// whatever the unit the host reads in: 0.25 (weakest field in gauss) to 65,000 (the
/// strongest in nanotesla, or counts); microtesla (25 to 65) lie between.
pub const PLAUSIBLE_FIELD: (f64, f64) = (0.25, 65_000.0);

/// The three sensor models of a filter; `None` is the identity.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Models {
    pub gyro: Option<Model>,
    pub accel: Option<Model>,
    pub mag: Option<Model>,
}

impl Models {
    pub fn any(&self) -> bool {
        self.gyro.is_some() || self.accel.is_some() || self.mag.is_some()
    }

    pub(crate) fn apply<S: SampleView>(&self, s: &S) -> Sample {
        let with = |m: &Option<Model>, v: Option<Vec3>| match (m, v) {
            (Some(m), Some(v)) => Some(m.apply(v)),
            (_, v) => v,
        };
        Sample {
            dt: s.dt(),
            gyro: with(&self.gyro, s.gyro()),
            accel: with(&self.accel, s.accel()),
            mag: with(&self.mag, s.mag()),
        }
    }

    pub fn valid(&self) -> bool {
        [(self.gyro, Field::Gyro), (self.accel, Field::Accel), (self.mag, Field::Mag)]
            .iter()
            .all(|(m, f)| m.map_or(true, |m| m.check(*f).is_ok()))
    }
}

/// The models' fields of a snapshot: for each sensor a presence flag and its 12 values.
pub(crate) fn codec(models: &mut Models, c: &mut dyn Codec) {
    for m in [&mut models.gyro, &mut models.accel, &mut models.mag] {
        let mut present = m.is_some();
        c.bool(&mut present);
        let mut v = m.unwrap_or(Model::IDENTITY);
        for row in v.matrix.iter_mut() {
            for x in row.iter_mut() {
                c.f64(x);
            }
        }
        c.vec3(&mut v.offset);
        *m = present.then_some(v);
    }
}

/// Which sensor a model is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sensor {
    Gyro,
    Accel,
    Mag,
}

impl Filter {
    /// Sets (or with `None` clears) the model applied to one sensor's readings before
    /// every update, in every kind. The raw reading is checked first (finite, within its
    /// range and physical bound), then the calibrated one (finite, within its physical
    /// bound: a range is the raw sensor's full scale). A model must map the sensor's
    /// plausible readings to usable ones (`Model::check`): NonFinite for a NaN or
    /// infinite entry, ZeroVector for a singular matrix or one that sends a plausible
    /// reading to zero, TooLarge for an offset beyond the physical bound or one that
    /// sends a plausible reading beyond it; nothing changes then.
    pub fn set_sensor_model(&mut self, sensor: Sensor, model: Option<Model>) -> Result<(), Error> {
        let field = match sensor {
            Sensor::Gyro => Field::Gyro,
            Sensor::Accel => Field::Accel,
            Sensor::Mag => Field::Mag,
        };
        if let Some(m) = model {
            m.check(field)?;
        }
        match sensor {
            Sensor::Gyro => self.models_mut().gyro = model,
            Sensor::Accel => self.models_mut().accel = model,
            Sensor::Mag => self.models_mut().mag = model,
        }
        self.refresh_models();
        Ok(())
    }

    /// The model set for `sensor`, if any.
    pub fn sensor_model(&self, sensor: Sensor) -> Option<Model> {
        match sensor {
            Sensor::Gyro => self.models().gyro,
            Sensor::Accel => self.models().accel,
            Sensor::Mag => self.models().mag,
        }
    }
}

/// Number of direction bins of [`MagCalibrator`]'s coverage: 6 cube faces of 3 × 3.
pub const COVERAGE_BINS: u32 = 54;

/// [`MagCalibrator`]'s outlier gate once a fit can be trusted: a reading whose calibrated
/// norm is more than this fraction of the field off the field is set aside (20 %: ten
/// times the largest residual of a trustworthy fit, while a magnet or a corrupted byte
/// moves a reading much further). A reading kept before the gate acts stays in the sums,
/// its weight falling as more readings are kept: one reading 2.5 times the field off
/// among 3,000 lifts the residual by about 0.04, and the fit is not trustworthy.
pub const MAG_GATE_FIT: f64 = 0.2;
/// The coverage from which a trustworthy fit becomes the outlier gate's: three quarters
/// of the directions. Over half a sphere an ellipsoid can bend to take in a reading far
/// off (2.5 times the field) with a residual under 0.02, and a gate on that fit would set
/// good readings aside; over three quarters it cannot.
pub const MAG_GATE_COVERAGE: f64 = 0.75;
/// [`MagCalibrator`]'s outlier gate before a fit can be trusted: a reading whose norm is
/// more than this factor above the RMS norm of the readings kept (or, among the first
/// [`MAG_GATE_RESTART`] readings, below it) is set aside. The norms of one sensor's
/// readings differ by less: `|h| ± F` for a hard-iron offset `h` and a field `F`.
pub const MAG_GATE_BAND: f64 = 8.0;
/// When more readings in a row than the calibrator keeps (and at least this many) were
/// set aside, the kept ones were the outliers (a first reading from a corrupted frame,
/// a sensor moved to another place): the calibrator starts over from the next reading,
/// and counts the readings it held as set aside.
pub const MAG_GATE_RESTART: u64 = 32;
/// Readings are scaled by the first kept one's norm; one more than 10⁶⁰ times larger is
/// set aside, so that no sum of fourth powers can overflow.
const MAG_SCALED_MAX: f64 = 1e60;

/// A magnetometer calibration estimator: an ellipsoid fit (the 10-parameter quadric
/// `a x² + b y² + c z² + 2f yz + 2g xz + 2h xy + 2p x + 2q y + 2r z + d = 0`, algebraic
/// least squares: the coefficients are the eigenvector of the scatter matrix `Σ dᵢ dᵢᵀ`
/// with the smallest eigenvalue) whose scatter matrix is summed sample by sample in a
/// fixed-size array, so `add` neither allocates nor keeps the samples;
/// [`MagCalibrator::solve`] solves it on demand. Readings are scaled by the first one's
/// norm, for conditioning.
///
/// Outliers (a dropped byte, a magnet passing) are set aside before they reach the sums:
/// once the readings kept give a trustworthy fit ([`MagFit::trustworthy`]) over
/// [`MAG_GATE_COVERAGE`] of the directions, by their distance from that fit's sphere
/// ([`MAG_GATE_FIT`]); before, by a generous band on their norm
/// ([`MAG_GATE_BAND`]), which a large hard-iron offset does not trip. The fit the gate uses
/// is solved again every 64 kept readings, and replaced when it is trustworthy. See
/// [`MAG_GATE_RESTART`] for a calibrator whose kept readings were the outliers.
#[derive(Clone, Debug, PartialEq)]
pub struct MagCalibrator {
    /// Σ dᵢ dᵢᵀ of the design rows (upper triangle).
    dtd: [[f64; 10]; 10],
    count: u64,
    scale: f64,
    /// Running mean of the readings: the coverage's centre.
    mean: Vec3,
    bins: u64,
    /// Readings set aside.
    rejected: u64,
    /// Readings set aside in a row.
    streak: u64,
    /// The gate's fit: the quadric `w` (scaled units) with `dᵢ·w = |calᵢ|²/F² - 1`; all
    /// zero while no fit is trusted.
    gate: [f64; 10],
}

/// What [`MagCalibrator::solve`] found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MagFit {
    /// `calibrated = soft_iron (raw - hard_iron)`: readings on a sphere of radius
    /// `field` (same unit as the readings).
    pub model: Model,
    /// The field's magnitude after calibration: the ellipsoid's mean radius
    /// (the cube root of its semi-axes' product).
    pub field: f64,
    /// RMS of `|calibrated|/field - 1` over the readings kept, to first order: the RMS of
    /// `(|calibrated|²/field² - 1) / 2`, which the sums give exactly (it differs from the
    /// RMS of `|calibrated|/field - 1` by a few per cent of itself at 0.02). 0.01 is 1 %
    /// of the field.
    pub residual: f64,
    /// Fraction of the 54 direction bins (directions from the readings' running mean)
    /// that readings fell in: 1 is a full sphere. Measured from the running mean, it is
    /// less than the directions covered when the sphere is swept in order.
    pub coverage: f64,
    /// Readings kept (in the fit).
    pub samples: u64,
    /// Readings set aside as outliers (see [`MagCalibrator`]).
    pub rejected: u64,
}

impl MagFit {
    /// The rule of thumb for trusting a fit: at least half the sphere's directions
    /// covered and a residual under 2 % of the field.
    pub fn trustworthy(&self) -> bool {
        self.coverage >= 0.5 && self.residual < 0.02
    }
}

impl Default for MagCalibrator {
    fn default() -> Self {
        MagCalibrator::new()
    }
}

fn bin_of(d: Vec3) -> Option<u32> {
    let a = [d.x.abs(), d.y.abs(), d.z.abs()];
    let (axis, big) = if a[0] >= a[1] && a[0] >= a[2] {
        (0, d.x)
    } else if a[1] >= a[2] {
        (1, d.y)
    } else {
        (2, d.z)
    };
    let m = a[axis];
    if !(m > 0.0 && m.is_finite()) {
        return None;
    }
    let face = axis * 2 + usize::from(big < 0.0);
    let others = match axis {
        0 => (d.y, d.z),
        1 => (d.x, d.z),
        _ => (d.x, d.y),
    };
    let cell = |u: f64| (((u / m + 1.0) * 1.5) as usize).min(2);
    Some((face * 9 + cell(others.0) * 3 + cell(others.1)) as u32)
}

/// The design row of a scaled reading `p`.
fn design(p: Vec3) -> [f64; 10] {
    [
        p.x * p.x,
        p.y * p.y,
        p.z * p.z,
        2.0 * p.y * p.z,
        2.0 * p.x * p.z,
        2.0 * p.x * p.y,
        2.0 * p.x,
        2.0 * p.y,
        2.0 * p.z,
        1.0,
    ]
}

/// A [`MagCalibrator`]'s state as plain values (for a host-owned C struct): the scatter
/// matrix's upper triangle row by row, the scale, the running mean, the count, the
/// coverage bits, the readings set aside (in all and in a row) and the gate's quadric.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MagCalibratorParts {
    pub sums: [f64; 55],
    pub scale: f64,
    pub mean: Vec3,
    pub count: u64,
    pub bins: u64,
    pub rejected: u64,
    pub streak: u64,
    pub gate: [f64; 10],
}

/// The fit of a scatter matrix: the model, the field, the quadric `w` with
/// `d(p)·w = |cal|²/F² - 1` (scaled units), and `Σ (d(p)·w)²`.
struct Quadric {
    model: Model,
    field: f64,
    w: [f64; 10],
    sum_sq: f64,
}

impl MagCalibrator {
    pub fn to_parts(&self) -> MagCalibratorParts {
        let mut sums = [0.0; 55];
        let mut k = 0;
        for i in 0..10 {
            for j in i..10 {
                sums[k] = self.dtd[i][j];
                k += 1;
            }
        }
        MagCalibratorParts {
            sums,
            scale: self.scale,
            mean: self.mean,
            count: self.count,
            bins: self.bins,
            rejected: self.rejected,
            streak: self.streak,
            gate: self.gate,
        }
    }

    /// The calibrator of [`MagCalibrator::to_parts`]'s values; `None` for values no
    /// calibrator holds (non-finite, a scale not positive, bits beyond the 54 bins).
    pub fn from_parts(p: &MagCalibratorParts) -> Option<MagCalibrator> {
        let ok = p.sums.iter().all(|x| x.is_finite())
            && p.scale.is_finite()
            && p.scale > 0.0
            && p.mean.is_finite()
            && p.bins >> COVERAGE_BINS == 0
            && p.gate.iter().all(|x| x.is_finite());
        if !ok {
            return None;
        }
        let mut c = MagCalibrator::new();
        let mut k = 0;
        for i in 0..10 {
            for j in i..10 {
                c.dtd[i][j] = p.sums[k];
                k += 1;
            }
        }
        c.scale = p.scale;
        c.mean = p.mean;
        c.count = p.count;
        c.bins = p.bins;
        c.rejected = p.rejected;
        c.streak = p.streak;
        c.gate = p.gate;
        Some(c)
    }

    pub fn new() -> MagCalibrator {
        MagCalibrator {
            dtd: [[0.0; 10]; 10],
            count: 0,
            scale: 1.0,
            mean: Vec3::ZERO,
            bins: 0,
            rejected: 0,
            streak: 0,
            gate: [0.0; 10],
        }
    }

    /// Adds one reading (any unit). The filters' magnetometer check first (NonFinite for
    /// a NaN or infinite component, ZeroVector for a zero or subnormal norm, TooLarge for
    /// a component at or beyond [`MAX_MAG`](crate::filters::pipeline::sample::MAX_MAG) or a norm that overflows);
    /// nothing changes then. An accepted reading is kept or, by the outlier gate (see
    /// [`MagCalibrator`]), set aside and counted in [`MagCalibrator::rejected`].
    pub fn add(&mut self, m: Vec3) -> Result<(), Error> {
        crate::filters::pipeline::sample::check_mag(m)?;
        if self.count == 0 {
            self.scale = m.norm();
            self.keep(m);
            return Ok(());
        }
        if !self.is_outlier(m * (1.0 / self.scale)) {
            self.keep(m);
            return Ok(());
        }
        if self.streak + 1 >= MAG_GATE_RESTART.max(self.count) {
            // The readings kept were the outliers: start over from this one.
            let rejected = self.rejected.saturating_add(self.count);
            *self = MagCalibrator::new();
            self.rejected = rejected;
            self.scale = m.norm();
            self.keep(m);
        } else {
            self.rejected = self.rejected.saturating_add(1);
            self.streak += 1;
        }
        Ok(())
    }

    /// The outlier gate for the scaled reading `p` (see [`MagCalibrator`]).
    fn is_outlier(&self, p: Vec3) -> bool {
        let n2 = p.norm_squared();
        if n2 > MAG_SCALED_MAX * MAG_SCALED_MAX {
            return true;
        }
        if self.gate.iter().any(|x| *x != 0.0) {
            // |cal|²/F² - 1 within ((1 ∓ g)² - 1).
            let d = design(p);
            let e: f64 = d.iter().zip(&self.gate).map(|(a, b)| a * b).sum();
            let (lo, hi) = ((1.0 - MAG_GATE_FIT).powi(2) - 1.0, (1.0 + MAG_GATE_FIT).powi(2) - 1.0);
            return !(lo..=hi).contains(&e);
        }
        // The RMS norm of the readings kept: Σ|p|² / N from the sums (d₀..d₂ times d₉ = 1).
        let rms2 = (self.dtd[0][9] + self.dtd[1][9] + self.dtd[2][9]) / self.dtd[9][9];
        let band2 = MAG_GATE_BAND * MAG_GATE_BAND;
        n2 > band2 * rms2 || (self.count < MAG_GATE_RESTART && n2 * band2 < rms2)
    }

    /// Adds a reading to the sums, the mean and the coverage; refreshes the gate's fit.
    fn keep(&mut self, m: Vec3) {
        let d = design(m * (1.0 / self.scale));
        for i in 0..10 {
            for j in i..10 {
                self.dtd[i][j] += d[i] * d[j];
            }
        }
        self.count += 1;
        self.streak = 0;
        self.mean = self.mean + (m - self.mean) * (1.0 / self.count as f64);
        if let Some(b) = bin_of(m - self.mean) {
            self.bins |= 1 << b;
        }
        if self.count % 64 == 0 {
            if let Some((fit, q)) = self.fit() {
                if fit.coverage >= MAG_GATE_COVERAGE && fit.trustworthy() {
                    self.gate = q.w;
                }
            }
        }
    }

    pub fn samples(&self) -> u64 {
        self.count
    }

    /// Readings set aside as outliers (see [`MagCalibrator`]).
    pub fn rejected(&self) -> u64 {
        self.rejected
    }

    /// Fraction of the direction bins seen so far (see [`MagFit::coverage`]).
    pub fn coverage(&self) -> f64 {
        self.bins.count_ones() as f64 / COVERAGE_BINS as f64
    }

    /// Solves the fit. `None` with fewer than 10 samples, or when the samples do not
    /// determine an ellipsoid (all on a plane or a line, or a fit that is no ellipsoid).
    pub fn solve(&self) -> Option<MagFit> {
        self.fit().map(|(fit, _)| fit)
    }

    fn fit(&self) -> Option<(MagFit, Quadric)> {
        let q = self.quadric()?;
        let fit = MagFit {
            model: q.model,
            field: q.field,
            residual: (q.sum_sq.max(0.0) / self.count as f64).sqrt() / 2.0,
            coverage: self.coverage(),
            samples: self.count,
            rejected: self.rejected,
        };
        Some((fit, q))
    }

    fn quadric(&self) -> Option<Quadric> {
        if self.count < 10 {
            return None;
        }
        let mut a = SMatrix::<f64, 10, 10>::zeros();
        for i in 0..10 {
            for j in i..10 {
                a[(i, j)] = self.dtd[i][j];
                a[(j, i)] = self.dtd[i][j];
            }
        }
        let eig = a.symmetric_eigen();
        let smallest = eig.eigenvalues.imin();
        // A second eigenvalue as small: the samples do not fix one quadric (a plane, a
        // circle).
        let next = eig
            .eigenvalues
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != smallest)
            .fold(f64::INFINITY, |m, (_, l)| m.min(*l));
        if next <= 1e-9 * eig.eigenvalues.amax() {
            return None;
        }
        let v: SVector<f64, 10> = eig.eigenvectors.column(smallest).into_owned();
        let q = Matrix3::new(v[0], v[5], v[4], v[5], v[1], v[3], v[4], v[3], v[2]);
        let lin = nalgebra::Vector3::new(v[6], v[7], v[8]);
        let center = -(q.try_inverse()? * lin);
        // (p - c)ᵀ Q (p - c) = cᵀ Q c - d = k
        let k = center.dot(&(q * center)) - v[9];
        if !(k != 0.0 && k.is_finite()) {
            return None;
        }
        let shape = q / k; // (p - c)ᵀ shape (p - c) = 1
        let eig = shape.symmetric_eigen();
        if eig.eigenvalues.iter().any(|l| l.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater)) {
            return None;
        }
        // Semi-axes 1/√λ (scaled units); the field is their geometric mean.
        let radius = eig.eigenvalues.iter().map(|l| 1.0 / l.sqrt()).product::<f64>().cbrt();
        let sqrt = eig.eigenvectors
            * Matrix3::from_diagonal(&eig.eigenvalues.map(|l| l.sqrt()))
            * eig.eigenvectors.transpose();
        // calibrated = radius·√shape (p - c), p = raw/scale; in raw units the field is
        // radius·scale and the matrix radius·√shape.
        let w = sqrt * radius;
        let hard = Vec3::new(center.x, center.y, center.z) * self.scale;
        // d(p)·v = (p - c)ᵀ Q (p - c) - k = k (|cal|²/radius² - 1): w = v/k gives
        // |cal|²/F² - 1 for each reading, and Σ (dᵢ·w)² = wᵀ (Σ dᵢ dᵢᵀ) w.
        let mut quad = [0.0; 10];
        for (x, vi) in quad.iter_mut().zip(v.iter()) {
            *x = vi / k;
        }
        let wv = SVector::<f64, 10>::from_column_slice(&quad);
        let sum_sq = wv.dot(&(a * wv));
        let mut matrix = [[0.0; 3]; 3];
        for (i, row) in matrix.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = w[(i, j)];
            }
        }
        let model = Model { matrix, offset: hard };
        let field = radius * self.scale;
        let ok = model.check(Field::Mag).is_ok()
            && field.is_finite()
            && quad.iter().all(|x| x.is_finite())
            && sum_sq.is_finite();
        ok.then_some(Quadric { model, field, w: quad, sum_sq })
    }
}

/// A gyroscope offset estimate from a still period: the mean of the readings, with
/// their spread to say whether the period was still.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GyroOffset {
    count: u64,
    mean: Vec3,
    m2: f64,
}

impl GyroOffset {
    /// Adds one gyroscope reading (rad/s) taken while the sensor is still. The filters'
    /// gyroscope check first: NonFinite for a NaN or infinite component, TooLarge for one
    /// at or beyond [`MAX_GYRO`](crate::filters::pipeline::sample::MAX_GYRO); nothing changes then.
    pub fn add(&mut self, g: Vec3) -> Result<(), Error> {
        crate::filters::pipeline::sample::check_gyro(g)?;
        self.count += 1;
        let delta = g - self.mean;
        self.mean = self.mean + delta * (1.0 / self.count as f64);
        self.m2 += delta.dot(g - self.mean);
        Ok(())
    }

    /// The offset (mean reading, rad/s); `None` before the first reading.
    pub fn offset(&self) -> Option<Vec3> {
        (self.count > 0).then_some(self.mean)
    }

    /// RMS deviation of the readings from the mean (rad/s, all axes): a still period's
    /// noise; a much larger value says the sensor moved.
    pub fn spread(&self) -> f64 {
        if self.count < 2 {
            0.0
        } else {
            (self.m2 / (3.0 * (self.count - 1) as f64)).sqrt()
        }
    }

    /// An inertial model that removes the offset (identity matrix).
    pub fn model(&self) -> Option<Model> {
        self.offset().map(|o| Model { offset: o, ..Model::IDENTITY })
    }
}

#[cfg(test)]
mod tests;
