//! [`Filter`]: a filter of any kind behind one type, for hosts that choose the kind at
//! run time (the C API, the bindings, the replay tool). It holds one boxed
//! [`Runner`] of its kind, so its memory is that kind's state and a few words (see
//! [`Filter::memory`]); every call is one match on the kind and the kind's own code.

use crate::filters::config::Config;
use crate::filters::diagnostics::Diagnostics;
use crate::filters::error::Error;
use crate::filters::kind::Kind;
use crate::filters::kinds::complementary::Complementary;
use crate::filters::kinds::ekf::Ekf;
use crate::filters::kinds::gmvdk::Gmvdk;
use crate::filters::kinds::madgwick::{Madgwick, LANES};
use crate::filters::kinds::mahony::Mahony;
use crate::filters::kinds::robust::Robust;
use crate::filters::pipeline::estimator::Estimator;
use crate::filters::pipeline::runner::Runner;
use crate::filters::pipeline::sample::Sample;
use crate::filters::pipeline::sample::SampleView;
use crate::filters::state::StateError;
use crate::math::{Euler, Quat, Vec3};

/// One runner per kind, boxed: a handle takes what its kind needs.
#[derive(Clone, Debug, PartialEq)]
enum Inner {
    Madgwick(Box<Runner<Madgwick>>),
    Mahony(Box<Runner<Mahony>>),
    Complementary(Box<Runner<Complementary>>),
    Ekf(Box<Runner<Ekf>>),
    Gmvdk(Box<Runner<Gmvdk>>),
    Robust(Box<Runner<Robust>>),
}

/// Runs the same expression on whichever kind's runner the filter holds.
macro_rules! each {
    ($inner:expr, $r:ident => $body:expr) => {
        match $inner {
            Inner::Madgwick($r) => $body,
            Inner::Mahony($r) => $body,
            Inner::Complementary($r) => $body,
            Inner::Ekf($r) => $body,
            Inner::Gmvdk($r) => $body,
            Inner::Robust($r) => $body,
        }
    };
}

/// Runs `$body` with `$E` naming the [`Estimator`] type of `$kind`: code generic over
/// the kind, run for a kind chosen at run time (tests are driven from [`Kind::ALL`]).
#[allow(unused_macros)]
macro_rules! with_kind {
    ($kind:expr, $E:ident => $body:expr) => {
        match $kind {
            $crate::filters::kind::Kind::Madgwick => {
                type $E = $crate::filters::kinds::madgwick::Madgwick;
                $body
            }
            $crate::filters::kind::Kind::Mahony => {
                type $E = $crate::filters::kinds::mahony::Mahony;
                $body
            }
            $crate::filters::kind::Kind::Complementary => {
                type $E = $crate::filters::kinds::complementary::Complementary;
                $body
            }
            $crate::filters::kind::Kind::Ekf => {
                type $E = $crate::filters::kinds::ekf::Ekf;
                $body
            }
            $crate::filters::kind::Kind::Gmvdk => {
                type $E = $crate::filters::kinds::gmvdk::Gmvdk;
                $body
            }
            $crate::filters::kind::Kind::Robust => {
                type $E = $crate::filters::kinds::robust::Robust;
                $body
            }
        }
    };
}
#[allow(unused_imports)]
pub(crate) use with_kind;

/// An orientation filter of any kind, with the common lifecycle:
/// [`Filter::new`], [`Filter::update`], the getters, [`Filter::reset`].
#[derive(Clone, Debug, PartialEq)]
pub struct Filter(Inner);

/// Whether [`Filter::update_group`] steps Madgwick filters in lanes on this target: the
/// two where it was measured to pay, and where two f64 lanes are one register (x86-64's
/// SSE2, aarch64's NEON). On armv7, without f64 SIMD, the `wide` crate's lanes are arrays,
/// and the 20-sensor frame took more guest instructions in lanes than one filter at a
/// time (docs/PERFORMANCE.md); other targets were not measured. The C rig call takes
/// its pairs only where this holds.
pub(crate) const LANES_PAY: bool = cfg!(any(target_arch = "x86_64", target_arch = "aarch64"));

impl Filter {
    pub fn new(config: &Config) -> Result<Filter, Error> {
        fn boxed<E: Estimator>(c: &Config) -> Result<Box<Runner<E>>, Error> {
            Runner::<E>::new(c).map(Box::new)
        }
        Ok(Filter(match config.kind() {
            Kind::Madgwick => Inner::Madgwick(boxed(config)?),
            Kind::Mahony => Inner::Mahony(boxed(config)?),
            Kind::Complementary => Inner::Complementary(boxed(config)?),
            Kind::Ekf => Inner::Ekf(boxed(config)?),
            Kind::Gmvdk => Inner::Gmvdk(boxed(config)?),
            Kind::Robust => Inner::Robust(boxed(config)?),
        }))
    }

    pub fn kind(&self) -> Kind {
        fn kind_of<E: Estimator>(_: &Runner<E>) -> Kind {
            E::KIND
        }
        each!(&self.0, r => kind_of(r))
    }

    /// Bytes this filter occupies: the value itself, its kind's boxed state, and the heap
    /// blocks that state holds (GMVDK's μ window). Constant per kind.
    pub fn memory(&self) -> usize {
        fn size_of<E: Estimator>(r: &Runner<E>) -> usize {
            core::mem::size_of::<Runner<E>>() + r.core.heap_bytes()
        }
        core::mem::size_of::<Filter>() + each!(&self.0, r => size_of(r))
    }

    /// The configuration: kind, frame, initial orientation, and every parameter as set
    /// (by the configuration it was made with and by [`Filter::set_param`] since).
    pub fn config(&self) -> Config {
        each!(&self.0, r => r.config())
    }

    /// Back to the state right after [`Filter::new`]; the settings are kept.
    pub fn reset(&mut self) {
        each!(&mut self.0, r => r.reset())
    }

    /// Changes a parameter while running; the orientation is kept.
    pub fn set_param(&mut self, id: u32, value: f64) -> Result<(), Error> {
        each!(&mut self.0, r => r.set_param(id, value))
    }

    pub fn param(&self, id: u32) -> Result<f64, Error> {
        each!(&self.0, r => r.param(id))
    }

    /// Sets the orientation (in the configured frame; normalised). The filter counts as
    /// initialised afterwards.
    pub fn set_quaternion(&mut self, q: Quat) -> Result<(), Error> {
        each!(&mut self.0, r => r.set_quaternion(q))
    }

    /// Checks a sample against every rule without touching the state.
    #[inline]
    pub fn check(&self, s: &Sample) -> Result<(), Error> {
        each!(&self.0, r => r.check_view(s))
    }

    /// One step. On error nothing changes: the state is bit-identical to before.
    #[inline]
    pub fn update(&mut self, s: &Sample) -> Result<(), Error> {
        self.update_inline(s)
    }

    /// [`Filter::update`] for any [`SampleView`]: the kind's dispatch, inlined into its
    /// caller, then one update function per kind and sample type; the C calls pass the
    /// host's struct and the update reads it in place (see [`SampleView`]).
    #[inline(always)]
    pub(crate) fn update_inline<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        each!(&mut self.0, r => r.update_outline(s))
    }

    /// Updates `N` distinct filters, `filters[i]` with `samples[i]`, in order: the result
    /// is exactly that of calling [`Filter::update`] on each (same bits, same errors),
    /// stopping at the first error, whose index is returned with it. On x86-64 and
    /// aarch64, where consecutive filters, [`Filter::GROUP_LANES`] at a time from the
    /// first, are Madgwick filters whose usual step takes their samples (past
    /// initialisation, nothing pending, no policy or rest-bias option, no gap, an
    /// accelerometer reading, the same sensors present), their steps may run side by side
    /// in lanes, which takes fewer instructions than one by one; nothing else depends on
    /// whether they do.
    pub fn update_group<const N: usize>(
        filters: &mut [&mut Filter; N],
        samples: [&Sample; N],
    ) -> Result<(), (usize, Error)> {
        Filter::update_group_view::<_, N, false>(filters, samples, |_, _| ())
    }

    /// [`Filter::update_group`] for any [`SampleView`] (the C call passes the host's
    /// structs, read in place). With `OUT`, calls `out(i, q)` with each filter's
    /// [`Filter::quaternion`] once its update has succeeded: a filter updated alone right
    /// after its update, a pair in lanes after their shared step (read from the Madgwick
    /// runners directly, without the kind's dispatch), in both cases before the next
    /// filter's update; without `OUT`, reads none.
    #[inline(always)]
    pub(crate) fn update_group_view<S: SampleView, const N: usize, const OUT: bool>(
        filters: &mut [&mut Filter; N],
        samples: [&S; N],
        mut out: impl FnMut(usize, Quat),
    ) -> Result<(), (usize, Error)> {
        let mut start = 0;
        while start < N {
            let end = N.min(start + LANES);
            let lanes = (
                <&mut [&mut Filter; LANES]>::try_from(&mut filters[start..end]),
                <[&S; LANES]>::try_from(&samples[start..end]),
            );
            if let (true, Ok(fs), Ok(ss)) = (LANES_PAY, lanes.0, lanes.1) {
                if Filter::try_lanes::<S, OUT>(fs, ss, |k, q| out(start + k, q)).is_some() {
                    start = end;
                    continue;
                }
            }
            for (i, (f, s)) in filters[start..end].iter_mut().zip(&samples[start..end]).enumerate() {
                f.update_inline(*s).map_err(|e| (start + i, e))?;
                if OUT {
                    out(start + i, f.quaternion());
                }
            }
            start = end;
        }
        Ok(())
    }

    /// How many filters [`Filter::update_group`] steps side by side (on x86-64 and
    /// aarch64).
    pub const GROUP_LANES: usize = LANES;

    /// The lane path of [`Filter::update_group`]: `None`, with nothing changed, unless
    /// every filter is a Madgwick filter whose usual step takes its sample
    /// ([`Runner::lane_usual`]) and the samples all have a magnetometer reading or none
    /// has. Anything else (a sample the rules refuse, a gap, a policy) goes one filter at
    /// a time, which gives the same result and reports the same error. After the step,
    /// with `OUT`, `out(k, q)` with each filter's [`Filter::quaternion`].
    pub(crate) fn try_lanes<S: SampleView, const OUT: bool>(
        filters: &mut [&mut Filter; LANES],
        samples: [&S; LANES],
        mut out: impl FnMut(usize, Quat),
    ) -> Option<()> {
        let mut runners = filters.each_mut().map(|f| match &mut f.0 {
            Inner::Madgwick(r) => Some(r),
            _ => None,
        });
        let mut usual = [None; LANES];
        for ((r, s), u) in runners.iter().zip(samples).zip(&mut usual) {
            *u = Some(r.as_ref()?.lane_usual(s)?);
        }
        let usual = usual.map(|u| u.expect("set above"));
        let with_mag = usual[0].mag.is_some();
        if usual.iter().any(|u| u.mag.is_some() != with_mag) {
            return None;
        }
        let mut runners = runners.each_mut().map(|r| r.take().expect("checked above"));
        let step = {
            let mut cores = runners.each_mut().map(|r| &mut r.core);
            Madgwick::update_lanes(&mut cores, &usual)?
        };
        for (k, (r, u)) in runners.iter_mut().zip(&usual).enumerate() {
            r.lane_done(u, step);
            if OUT {
                out(k, r.output());
            }
        }
        Some(())
    }

    /// The GMVDK state, for tests.
    #[cfg(test)]
    pub(crate) fn gmvdk(&self) -> Option<&Gmvdk> {
        match &self.0 {
            Inner::Gmvdk(r) => Some(&r.core),
            _ => None,
        }
    }

    /// The quick sample test, for tests.
    #[cfg(test)]
    pub(crate) fn plainly_valid(&self, s: &Sample) -> bool {
        each!(&self.0, r => r.plainly_valid(s))
    }

    /// The exact sample rules, for tests.
    #[cfg(test)]
    pub(crate) fn check_exactly(&self, s: &Sample) -> Result<(), Error> {
        each!(&self.0, r => r.check_exactly(s))
    }

    /// Internal states for display: bias, trust values, rest flag, covariance (see
    /// [`Diagnostics`]; fields that do not apply are absent and NaN).
    pub fn diagnostics(&self) -> Diagnostics {
        each!(&self.0, r => r.diagnostics())
    }

    /// One standard deviation (rad) of the heading and inclination errors, from the kinds
    /// that model them: the EKF (both, from its covariance P) and the robust kind (heading:
    /// it grows while the magnetometer is distrusted or absent, and settles while it is
    /// used to about √(σ_v² + (σ τ_mag)²) plus the turning's share, σ_v growing from
    /// `mag_heading_sigma` with the used field's deviation from the reference and σ the
    /// bias uncertainty, `bias_sigma_rest` after a rest, else `bias_sigma`;
    /// `src/filters/robust.rs`, eqs. (H1)-(H5): a used field that disagrees with the
    /// estimate, and a gyroscope step too fast to be a turn, raise it). `set_quaternion`
    /// makes the robust kind's heading exact until the next update; the EKF keeps its
    /// covariance.
    /// Every field is `None` for the other kinds and before initialisation. The heading
    /// is against the kind's reference (magnetic north once a magnetometer was used, else
    /// the start heading); offsets the host sets (heading, declination, rig calibration,
    /// mounting, frame) are exact and add none.
    pub fn uncertainty(&self) -> crate::filters::diagnostics::Uncertainty {
        each!(&self.0, r => r.uncertainty())
    }

    /// True when this filter, with its settings, learns its gyroscope bias in motion (the
    /// horizontal part, which its inclination correction measures): the recommended kind
    /// unless `bias_sigma_motion`, `bias_walk` or `bias_sigma` is 0, the EKF, and Mahony
    /// with `ki` above 0. Madgwick, Mahony without `ki` (its rest learner learns at rest),
    /// the complementary filter and GMVDK learn theirs at rest, in a still start, or not
    /// at all. The joints read it ([`crate::joints::Joints::update_from`]).
    pub fn learns_bias_in_motion(&self) -> bool {
        each!(&self.0, r => r.learns_bias_in_motion())
    }

    /// The [`crate::filters::diagnostics::diag`] bits of the [`Diagnostics`] fields this filter reports with its
    /// settings: [`Kind::diagnostics`] less those of an option that is off (Madgwick's bias
    /// and rest, Mahony's and the EKF's rest without their rest options). GMVDK's μ values
    /// are among them, though absent until its first magnetometer reading.
    pub fn diagnostic_fields(&self) -> u32 {
        each!(&self.0, r => r.diagnostic_fields())
    }

    /// Size in bytes of [`Filter::save`]'s blob for this filter (constant per kind).
    pub fn state_size(&self) -> usize {
        each!(&self.0, r => r.state_size())
    }

    /// Writes a snapshot of the configuration and state into `out`; returns its length.
    /// Loading it into a filter of the same kind continues bit for bit as this one would.
    pub fn save(&self, out: &mut [u8]) -> Result<usize, StateError> {
        each!(&self.0, r => r.save(out))
    }

    /// Restores a snapshot from [`Filter::save`]. On error nothing changes: the blob
    /// must be whole, unmodified (checksum), of this format version and of this kind.
    pub fn load(&mut self, blob: &[u8]) -> Result<(), StateError> {
        each!(&mut self.0, r => r.load(blob))
    }

    /// True once the filter has an orientation.
    pub fn is_initialized(&self) -> bool {
        self.flags() & crate::filters::flags::INITIALIZED != 0
    }

    /// [`crate::filters::flags`] bits.
    pub fn flags(&self) -> u32 {
        each!(&self.0, r => r.flags())
    }

    /// The orientation in the configured frame (identity before initialisation): the
    /// segment's when a mounting is set, with the heading offset and declination applied
    /// (see [`Filter::set_mounting`], [`Filter::set_heading`], [`Filter::set_declination`]).
    #[inline(always)]
    pub fn quaternion(&self) -> Quat {
        each!(&self.0, r => r.output())
    }

    /// The sensor's orientation as the kind estimates it, in the configured frame (no
    /// mounting, heading offset or declination).
    pub(crate) fn frame_quaternion(&self) -> Quat {
        each!(&self.0, r => r.quaternion())
    }

    /// The configured earth frame.
    pub fn frame(&self) -> crate::math::Frame {
        each!(&self.0, r => r.frame())
    }

    pub(crate) fn host(&self) -> crate::filters::pipeline::host::Host {
        each!(&self.0, r => r.host())
    }

    /// The host's frames, made when first set (not in an update).
    pub(crate) fn host_mut(&mut self) -> &mut crate::filters::pipeline::host::Host {
        each!(&mut self.0, r => &mut r.extras_mut().host)
    }

    pub(crate) fn models(&self) -> crate::filters::calibration::Models {
        each!(&self.0, r => r.models())
    }

    pub(crate) fn models_mut(&mut self) -> &mut crate::filters::calibration::Models {
        each!(&mut self.0, r => &mut r.extras_mut().models)
    }

    /// After [`Filter::models_mut`]: the runner's note of whether any model is set.
    pub(crate) fn refresh_models(&mut self) {
        each!(&mut self.0, r => r.refresh_models())
    }

    /// Euler angles (Z-Y'-X'': yaw, pitch, roll) of [`Filter::quaternion`], radians.
    pub fn euler(&self) -> Euler {
        self.quaternion().to_euler()
    }

    /// Rotation matrix (row-major, body to earth) of [`Filter::quaternion`].
    pub fn rotation_matrix(&self) -> [[f64; 3]; 3] {
        self.quaternion().to_matrix()
    }

    /// What the accelerometer reads at rest in the current orientation: gravity's
    /// reaction (pointing up) in the sensor frame, m/s², magnitude `gravity`.
    pub fn gravity(&self) -> Vec3 {
        let (frame, g) = each!(&self.0, r => (r.frame(), r.gravity_magnitude()));
        let up = self.frame_quaternion().rotate_inverse(frame.up());
        up * g
    }

    /// The last accelerometer reading minus [`Filter::gravity`], in the sensor frame;
    /// `None` before the first accelerometer reading.
    pub fn linear_accel(&self) -> Option<Vec3> {
        each!(&self.0, r => r.last_accel()).map(|a| a - self.gravity())
    }

    /// [`Filter::linear_accel`] rotated into the earth frame.
    pub fn linear_accel_earth(&self) -> Option<Vec3> {
        self.linear_accel().map(|a| self.host().earth(self.frame_quaternion().rotate(a)))
    }
}
