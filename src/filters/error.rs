//! Why a call was refused.

use core::fmt;

/// Which quantity a problem was found in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    Dt,
    Gyro,
    Accel,
    Mag,
    Quaternion,
    /// An angle argument (heading, declination).
    Angle,
}

impl Field {
    fn name(self) -> &'static str {
        match self {
            Field::Dt => "dt",
            Field::Gyro => "gyroscope",
            Field::Accel => "accelerometer",
            Field::Mag => "magnetometer",
            Field::Quaternion => "quaternion",
            Field::Angle => "angle",
        }
    }
}

/// Why a call was refused. A refused call changes nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Error {
    /// This kind has no parameter in that slot.
    UnknownParam(u32),
    /// A parameter value outside its range or not finite.
    ParamOutOfRange { id: u32, value: f64 },
    /// A NaN or infinite value in a present field.
    NonFinite(Field),
    /// dt is below 1 ns (zero, negative, subnormal), above [`MAX_DT`](crate::filters::MAX_DT) or not finite.
    InvalidDt(f64),
    /// A vector whose norm is zero or too small to normalise.
    ZeroVector(Field),
    /// A vector whose squared norm overflows, or a reading at or beyond its physical
    /// bound ([`MAX_GYRO`](crate::filters::MAX_GYRO), [`MAX_ACCEL`](crate::filters::MAX_ACCEL),
    /// [`MAX_MAG`](crate::filters::MAX_MAG)).
    TooLarge(Field),
    /// A reading at or beyond the configured full-scale range.
    Saturated(Field),
    /// A sensor the filter needs is absent from the sample.
    MissingSensor(Field),
    /// The filter waits for a first sample with an accelerometer reading (and, with
    /// `same_instant`, dt > 0), or its start-up period for samples with one.
    NotInitialized,
    /// The update would have produced a non-finite orientation.
    Numeric,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::UnknownParam(id) => write!(f, "this filter kind has no parameter {id}"),
            Error::ParamOutOfRange { id, value } => {
                write!(f, "parameter {id}: value {value} is out of range")
            }
            Error::NonFinite(field) => write!(f, "{} has a NaN or infinite value", field.name()),
            Error::InvalidDt(dt) => {
                write!(f, "dt must be finite, at least 1e-9 s and at most 1e6 s, got {dt:e}")
            }
            Error::ZeroVector(field) => {
                write!(f, "{} vector is zero or too small to normalise", field.name())
            }
            Error::TooLarge(field) => {
                write!(
                    f,
                    "{} reading is too large (beyond its physical bound, or its norm overflows)",
                    field.name()
                )
            }
            Error::Saturated(field) => {
                write!(f, "{} reading is at or beyond its configured range", field.name())
            }
            Error::MissingSensor(field) => {
                write!(f, "sample has no {} reading, which this filter needs", field.name())
            }
            Error::NotInitialized => {
                write!(
                    f,
                    "filter waits for a sample with an accelerometer reading (and dt > 0) to initialise"
                )
            }
            Error::Numeric => write!(f, "update would produce a non-finite orientation"),
        }
    }
}

impl std::error::Error for Error {}
