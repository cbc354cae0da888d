//! The update, stage by stage, in the order a sample meets them:
//!
//! 1. [`Runner::update_outline`]: the usual step, when nothing but the kind's step is
//!    due (initialised, no policy, nothing pending, a sample the quick check passes);
//!    anything else goes, with nothing changed, to the general update.
//! 2. The host's policies ([`Runner::update_with_policies`]): same-instant bursts
//!    (`same_instant`), clipping and saturation recovery (`saturation_recovery`), the
//!    sensor models; each hands its sample on to the plain update.
//! 3. The checks: the quick check ([`Runner::usual`]) and, for a sample it turns down,
//!    the exact rules in the order that picks the reported error
//!    ([`Runner::check_exactly`]).
//! 4. The step: the kind's update, or the start, a gap's re-acquisition, the rest
//!    watch's look (`crate::filters::pipeline::watch`).
//!
//! The outputs are read from the state ([`Runner::output`]). On error nothing changes:
//! the state is bit-identical to before.

use super::*;
use crate::filters::pipeline::sample::MAX_ACCEL;
use crate::filters::pipeline::sample::MAX_GYRO;

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
    /// The quick test on the sample where it lies, the exact rules (on a copy) only when
    /// it fails.
    #[inline(always)]
    pub(crate) fn check_view<S: SampleView>(&self, s: &S) -> Result<(), Error> {
        if self.plainly_valid(s) {
            Ok(())
        } else {
            self.check_exactly(&s.to_sample())
        }
    }

    /// A conservative test that `check_exactly` would accept the sample (a gap fails it
    /// too): see [`Runner::usual`].
    #[inline(always)]
    pub(crate) fn plainly_valid<S: SampleView>(&self, s: &S) -> bool {
        self.usual(s).is_some()
    }

    /// The sample, when a conservative test finds that `check_exactly` would accept it and
    /// that it is no gap: each reading's squared norm is under the square of its sensor's
    /// range or physical bound (which bounds every component: `x² ≤ |v|²`, and rounding
    /// keeps that order; a NaN or ±∞ component makes the norm fail the test), the
    /// accelerometer's and magnetometer's are above 1e-300 (not zero, no underflow, and in
    /// `inv_sqrt`'s fast range, so that the usual update normalises them without a test);
    /// dt is in range and at most `gap_dt`; and a sample without an accelerometer reading
    /// comes after initialisation. A sample it turns down goes through the exact rules,
    /// which tell the reason (or accept it: a reading whose components are each under the
    /// range but whose norm is not, say), and tell a gap. The rule for a field that gives
    /// no heading ([`no_heading`]) is no rule of acceptance: the steps apply it
    /// ([`Usual::surely_gives_heading`], [`Checked::heading_units`]).
    #[inline(always)]
    pub(crate) fn usual<S: SampleView>(&self, s: &S) -> Option<Usual> {
        let (dt, gyro) = (s.dt(), s.gyro()?);
        // gap_dt ≤ MAX_DT, and MAX_DT when off: a gap fails here too.
        if !((MIN_DT..=self.common.gap_limit).contains(&dt) && gyro.norm_squared() < self.common.gyro_limit2)
        {
            return None;
        }
        let accel = match s.accel() {
            Some(a) => Some(Some(Checked::of(a)).filter(|a| a.within(self.common.accel_limit2))?),
            None if self.flags & flags::INITIALIZED != 0 => None,
            None => return None,
        };
        let mag = match s.mag() {
            Some(m) => Some(Some(Checked::of(m)).filter(|m| m.within(MAX_MAG * MAX_MAG))?),
            None => None,
        };
        Some(Usual { dt, gyro, accel, mag })
    }

    /// The rules one by one, in the order that picks the reported error. A configured
    /// range refuses a reading (Saturated) only without `saturation_recovery`: with it, a
    /// reading between the range and the physical bound is used clipped (the policies
    /// clip it before they check), and one at or beyond the bound is TooLarge, as the
    /// order's next rule says, for every kind, field and path (bursts included).
    #[cold]
    #[inline(never)]
    pub(crate) fn check_exactly(&self, s: &Sample) -> Result<(), Error> {
        let refuses =
            |range: Option<f64>, v: Vec3| !self.recover() && range.is_some_and(|r| v.max_abs() >= r);
        // No sensor samples faster than 1 GHz: a smaller dt (a subnormal one, say) is a
        // host bug, and would overflow noise variances that scale with 1/dt.
        if !(s.dt.is_finite() && (MIN_DT..=MAX_DT).contains(&s.dt)) {
            return Err(Error::InvalidDt(s.dt));
        }
        let gyro = s.gyro.ok_or(Error::MissingSensor(Field::Gyro))?;
        if !gyro.is_finite() {
            return Err(Error::NonFinite(Field::Gyro));
        }
        if refuses(self.common.gyro_range(self.bits), gyro) {
            return Err(Error::Saturated(Field::Gyro));
        }
        if gyro.max_abs() >= MAX_GYRO {
            return Err(Error::TooLarge(Field::Gyro));
        }
        if let Some(a) = s.accel {
            check_vector(a, Field::Accel)?;
            if refuses(self.common.accel_range(self.bits), a) {
                return Err(Error::Saturated(Field::Accel));
            }
            if a.max_abs() >= MAX_ACCEL {
                return Err(Error::TooLarge(Field::Accel));
            }
        }
        if let Some(m) = s.mag {
            check_vector(m, Field::Mag)?;
            if m.max_abs() >= MAX_MAG {
                return Err(Error::TooLarge(Field::Mag));
            }
        }
        if self.flags & flags::INITIALIZED == 0 && s.accel.is_none() {
            return Err(Error::NotInitialized);
        }
        Ok(())
    }

    /// One step, in a function of its own per kind and sample type. For a kind with a
    /// usual step of its own ([`Estimator::USUAL`]) the function's usual path calls
    /// nothing, so that it saves and restores no registers: initialised, no policy,
    /// nothing pending, a sample the quick check passes with no gap, and a step
    /// [`Estimator::update_usual`] takes. Anything else goes, with nothing changed yet, to
    /// [`Runner::update_general`] (a tail call), which gives the same result.
    #[inline(never)]
    pub(crate) fn update_outline<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        if !E::USUAL {
            return self.update_inline(s);
        }
        if let Some(u) = if self.usual_state() { self.usual(s) } else { None } {
            if let Some(flags) = self.core.update_usual(&u) {
                self.stepped(flags, u.accel.map(|a| a.v));
                return Ok(());
            }
        }
        // A sample the usual step declined (an edge case of the kind's arithmetic) meets
        // the quick check again on the general path. Handing the checked sample on
        // instead cost the usual path 6 to 13 instructions per update (callgrind: its
        // two out-of-line continuations made it save registers), for a case that is rare.
        self.update_general(s)
    }

    /// The state the usual step is for: initialised, nothing pending, no policy or kind
    /// option.
    #[inline(always)]
    fn usual_state(&self) -> bool {
        debug_assert_eq!(self.policy & Self::UNSETTLED == 0, self.settled());
        self.policy == 0
    }

    /// [`Runner::update_inline`] out of line: every case [`Runner::update_outline`] leaves.
    /// Marked cold although a rest-bias filter or a gyroscope-only sample takes it on every
    /// update: without the mark LLVM laid the usual path out worse (docs/PERFORMANCE.md).
    #[cold]
    #[inline(never)]
    fn update_general<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        self.update_inline(s)
    }

    /// What a successful step leaves besides the core's state: its `flags` and the
    /// accelerometer reading (the usual and lane steps, the general step, the start and
    /// the re-acquisition; the start and the re-acquisition then synchronise the state
    /// bits, which the others leave as they were).
    #[inline(always)]
    fn stepped(&mut self, flags: u32, accel: Option<Vec3>) {
        if let Some(a) = accel {
            self.last_accel = a;
            self.bits |= Self::HAS_ACCEL;
        }
        self.flags = flags;
        if self.watch.tick() {
            self.policy |= Self::WATCH;
        }
    }

    /// The rest watch's look ([`crate::filters::pipeline::watch`]) at an accepted sample (its `dt` and
    /// gyroscope reading, the accelerometer reading the step took): a re-acquisition
    /// left pending when the estimate has stayed off the accelerometer's vertical at
    /// rest. Taken by the sample after the count ran out ([`Runner::WATCH`]), on the
    /// policies' path, so that the usual step only counts.
    fn look(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>) {
        self.policy &= !Self::WATCH;
        let initialized = self.flags & flags::INITIALIZED != 0;
        let q = self.core.absolute_quaternion();
        let bias = self.diagnostics().gyro_bias;
        if self.watch.look(
            dt,
            gyro,
            accel.filter(|_| initialized),
            q,
            bias,
            E::NATIVE.up(),
            self.common.gravity,
        ) {
            self.flags |= flags::REACQUIRE_PENDING;
            self.sync_state();
        }
    }

    /// One step. On error nothing changes: the state is bit-identical to before.
    #[inline(always)]
    pub(crate) fn update_inline<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        // Issue 20's policies, out of line behind one test of the byte that says which
        // are on (the kind's option bit needs nothing here: the plain update takes the
        // kind's own update; nor does UNSETTLED: the plain update tests the flags
        // themselves). The rest watch's look takes this path too.
        if self.policy & !(Self::KIND_OPTION | Self::UNSETTLED) != 0 {
            return self.update_with_policies(s);
        }
        self.update_plain(s)
    }

    /// [`Runner::update_inline`] with a policy on: bursts, clipping, sensor models, each
    /// out of line, or the plain update when none applies to this sample.
    #[cold]
    #[inline(never)]
    fn update_with_policies<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        let result = if self.same_instant() && (s.dt() == 0.0 || self.burst().1 != 0) {
            self.update_same_instant(s)
        } else if self.recover() && self.saturated(s) {
            self.update_saturated(s)
        } else if self.policy & Self::MODELS != 0 {
            self.update_calibrated(s)
        } else {
            self.update_plain(s)
        };
        if result.is_ok() && self.policy & Self::WATCH != 0 {
            // The accelerometer reading as the step took it (a sensor model applied).
            let accel = s.accel().map(|_| self.last_accel);
            self.look(s.dt(), s.gyro().unwrap_or_default(), accel);
        }
        // The policies write the flags themselves (a clipped gyroscope reading leaves a
        // re-acquisition pending).
        self.sync_state();
        result
    }

    /// The update without the policies: the quick check, then the step; a sample the quick
    /// check turns down goes through the exact rules out of line.
    #[inline(always)]
    fn update_plain<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        // The readings read again where they lie rather than taken from the check's
        // decoding: up to 8 fewer instructions per update (callgrind, IMU / MARG: robust
        // 3.9 / 8.0, GMVDK 0 / 2.0, EKF 0 / 3.1; the decoded copy costs registers across
        // their steps). Each kind normalises the readings it uses once, in its step.
        match (self.usual(s).is_some_and(|u| u.surely_gives_heading()), s.gyro()) {
            // No field, or one that surely gives a heading.
            (true, Some(gyro)) => self.update_step(s.dt(), gyro, s.accel(), s.mag()),
            _ => self.update_plain_slowly(s),
        }
    }

    /// [`Runner::update_plain`] for a sample the quick check turned down, or whose field
    /// may give no heading: the exact rules, then the step with the rule applied.
    #[cold]
    #[inline(never)]
    fn update_plain_slowly<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        self.check_exactly(&s.to_sample())?;
        // check_exactly guarantees a gyro reading.
        self.update_checked(s.dt(), s.gyro().unwrap_or_default(), s.accel(), s.mag())
    }

    /// The step of a sample that passed the checks. A magnetometer reading that gives no
    /// heading ([`no_heading`]: parallel to gravity) is left out, for every kind and
    /// every stage: the step is the IMU update, with [`flags::MAG_REJECTED`].
    #[inline(always)]
    fn update_checked(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        mag: Option<Vec3>,
    ) -> Result<(), Error> {
        if let (Some(a), Some(m)) = (accel, mag) {
            if no_heading(a, m) {
                return self.update_without_heading(dt, gyro, a);
            }
        }
        self.update_step(dt, gyro, accel, mag)
    }

    /// [`Runner::update_checked`] for a sample whose field gives no heading: the step
    /// without it, the reading flagged as not used.
    #[cold]
    #[inline(never)]
    fn update_without_heading(&mut self, dt: f64, gyro: Vec3, accel: Vec3) -> Result<(), Error> {
        self.update_step(dt, gyro, Some(accel), None)?;
        self.flags |= flags::MAG_REJECTED;
        Ok(())
    }

    /// The step of a sample that passed the checks, with no field or one that gives a
    /// heading ([`Runner::update_checked`] applied the rule, or
    /// [`Usual::surely_gives_heading`] found it).
    #[inline(always)]
    fn update_step(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        mag: Option<Vec3>,
    ) -> Result<(), Error> {
        let gap = dt > self.common.gap_limit;
        // The usual step: initialised, nothing pending, no gap.
        if self.settled() & !gap {
            return match self.core.update(dt, gyro, accel, mag) {
                Some(step) => {
                    self.stepped(step.flags(accel.is_some(), mag.is_some()), accel);
                    Ok(())
                }
                None => Err(Error::Numeric),
            };
        }
        self.update_unusual(dt, gyro, accel, mag, gap)
    }

    /// The plain update before initialisation, after a gap or with a re-acquisition
    /// pending.
    #[cold]
    #[inline(never)]
    fn update_unusual(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        mag: Option<Vec3>,
        gap: bool,
    ) -> Result<(), Error> {
        let pending = self.flags & flags::REACQUIRE_PENDING;
        if self.flags & flags::INITIALIZED != 0 && (gap || pending != 0) {
            match accel {
                Some(accel) => return self.reacquire(dt, gyro, accel, mag, gap),
                None if gap => {
                    // Nothing to re-acquire from: hold the orientation until a sample
                    // with an accelerometer reading.
                    self.flags = flags::INITIALIZED | flags::GAP | flags::REACQUIRE_PENDING;
                    self.sync_state();
                    return Ok(());
                }
                // Gyroscope only while pending: integrate as usual, still pending.
                None => {}
            }
        }
        if self.flags & flags::INITIALIZED == 0 {
            return self.start(dt, gyro, accel, mag, gap);
        }
        let dt = if gap { self.common.gap_limit } else { dt };
        match self.core.update(dt, gyro, accel, mag) {
            Some(step) => {
                let gap_flag = if gap { flags::GAP } else { 0 };
                self.stepped(step.flags(accel.is_some(), mag.is_some()) | gap_flag | pending, accel);
                Ok(())
            }
            None => Err(Error::Numeric),
        }
    }

    /// An update before the filter has an orientation: from this sample's accelerometer
    /// (and magnetometer), or a step of the kind's own start-up period. Out of line: it
    /// runs once (or for a start-up period's samples).
    #[cold]
    #[inline(never)]
    fn start(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        mag: Option<Vec3>,
        gap: bool,
    ) -> Result<(), Error> {
        let saved = if E::OWN_STARTUP {
            None
        } else {
            // check() guarantees an accelerometer reading here.
            let a = accel.unwrap_or_default();
            let frame = self.frame;
            let q =
                frame.attitude_from(a, mag).or_else(|| frame.attitude_from(a, None)).ok_or(Error::Numeric)?;
            // Before initialisation the core is as `restart` leaves it (new, reset, or a
            // snapshot of either): a failure restarts it rather than restoring a clone,
            // which would allocate where a kind keeps boxed state.
            let saved = self.flags;
            self.set_frame_quaternion(q);
            Some(saved)
        };
        // An own start-up's still period is broken by a gap: it starts over with this
        // sample, counted as gap_dt. Not again at the gap after a gap: where every sample
        // is one (gap_dt below the sample period) the period would never end; the
        // period's stillness test still starts it over when the readings move.
        if gap && saved.is_none() && self.flags & flags::GAP == 0 {
            self.core.restart(*self.core.settings());
        }
        let dt = if gap { self.common.gap_limit } else { dt };
        match self.core.update(dt, gyro, accel, mag) {
            Some(step) => {
                // A start-up sample's readings go into the period's means: its flags say
                // which, with INITIALIZED still clear.
                let gap_flag = if gap { flags::GAP } else { 0 };
                let flags = if step.initializing {
                    (step.flags(accel.is_some(), mag.is_some()) & !flags::INITIALIZED) | gap_flag
                } else {
                    step.flags(accel.is_some(), mag.is_some()) | gap_flag
                };
                self.stepped(flags, accel);
                self.sync_state();
                Ok(())
            }
            None => {
                if let Some(flags) = saved {
                    self.core.restart(*self.core.settings());
                    self.flags = flags;
                    self.sync_state();
                }
                Err(Error::Numeric)
            }
        }
    }

    /// Re-acquisition after a gap (see [`flags::REACQUIRED`]): inclination from this
    /// accelerometer reading; heading from the magnetometer when the sample has one that
    /// defines north (and the kind accepts it), else the heading held before the gap.
    #[cold]
    #[inline(never)]
    fn reacquire(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Vec3,
        mag: Option<Vec3>,
        gap: bool,
    ) -> Result<(), Error> {
        let native = E::NATIVE;
        let tilt = native.attitude_from(accel, None).ok_or(Error::Numeric)?;
        // The rotation about the vertical that brings the tilt nearest to the old
        // orientation: that orientation's heading on the new inclination.
        let before = self.core.absolute_quaternion();
        let keep = (twist_about(before * tilt.conj(), native.up()) * tilt).normalized();
        let with_mag = mag.and_then(|m| native.attitude_from(accel, Some(m)));
        let still = self.watch.still(gyro);
        let r = Reacquisition { keep, with_mag, dt, gyro, accel, mag, still };
        let used_mag = self.core.reacquire(&r);
        self.watch.restart();
        let flags = flags::INITIALIZED
            | flags::ACCEL_USED
            | flags::REACQUIRED
            | match (used_mag, mag.is_some()) {
                (true, _) => flags::MAG_USED,
                (false, true) => flags::MAG_REJECTED,
                (false, false) => 0,
            }
            | if gap { flags::GAP } else { 0 };
        self.stepped(flags, Some(accel));
        self.sync_state();
        Ok(())
    }

    /// The sample when the lanes of [`crate::filters::pipeline::filter::Filter::update_group`] may take this filter's
    /// step with it: the conditions of [`Runner::update_outline`]'s usual step
    /// (initialised, nothing pending, no policy or kind option, a sample the quick check
    /// passes with no gap), and an accelerometer reading.
    #[inline(always)]
    pub(crate) fn lane_usual<S: SampleView>(&self, s: &S) -> Option<Usual> {
        if !self.usual_state() {
            return None;
        }
        self.usual(s).filter(|u| u.accel.is_some() && u.surely_gives_heading())
    }

    /// What a lane step with the sample `u` leaves besides the core's state.
    pub(crate) fn lane_done(&mut self, u: &Usual, step: Step) {
        self.stepped(step.flags(true, u.mag.is_some()), u.accel.map(|a| a.v));
    }

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
    /// reading beyond its range left out (a clipped one points the wrong way); and
    /// whether the gyroscope, or any reading, was.
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
        let (clipped, gyro_saturated, _) = self.clipped(&s.to_sample());
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

    /// The update with the sensor models applied: the raw sample is checked (its ranges
    /// and physical bounds), then the calibrated one goes through the usual update, which
    /// checks it against the physical bounds only. The configured ranges are the raw
    /// sensor's full scale: a calibrated reading past one is no saturation, and a model
    /// whose offset moves a still sensor's reading past a small range would otherwise
    /// have every sample refused (the fuzz target found one: a gyroscope range of 0.25
    /// rad/s and an offset of 0.254).
    #[inline(never)]
    pub(crate) fn update_calibrated<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        self.check_view(s)?;
        let models = self.models();
        let calibrated = models.apply(s);
        // The calibrated sample takes the plain path (the models are not applied twice)
        // without the ranges.
        if let Some(x) = &mut self.extras.0 {
            x.models = Models::default();
        }
        self.refresh_models();
        let (common, ranges) = (self.common, self.bits & (Common::GYRO_SET | Common::ACCEL_SET));
        self.common = self.common.without_ranges();
        self.bits &= !ranges;
        let result = self.update_inline(&calibrated);
        self.common = common;
        self.bits |= ranges;
        if let Some(x) = &mut self.extras.0 {
            x.models = models;
        }
        self.refresh_models();
        result
    }
}
