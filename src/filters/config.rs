//! A filter's configuration.

use crate::filters::error::Error;
use crate::filters::kind::Kind;
use crate::filters::params::MAX_PARAMS;
use crate::math::{Frame, Quat};

/// How the filter gets its first orientation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Init {
    /// From the first sample that has an accelerometer reading (and, if it has one, the
    /// magnetometer): see [`Frame::attitude_from`]. That sample is then also used for a
    /// normal update. Until then the filter reports that it is not initialised.
    #[default]
    AccMag,
    /// The identity orientation in the configured frame.
    Identity,
    /// This orientation, in the configured frame (normalised on use).
    Given(Quat),
}

/// A filter's configuration: kind, frame, initial orientation and parameter slots.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    kind: Kind,
    pub frame: Frame,
    pub init: Init,
    params: [f64; MAX_PARAMS],
}

impl Config {
    /// The defaults of `kind`: ENU, initialised from the first accelerometer (and
    /// magnetometer) sample, every parameter at its documented default. Every kind is
    /// built today; the `Result` leaves room for kinds a build may leave out.
    pub fn new(kind: Kind) -> Result<Config, Error> {
        let mut params = [0.0; MAX_PARAMS];
        for p in kind.params() {
            params[p.id as usize] = p.default;
        }
        Ok(Config { kind, frame: Frame::Enu, init: Init::AccMag, params })
    }

    /// A configuration from raw slots, every known slot checked against its range.
    /// Slots this kind does not use are ignored.
    pub fn from_slots(
        kind: Kind,
        frame: Frame,
        init: Init,
        slots: &[f64; MAX_PARAMS],
    ) -> Result<Config, Error> {
        let mut config = Config::new(kind)?;
        config.frame = frame;
        config.init = init;
        for p in kind.params() {
            config.set_param(p.id, slots[p.id as usize])?;
        }
        Ok(config)
    }

    /// A configuration from slots already checked (a filter's own settings).
    pub(crate) fn from_parts(kind: Kind, frame: Frame, init: Init, params: [f64; MAX_PARAMS]) -> Config {
        Config { kind, frame, init, params }
    }

    pub fn kind(&self) -> Kind {
        self.kind
    }

    /// The value in slot `id`.
    pub fn param(&self, id: u32) -> Result<f64, Error> {
        self.kind.param(id).map(|p| self.params[p.id as usize]).ok_or(Error::UnknownParam(id))
    }

    /// Sets slot `id` after checking the value against the parameter's range.
    pub fn set_param(&mut self, id: u32, value: f64) -> Result<(), Error> {
        let spec = self.kind.param(id).ok_or(Error::UnknownParam(id))?;
        if !spec.accepts(value) {
            return Err(Error::ParamOutOfRange { id, value });
        }
        self.params[id as usize] = value;
        Ok(())
    }

    /// Sets the parameter called `name`; `None` when the kind has no such parameter.
    pub fn set(&mut self, name: &str, value: f64) -> Option<Result<(), Error>> {
        let spec = self.kind.param_by_name(name)?;
        Some(self.set_param(spec.id, value))
    }

    /// All slots (unused ones are zero).
    pub fn slots(&self) -> &[f64; MAX_PARAMS] {
        &self.params
    }
}
