//! The common lifecycle, generic over the kind: [`Runner<E>`] holds exactly one kind's
//! state `E` and a head of a few words (flags, the common settings, the last
//! accelerometer reading, the output frame), and does for every kind what is not in a
//! paper: the checks, the start from the first sample, gaps, frames, flags, snapshots and
//! the outputs. [`crate::filters::pipeline::filter::Filter`] holds one `Runner` of its kind.

use crate::filters::calibration::{self, Models};
use crate::filters::config::Config;
use crate::filters::config::Init;
use crate::filters::diagnostics::Diagnostics;
use crate::filters::error::Error;
use crate::filters::error::Field;
use crate::filters::flags;
use crate::filters::kind::Kind;
use crate::filters::params::{id, Settings, MAX_PARAMS};
use crate::filters::pipeline::estimator::{twist_about, Estimator, Reacquisition, Step};
use crate::filters::pipeline::host::Host;
use crate::filters::pipeline::sample::Sample;
use crate::filters::pipeline::sample::MAX_ACCEL;
use crate::filters::pipeline::sample::MAX_DT;
use crate::filters::pipeline::sample::MAX_GYRO;
use crate::filters::pipeline::sample::MAX_MAG;
use crate::filters::pipeline::sample::MIN_DT;
use crate::filters::pipeline::sample::{check_quaternion, check_vector, Checked, SampleView, Usual};
use crate::filters::pipeline::watch::Watch;
use crate::filters::state::holds;
use crate::filters::state::{self, Codec, Reader, StateError, Writer};
use crate::math::frame::no_heading;
use crate::math::{Frame, Quat, Vec3};

mod update;

/// The common settings (slots 0-3) and the sample limits the checks compare with, kept
/// ready for each update: a range of zero (none set) is the physical bound here, and a
/// gap dt of zero [`MAX_DT`], so that each test is one comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Common {
    pub gravity: f64,
    /// The square of the gyroscope's full-scale range, or of [`MAX_GYRO`] when none is
    /// set ((rad/s)²): the quick check compares squared norms with it.
    gyro_limit2: f64,
    /// The square of the accelerometer's full-scale range, or of [`MAX_ACCEL`] when none
    /// is set ((m/s²)²).
    accel_limit2: f64,
    /// dt above which a step is a gap, or [`MAX_DT`] when the policy is off (s): no
    /// accepted dt is larger, so that the quick check's one bound covers both.
    pub gap_limit: f64,
}

impl Common {
    const GYRO_SET: u16 = 1;
    const ACCEL_SET: u16 = 2;
    /// `gap_dt` is set (not 0).
    const GAP_SET: u16 = 32;
    /// The bits of [`Runner::bits`] that `from_slots` sets.
    const RANGE_BITS: u16 = Common::GYRO_SET | Common::ACCEL_SET | Common::GAP_SET;

    /// The common settings, and which of the ranges and the gap dt are set
    /// ([`Common::GYRO_SET`], [`Common::ACCEL_SET`]: a range equal to the physical bound is
    /// a saturation, not a bound; [`Common::GAP_SET`]).
    fn from_slots(s: &[f64; MAX_PARAMS]) -> (Common, u16) {
        let (gyro, accel, gap) =
            (s[id::GYRO_RANGE as usize], s[id::ACCEL_RANGE as usize], s[id::GAP_DT as usize]);
        let gyro_limit = if gyro > 0.0 { gyro.min(MAX_GYRO) } else { MAX_GYRO };
        let accel_limit = if accel > 0.0 { accel.min(MAX_ACCEL) } else { MAX_ACCEL };
        let common = Common {
            gravity: s[id::GRAVITY as usize],
            gyro_limit2: gyro_limit * gyro_limit,
            accel_limit2: accel_limit * accel_limit,
            gap_limit: if gap > 0.0 { gap.min(MAX_DT) } else { MAX_DT },
        };
        debug_assert!(common.gyro_limit() == gyro_limit && common.accel_limit() == accel_limit);
        let set = if gyro > 0.0 { Common::GYRO_SET } else { 0 }
            | if accel > 0.0 { Common::ACCEL_SET } else { 0 }
            | if gap > 0.0 { Common::GAP_SET } else { 0 };
        (common, set)
    }

    /// These settings with no range set: the limits are the physical bounds.
    pub(crate) fn without_ranges(self) -> Common {
        Common { gyro_limit2: MAX_GYRO * MAX_GYRO, accel_limit2: MAX_ACCEL * MAX_ACCEL, ..self }
    }

    /// The gyroscope's limit (rad/s): the root of its square is the limit itself, as in
    /// binary floating point `√(x²)` rounds back to `x` when `x²` neither overflows nor
    /// underflows (the ranges are 0.1 to 1e4 and 1 to 1e5; `from_slots` checks it in
    /// debug builds).
    pub fn gyro_limit(&self) -> f64 {
        self.gyro_limit2.sqrt()
    }

    /// The accelerometer's limit (m/s²), as [`Common::gyro_limit`].
    pub fn accel_limit(&self) -> f64 {
        self.accel_limit2.sqrt()
    }

    fn write_slots(&self, set: u16, s: &mut [f64; MAX_PARAMS]) {
        s[id::GRAVITY as usize] = self.gravity;
        s[id::GYRO_RANGE as usize] = if set & Common::GYRO_SET != 0 { self.gyro_limit() } else { 0.0 };
        s[id::ACCEL_RANGE as usize] = if set & Common::ACCEL_SET != 0 { self.accel_limit() } else { 0.0 };
        s[id::GAP_DT as usize] = if set & Common::GAP_SET != 0 { self.gap_limit } else { 0.0 };
    }

    fn gyro_range(&self, set: u16) -> Option<f64> {
        (set & Common::GYRO_SET != 0).then(|| self.gyro_limit())
    }

    fn accel_range(&self, set: u16) -> Option<f64> {
        (set & Common::ACCEL_SET != 0).then(|| self.accel_limit())
    }
}

/// One filter of kind `E`: its state and the common head.
#[derive(Clone, Debug)]
pub(crate) struct Runner<E: Estimator> {
    pub(crate) core: E,
    pub(crate) flags: u32,
    frame: Frame,
    /// Which sensor ranges and gap dt are set ([`Common::GYRO_SET`],
    /// [`Common::ACCEL_SET`], [`Common::GAP_SET`], see [`Common::from_slots`]),
    /// [`Runner::HAS_ACCEL`], [`Runner::RELATIVE`], [`Runner::IDENTITY_INIT`],
    /// [`Runner::HOSTED`], [`Runner::UNINIT`] and [`Runner::REFRAME`]: two bytes, so that
    /// the head stays a few words.
    bits: u16,
    /// Issue 20's policies that are on ([`Runner::RECOVER`], [`Runner::SAME_INSTANT`],
    /// [`Runner::MODELS`]), [`Runner::KIND_OPTION`] (the kind's settings keep it from
    /// its usual step) and [`Runner::UNSETTLED`]: the usual update tests this byte alone.
    policy: u8,
    pub(crate) common: Common,
    pub(crate) last_accel: Vec3,
    /// The configured initial orientation when it is [`Init::Given`] (kept for reset);
    /// boxed, since few filters have one.
    given: Option<Box<Quat>>,
    /// The host's frames, sensor models and burst readings (issue 20), boxed and made
    /// when first set (or when `same_instant` is switched on), never in an update: a
    /// filter without them carries 8 bytes here.
    pub(crate) extras: ExtrasBox,
    /// The rest watch ([`crate::filters::pipeline::watch`]).
    watch: Watch,
}

/// Field by field, except that [`Runner::HOSTED`] is left out: it says whether the
/// extras' box is made, and [`ExtrasBox`]'s equality already takes no box for a plain one.
impl<E: Estimator> PartialEq for Runner<E> {
    fn eq(&self, o: &Runner<E>) -> bool {
        let Runner { core, flags, frame, bits, policy, common, last_accel, given, extras, watch } = self;
        let kept = !Self::HOSTED;
        *core == o.core
            && *flags == o.flags
            && *frame == o.frame
            && bits & kept == o.bits & kept
            && *policy == o.policy
            && *common == o.common
            && *last_accel == o.last_accel
            && *given == o.given
            && *extras == o.extras
            && *watch == o.watch
    }
}

/// The extras' box; equal when what they hold is, with no box equal to a plain one.
#[derive(Clone, Debug, Default)]
pub(crate) struct ExtrasBox(pub Option<Box<Extras>>);

impl PartialEq for ExtrasBox {
    fn eq(&self, other: &ExtrasBox) -> bool {
        let plain = Extras::default();
        let a = self.0.as_deref().unwrap_or(&plain);
        let b = other.0.as_deref().unwrap_or(&plain);
        (a.is_plain() && b.is_plain()) || a == b
    }
}

/// What a filter has around its kind when a host sets it: mounting, heading offset and
/// declination ([`crate::filters::pipeline::host`]), sensor models ([`crate::filters::calibration`]), and the
/// gyroscope readings of dt = 0 samples waiting for the next step (sum, count;
/// [`crate::filters::pipeline::saturation`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Extras {
    pub host: Host,
    pub models: Models,
    pub burst: (Vec3, u32),
}

impl<E: Estimator> Runner<E> {
    /// `last_accel` holds a reading.
    const HAS_ACCEL: u16 = 4;
    /// GMVDK's relative output is on: no frame rotation applies.
    const RELATIVE: u16 = 8;
    /// The configured initial orientation is [`Init::Identity`].
    const IDENTITY_INIT: u16 = 16;
    /// The extras' box is made: the output goes through the host's frames. Kept beside
    /// [`Runner::RELATIVE`] so that the read tests both with one instruction.
    const HOSTED: u16 = 64;
    /// The filter has no orientation yet ([`flags::INITIALIZED`] clear), kept beside
    /// [`Runner::RELATIVE`] and [`Runner::HOSTED`] so that the read tests all three with
    /// one instruction. [`Runner::sync_state`] sets it wherever `INITIALIZED` may change;
    /// the usual step and the lane step find it clear and leave it so.
    const UNINIT: u16 = 128;
    /// The configured frame is not the kind's native frame: the read rotates the
    /// estimate ([`Frame::express`]). Set where the frame is, in [`Runner::new`] (a
    /// snapshot's frame is loaded by making a new runner), beside the read's other bits so
    /// that a kind whose native frame is the default one, East-North-Up, reads it with one
    /// test in the default configuration ([`Runner::output`]).
    const REFRAME: u16 = 256;
    /// Whether this kind's native frame is the default configured frame (East-North-Up,
    /// [`Config::new`]).
    const NATIVE_IS_DEFAULT: bool = matches!(E::NATIVE, Frame::Enu);
    /// `saturation_recovery`: readings beyond the ranges are clipped and recovered from.
    const RECOVER: u8 = 1;
    /// `same_instant`: dt = 0 is the same instant as the next step.
    const SAME_INSTANT: u8 = 2;
    /// Sensor models are set (in the extras).
    const MODELS: u8 = 4;
    /// The kind's settings keep it from its usual step ([`Estimator::usual_settings`]).
    const KIND_OPTION: u8 = 8;
    /// No orientation yet or a re-acquisition pending ([`flags::INITIALIZED`] clear or
    /// [`flags::REACQUIRE_PENDING`] set). Not a policy: kept in [`Runner::policy`] so that
    /// the usual update's state test is that byte's one test. [`Runner::sync_state`] sets
    /// it wherever either flag may change; the usual step and the lane step find it clear
    /// and leave it so.
    const UNSETTLED: u8 = 16;
    /// The rest watch looks at the next sample ([`Runner::look`]). Not a policy: kept in
    /// [`Runner::policy`] so that the sample takes the policies' path, and the usual
    /// step's only cost of the watch is its count.
    const WATCH: u8 = 32;

    pub(crate) fn new(config: &Config) -> Result<Runner<E>, Error> {
        debug_assert_eq!(config.kind(), E::KIND);
        // A configuration is validated once: its slots when they were set (no other way
        // writes them), its initial orientation (a public field) here.
        if let Init::Given(q) = config.init {
            check_quaternion(q)?;
        }
        let core = E::create(E::Settings::from_slots(config.slots()));
        let (common, ranges_set) = Common::from_slots(config.slots());
        let identity = if config.init == Init::Identity { Self::IDENTITY_INIT } else { 0 };
        let reframe = if config.frame != E::NATIVE { Self::REFRAME } else { 0 };
        let mut r = Runner {
            core,
            flags: 0,
            frame: config.frame,
            bits: ranges_set | identity | reframe,
            policy: 0,
            common,
            last_accel: Vec3::ZERO,
            given: match config.init {
                Init::Given(q) => Some(Box::new(q)),
                _ => None,
            },
            extras: ExtrasBox(None),
            watch: Watch::default(),
        };
        r.set_policies(config.slots());
        r.set_frame_rotation();
        r.reset();
        Ok(r)
    }

    /// The saturation and same-instant policies from the slots, and the kind's option bit
    /// ([`Estimator::usual_settings`]); the extras' box is made here for the burst
    /// readings, so that no update allocates. Called whenever the settings change.
    fn set_policies(&mut self, slots: &[f64; MAX_PARAMS]) {
        let recover = if slots[id::SATURATION_RECOVERY as usize] != 0.0 { Self::RECOVER } else { 0 };
        let same_instant = if slots[id::SAME_INSTANT as usize] != 0.0 { Self::SAME_INSTANT } else { 0 };
        let option = if self.core.usual_settings() { 0 } else { Self::KIND_OPTION };
        self.policy =
            (self.policy & (Self::MODELS | Self::UNSETTLED | Self::WATCH)) | recover | same_instant | option;
        if self.same_instant() {
            self.extras_mut();
        } else if let Some(x) = &mut self.extras.0 {
            // Readings held for a step that will not come.
            x.burst = (Vec3::ZERO, 0);
        }
    }

    /// `saturation_recovery` is on.
    #[inline(always)]
    pub(crate) fn recover(&self) -> bool {
        self.policy & Self::RECOVER != 0
    }

    /// `same_instant` is on.
    #[inline(always)]
    pub(crate) fn same_instant(&self) -> bool {
        self.policy & Self::SAME_INSTANT != 0
    }

    /// The models bit of [`Runner::policy`] after the extras' models changed (set,
    /// loaded, or put aside for a calibrated sample's plain update).
    pub(crate) fn refresh_models(&mut self) {
        let any = self.extras.0.as_ref().is_some_and(|x| x.models.any());
        self.policy = (self.policy & !Self::MODELS) | if any { Self::MODELS } else { 0 };
    }

    #[inline(always)]
    fn has_accel(&self) -> bool {
        self.bits & Self::HAS_ACCEL != 0
    }

    #[inline(always)]
    fn set_has_accel(&mut self, has: bool) {
        self.bits = (self.bits & !Self::HAS_ACCEL) | if has { Self::HAS_ACCEL } else { 0 };
    }

    /// The extras, made (with the frame's up direction) when first needed.
    pub(crate) fn extras_mut(&mut self) -> &mut Extras {
        let up_z = self.frame.up().z;
        self.bits |= Self::HOSTED;
        self.extras.0.get_or_insert_with(|| {
            let mut x = Box::<Extras>::default();
            x.host.refresh(up_z);
            x
        })
    }

    /// Read extras: kept in the box, made only when they are not plain.
    fn put_extras(&mut self, x: Extras) {
        if self.extras.0.is_some() || !x.is_plain() {
            **self.extras.0.get_or_insert_with(Box::default) = x;
            self.bits |= Self::HOSTED;
        }
    }

    /// The host's frames (the identity ones when none are set).
    pub(crate) fn host(&self) -> Host {
        match &self.extras.0 {
            Some(x) => x.host,
            None => {
                let mut h = Host::default();
                h.refresh(self.frame.up().z);
                h
            }
        }
    }

    pub(crate) fn models(&self) -> Models {
        self.extras.0.as_ref().map_or_else(Models::default, |x| x.models)
    }

    fn init(&self) -> Init {
        match (&self.given, self.bits & Self::IDENTITY_INIT != 0) {
            (Some(q), _) => Init::Given(**q),
            (None, true) => Init::Identity,
            (None, false) => Init::AccMag,
        }
    }

    fn set_frame_rotation(&mut self) {
        let relative = if self.core.relative() { Self::RELATIVE } else { 0 };
        self.bits = (self.bits & !Self::RELATIVE) | relative;
    }

    /// Native frame to configured frame (a constant); none for a relative output.
    #[inline(always)]
    fn to_frame(&self) -> Option<Quat> {
        if self.bits & Self::RELATIVE != 0 {
            None
        } else {
            E::NATIVE.rotation_to(self.frame)
        }
    }

    /// The configuration this filter was made with, as changed by `set_param` since.
    pub(crate) fn config(&self) -> Config {
        let mut slots = [0.0; MAX_PARAMS];
        self.common.write_slots(self.bits, &mut slots);
        slots[id::SATURATION_RECOVERY as usize] = if self.recover() { 1.0 } else { 0.0 };
        slots[id::SAME_INSTANT as usize] = if self.same_instant() { 1.0 } else { 0.0 };
        self.core.settings().write_slots(&mut slots);
        Config::from_parts(E::KIND, self.frame, self.init(), slots)
    }

    pub(crate) fn reset(&mut self) {
        self.core.restart(*self.core.settings());
        if let Some(x) = &mut self.extras.0 {
            x.burst = (Vec3::ZERO, 0);
        }
        self.last_accel = Vec3::ZERO;
        self.set_has_accel(false);
        self.watch.restart();
        self.flags = 0;
        self.sync_state();
        match self.init() {
            // From the first sample, or the core's own start-up period.
            Init::AccMag => {}
            Init::Identity => self.set_frame_quaternion(Quat::IDENTITY),
            Init::Given(q) => self.set_frame_quaternion(q.normalized()),
        }
    }

    pub(crate) fn set_param(&mut self, pid: u32, value: f64) -> Result<(), Error> {
        let mut config = self.config();
        config.set_param(pid, value)?;
        self.core.configure(E::Settings::from_slots(config.slots()));
        let (common, ranges_set) = Common::from_slots(config.slots());
        self.common = common;
        self.bits = (self.bits & !Common::RANGE_BITS) | ranges_set;
        self.set_policies(config.slots());
        self.set_frame_rotation();
        Ok(())
    }

    pub(crate) fn param(&self, pid: u32) -> Result<f64, Error> {
        self.config().param(pid)
    }

    pub(crate) fn set_quaternion(&mut self, q: Quat) -> Result<(), Error> {
        check_quaternion(q)?;
        // `q` is the output's (segment's) orientation.
        let q = match &self.extras.0 {
            Some(x) => x.host.sensor_for(q.normalized()),
            None => q.normalized(),
        };
        self.set_frame_quaternion(q);
        Ok(())
    }

    fn set_frame_quaternion(&mut self, q: Quat) {
        let native = match self.to_frame() {
            Some(c) => c.conj() * q,
            None => q,
        };
        self.core.set_quaternion(native);
        self.watch.restart();
        self.flags |= flags::INITIALIZED;
        self.sync_state();
    }

    /// [`Runner::UNINIT`] and [`Runner::UNSETTLED`] from [`flags::INITIALIZED`] and
    /// [`flags::REACQUIRE_PENDING`], after any write that may change them.
    fn sync_state(&mut self) {
        let uninit = if self.flags & flags::INITIALIZED == 0 { Self::UNINIT } else { 0 };
        self.bits = (self.bits & !Self::UNINIT) | uninit;
        let unsettled = if self.settled() { 0 } else { Self::UNSETTLED };
        self.policy = (self.policy & !Self::UNSETTLED) | unsettled;
    }

    /// The lifecycle's first stage: no orientation and no start-up period begun (the
    /// kind's own, [`Estimator::starting`]), so the filter waits for a first sample with
    /// dt > 0 and an accelerometer reading.
    pub(crate) fn waiting(&self) -> bool {
        self.flags & flags::INITIALIZED == 0 && !self.core.starting()
    }

    /// Initialised, no re-acquisition pending.
    #[inline(always)]
    fn settled(&self) -> bool {
        self.flags & (flags::INITIALIZED | flags::REACQUIRE_PENDING) == flags::INITIALIZED
    }

    pub(crate) fn diagnostic_fields(&self) -> u32 {
        self.core.fields()
    }

    pub(crate) fn diagnostics(&self) -> Diagnostics {
        let mut d = Diagnostics { present: self.core.fields(), ..Diagnostics::default() };
        self.core.diagnose(&mut d);
        d.clear_absent();
        d
    }

    /// The kind's error model; none before initialisation.
    pub(crate) fn uncertainty(&self) -> crate::filters::diagnostics::Uncertainty {
        if self.flags() & flags::INITIALIZED == 0 {
            return crate::filters::diagnostics::Uncertainty::default();
        }
        self.core.uncertainty()
    }

    /// [`Estimator::learns_bias_in_motion`] with the settings as they are.
    pub(crate) fn learns_bias_in_motion(&self) -> bool {
        self.core.learns_bias_in_motion()
    }

    /// The configuration and state fields of a snapshot, in order (see [`state`]).
    fn codec(&mut self, c: &mut dyn Codec) {
        let mut head = ConfigFields::of(&self.config());
        head.codec(c);
        c.u32(&mut self.flags);
        let mut last = self.has_accel().then_some(self.last_accel);
        c.opt_vec3(&mut last);
        self.set_has_accel(last.is_some());
        self.last_accel = last.unwrap_or(Vec3::ZERO);
        // Since format version 3: the host's frames, the sensor models, the burst readings.
        let mut x = self.extras.0.as_deref().copied().unwrap_or_default();
        extras_codec(&mut x, c);
        self.put_extras(x);
        self.refresh_models();
        self.core.codec(c);
        // Since format version 8: the rest watch.
        self.watch.codec(c);
    }

    fn kind_byte() -> u8 {
        Kind::ALL.iter().position(|k| *k == E::KIND).unwrap_or(0) as u8 + 1
    }

    fn payload_len(&self) -> usize {
        let mut counter = Writer { buf: None, pos: 0 };
        self.clone().codec(&mut counter);
        counter.pos
    }

    pub(crate) fn state_size(&self) -> usize {
        state::HEADER + self.payload_len() + state::TRAILER
    }

    pub(crate) fn save(&self, out: &mut [u8]) -> Result<usize, StateError> {
        let len = self.payload_len();
        let mut copy = self.clone();
        state::seal(out, Self::kind_byte(), len, |w| copy.codec(w))
    }

    pub(crate) fn load(&mut self, blob: &[u8]) -> Result<(), StateError> {
        let payload = state::open(blob, Self::kind_byte(), self.payload_len())?;
        let mut r = Reader { buf: payload, pos: 0, ok: true };
        let mut head = ConfigFields::of(&self.config());
        head.codec(&mut r);
        let config = head.config(E::KIND).filter(|_| r.ok).ok_or(StateError::Corrupt)?;
        let mut fresh = Runner::<E>::new(&config).map_err(|_| StateError::Corrupt)?;
        r.u32(&mut fresh.flags);
        fresh.sync_state();
        let mut last = None;
        r.opt_vec3(&mut last);
        fresh.set_has_accel(last.is_some());
        fresh.last_accel = last.unwrap_or(Vec3::ZERO);
        let mut x = Extras::default();
        extras_codec(&mut x, &mut r);
        let (sum, n) = x.burst;
        let burst_ok = sum.is_finite() && (n > 0 || sum == Vec3::ZERO);
        x.host.refresh(fresh.frame.up().z);
        let extras_ok = x.host.valid() && x.models.valid() && burst_ok;
        fresh.put_extras(x);
        fresh.refresh_models();
        fresh.core.codec(&mut r);
        fresh.watch.codec(&mut r);
        if fresh.watch.looks_next() {
            fresh.policy |= Self::WATCH;
        }
        // Slots this kind does not use are zero in every snapshot it writes: a blob of
        // another kind relabelled (with a fresh checksum) has its own kind's slots set.
        let foreign =
            head.params.iter().enumerate().any(|(i, v)| *v != 0.0 && E::KIND.param(i as u32).is_none());
        let accel_ok = last.map_or(true, holds::accel);
        if !r.ok
            || r.pos != payload.len()
            || foreign
            || fresh.flags & !flags::STORED != 0
            || !accel_ok
            || !extras_ok
            || !fresh.core.valid()
        {
            return Err(StateError::Corrupt);
        }
        *self = fresh;
        Ok(())
    }

    /// [`flags`] bits: those the last update stored and those read from the state.
    #[inline]
    pub(crate) fn flags(&self) -> u32 {
        self.flags
            | if self.core.at_rest() { flags::REST } else { 0 }
            | if self.core.mag_disturbed() { flags::MAG_DISTURBED } else { 0 }
    }

    pub(crate) fn frame(&self) -> Frame {
        self.frame
    }

    /// The output orientation: the segment's when a mounting is set, with the heading
    /// offset and declination applied (see `host.rs`).
    #[inline(always)]
    pub(crate) fn output(&self) -> Quat {
        debug_assert_eq!(self.bits & Self::HOSTED != 0, self.extras.0.is_some());
        debug_assert_eq!(self.bits & Self::UNINIT != 0, self.flags & flags::INITIALIZED == 0);
        debug_assert_eq!(self.policy & Self::UNSETTLED == 0, self.settled());
        debug_assert_eq!(self.bits & Self::REFRAME != 0, self.frame != E::NATIVE);
        let hosted = Self::RELATIVE | Self::HOSTED | Self::UNINIT;
        if Self::NATIVE_IS_DEFAULT && self.bits & (hosted | Self::REFRAME) == 0 {
            // Initialised, not relative, no host frames, and the native frame configured.
            return self.core.quaternion();
        }
        if self.bits & hosted != 0 {
            return self.output_hosted();
        }
        // What `quaternion` gives when initialised and not relative.
        E::NATIVE.express(self.frame, self.core.quaternion())
    }

    /// [`Runner::output`] with a relative output, the extras' box made, or before
    /// initialisation.
    #[cold]
    #[inline(never)]
    fn output_hosted(&self) -> Quat {
        let q = self.quaternion();
        match &self.extras.0 {
            Some(x) => x.host.output(q),
            None => q,
        }
    }

    /// The sensor's orientation in the configured frame (identity before initialisation).
    #[inline(always)]
    pub(crate) fn quaternion(&self) -> Quat {
        if self.flags & flags::INITIALIZED == 0 {
            return Quat::IDENTITY;
        }
        let q = self.core.quaternion();
        if self.bits & Self::RELATIVE != 0 {
            q
        } else {
            E::NATIVE.express(self.frame, q)
        }
    }

    pub(crate) fn gravity_magnitude(&self) -> f64 {
        self.common.gravity
    }

    pub(crate) fn last_accel(&self) -> Option<Vec3> {
        self.has_accel().then_some(self.last_accel)
    }
}

impl Extras {
    /// Nothing set: what a filter without extras behaves as.
    fn is_plain(&self) -> bool {
        self.host.mounting == Quat::IDENTITY
            && self.host.heading == 0.0
            && self.host.declination == 0.0
            && self.models == Models::default()
            && self.burst == (Vec3::ZERO, 0)
    }
}

/// The extras' snapshot fields, in order (since format version 3).
fn extras_codec(x: &mut Extras, c: &mut dyn Codec) {
    c.quat(&mut x.host.mounting);
    c.f64(&mut x.host.heading);
    c.f64(&mut x.host.declination);
    calibration::codec(&mut x.models, c);
    c.vec3(&mut x.burst.0);
    let mut n = x.burst.1 as u64;
    c.u64(&mut n);
    x.burst.1 = n.min(u32::MAX as u64) as u32;
}

/// The configuration as it travels in a snapshot.
struct ConfigFields {
    frame: u32,
    init: u32,
    initial: Quat,
    params: [f64; MAX_PARAMS],
}

impl ConfigFields {
    fn of(c: &Config) -> ConfigFields {
        let (init, initial) = match c.init {
            Init::AccMag => (0, Quat::IDENTITY),
            Init::Identity => (1, Quat::IDENTITY),
            Init::Given(q) => (2, q),
        };
        let frame = Frame::ALL.iter().position(|f| *f == c.frame).unwrap_or(0) as u32;
        ConfigFields { frame, init, initial, params: *c.slots() }
    }

    fn codec(&mut self, c: &mut dyn Codec) {
        c.u32(&mut self.frame);
        c.u32(&mut self.init);
        c.quat(&mut self.initial);
        for p in self.params.iter_mut() {
            c.f64(p);
        }
    }

    /// The configuration, if every field is valid for `kind`.
    fn config(&self, kind: Kind) -> Option<Config> {
        let frame = *Frame::ALL.get(self.frame as usize)?;
        let init = match self.init {
            0 => Init::AccMag,
            1 => Init::Identity,
            2 => Init::Given(self.initial),
            _ => return None,
        };
        Config::from_slots(kind, frame, init, &self.params).ok()
    }
}
