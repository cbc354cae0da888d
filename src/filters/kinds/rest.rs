//! Rest detection shared by the filters that learn the gyroscope bias at rest.
//!
//! The sensor rests when, for `time` seconds (and at least the tilt test's window, below),
//! the gyroscope and accelerometer stay within `gyro` and `accel` of their own
//! low-passed values (time constant `tau`), the low-passed gyroscope is itself below
//! `gyro` (a bias is smaller than that), and the accelerometer's direction stays within
//! `tilt` of where the still period began. The last test keeps a slow turn, whose rate is
//! below a bias's size, from being taken for rest: at rest gravity keeps its direction in
//! the sensor frame.
//!
//! The tilt test looks at the still period's own readings only. When a period begins,
//! the accelerometer's low-pass starts over from that sample as the mean of the
//! period's readings (a low-pass, time constant `tau`, once the period is that long; a
//! single still sample amid motion thus restarts it, from a reading within `accel` of
//! it); the reference direction is that mean after the tilt test's window (`tau / 2`, or
//! `time / 6` when shorter: [`RestThresholds::tilt_window`]), and from then on it is
//! compared with a second such mean of the period that becomes a low-pass of that window. A
//! low-pass that carried the motion before the pause would keep moving while it settled
//! (by up to the `accel` bound, about 3°, at the first still sample), leave the `tilt`
//! bound and start the period over: at the still start of a simulated glove, rest came
//! after 2.9 s instead of 1.5 s. The shorter low-pass follows a slow turn with less lag
//! than the `tau` one did, so a turn is found sooner as well (a day of turning at
//! 1.15°/s, `tests/long_run.rs`: the robust kind's worst inclination 0.87° → 0.63°).

use crate::filters::state::Codec;
use crate::math::Vec3;

/// The gain of a first-order low-pass for one step of `dt` with time constant `tau`:
/// `dt / (tau + dt)` (backward Euler, stable for any dt, no transcendental).
#[inline]
pub(crate) fn lp_gain(dt: f64, tau: f64) -> f64 {
    dt / (tau + dt)
}

/// The thresholds of [`RestDetector`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RestThresholds {
    /// rad/s.
    pub gyro: f64,
    /// m/s².
    pub accel: f64,
    /// rad.
    pub tilt: f64,
    /// s.
    pub time: f64,
    /// Low-pass time constant (s).
    pub tau: f64,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct RestDetector {
    primed: bool,
    gyro_lp: Vec3,
    acc_lp: Vec3,
    /// The mean of the current still period's accelerometer readings over the tilt test's
    /// window (until the period is that long, the previous period's).
    acc_ref: Vec3,
    /// The current still period's accelerometer readings: their mean, a low-pass with the
    /// tilt test's window as time constant once the period is that long; compared with
    /// `acc_ref`.
    acc_still: Vec3,
    /// How long the conditions have held (s).
    clock: f64,
    rest: bool,
}

impl RestDetector {
    /// Values an update could leave (see `filters::holds`).
    pub(crate) fn valid(&self) -> bool {
        use crate::filters::state::holds;
        holds::rate(self.gyro_lp)
            && holds::accel(self.acc_lp)
            && holds::accel(self.acc_ref)
            && holds::accel(self.acc_still)
            && self.clock >= 0.0
    }

    /// True when the sensor counts as resting after this sample. Without an
    /// accelerometer reading rest cannot be told, and the period starts over.
    pub fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, th: &RestThresholds) -> bool {
        self.update_with_bias(dt, gyro, Vec3::ZERO, accel, th)
    }

    /// [`RestDetector::update`] for a filter that knows a bias estimate: the low-passed
    /// gyroscope must be below `th.gyro` itself *or* within `th.gyro` of `bias`, so a bias
    /// larger than the threshold that the filter tracks (a drifting one) still lets rest
    /// be found. With a zero bias this is `update`, bit for bit.
    #[inline(always)]
    pub fn update_with_bias(
        &mut self,
        dt: f64,
        gyro: Vec3,
        bias: Vec3,
        accel: Option<Vec3>,
        th: &RestThresholds,
    ) -> bool {
        let Some(a) = accel else {
            self.clock = 0.0;
            self.rest = false;
            return false;
        };
        if !self.primed {
            self.gyro_lp = gyro;
            self.acc_lp = a;
            self.primed = true;
        }
        let k = lp_gain(dt, th.tau);
        self.gyro_lp = self.gyro_lp + (gyro - self.gyro_lp) * k;
        let acc_lp = self.acc_lp + (a - self.acc_lp) * k;
        let th_g = th.gyro * th.gyro;
        let still = (gyro - self.gyro_lp).norm_squared() < th_g
            && self.gyro_lp.norm_squared().min((self.gyro_lp - bias).norm_squared()) < th_g
            && (a - acc_lp).norm_squared() < th.accel * th.accel;
        if !still {
            self.acc_lp = acc_lp;
            self.clock = 0.0;
            self.rest = false;
            return false;
        }
        // The period's length with this sample, and its readings' means (module
        // documentation): each a mean while the period is shorter than its time constant,
        // τ for `acc_lp` and the tilt window for `acc_still`.
        let t = self.clock + dt;
        let half = th.tilt_window();
        if self.clock == 0.0 {
            self.acc_lp = a;
            self.acc_still = a;
        } else {
            self.acc_lp = self.acc_lp + (a - self.acc_lp) * (dt / t).max(k);
            self.acc_still = self.acc_still + (a - self.acc_still) * (dt / t).max(lp_gain(dt, half));
        }
        if self.clock < half && t >= half {
            self.acc_ref = self.acc_lp;
        }
        if t >= half {
            let (u, v) = (self.acc_still, self.acc_ref);
            let level = u.cross(v).norm() / (u.norm() * v.norm()).max(1e-300) < th.tilt;
            if !level {
                self.clock = 0.0;
                self.rest = false;
                return false;
            }
        }
        self.clock = t;
        // Not before the tilt test has run (a rest time of 0 is shorter than its window).
        self.rest = t >= th.time.max(half);
        self.rest
    }

    pub fn at_rest(&self) -> bool {
        self.rest
    }

    /// The low-passed gyroscope: at rest, the bias.
    pub fn gyro_lp(&self) -> Vec3 {
        self.gyro_lp
    }

    pub fn codec(&mut self, c: &mut dyn Codec) {
        c.bool(&mut self.primed);
        c.vec3(&mut self.gyro_lp);
        c.vec3(&mut self.acc_lp);
        c.vec3(&mut self.acc_ref);
        c.vec3(&mut self.acc_still);
        c.f64(&mut self.clock);
        c.bool(&mut self.rest);
    }
}

impl RestThresholds {
    /// The tilt test's window (s): `tau / 2`, or `time / 6` when shorter, so that the test
    /// has run for most of the rest time before rest is declared (a longer window lags a
    /// slow turn by more); `tau / 2` when `time` is 0.
    pub fn tilt_window(&self) -> f64 {
        let w = 0.5 * self.tau;
        if self.time > 0.0 {
            w.min(self.time / 6.0)
        } else {
            w
        }
    }

    /// Thresholds for consumer MEMS sensors held in the hand or worn: 2 °/s, 0.5 m/s²,
    /// 0.5° of tilt, 1.5 s, 0.5 s low-pass (the robust kind's defaults).
    pub const DEFAULT: RestThresholds = RestThresholds {
        gyro: 0.03490658503988659,
        accel: 0.5,
        tilt: 0.008726646259971648,
        time: 1.5,
        tau: 0.5,
    };
}

/// Rest detection with [`RestThresholds::DEFAULT`] feeding a gyroscope bias: the option
/// that gives the seed filters bias estimation at rest.
#[derive(Clone, Debug, Default)]
pub struct RestBias {
    /// The detector, boxed: the option is off by default, and a filter without it keeps
    /// 8 bytes here instead of the detector's 112. `None` is a detector that has seen no
    /// sample. The box is made when the option is switched on ([`RestBias::prepare`]),
    /// never in an update.
    detector: Option<Box<RestDetector>>,
}

/// Equal when the detectors are: no box is a fresh detector.
impl PartialEq for RestBias {
    fn eq(&self, other: &RestBias) -> bool {
        let fresh = RestDetector::default();
        self.detector.as_deref().unwrap_or(&fresh) == other.detector.as_deref().unwrap_or(&fresh)
    }
}

impl RestBias {
    /// Makes the detector's box when the option is on, so that no update allocates.
    pub fn prepare(&mut self, on: bool) {
        if on && self.detector.is_none() {
            self.detector = Some(Box::default());
        }
    }

    /// The bias after this sample and the detector state that goes with it: at rest the
    /// bias moves towards the low-passed gyroscope with time constant `tau` (s);
    /// otherwise it is returned unchanged. Nothing is stored: [`RestBias::commit`] keeps
    /// the detector once the filter's step has succeeded.
    pub fn update(
        &self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        tau: f64,
        bias: Vec3,
    ) -> (RestDetector, Vec3) {
        let mut detector = self.detector.as_deref().cloned().unwrap_or_default();
        let bias = if detector.update(dt, gyro, accel, &RestThresholds::DEFAULT) {
            bias + (detector.gyro_lp() - bias) * lp_gain(dt, tau)
        } else {
            bias
        };
        (detector, bias)
    }

    /// Keeps the detector state of a successful step.
    pub fn commit(&mut self, detector: RestDetector) {
        match &mut self.detector {
            Some(d) => **d = detector,
            // Only when prepare() was not called for an option that is on.
            None => self.detector = Some(Box::new(detector)),
        }
    }

    /// Starts detection over (the box is kept).
    pub fn restart(&mut self) {
        if let Some(d) = &mut self.detector {
            **d = RestDetector::default();
        }
    }

    pub fn at_rest(&self) -> bool {
        self.detector.as_ref().is_some_and(|d| d.at_rest())
    }

    pub(crate) fn valid(&self) -> bool {
        self.detector.as_ref().map_or(true, |d| d.valid())
    }

    /// The detector's fields (a fresh detector's when there is none).
    pub fn codec(&mut self, c: &mut dyn Codec) {
        let mut d = self.detector.as_deref().cloned().unwrap_or_default();
        d.codec(c);
        if self.detector.is_some() || d != RestDetector::default() {
            self.commit(d);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filters::params::id;
    use crate::{Config, Filter, Kind, Sample};

    /// Heading drift (rad) after 60 s at rest with a 0.01 rad/s bias about the vertical.
    fn drift(kind: Kind, option: Option<(u32, f64)>) -> f64 {
        let mut c = Config::new(kind).unwrap();
        if let Some((slot, v)) = option {
            c.set_param(slot, v).unwrap();
        }
        let mut f = Filter::new(&c).unwrap();
        let s = Sample {
            dt: 0.01,
            gyro: Some(Vec3::new(0.0, 0.0, 0.01)),
            accel: Some(Vec3::new(0.0, 0.0, 9.81)),
            mag: None,
        };
        f.update(&s).unwrap();
        let q0 = f.quaternion();
        for _ in 0..6000 {
            f.update(&s).unwrap();
        }
        f.quaternion().angle_to(q0)
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn the_seed_options_stop_heading_drift_at_rest() {
        for (kind, slot, value) in [
            (Kind::Madgwick, id::MADGWICK_REST_BIAS_TAU, 2.0),
            (Kind::Mahony, id::MAHONY_REST_BIAS_TAU, 2.0),
            (Kind::Ekf, id::EKF_REST_RATE_STD, 0.01),
        ] {
            let off = drift(kind, None);
            let on = drift(kind, Some((slot, value)));
            // Off: the bias integrates (0.6 rad in 60 s, less where the filter itself
            // learns some of it). On: rest is found after 1.5 s and the bias learned.
            assert!(off > 0.1 && on < 0.05, "{kind:?}: off {off}, on {on}");
        }
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn no_rest_while_moving_or_without_an_accelerometer() {
        let th = RestThresholds::DEFAULT;
        let mut d = RestDetector::default();
        let up = Vec3::new(0.0, 0.0, 9.81);
        for _ in 0..200 {
            d.update(0.01, Vec3::ZERO, Some(up), &th);
        }
        assert!(d.at_rest());
        // Shaking: the accelerometer leaves its low-pass.
        assert!(!d.update(0.01, Vec3::ZERO, Some(up * 1.2), &th));
        // Resting again needs the full rest time: 150 samples of 10 ms.
        for i in 1..=200 {
            let r = d.update(0.01, Vec3::ZERO, Some(up), &th);
            assert_eq!(r, i >= 150, "sample {i}");
        }
        assert!(!d.update(0.01, Vec3::ZERO, None, &th));
    }

    /// The sample at which `d` first reports rest, of `n` made by `sample`.
    fn first_rest(
        d: &mut RestDetector,
        n: usize,
        mut sample: impl FnMut(usize) -> (Vec3, Vec3),
    ) -> Option<usize> {
        let th = RestThresholds::DEFAULT;
        (0..n).find(|&i| {
            let (gyro, accel) = sample(i);
            d.update(1.0 / 60.0, gyro, Some(accel), &th)
        })
    }

    /// Rest comes `time` after the first still sample, both at a still start with a noisy
    /// accelerometer whose first reading is more than the tilt bound off the mean and in a
    /// pause after motion that leaves the accelerometer's low-pass beyond the tilt bound
    /// off gravity: the tilt test looks at the still period's own readings. (Against a
    /// reference from the low-pass at the first still sample, a simulated glove's still
    /// start was rest after 2.9 s.)
    #[test]
    fn rest_comes_rest_time_after_the_first_still_sample() {
        // 60 Hz: 1.5 s is sample 89 (the 90th), or the next when the sum of dt rounds low.
        let at_rest_time = |i: Option<usize>| matches!(i, Some(89 | 90));
        let angle = |a: Vec3, b: Vec3| libm::atan2(a.cross(b).norm(), a.dot(b));
        let g = Vec3::new(-1.4, 2.0, 9.6);
        let bias = Vec3::new(0.01, -0.005, 0.008);
        let mut u = crate::math::test_uniform(26);
        let readings: Vec<(Vec3, Vec3)> = (0..600)
            .map(|_| {
                let mut n = || 0.1 * u();
                (bias + Vec3::new(n(), n(), n()) * 0.03, g + Vec3::new(n(), n(), n()))
            })
            .collect();
        let mean = readings[..30].iter().fold(Vec3::ZERO, |m, r| m + r.1) * (1.0 / 30.0);
        let first_off = angle(readings[0].1, mean);
        assert!(first_off > RestThresholds::DEFAULT.tilt, "{}", first_off.to_degrees());
        let mut d = RestDetector::default();
        let start = first_rest(&mut d, readings.len(), |i| readings[i]);
        assert!(at_rest_time(start), "{start:?}");

        // Two seconds of a hand shaken sideways (±1.5 m/s², a square wave of 2 Hz: never
        // still), ending with the low-pass beyond the 0.5° tilt bound off gravity, then
        // still.
        let th = RestThresholds::DEFAULT;
        let mut d = RestDetector::default();
        for i in 0..120 {
            let shake = if (i / 15) % 2 == 0 { 1.5 } else { -1.5 };
            assert!(!d.update(1.0 / 60.0, bias, Some(g + Vec3::new(shake, 0.0, 0.0)), &th));
            // The detector starts from the first reading: still until the first reversal.
            assert!(d.clock == 0.0 || i < 15, "still at sample {i}");
        }
        let off = angle(d.acc_lp, g);
        assert!(off > 2.0 * th.tilt && (d.acc_lp - g).norm() < th.accel, "{}", off.to_degrees());
        let pause = first_rest(&mut d, 600, |_| (bias, g));
        assert!(at_rest_time(pause), "{pause:?}");
    }

    /// A rest time of 0 (the robust kind's `rest_time` 0) is rest once the tilt test's window,
    /// `tau / 2`, has passed, not at the first still sample.
    #[test]
    fn a_zero_rest_time_waits_for_the_tilt_window() {
        let th = RestThresholds { time: 0.0, ..RestThresholds::DEFAULT };
        assert_eq!(th.tilt_window(), 0.5 * th.tau);
        let mut d = RestDetector::default();
        let up = Vec3::new(0.0, 0.0, 9.81);
        let first = (0..100).find(|_| d.update(0.01, Vec3::ZERO, Some(up), &th));
        // 0.25 s at 100 Hz: sample 24 (the 25th), or the next when the sum of dt rounds low.
        assert!(matches!(first, Some(24 | 25)), "{first:?}");
    }

    /// A turn of 1.15 °/s, under the gyroscope threshold, is never rest, also with a
    /// low-pass time constant `tau` far longer than the rest time (the tilt window stays
    /// `time / 6`) or a rest time long enough for `tau / 2` to be the window.
    #[test]
    fn a_slow_turn_is_not_rest_whatever_the_windows() {
        let dt = 0.01;
        let w = Vec3::new(0.02, 0.0, 0.0);
        for (tau, time) in [(0.5, 1.5), (2.0, 1.5), (4.0, 1.5), (0.5, 6.0)] {
            let th = RestThresholds { tau, time, ..RestThresholds::DEFAULT };
            let mut d = RestDetector::default();
            for i in 0..6000 {
                let turned =
                    crate::math::Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.02 * dt * i as f64);
                let a = turned.rotate_inverse(Vec3::new(0.0, 0.0, 9.81));
                assert!(!d.update(dt, w, Some(a), &th), "tau {tau}, time {time}: rest at sample {i}");
            }
        }
    }
}
