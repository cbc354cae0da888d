//! The C calls for sensor calibration (issue 20): the models applied before every
//! update, the magnetometer calibrator (a host-owned struct: no handle, no
//! allocation) and the gyroscope offset from a still period. See
//! `filters/calibration`.

use super::{
    fail, from_core, guard, handle, handle_mut, items, need, put, OrientFilter, OrientStatus, OrientVec3,
};
use crate::filters::calibration::{GyroOffset, MagCalibrator, MagCalibratorParts, Model, Sensor};
use crate::math::Vec3;

/// orient_filter_set_sensor_model's `sensor`: the gyroscope.
pub const ORIENT_SENSOR_GYRO: u32 = 0;
/// The accelerometer.
pub const ORIENT_SENSOR_ACCEL: u32 = 1;
/// The magnetometer.
pub const ORIENT_SENSOR_MAG: u32 = 2;

/// A sensor model: calibrated = matrix (raw - offset), `matrix` row-major. For the
/// gyroscope and accelerometer the matrix is the misalignment times the sensitivity;
/// for the magnetometer it is the soft-iron matrix and `offset` the hard-iron offset.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OrientSensorModel {
    pub matrix: [f64; 9],
    pub offset: OrientVec3,
}

/// A magnetometer calibrator's state, owned by the host (on its stack or in its own
/// struct): initialise it with orient_mag_calibrator_init, feed it readings with
/// orient_mag_calibrator_add (no allocation, no samples kept), solve it with
/// orient_mag_calibrator_solve. Its fields are the fit's sums and its outlier gate's
/// state; do not write them.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrientMagCalibrator {
    pub sums: [f64; 55],
    pub scale: f64,
    pub mean: OrientVec3,
    pub count: u64,
    pub bins: u64,
    pub rejected: u64,
    pub streak: u64,
    pub gate: [f64; 10],
}

/// What orient_mag_calibrator_solve found.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OrientMagFit {
    /// calibrated = soft_iron (raw - hard_iron): pass to orient_filter_set_sensor_model
    /// with ORIENT_SENSOR_MAG.
    pub model: OrientSensorModel,
    /// The field's magnitude after calibration (the readings' unit).
    pub field: f64,
    /// RMS of |calibrated| / field - 1 over the readings kept, to first order: the RMS
    /// of (|calibrated|^2 / field^2 - 1) / 2, which the sums give exactly (within a few
    /// per cent of the RMS of |calibrated| / field - 1 for residuals up to 0.02). 0.01 is
    /// 1 %.
    pub residual: f64,
    /// Fraction of 54 direction bins on the sphere that readings fell in (1: all), the
    /// directions taken from the readings' running mean: a sensor that sweeps the sphere
    /// in order (one latitude after another) gets less than it covered.
    pub coverage: f64,
    /// Readings kept (in the fit); orient_mag_calibrator_rejected gives those set aside.
    pub samples: u64,
    /// 1 when coverage >= 0.5 and residual < 0.02 (the fit can be trusted), else 0.
    pub trustworthy: i32,
    pub reserved: i32,
}

fn model_from(m: &OrientSensorModel) -> Model {
    let a = m.matrix;
    Model {
        matrix: [[a[0], a[1], a[2]], [a[3], a[4], a[5]], [a[6], a[7], a[8]]],
        offset: Vec3::new(m.offset.x, m.offset.y, m.offset.z),
    }
}

fn model_to(m: &Model) -> OrientSensorModel {
    let r = m.matrix;
    OrientSensorModel {
        matrix: [r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2]],
        offset: OrientVec3 { x: m.offset.x, y: m.offset.y, z: m.offset.z },
    }
}

fn sensor_from(sensor: u32) -> Result<Sensor, OrientStatus> {
    match sensor {
        ORIENT_SENSOR_GYRO => Ok(Sensor::Gyro),
        ORIENT_SENSOR_ACCEL => Ok(Sensor::Accel),
        ORIENT_SENSOR_MAG => Ok(Sensor::Mag),
        _ => Err(fail(OrientStatus::InvalidArgument, format_args!("unknown sensor {sensor}"))),
    }
}

/// Sets the model applied to one sensor's readings (ORIENT_SENSOR_*) before every
/// update, in every kind; NULL clears it (the readings are used as they come). The raw
/// reading is checked first (finite, within its range and physical bound), then the
/// calibrated one (finite, within its physical bound: ORIENT_PARAM_GYRO_RANGE and
/// ORIENT_PARAM_ACCEL_RANGE are the raw sensor's full scale). Kept by orient_filter_reset
/// and saved in snapshots.
/// A model must map the sensor's plausible readings to readings every update accepts:
/// for the gyroscope every reading of at most 1 rad/s (0 among them), for the
/// accelerometer standard gravity (9.80665) in any direction, for the magnetometer (any
/// unit) the earth's field of any strength from 0.25 (gauss) to 65000 (nanotesla) in
/// any direction, read with the hard-iron offset added.
/// INVALID_ARGUMENT for an unknown sensor, NON_FINITE for a NaN or infinite entry,
/// ZERO_VECTOR for a singular matrix (whatever its scale: |det| <= 1e-12 (|matrix|_F /
/// sqrt 3)^3) or one that sends a plausible reading to zero (|calibrated|^2 below
/// DBL_MIN, by the bound sigma_min(matrix) >= 1 / |matrix^-1|_F), TOO_LARGE for an
/// offset with a component at or beyond the sensor's physical bound (1e4 rad/s, 1e5
/// m/s^2, 1e12) or a model that sends a plausible reading to a component at or beyond
/// it; nothing changes then.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_set_sensor_model(
    filter: *mut OrientFilter,
    sensor: u32,
    model: *const OrientSensorModel,
) -> OrientStatus {
    guard(|| {
        let h = handle_mut(filter)?;
        let s = sensor_from(sensor)?;
        let m = if model.is_null() { None } else { Some(model_from(&*model)) };
        h.filter.set_sensor_model(s, m).map_err(from_core)
    })
}

/// The model set for `sensor`; NO_DATA when none is set, INVALID_ARGUMENT for an unknown
/// sensor.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_sensor_model(
    filter: *const OrientFilter,
    sensor: u32,
    model: *mut OrientSensorModel,
) -> OrientStatus {
    guard(|| {
        put(model, || {
            let h = handle(filter)?;
            let m = h.filter.sensor_model(sensor_from(sensor)?);
            m.map(|m| model_to(&m)).ok_or_else(|| {
                fail(OrientStatus::NoData, format_args!("no model is set for sensor {sensor}"))
            })
        })
    })
}

fn calibrator_from(c: &OrientMagCalibrator) -> Result<MagCalibrator, OrientStatus> {
    let parts = MagCalibratorParts {
        sums: c.sums,
        scale: c.scale,
        mean: Vec3::new(c.mean.x, c.mean.y, c.mean.z),
        count: c.count,
        bins: c.bins,
        rejected: c.rejected,
        streak: c.streak,
        gate: c.gate,
    };
    MagCalibrator::from_parts(&parts).ok_or_else(|| {
        fail(
            OrientStatus::InvalidArgument,
            format_args!("not a calibrator's state (initialise it with orient_mag_calibrator_init)"),
        )
    })
}

fn calibrator_to(c: &MagCalibrator) -> OrientMagCalibrator {
    let p = c.to_parts();
    OrientMagCalibrator {
        sums: p.sums,
        scale: p.scale,
        mean: OrientVec3 { x: p.mean.x, y: p.mean.y, z: p.mean.z },
        count: p.count,
        bins: p.bins,
        rejected: p.rejected,
        streak: p.streak,
        gate: p.gate,
    }
}

/// Initialises a magnetometer calibrator: no readings yet.
#[no_mangle]
pub unsafe extern "C" fn orient_mag_calibrator_init(calibrator: *mut OrientMagCalibrator) -> OrientStatus {
    guard(|| put(calibrator, || Ok(calibrator_to(&MagCalibrator::new()))))
}

/// Adds one magnetometer reading (any unit; raw, before any model). Rotate the sensor
/// over as many directions as possible. The reading is checked as orient_filter_update
/// checks a magnetometer reading: NON_FINITE for a NaN or infinite component,
/// ZERO_VECTOR for a zero (or subnormal) norm, TOO_LARGE for a component at or beyond
/// 1e12 or a norm that overflows; INVALID_ARGUMENT for a struct that is not a
/// calibrator's state; nothing changes then. An accepted reading is kept, or set aside
/// as an outlier (a dropped byte, a magnet passing) and counted by
/// orient_mag_calibrator_rejected: once the readings kept give a fit with `trustworthy`
/// set and coverage >= 0.75 (solved every 64 readings kept), a reading whose calibrated
/// norm is more than 20 % off that fit's field; before, one whose norm is more than 8
/// times the RMS norm of the readings kept (or, among the first 32, less than 1/8 of
/// it). A reading kept before the first such fit stays in the fit, its weight falling
/// as more readings are kept (one reading 2.5 times the field off among 3,000 lifts the
/// residual by about 0.04): a fit that stays untrustworthy, or NO_DATA, after the sensor
/// covered the sphere holds a disturbance (a magnet near the start, say); initialise
/// the calibrator again. When more readings in a row are set aside than the
/// calibrator keeps (and at least 32), the ones kept were the outliers: it starts over
/// from the current reading, and counts those it kept as set aside.
#[no_mangle]
pub unsafe extern "C" fn orient_mag_calibrator_add(
    calibrator: *mut OrientMagCalibrator,
    mag: *const OrientVec3,
) -> OrientStatus {
    guard(|| {
        need(calibrator.is_null() || mag.is_null())?;
        let mut c = calibrator_from(&*calibrator)?;
        c.add(Vec3::new((*mag).x, (*mag).y, (*mag).z)).map_err(from_core)?;
        calibrator.write(calibrator_to(&c));
        Ok(())
    })
}

/// Solves the ellipsoid fit of the readings kept so far (the calibrator is not changed,
/// so it can be solved again after more readings). NO_DATA with fewer than 10 readings
/// or when they do not determine an ellipsoid (all on a plane, say), INVALID_ARGUMENT
/// for a struct that is not a calibrator's state. Readings near a plane (a sensor turned
/// about one axis only) determine an ellipsoid only through their noise: the fit's
/// coverage is low and its model wrong off that plane; check `trustworthy` (or coverage
/// and residual) before using the model.
#[no_mangle]
pub unsafe extern "C" fn orient_mag_calibrator_solve(
    calibrator: *const OrientMagCalibrator,
    fit: *mut OrientMagFit,
) -> OrientStatus {
    guard(|| {
        need(calibrator.is_null())?;
        put(fit, || {
            let c = calibrator_from(&*calibrator)?;
            let f = c.solve().ok_or_else(|| {
                fail(OrientStatus::NoData, format_args!("the readings do not determine an ellipsoid yet"))
            })?;
            Ok(OrientMagFit {
                model: model_to(&f.model),
                field: f.field,
                residual: f.residual,
                coverage: f.coverage,
                samples: f.samples,
                trustworthy: i32::from(f.trustworthy()),
                reserved: 0,
            })
        })
    })
}

/// The number of readings orient_mag_calibrator_add set aside as outliers (including
/// those a restart discarded), into `*rejected`. INVALID_ARGUMENT for a struct that is
/// not a calibrator's state.
#[no_mangle]
pub unsafe extern "C" fn orient_mag_calibrator_rejected(
    calibrator: *const OrientMagCalibrator,
    rejected: *mut u64,
) -> OrientStatus {
    guard(|| {
        need(calibrator.is_null())?;
        put(rejected, || Ok(calibrator_from(&*calibrator)?.rejected()))
    })
}

/// The gyroscope offset from `n` readings (rad/s) taken while the sensor was still: the
/// model that removes their mean (identity matrix, offset = mean), for
/// orient_filter_set_sensor_model with ORIENT_SENSOR_GYRO. `*spread` (when not NULL)
/// receives the readings' RMS deviation from the mean (rad/s): the still period's
/// noise; a much larger value says the sensor moved. Each reading is checked as
/// orient_filter_update checks a gyroscope reading: NON_FINITE for a NaN or infinite
/// component, TOO_LARGE for one at or beyond 1e4 rad/s. INVALID_ARGUMENT for n = 0,
/// COUNT_TOO_LARGE for an `n` no array can hold; nothing is written then.
#[no_mangle]
pub unsafe extern "C" fn orient_gyro_offset(
    readings: *const OrientVec3,
    n: usize,
    model: *mut OrientSensorModel,
    spread: *mut f64,
) -> OrientStatus {
    guard(|| {
        need(readings.is_null() || model.is_null())?;
        if n == 0 {
            return Err(fail(OrientStatus::InvalidArgument, format_args!("no readings")));
        }
        let mut g = GyroOffset::default();
        for r in items(readings, n, "readings")? {
            g.add(Vec3::new(r.x, r.y, r.z)).map_err(from_core)?;
        }
        let m = g.model().ok_or_else(|| fail(OrientStatus::InvalidArgument, format_args!("no readings")))?;
        model.write(model_to(&m));
        if !spread.is_null() {
            spread.write(g.spread());
        }
        Ok(())
    })
}
