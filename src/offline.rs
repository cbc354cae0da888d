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
//! # Memory
//!
//! The priming pass is the refusal check: it is a forward run of a new filter of the
//! configuration, so the smoother refuses exactly the samples such a run refuses, before
//! any output is written. The backward pass writes its orientation straight into the
//! output slots and keeps only its heading sigma on the side; the final forward pass
//! fuses each sample as it goes and overwrites that sample's slot. Samples are read where
//! they lie ([`SampleSource`](crate::offline::SampleSource)), never copied. So beyond the
//! caller's samples and outputs, [`smooth_into`](crate::offline::smooth_into) allocates
//! [`MEMORY_PER_SAMPLE`](crate::offline::MEMORY_PER_SAMPLE) (8) bytes per sample, in one
//! block reserved fallibly before the first pass
//! ([`SmoothError::OutOfMemory`](crate::offline::SmoothError::OutOfMemory) when it cannot
//! be had), and one filter (at most [`FIXED_MEMORY`](crate::offline::FIXED_MEMORY) bytes,
//! every kind) at a time: [`memory`](crate::offline::memory) is the sum.
//! [`smooth`](crate::offline::smooth) adds its result, 32 bytes per sample, also reserved
//! fallibly.
//!
//! Unlike [`crate::Filter::update`], this allocates; [`passes`](crate::offline::passes)
//! and [`fuse`](crate::offline::fuse) give the two passes apart, for analysis, at 64 more
//! bytes per sample.

#![forbid(unsafe_code)]

use crate::filters::{Config, Error, Filter, Init, Kind, Sample};
use crate::math::{Quat, Vec3};
use core::fmt;

/// Why a recording could not be smoothed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SmoothError {
    /// The first sample a forward run of a new filter of the configuration refuses: its
    /// index and the error [`Filter::update`] gave for it (or the configuration's own
    /// error, at index 0, when no filter can be built from it).
    Sample { index: usize, error: Error },
    /// A buffer the call needs, of `bytes` bytes, could not be allocated (or its size
    /// overflows); nothing was written.
    OutOfMemory { bytes: usize },
}

impl fmt::Display for SmoothError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SmoothError::Sample { index, error } => write!(f, "sample {index}: {error}"),
            SmoothError::OutOfMemory { bytes } => {
                write!(f, "a buffer of {bytes} bytes could not be allocated")
            }
        }
    }
}

impl std::error::Error for SmoothError {}

/// Bytes [`smooth_into`] allocates per sample: the backward pass's heading sigma (one
/// `f64`).
pub const MEMORY_PER_SAMPLE: usize = core::mem::size_of::<f64>();

/// A bound on the bytes [`smooth_into`] allocates besides [`MEMORY_PER_SAMPLE`] per
/// sample: one filter of any kind at a time ([`Filter::memory`]; GMVDK's, with its 16 KB
/// window, is the largest).
pub const FIXED_MEMORY: usize = 32 * 1024;

/// The bytes [`smooth_into`] may allocate for `n` samples, at most: `8 n` plus
/// [`FIXED_MEMORY`]. None when no recording of `n` samples can exist: its outputs (32
/// bytes each) or this figure would exceed `isize::MAX` bytes.
pub fn memory(n: usize) -> Option<usize> {
    if n > max_samples() {
        return None;
    }
    n.checked_mul(MEMORY_PER_SAMPLE)?.checked_add(FIXED_MEMORY)
}

/// The largest count of samples a recording can have: its outputs, one [`Quat`] each,
/// must fit in `isize::MAX` bytes.
pub const fn max_samples() -> usize {
    isize::MAX as usize / core::mem::size_of::<Quat>()
}

/// A recording the smoother reads in place, one sample at a time by index (each sample
/// is read three times, once per pass). Implemented for `[Sample]`; the C ABI implements
/// it over the host's arrays.
pub trait SampleSource {
    /// The number of samples.
    fn len(&self) -> usize;
    /// Sample `i`, for `i < self.len()`.
    fn sample(&self, i: usize) -> Sample;
    /// True for a recording without samples.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl SampleSource for [Sample] {
    fn len(&self) -> usize {
        <[Sample]>::len(self)
    }
    fn sample(&self, i: usize) -> Sample {
        self[i]
    }
}

/// The smoother's output slots, one orientation per sample: the backward pass's
/// estimate is stored in a slot, read back once by the final forward pass and replaced
/// with the fused orientation. Implemented for `[Quat]`; the C ABI implements it over
/// the host's output array.
pub trait Orientations {
    /// The number of slots.
    fn len(&self) -> usize;
    /// The orientation last stored in slot `i`.
    fn get(&self, i: usize) -> Quat;
    /// Stores `q` in slot `i`.
    fn set(&mut self, i: usize, q: Quat);
    /// True for no slots.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl Orientations for [Quat] {
    fn len(&self) -> usize {
        <[Quat]>::len(self)
    }
    fn get(&self, i: usize) -> Quat {
        self[i]
    }
    fn set(&mut self, i: usize, q: Quat) {
        self[i] = q;
    }
}

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
/// configured kind and parameters: [`smooth_into`] a new vector, reserved fallibly.
/// Fails at the first sample [`Filter::update`] refuses in a forward run of the same
/// configuration, naming its index, or when memory runs out; an empty recording gives
/// an empty result.
pub fn smooth(config: &Config, samples: &[Sample]) -> Result<Vec<Quat>, SmoothError> {
    let mut out = Vec::new();
    reserve(&mut out, samples.len())?;
    out.resize(samples.len(), Quat::IDENTITY);
    smooth_into(config, samples, &mut out[..])?;
    Ok(out)
}

/// [`smooth`] into the caller's slots: `out[i]` receives the smoothed orientation at
/// sample `i`. Allocates at most [`memory`]`(n)` bytes (see the module's "Memory").
/// On an error `out` is unchanged: a refused sample is found by the priming pass and
/// the side buffer is reserved before it, both before anything is written. Steps the
/// backward or the final forward pass refuses although the forward run accepted them
/// (a gyroscope reading re-signed and offset by the bias estimate reaching a bound the
/// original stayed within) are skipped: that pass holds its state over the step.
///
/// # Panics
///
/// When `out` and `samples` differ in length.
pub fn smooth_into<S, O>(config: &Config, samples: &S, out: &mut O) -> Result<(), SmoothError>
where
    S: SampleSource + ?Sized,
    O: Orientations + ?Sized,
{
    let n = samples.len();
    assert_eq!(out.len(), n, "one output slot per sample");
    if n == 0 {
        return Ok(());
    }
    let mut back_sigma: Vec<f64> = Vec::new();
    reserve(&mut back_sigma, n)?;
    back_sigma.resize(n, 0.0);
    run(config, samples, &mut InPlace { out, back_sigma })
}

/// The passes' estimates as [`smooth_into`] keeps them: the backward pass's orientation
/// in the output slot, its heading sigma on the side; the forward pass's fused at once.
struct InPlace<'a, O: ?Sized> {
    out: &'a mut O,
    back_sigma: Vec<f64>,
}

impl<O: Orientations + ?Sized> Estimates for InPlace<'_, O> {
    fn back(&mut self, j: usize, q: Quat, sigma: f64) {
        self.out.set(j, q);
        self.back_sigma[j] = sigma;
    }
    fn fore(&mut self, i: usize, q: Quat, sigma: f64) {
        let fused = fuse_one(q, self.out.get(i), sigma, self.back_sigma[i]);
        self.out.set(i, fused);
    }
}

/// Where the passes hand their estimate at each sample: an orientation and the modelled
/// heading sigma.
trait Estimates {
    /// The backward pass's at sample `j`, from the last sample to the first.
    fn back(&mut self, j: usize, q: Quat, sigma: f64);
    /// The final forward pass's at sample `i`, from the first sample to the last, each
    /// after the backward pass's at the same sample.
    fn fore(&mut self, i: usize, q: Quat, sigma: f64);
}

/// Reserves exactly `n` more elements, or says how many bytes could not be had.
fn reserve<T>(v: &mut Vec<T>, n: usize) -> Result<(), SmoothError> {
    v.try_reserve_exact(n)
        .map_err(|_| SmoothError::OutOfMemory { bytes: n.saturating_mul(core::mem::size_of::<T>()) })
}

/// The forward and the backward pass of [`smooth`] before fusion (steps 1-3), each an
/// orientation and a heading sigma at every sample (64 bytes per sample, reserved
/// fallibly).
pub fn passes(config: &Config, samples: &[Sample]) -> Result<(Track, Track), SmoothError> {
    let n = samples.len();
    let mut tracks = (Track::default(), Track::default());
    for t in [&mut tracks.0, &mut tracks.1] {
        reserve(&mut t.q, n)?;
        reserve(&mut t.sigma, n)?;
        t.q.resize(n, Quat::IDENTITY);
        t.sigma.resize(n, 0.0);
    }
    run(config, samples, &mut tracks)?;
    Ok(tracks)
}

/// (forward, backward): each pass's estimates in full.
impl Estimates for (Track, Track) {
    fn back(&mut self, j: usize, q: Quat, sigma: f64) {
        (self.1.q[j], self.1.sigma[j]) = (q, sigma);
    }
    fn fore(&mut self, i: usize, q: Quat, sigma: f64) {
        (self.0.q[i], self.0.sigma[i]) = (q, sigma);
    }
}

/// Steps 1-3: the priming pass (whose refusals are the call's), then the backward and
/// the forward pass, handing their estimates to `to`.
fn run<S: SampleSource + ?Sized>(
    config: &Config,
    samples: &S,
    to: &mut impl Estimates,
) -> Result<(), SmoothError> {
    let n = samples.len();
    if n == 0 {
        return Ok(());
    }
    let fail = |index: usize| move |error: Error| SmoothError::Sample { index, error };
    // 1. Priming forward pass: the whole state at the recording's end. Exactly a forward
    // run of a new filter, so it refuses exactly what such a run refuses.
    let mut prime = Pass { filter: Filter::new(config).map_err(fail(0))?, sign: 1.0, offset: Vec3::ZERO };
    for i in 0..n {
        let s = samples.sample(i);
        prime.step(&s, s.gyro).map_err(fail(i))?;
    }
    // 2. Backward pass, continuing from the priming pass's end state.
    let mut backward = prime.turned();
    let mut sigma = FLOOR;
    let mut next = None::<Sample>;
    for j in (0..n).rev() {
        let s = samples.sample(j);
        // The step back to sample j is sample j + 1's reading; the last sample is where
        // the pass starts, so it takes no rotation.
        let gyro = next.map_or(Some(Vec3::ZERO), |s| s.gyro);
        let dt = next.map_or(s.dt, |s| s.dt);
        // A refused step is held (see smooth_into): the filter is unchanged by it.
        let _ = backward.step(&Sample { dt, ..s }, gyro);
        sigma = heading_sigma(sigma, dt, &backward.filter);
        to.back(j, backward.filter.quaternion(), sigma);
        next = Some(s);
    }
    // 3. Forward pass, continuing from the backward pass's state at the first sample;
    // from the host's own initial orientation when the configuration gives one.
    let mut fore_pass = if matches!(config.init, Init::AccMag) {
        backward.turned()
    } else {
        drop(backward);
        Pass { filter: Filter::new(config).map_err(fail(0))?, sign: 1.0, offset: Vec3::ZERO }
    };
    let mut sigma = FLOOR;
    for i in 0..n {
        let s = samples.sample(i);
        let _ = fore_pass.step(&s, s.gyro);
        sigma = heading_sigma(sigma, s.dt, &fore_pass.filter);
        to.fore(i, fore_pass.filter.quaternion(), sigma);
    }
    Ok(())
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
    /// its offset makes `-sign g + offset - β = -sign (g - b)`. The filter moves over:
    /// one filter is alive at a time.
    fn turned(self) -> Pass {
        let sign = -self.sign;
        let offset = self.subtracted() - self.bias() * sign;
        Pass { filter: self.filter, sign, offset }
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
        .map(|((f, b), (sf, sb))| fuse_one(*f, *b, *sf, *sb))
        .collect()
}

/// One sample's fusion: the SLERP from the forward pass's `f` towards the backward
/// pass's `b` by the share of the forward pass's heading variance.
fn fuse_one(f: Quat, b: Quat, sigma_f: f64, sigma_b: f64) -> Quat {
    let (vf, vb) = (sigma_f * sigma_f, sigma_b * sigma_b);
    slerp(f, b, vf / (vf + vb))
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
        assert!(matches!(e, SmoothError::Sample { index: 3, error: Error::NonFinite(_) }), "{e:?}");
        assert_eq!(smooth_default(&[]).unwrap(), Vec::<Quat>::new());
        assert_eq!(smooth_default(&samples[..3]).unwrap().len(), 3);
    }

    #[test]
    fn one_filter_of_any_kind_fits_the_fixed_part() {
        for kind in Kind::ALL {
            let f = Filter::new(&Config::new(kind).unwrap()).unwrap();
            assert!(f.memory() <= FIXED_MEMORY, "{kind:?}: {} bytes", f.memory());
        }
        assert_eq!(memory(0), Some(FIXED_MEMORY));
        assert_eq!(memory(1000), Some(8000 + FIXED_MEMORY));
        assert_eq!(memory(max_samples()), Some(max_samples() * 8 + FIXED_MEMORY));
        assert_eq!(memory(max_samples() + 1), None);
        assert_eq!(memory(usize::MAX), None);
    }
}
