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

use super::estimator::Estimator;
use super::runner::Runner;
use super::state::Codec;
use super::{Error, Field, Filter, Sample, SampleView};
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

    fn determinant(&self) -> f64 {
        let m = &self.matrix;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }

    /// NonFinite for a NaN or infinite entry, ZeroVector for a singular matrix.
    fn check(&self, field: Field) -> Result<(), Error> {
        let finite = self.matrix.iter().flatten().all(|x| x.is_finite()) && self.offset.is_finite();
        if !finite {
            return Err(Error::NonFinite(field));
        }
        let det = self.determinant();
        if !(det.is_finite() && det.abs() >= 1e-12) {
            return Err(Error::ZeroVector(field));
        }
        Ok(())
    }
}

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
    /// range and physical bound), then the calibrated one. NonFinite for a NaN or
    /// infinite entry, ZeroVector for a singular matrix; nothing changes then.
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

impl<E: Estimator> Runner<E> {
    /// The update with the sensor models applied: the raw sample is checked, then the
    /// calibrated one goes through the usual update (which checks it again).
    #[inline(never)]
    pub(crate) fn update_calibrated<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        self.check_view(s)?;
        let models = self.models();
        let calibrated = models.apply(s);
        // The calibrated sample takes the plain path (the models are not applied twice).
        if let Some(x) = &mut self.extras.0 {
            x.models = Models::default();
        }
        self.refresh_models();
        let result = self.update_inline(&calibrated);
        if let Some(x) = &mut self.extras.0 {
            x.models = models;
        }
        self.refresh_models();
        result
    }
}

/// Number of direction bins of [`MagCalibrator`]'s coverage: 6 cube faces of 3 × 3.
pub const COVERAGE_BINS: u32 = 54;

/// A magnetometer calibration estimator: an ellipsoid fit (the 10-parameter quadric
/// `a x² + b y² + c z² + 2f yz + 2g xz + 2h xy + 2p x + 2q y + 2r z + d = 0`, algebraic
/// least squares: the coefficients are the eigenvector of the scatter matrix `Σ dᵢ dᵢᵀ`
/// with the smallest eigenvalue) whose scatter matrix is summed sample by sample in a
/// fixed-size array, so `add` neither allocates nor keeps the samples;
/// [`MagCalibrator::solve`] solves it on demand. Readings are scaled by the first one's
/// norm, for conditioning.
#[derive(Clone, Debug, PartialEq)]
pub struct MagCalibrator {
    /// Σ dᵢ dᵢᵀ of the design rows (upper triangle).
    dtd: [[f64; 10]; 10],
    count: u64,
    scale: f64,
    /// Running mean of the readings: the coverage's centre.
    mean: Vec3,
    bins: u64,
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
    /// RMS of `|calibrated|/field - 1` over the samples, from the fit's algebraic residual
    /// (`(|c|²/field² - 1) / 2`, first order): 0.01 is 1 % of the field.
    pub residual: f64,
    /// Fraction of the 54 direction bins (directions from the readings' running mean)
    /// that readings fell in: 1 is a full sphere. Measured from the running mean, it is
    /// less than the directions covered when the sphere is swept in order.
    pub coverage: f64,
    pub samples: u64,
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

/// A [`MagCalibrator`]'s state as plain values (for a host-owned C struct): the scatter
/// matrix's upper triangle row by row, the scale, the running mean, the count and the
/// coverage bits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MagCalibratorParts {
    pub sums: [f64; 55],
    pub scale: f64,
    pub mean: Vec3,
    pub count: u64,
    pub bins: u64,
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
        MagCalibratorParts { sums, scale: self.scale, mean: self.mean, count: self.count, bins: self.bins }
    }

    /// The calibrator of [`MagCalibrator::to_parts`]'s values; `None` for values no
    /// calibrator holds (non-finite, a scale not positive, bits beyond the 54 bins).
    pub fn from_parts(p: &MagCalibratorParts) -> Option<MagCalibrator> {
        let ok = p.sums.iter().all(|x| x.is_finite())
            && p.scale.is_finite()
            && p.scale > 0.0
            && p.mean.is_finite()
            && p.bins >> COVERAGE_BINS == 0;
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
        Some(c)
    }

    pub fn new() -> MagCalibrator {
        MagCalibrator { dtd: [[0.0; 10]; 10], count: 0, scale: 1.0, mean: Vec3::ZERO, bins: 0 }
    }

    /// Adds one reading (any unit). NonFinite for a NaN or infinite one, ZeroVector for
    /// a first reading of zero (it sets the scale); nothing changes then.
    pub fn add(&mut self, m: Vec3) -> Result<(), Error> {
        if !m.is_finite() {
            return Err(Error::NonFinite(Field::Mag));
        }
        if self.count == 0 {
            let n = m.norm();
            if !(n > 0.0 && n.is_finite()) {
                return Err(Error::ZeroVector(Field::Mag));
            }
            self.scale = n;
        }
        let p = m * (1.0 / self.scale);
        let d = [
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
        ];
        for i in 0..10 {
            for j in i..10 {
                self.dtd[i][j] += d[i] * d[j];
            }
        }
        self.count += 1;
        self.mean = self.mean + (m - self.mean) * (1.0 / self.count as f64);
        if let Some(b) = bin_of(m - self.mean) {
            self.bins |= 1 << b;
        }
        Ok(())
    }

    pub fn samples(&self) -> u64 {
        self.count
    }

    /// Fraction of the direction bins seen so far (see [`MagFit::coverage`]).
    pub fn coverage(&self) -> f64 {
        self.bins.count_ones() as f64 / COVERAGE_BINS as f64
    }

    /// Solves the fit. `None` with fewer than 10 samples, or when the samples do not
    /// determine an ellipsoid (all on a plane or a line, or a fit that is no ellipsoid).
    pub fn solve(&self) -> Option<MagFit> {
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
        let lambda = eig.eigenvalues[smallest].max(0.0);
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
        // dᵢ·v = k (|calᵢ|²/radius² - 1), and Σ (dᵢ·v)² = λ for the unit eigenvector:
        // the normalised residual is √(λ/N)/|k|, and its half the relative norm error
        // to first order.
        let residual = (lambda / self.count as f64).sqrt() / k.abs() / 2.0;
        let mut matrix = [[0.0; 3]; 3];
        for (i, row) in matrix.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = w[(i, j)];
            }
        }
        let fit = MagFit {
            model: Model { matrix, offset: hard },
            field: radius * self.scale,
            residual,
            coverage: self.coverage(),
            samples: self.count,
        };
        (fit.model.check(Field::Mag).is_ok() && fit.field.is_finite()).then_some(fit)
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
    /// Adds one gyroscope reading (rad/s) taken while the sensor is still. NonFinite
    /// for a NaN or infinite one; nothing changes then.
    pub fn add(&mut self, g: Vec3) -> Result<(), Error> {
        if !g.is_finite() {
            return Err(Error::NonFinite(Field::Gyro));
        }
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
mod tests {
    use super::*;

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn a_model_is_matrix_times_offset_removed() {
        let m = Model {
            matrix: [[2.0, 0.0, 0.0], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]],
            offset: Vec3::new(1.0, 1.0, 1.0),
        };
        assert_eq!(m.apply(Vec3::new(2.0, 3.0, 5.0)), Vec3::new(2.0, 4.0, 4.0));
        let singular =
            Model { matrix: [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]], offset: Vec3::ZERO };
        assert_eq!(singular.check(Field::Mag), Err(Error::ZeroVector(Field::Mag)));
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn the_gyro_offset_is_the_still_mean() {
        let mut g = GyroOffset::default();
        assert_eq!(g.offset(), None);
        for i in 0..100 {
            let s = if i % 2 == 0 { 0.001 } else { -0.001 };
            g.add(Vec3::new(0.01 + s, -0.02, 0.03 - s)).unwrap();
        }
        let o = g.offset().unwrap();
        assert!((o - Vec3::new(0.01, -0.02, 0.03)).norm() < 1e-12);
        assert!((g.spread() - 0.001 * (2.0f64 / 3.0).sqrt()).abs() < 1e-5, "{}", g.spread());
        assert_eq!(g.add(Vec3::new(f64::NAN, 0.0, 0.0)), Err(Error::NonFinite(Field::Gyro)));
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn too_few_or_planar_samples_give_no_fit() {
        let mut c = MagCalibrator::new();
        for i in 0..9 {
            c.add(Vec3::new(i as f64, 1.0, 2.0)).unwrap();
        }
        assert!(c.solve().is_none());
        let mut c = MagCalibrator::new();
        for i in 0..100 {
            let a = i as f64 * 0.1;
            c.add(Vec3::new(a.cos(), a.sin(), 0.0)).unwrap();
        }
        assert!(c.solve().is_none(), "a circle does not fix an ellipsoid");
        assert_eq!(MagCalibrator::new().add(Vec3::ZERO), Err(Error::ZeroVector(Field::Mag)));
    }
}
