//! The clip-and-recover saturation policy (issue 20, parameter `saturation_recovery`):
//! a reading at or beyond its configured range is used clipped and flagged, and after
//! gyroscope saturation the orientation is re-acquired from the accelerometer (and
//! magnetometer) through the gap path's re-acquisition, as x-io Fusion's angular-rate
//! recovery re-initialises. Readings at or beyond the physical bounds stay errors.

use crate::filters::error::Error;
use crate::filters::flags;
use crate::filters::pipeline::estimator::Estimator;
use crate::filters::pipeline::runner::Runner;
use crate::filters::pipeline::sample::Sample;
use crate::filters::pipeline::sample::SampleView;
use crate::filters::pipeline::sample::MAX_ACCEL;
use crate::filters::pipeline::sample::MAX_GYRO;
use crate::filters::pipeline::sample::MIN_DT;
use crate::math::Vec3;

/// The largest value under `range` (> 0).
fn under(range: f64) -> f64 {
    f64::from_bits(range.to_bits() - 1)
}

fn clip(v: Vec3, range: f64) -> Vec3 {
    let c = |x: f64| x.clamp(-under(range), under(range));
    Vec3::new(c(v.x), c(v.y), c(v.z))
}

/// A finite reading at or beyond `range` and under the physical `bound`.
fn beyond(v: Option<Vec3>, range: f64, bound: f64) -> bool {
    v.is_some_and(|v| v.is_finite() && range < bound && v.max_abs() >= range && v.max_abs() < bound)
}

impl<E: Estimator> Runner<E> {
    /// The gyroscope readings of dt = 0 samples waiting for the next step (sum, count).
    pub(crate) fn burst(&self) -> (Vec3, u32) {
        self.extras.0.as_ref().map_or((Vec3::ZERO, 0), |x| x.burst)
    }

    fn set_burst(&mut self, b: (Vec3, u32)) {
        // The box exists whenever `same_instant` is on (set_policies).
        if let Some(x) = &mut self.extras.0 {
            x.burst = b;
        }
    }

    /// The `same_instant` policy: a dt = 0 sample is checked (as if its dt were valid;
    /// clipped first under the clipping policy, then flagged SATURATED) and its gyroscope
    /// reading kept; the next sample with dt > 0, checked the same way, integrates the
    /// average of the kept readings and its own over its dt. Nothing changes on error.
    #[cold]
    #[inline(never)]
    pub(crate) fn update_same_instant<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        let (sum, n) = self.burst();
        // Every sample of a burst meets the rules a lone sample would: under the
        // clipping policy its clipped form is checked, else the reading as it is.
        // (The smallest valid dt stands in for 0: never a gap, so the quick check can pass.)
        let probe = Sample { dt: if s.dt() == 0.0 { MIN_DT } else { s.dt() }, ..s.to_sample() };
        let (checked, gyro_clipped, clipped) = self.clipped(&probe);
        self.check_view(&checked)?;
        if s.dt() == 0.0 {
            // Refused only while the filter waits for its first sample with dt > 0; a
            // kind's start-up period takes a burst like any other sample.
            if self.waiting() {
                return Err(Error::NotInitialized);
            }
            let g = checked.gyro.unwrap_or_default();
            self.set_burst((sum + g, n.saturating_add(1)));
            let kept = self.flags & (flags::INITIALIZED | flags::REACQUIRE_PENDING);
            self.flags = kept
                | flags::SAME_INSTANT
                | if clipped { flags::SATURATED } else { 0 }
                | if gyro_clipped { flags::REACQUIRE_PENDING } else { 0 };
            return Ok(());
        }
        let own = checked.gyro.unwrap_or_default();
        let mean = (sum + own) * (1.0 / (n as f64 + 1.0));
        let folded = Sample { dt: s.dt(), gyro: checked.gyro.map(|_| mean), ..checked };
        self.set_burst((Vec3::ZERO, 0));
        let before = self.flags;
        match self.update_inline(&folded) {
            Ok(()) => {
                if clipped && self.flags & flags::INITIALIZED != 0 {
                    self.flags |= flags::SATURATED | if gyro_clipped { flags::REACQUIRE_PENDING } else { 0 };
                }
                Ok(())
            }
            Err(e) => {
                self.set_burst((sum, n));
                self.flags = before;
                Err(e)
            }
        }
    }

    /// The sample as the clipping policy uses it (the sample itself with the policy off):
    /// a gyroscope reading beyond its range clipped just under it, an accelerometer
    /// reading beyond its range left out; and whether the gyroscope, or any reading, was.
    fn clipped(&self, s: &Sample) -> (Sample, bool, bool) {
        if !(self.recover() && self.saturated(s)) {
            return (*s, false, false);
        }
        let gyro_saturated = beyond(s.gyro, self.common.gyro_limit(), MAX_GYRO);
        let accel_saturated = beyond(s.accel, self.common.accel_limit(), MAX_ACCEL);
        let sample = Sample {
            gyro: s.gyro.map(|g| if gyro_saturated { clip(g, self.common.gyro_limit()) } else { g }),
            accel: if accel_saturated { None } else { s.accel },
            ..*s
        };
        (sample, gyro_saturated, true)
    }

    /// True when the sample has a reading this policy clips.
    #[inline]
    pub(crate) fn saturated<S: SampleView>(&self, s: &S) -> bool {
        beyond(s.gyro(), self.common.gyro_limit(), MAX_GYRO)
            || beyond(s.accel(), self.common.accel_limit(), MAX_ACCEL)
    }

    #[cold]
    #[inline(never)]
    pub(crate) fn update_saturated<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        let gyro_saturated = beyond(s.gyro(), self.common.gyro_limit(), MAX_GYRO);
        let accel_saturated = beyond(s.accel(), self.common.accel_limit(), MAX_ACCEL);
        let clipped = Sample {
            dt: s.dt(),
            gyro: s.gyro().map(|g| if gyro_saturated { clip(g, self.common.gyro_limit()) } else { g }),
            // A clipped accelerometer reading points the wrong way: left out.
            accel: if accel_saturated { None } else { s.accel() },
            mag: s.mag(),
        };
        // No re-acquisition while saturated: the pending one waits for a clean sample.
        let before = self.flags;
        let pending = self.flags & flags::REACQUIRE_PENDING;
        self.flags &= !flags::REACQUIRE_PENDING;
        match self.update_inline(&clipped) {
            Ok(()) => {
                let recover = if gyro_saturated { flags::REACQUIRE_PENDING } else { pending };
                if self.flags & flags::INITIALIZED != 0 {
                    self.flags |= flags::SATURATED | recover;
                }
                Ok(())
            }
            Err(e) => {
                self.flags = before;
                Err(e)
            }
        }
    }
}
