//! Offline mode: a whole recording in, a smoothed orientation out, for motion-capture
//! post-processing where every sample's future is known.
//!
//! Non-causal forward-backward smoothing through any filter kind (by default the
//! recommended kind with a longer heading time constant, [`config`](crate::offline::config)):
//!
//! 1. A priming forward pass over the recording finds the orientation at its end.
//! 2. A backward pass runs a copy of that filter on the time-reversed recording
//!    (gyroscope negated, each step taking the interval that follows the sample).
//! 3. A forward pass continues from a copy of the backward pass at the first sample
//!    (or starts fresh when the configuration gives its own initial orientation).
//! 4. Each sample's output is the SLERP of the two passes, weighted by each pass's
//!    confidence: the inverse variance of a heading-error model that grows while the
//!    pass runs without its magnetometer and recovers while it uses it. Both passes
//!    start from a converged state (the whole filter state is carried across each turn,
//!    the gyroscope bias re-signed), so neither has a start-up transient: the backward
//!    pass covers the recording's start with everything after it, the forward pass the
//!    end.
//!
//! Unlike [`crate::Filter::update`], this allocates (one output per sample and the
//! passes' estimates).

#![forbid(unsafe_code)]

use crate::filters::{Config, Error, Filter, Init, Kind, Sample};
use crate::math::{Quat, Vec3};
use core::fmt;

/// Why a recording could not be smoothed: the first bad sample's index and the error
/// [`Filter::update`] gave for it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmoothError {
    pub index: usize,
    pub error: Error,
}

impl fmt::Display for SmoothError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "sample {}: {}", self.index, self.error)
    }
}

impl std::error::Error for SmoothError {}

/// The recommended kind's heading time constant `tau_mag` in the offline defaults (s),
/// three times its causal default. A residual gyroscope bias turns a causal pass's
/// heading away from the magnetometer's one way and the time-reversed pass's the other
/// way, so the fusion cancels that error to first order and each pass can lean on the
/// gyroscope longer; what remains is the magnetometer's error, which a longer average
/// shrinks. Chosen by leave-one-group-out cross-validation over the 14 shared BROAD
/// trials (tools/src/bin/offline_cv.rs: 27 s in six of the seven folds, 36 s in the other).
pub const OFFLINE_TAU_MAG: f64 = 27.0;

/// The offline defaults: the recommended kind with its defaults, but for the heading time
/// constant [`OFFLINE_TAU_MAG`].
pub fn config() -> Config {
    let mut c = Config::new(Kind::Robust).expect("the recommended kind is always built");
    c.set("tau_mag", OFFLINE_TAU_MAG)
        .expect("the recommended kind has tau_mag")
        .expect("OFFLINE_TAU_MAG is in tau_mag's range");
    c
}

/// Smooths a recording with the offline defaults ([`config`]); see [`smooth`].
pub fn smooth_default(samples: &[Sample]) -> Result<Vec<Quat>, SmoothError> {
    smooth(&config(), samples)
}

/// The smoothed orientation at every sample (in the configuration's frame), through the
/// configured kind and parameters. Fails at the first sample [`Filter::update`] refuses
/// in a forward run of the same configuration, naming its index; an empty recording
/// gives an empty result.
pub fn smooth(config: &Config, samples: &[Sample]) -> Result<Vec<Quat>, SmoothError> {
    let (fore, back) = passes(config, samples)?;
    Ok(fuse(&fore, &back))
}

/// The forward and the backward pass of [`smooth`] before fusion (steps 1-3), each an
/// orientation at every sample.
pub fn passes(config: &Config, samples: &[Sample]) -> Result<(Track, Track), SmoothError> {
    let n = samples.len();
    if n == 0 {
        return Ok((Track::default(), Track::default()));
    }
    let fail = |index: usize| move |error: Error| SmoothError { index, error };
    // 1. Priming forward pass: the whole state at the recording's end.
    let mut prime = Pass { filter: Filter::new(config).map_err(fail(0))?, sign: 1.0, offset: Vec3::ZERO };
    for (i, s) in samples.iter().enumerate() {
        prime.step(s, s.gyro).map_err(fail(i))?;
    }
    // 2. Backward pass, continuing from the priming pass's end state.
    let mut backward = prime.turned();
    let mut back = Track { q: vec![Quat::IDENTITY; n], sigma: vec![0.0; n] };
    let mut sigma = FLOOR;
    for j in (0..n).rev() {
        // The step back to sample j is sample j + 1's reading; the last sample is where
        // the pass starts, so it takes no rotation.
        let gyro = samples.get(j + 1).map_or(Some(Vec3::ZERO), |s| s.gyro);
        let dt = samples.get(j + 1).map_or(samples[j].dt, |s| s.dt);
        backward.step(&Sample { dt, ..samples[j] }, gyro).map_err(fail(j))?;
        sigma = heading_sigma(sigma, dt, &backward.filter);
        back.q[j] = backward.filter.quaternion();
        back.sigma[j] = sigma;
    }
    // 3. Forward pass, continuing from the backward pass's state at the first sample;
    // from the host's own initial orientation when the configuration gives one.
    let mut fore_pass = backward.turned();
    if !matches!(config.init, Init::AccMag) {
        fore_pass = Pass { filter: Filter::new(config).map_err(fail(0))?, sign: 1.0, offset: Vec3::ZERO };
    }
    let mut fore = Track { q: Vec::with_capacity(n), sigma: Vec::with_capacity(n) };
    let mut sigma = FLOOR;
    for (i, s) in samples.iter().enumerate() {
        fore_pass.step(s, s.gyro).map_err(fail(i))?;
        sigma = heading_sigma(sigma, s.dt, &fore_pass.filter);
        fore.q.push(fore_pass.filter.quaternion());
        fore.sigma.push(sigma);
    }
    Ok((fore, back))
}

/// A filter run over the recording in one direction (`sign` +1 forward, -1 backward in
/// time), fed `sign * gyro + offset`.
struct Pass {
    filter: Filter,
    sign: f64,
    offset: Vec3,
}

impl Pass {
    fn step(&mut self, s: &Sample, gyro: Option<Vec3>) -> Result<(), Error> {
        let gyro = gyro.map(|g| g * self.sign + self.offset);
        self.filter.update(&Sample { gyro, ..*s })
    }

    /// The bias the filter subtracts, zero for a kind that estimates none.
    fn subtracted(&self) -> Vec3 {
        let b = self.filter.diagnostics().gyro_bias;
        if b.is_finite() {
            b
        } else {
            Vec3::ZERO
        }
    }

    /// The sensor's own gyroscope bias as this pass estimates it: the pass computes
    /// `sign g + offset - β = sign (g - b)`, so `b = sign (β - offset)`.
    fn bias(&self) -> Vec3 {
        (self.subtracted() - self.offset) * self.sign
    }

    /// A pass in the other direction that continues from this one's whole state
    /// (orientation, bias, field reference, rest detection): with the same subtracted β,
    /// its offset makes `-sign g + offset - β = -sign (g - b)`.
    fn turned(&self) -> Pass {
        let sign = -self.sign;
        Pass { filter: self.filter.clone(), sign, offset: self.subtracted() - self.bias() * sign }
    }
}

/// One pass's estimate at every sample: the orientation and the modelled standard
/// deviation of its heading error (rad).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Track {
    pub q: Vec<Quat>,
    pub sigma: Vec<f64>,
}

/// Heading error (standard deviation, rad) of a pass right after its magnetometer has
/// been in use for a long time: the spread of the earth field's direction indoors.
pub const FLOOR: f64 = 0.02;
/// How fast a pass's heading error grows while its magnetometer is unused (rad/s): a
/// residual gyroscope bias of 0.3°/s, plus integration error in motion.
pub const DRIFT: f64 = 0.005;
/// Time constant (s) over which magnetometer corrections bring a heading error back to
/// [`FLOOR`] (the order of the kinds' heading correction time constants).
pub const RECOVERY: f64 = 10.0;

/// The heading-error model of one step of `dt`: the error grows at [`DRIFT`], and the
/// magnetometer, when the filter used it, pulls it back towards [`FLOOR`].
fn heading_sigma(sigma: f64, dt: f64, filter: &Filter) -> f64 {
    let mut s = sigma + DRIFT * dt;
    if filter.flags() & crate::filters::flags::MAG_USED != 0 {
        s -= (s - FLOOR) * (dt / (RECOVERY + dt));
    }
    s
}

/// Step 4 of [`smooth`]: each sample's SLERP of the two passes, each weighted by the
/// inverse variance of its heading error.
pub fn fuse(fore: &Track, back: &Track) -> Vec<Quat> {
    fore.q
        .iter()
        .zip(&back.q)
        .zip(fore.sigma.iter().zip(&back.sigma))
        .map(|((f, b), (sf, sb))| {
            let (vf, vb) = (sf * sf, sb * sb);
            slerp(*f, *b, vf / (vf + vb))
        })
        .collect()
}

/// Spherical interpolation from `a` (share 0) to `b` (share 1) along the shorter arc.
pub fn slerp(a: Quat, b: Quat, share: f64) -> Quat {
    let b = if a.dot(b) < 0.0 { b.scale(-1.0) } else { b };
    let d = (a.conj() * b).normalized();
    let v = d.vector();
    let s = v.norm();
    if s < 1e-12 {
        return a;
    }
    let angle = libm::atan2(s, d.w) * share;
    let r = Quat::new(libm::cos(angle), 0.0, 0.0, 0.0);
    let axis = v * (libm::sin(angle) / s);
    (a * Quat::new(r.w, axis.x, axis.y, axis.z)).normalized()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn slerp_halves_a_rotation() {
        let z = Vec3::new(0.0, 0.0, 1.0);
        let a = Quat::from_axis_angle(z, 0.2);
        let b = Quat::from_axis_angle(z, 1.0);
        let m = slerp(a, b, 0.5);
        let e = Quat::from_axis_angle(z, 0.6);
        assert!((m.dot(e).abs() - 1.0).abs() < 1e-12, "{m:?}");
        assert_eq!(slerp(a, b.scale(-1.0), 0.0), a.normalized());
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn a_bad_sample_is_named() {
        let good = Sample {
            dt: 0.01,
            gyro: Some(Vec3::ZERO),
            accel: Some(Vec3::new(0.0, 0.0, 9.81)),
            mag: Some(Vec3::new(0.0, 20.0, -40.0)),
        };
        let mut samples = vec![good; 5];
        samples[3].gyro = Some(Vec3::new(f64::NAN, 0.0, 0.0));
        let e = smooth_default(&samples).unwrap_err();
        assert_eq!(e.index, 3);
        assert_eq!(smooth_default(&[]).unwrap(), Vec::<Quat>::new());
        assert_eq!(smooth_default(&samples[..3]).unwrap().len(), 3);
    }
}
