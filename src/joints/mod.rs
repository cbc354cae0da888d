//! Joints: a rig's segments held together by what its joints allow, without a
//! magnetometer.
//!
//! A hand, a glove or a mocap suit is a rig: sensors on segments, segments joined by
//! joints. Every sensor runs its own filter ([`crate::Filter`], 6D or 9D); without a
//! trustworthy magnetometer each one's heading drifts on its own, and after minutes the
//! model's segments twist apart. A joint fixes the relative heading of its two segments
//! whenever its axes are not vertical: a hinge's axis, seen from the parent and from the
//! child, is one line; a 2-DoF joint's two axes stay perpendicular; and the joint centre
//! moves with both segments. [`Joints`](crate::joints::Joints) estimates, sample by sample and in memory fixed
//! at creation, each child's heading relative to its parent ([`estimator`](crate::joints::estimator) has the
//! equations), and gives each segment's corrected orientation and each joint's angles.
//!
//! The joints form a forest: each segment is the child of at most one joint, and no chain
//! of joints returns to where it started. A segment that is no joint's child is a root:
//! its orientation is its filter's. Each child's correction is its parent's times its
//! own, so a chain (wrist, MCP, PIP) follows its root.
//!
//! Make each sensor's filter from a configuration given
//! [`Config::for_joints`](crate::Config::for_joints)
//! ([`SENSOR_SETTINGS`](crate::joints::SENSOR_SETTINGS)): under joints a filter may follow
//! its gyroscope's drifting bias faster than alone.
//!
//! ```
//! use orient::joints::{JointKind, JointParams, JointSpec, Joints};
//! use orient::{Quat, Sample, Vec3};
//! // A forearm (segment 0) and a hand (1) joined by a hinge about both sensors' x axis.
//! let hinge = JointSpec {
//!     kind: JointKind::Hinge,
//!     parent: 0,
//!     child: 1,
//!     axis_parent: Vec3::new(1.0, 0.0, 0.0),
//!     axis_child: Vec3::new(1.0, 0.0, 0.0),
//! };
//! let mut joints = Joints::new(2, &[hinge], &[], JointParams::default())?;
//! // Each row: every filter's sensor orientation after its update, and its sample.
//! let sample = Sample {
//!     dt: 0.01,
//!     gyro: Some(Vec3::new(0.5, 0.0, 0.0)),
//!     accel: Some(Vec3::new(0.0, 0.0, 9.81)),
//!     mag: None,
//! };
//! joints.update(&[Quat::IDENTITY, Quat::IDENTITY], &[sample, sample])?;
//! let hand = joints.segment_quaternion(1);
//! let [flexion, _] = joints.angles(0);
//! assert!(hand.is_finite() && flexion.abs() < 1e-9);
//! # Ok::<(), orient::joints::JointError>(())
//! ```

#![forbid(unsafe_code)]

mod axes;
pub mod estimator;

pub use axes::{
    estimate_hinge_axes, estimate_hinge_axes_by, estimate_two_dof_axes, estimate_two_dof_axes_by, JointAxes,
};
pub use estimator::{JointParams, JOINT_PARAMS};

use crate::filters::state::{self as snapshot, Codec, Reader, StateError, Writer};
use crate::filters::{Config, Filter, Sample};
use crate::math::{Quat, Vec3};
use estimator::JointEstimator;

/// The most joints one [`Joints`] holds: a suit of 20 segments has 19, two hands 30.
pub const MAX_JOINTS: usize = 64;
/// The most segments one [`Joints`] holds.
pub const MAX_SEGMENTS: usize = 256;

/// One setting a sensor's filter takes under joints: a parameter by its name (the
/// recommended kind's), its value in the parameter's unit, and why, as the C header's
/// orient_config_for_joints says it (rendered from [`SENSOR_SETTINGS`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorSetting {
    /// The parameter's name ([`Config::set`]).
    pub name: &'static str,
    /// Its value under joints, in the parameter's unit.
    pub value: f64,
    /// Why, a clause that follows the value.
    pub why: &'static str,
}

/// The settings a sensor's filter takes under joints ([`Config::for_joints`]), each with
/// its reason. Measured on simulated gloves and a leg (docs/ACCURACY.md); alone, on
/// BROAD's real trials, the defaults stay better. The C header's doc of
/// orient_config_for_joints, and through it the bindings', is rendered from this table.
pub const SENSOR_SETTINGS: [SensorSetting; 3] = [
    SensorSetting {
        name: "bias_walk",
        value: 8.726_646_259_971_648e-4,
        why: "so the motion bias filter follows a drifting bias more closely (the joints hold \
              the relative heading that a faster bias estimate would otherwise let wander)",
    },
    SensorSetting {
        name: "bias_limit",
        value: 0.069_813_170_079_773_18,
        why: "a bound on each axis, so a glove's bias up to 3 deg/s per axis is learned whole in \
              motion",
    },
    SensorSetting {
        name: "rest_gyro",
        value: 0.069_813_170_079_773_18,
        why: "a bound on the rate's length, so a sensor whose bias is up to that long is still \
              found at rest (the reference pose among its rests) and learns its bias there; a \
              turn about the vertical slower than it, held as long as rest takes (`rest_time`), \
              is then taken for rest too",
    },
];

impl Config {
    /// Sets [`SENSOR_SETTINGS`], the settings a sensor's filter runs with under joints,
    /// where the kind has them (the recommended kind); other kinds are left as they were.
    pub fn for_joints(&mut self) {
        for SensorSetting { name, value, .. } in SENSOR_SETTINGS {
            if let Some(set) = self.set(name, value) {
                debug_assert!(set.is_ok(), "{name} in range (tested)");
            }
        }
    }
}

/// `n` copies of `v`, or OutOfMemory.
fn filled<T: Clone>(n: usize, v: T) -> Result<Vec<T>, JointError> {
    let mut x = Vec::new();
    x.try_reserve_exact(n).map_err(|_| JointError::OutOfMemory)?;
    x.resize(n, v);
    Ok(x)
}

/// What a joint allows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// One degree of freedom: the child turns about one axis, `axis_parent` in the
    /// parent's sensor frame and `axis_child` in the child's, the same line at every
    /// instant (an elbow, a knee, a finger's PIP and DIP joints).
    Hinge,
    /// Two degrees of freedom: the child turns about `axis_parent` (fixed in the parent),
    /// then about `axis_child` (fixed in the child), the two perpendicular (a wrist, a
    /// finger's MCP joint, an ankle).
    TwoDof,
}

impl JointKind {
    /// The kind's name in rig descriptions and the Python binding: `"hinge"`, `"2dof"`.
    pub fn name(self) -> &'static str {
        match self {
            JointKind::Hinge => "hinge",
            JointKind::TwoDof => "2dof",
        }
    }
}

/// One joint: segment indices and unit axes in the sensors' frames.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointSpec {
    pub kind: JointKind,
    /// The parent segment (its sensor's index).
    pub parent: usize,
    /// The child segment.
    pub child: usize,
    /// The first axis in the parent sensor's frame (any length but zero).
    pub axis_parent: Vec3,
    /// The hinge's axis, or a 2-DoF joint's second axis, in the child sensor's frame.
    pub axis_child: Vec3,
}

impl JointSpec {
    /// This joint with its axes given in the segments' frames (anatomical axes: a
    /// finger's flexion axis in its bone's frame) turned into the sensors' frames through
    /// the mountings `m_parent`, `m_child` (sensor to segment, `v_segment = m v_sensor`,
    /// so `v_sensor = m⁻¹ v_segment`): for mountings from a rig calibration at the
    /// reference pose, or known from how the sensors are strapped on.
    pub fn in_sensor_frames(self, m_parent: Quat, m_child: Quat) -> JointSpec {
        JointSpec {
            axis_parent: m_parent.normalized().rotate_inverse(self.axis_parent),
            axis_child: m_child.normalized().rotate_inverse(self.axis_child),
            ..self
        }
    }
}

/// Why a rig's joints or a row of its samples were refused. Nothing changes on an error.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointError {
    /// More than [`MAX_JOINTS`] joints (the count).
    TooMany(usize),
    /// Joint `k` names a segment at or beyond the rig's count.
    NoSuchSegment(usize),
    /// Joint `k`'s child is its parent.
    OwnParent(usize),
    /// Joint `k`'s child is already another joint's child.
    TwoParents(usize),
    /// Joint `k` closes a cycle.
    Cycle(usize),
    /// Joint `k` has an axis that is NaN or infinite, or whose squared norm is not a normal
    /// finite number (zero, too small or too large to normalise).
    BadAxis(usize),
    /// Mounting `s` is not a usable quaternion (zero or not finite).
    BadMounting(usize),
    /// A parameter is outside its range in [`JOINT_PARAMS`] (not finite, or subnormal,
    /// included).
    BadParams,
    /// A slice's length is not the number of segments (what it is).
    WrongLength(usize),
    /// Segment `s`'s orientation or sample has a value that is not finite.
    NonFinite(usize),
    /// More than [`MAX_SEGMENTS`] segments (the count).
    TooManySegments(usize),
    /// The joints' memory could not be allocated.
    OutOfMemory,
    /// No [`JOINT_PARAMS`] entry has this name.
    UnknownParam,
    /// The value is outside the parameter's range in [`JOINT_PARAMS`] (its index there).
    ParamOutOfRange(usize),
}

impl core::fmt::Display for JointError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            JointError::TooMany(n) => write!(f, "{n} joints: at most {MAX_JOINTS}"),
            JointError::NoSuchSegment(k) => write!(f, "joint {k} names a segment the rig does not have"),
            JointError::OwnParent(k) => write!(f, "joint {k}: the child is its own parent"),
            JointError::TwoParents(k) => write!(f, "joint {k}: the child already has a parent"),
            JointError::Cycle(k) => write!(f, "joint {k} closes a cycle"),
            JointError::BadAxis(k) => write!(f, "joint {k}: an axis is zero or not finite"),
            JointError::BadMounting(s) => write!(f, "mounting {s} is not a rotation"),
            JointError::BadParams => write!(f, "a joint parameter is not finite or out of range"),
            JointError::WrongLength(n) => write!(f, "{n} entries: one per segment expected"),
            JointError::NonFinite(s) => write!(f, "segment {s}: a value is not finite"),
            JointError::TooManySegments(n) => write!(f, "{n} segments: at most {MAX_SEGMENTS}"),
            JointError::OutOfMemory => write!(f, "the joints' memory could not be allocated"),
            JointError::UnknownParam => write!(f, "no joint parameter has this name"),
            JointError::ParamOutOfRange(k) => {
                let s = &JOINT_PARAMS[k];
                write!(f, "{} outside [{}, {}]", s.name, s.min, s.max)
            }
        }
    }
}

impl std::error::Error for JointError {}

/// A rig's joints and their estimates. Made once ([`Joints::new`], which allocates);
/// [`Joints::update`] and every getter allocate nothing.
#[derive(Clone, Debug, PartialEq)]
pub struct Joints {
    specs: Vec<JointSpec>,
    /// One estimator per joint, in `specs`' order.
    estimators: Vec<JointEstimator>,
    /// The joints' indices, every parent's joint before its children's.
    order: Vec<usize>,
    /// Per segment: the mounting (sensor to segment, `v_segment = m v_sensor`).
    mountings: Vec<Quat>,
    /// Per segment: the correction (earth frame), the last sensor orientation given (from
    /// the filter), and the corrected one.
    corrections: Vec<Quat>,
    raw: Vec<Quat>,
    sensors: Vec<Quat>,
    /// An update has been taken (the angles are the last update's; before, zero).
    updated: bool,
    /// Per joint: the angles at the last update.
    angles: Vec<[f64; 2]>,
    /// Per segment: [`Joints::update_each`]'s buffers.
    scratch: Scratch,
    params: JointParams,
}

/// [`Joints::update_each`]'s buffers, one entry per segment: no state, so two joints
/// compare equal and print alike whatever they hold.
#[derive(Clone, Default)]
struct Scratch {
    sensors: Vec<Quat>,
    samples: Vec<Sample>,
    learns: Vec<bool>,
}

impl PartialEq for Scratch {
    fn eq(&self, _: &Scratch) -> bool {
        true
    }
}

impl core::fmt::Debug for Scratch {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("Scratch")
    }
}

impl Joints {
    /// The joints of a rig of `segments` segments (one sensor, one filter each), with the
    /// sensors' `mountings` (sensor to segment; empty for the identity everywhere) that
    /// give the angles' zero (the reference pose, where every segment's frame is the
    /// same), and the estimator's tuning. An error names the first joint (or segment)
    /// that is wrong.
    pub fn new(
        segments: usize,
        joints: &[JointSpec],
        mountings: &[Quat],
        params: JointParams,
    ) -> Result<Joints, JointError> {
        if joints.len() > MAX_JOINTS {
            return Err(JointError::TooMany(joints.len()));
        }
        if segments > MAX_SEGMENTS {
            return Err(JointError::TooManySegments(segments));
        }
        if !params.is_valid() {
            return Err(JointError::BadParams);
        }
        if !(mountings.is_empty() || mountings.len() == segments) {
            return Err(JointError::WrongLength(mountings.len()));
        }
        let mut m = filled(segments, Quat::IDENTITY)?;
        for (s, (into, q)) in m.iter_mut().zip(mountings).enumerate() {
            let n2 = q.norm_squared();
            if !(q.is_finite() && n2.is_finite() && n2 >= f64::MIN_POSITIVE) {
                return Err(JointError::BadMounting(s));
            }
            *into = q.normalized();
        }
        let mountings = m;
        let mut parent: Vec<Option<usize>> = filled(segments, None)?;
        let mut specs = filled(0, hinge_placeholder())?;
        specs.try_reserve_exact(joints.len()).map_err(|_| JointError::OutOfMemory)?;
        for (k, j) in joints.iter().enumerate() {
            if j.parent >= segments || j.child >= segments {
                return Err(JointError::NoSuchSegment(k));
            }
            if j.parent == j.child {
                return Err(JointError::OwnParent(k));
            }
            let usable = |a: Vec3| {
                a.is_finite() && a.norm_squared().is_finite() && a.norm_squared() >= f64::MIN_POSITIVE
            };
            if !(usable(j.axis_parent) && usable(j.axis_child)) {
                return Err(JointError::BadAxis(k));
            }
            if parent[j.child].is_some() {
                return Err(JointError::TwoParents(k));
            }
            parent[j.child] = Some(j.parent);
            // Up from the child: a cycle comes back to it within `segments` steps.
            let mut s = j.parent;
            for _ in 0..segments {
                if s == j.child {
                    return Err(JointError::Cycle(k));
                }
                match parent[s] {
                    Some(p) => s = p,
                    None => break,
                }
            }
            specs.push(JointSpec {
                axis_parent: j.axis_parent.normalized(),
                axis_child: j.axis_child.normalized(),
                ..*j
            });
        }
        let depth = |mut s: usize| {
            let mut d = 0;
            while let Some(p) = parent[s] {
                s = p;
                d += 1;
            }
            d
        };
        let mut order = filled(specs.len(), 0)?;
        for (k, o) in order.iter_mut().enumerate() {
            *o = k;
        }
        order.sort_by_key(|&k| depth(specs[k].child));
        let mut estimators = filled(0, JointEstimator::new(JointKind::Hinge, UNIT_X, UNIT_X, params))?;
        estimators.try_reserve_exact(specs.len()).map_err(|_| JointError::OutOfMemory)?;
        for j in &specs {
            estimators.push(JointEstimator::new(j.kind, j.axis_parent, j.axis_child, params));
        }
        Ok(Joints {
            angles: filled(specs.len(), [0.0, 0.0])?,
            specs,
            estimators,
            order,
            mountings,
            corrections: filled(segments, Quat::IDENTITY)?,
            raw: filled(segments, Quat::IDENTITY)?,
            sensors: filled(segments, Quat::IDENTITY)?,
            updated: false,
            scratch: Scratch {
                sensors: filled(segments, Quat::IDENTITY)?,
                samples: filled(segments, Sample::default())?,
                learns: filled(segments, true)?,
            },
            params,
        })
    }

    /// The number of segments.
    pub fn segments(&self) -> usize {
        self.mountings.len()
    }

    /// The joints as given (axes normalised).
    pub fn specs(&self) -> &[JointSpec] {
        &self.specs
    }

    /// Starts every estimate over: no correction (the outputs are the last orientations
    /// given, uncorrected), the given axes.
    pub fn reset(&mut self) {
        for (e, j) in self.estimators.iter_mut().zip(&self.specs) {
            *e = JointEstimator::new(j.kind, j.axis_parent, j.axis_child, self.params);
        }
        self.corrections.fill(Quat::IDENTITY);
        self.derive_outputs();
    }

    /// The corrected orientations and the angles from the corrections and the last
    /// orientations given, as the update makes them.
    fn derive_outputs(&mut self) {
        for s in 0..self.raw.len() {
            self.sensors[s] = (self.corrections[s] * self.raw[s]).normalized();
        }
        self.derive_angles();
    }

    /// The angles from the corrected orientations (zero before the first update).
    fn derive_angles(&mut self) {
        for k in 0..self.specs.len() {
            self.angles[k] = if self.updated { self.joint_angles(k) } else { [0.0, 0.0] };
        }
    }

    /// One row: each segment's sensor orientation (sensor to earth, from its filter after
    /// this row's sample: [`Filter::sensor_quaternion`]) and the sample that filter took.
    /// A joint whose two samples do not both have gyroscope and accelerometer readings
    /// holds its estimate this row; the child's `dt` is the joint's. `WrongLength` or
    /// `NonFinite` (a quaternion or reading) change nothing. Every sensor's filter is
    /// taken to learn its bias in motion at [`JointParams::bias_learn_rate`] (the
    /// recommended kind does); [`Joints::update_from`] and [`Joints::update_each`] take
    /// that from each filter.
    pub fn update(&mut self, sensors: &[Quat], samples: &[Sample]) -> Result<(), JointError> {
        self.step(sensors, samples, |_| true)
    }

    /// [`Joints::update`] with `learns(s)` saying whether segment `s`'s filter learns its
    /// gyroscope bias in motion ([`Filter::learns_bias_in_motion`]).
    fn step(
        &mut self,
        sensors: &[Quat],
        samples: &[Sample],
        learns: impl Fn(usize) -> bool,
    ) -> Result<(), JointError> {
        let n = self.segments();
        for len in [sensors.len(), samples.len()] {
            if len != n {
                return Err(JointError::WrongLength(len));
            }
        }
        for (s, (q, x)) in sensors.iter().zip(samples).enumerate() {
            let finite = |v: Option<Vec3>| v.map_or(true, Vec3::is_finite);
            let n2 = q.norm_squared();
            if !(q.is_finite()
                && n2.is_finite()
                && n2 >= f64::MIN_POSITIVE
                && x.dt.is_finite()
                && finite(x.gyro)
                && finite(x.accel))
            {
                return Err(JointError::NonFinite(s));
            }
        }
        for &k in &self.order {
            let j = self.specs[k];
            let (sp, sc) = (&samples[j.parent], &samples[j.child]);
            let est = &mut self.estimators[k];
            if let (Some(gp), Some(gc), Some(ap), Some(ac)) = (sp.gyro, sc.gyro, sp.accel, sc.accel) {
                let (qp, qc) = (sensors[j.parent].normalized(), sensors[j.child].normalized());
                est.update(qp, qc, gp, gc, ap, ac, sc.dt, [learns(j.parent), learns(j.child)]);
                if !(est.is_finite() && est.correction().is_finite()) {
                    // Finite inputs keep the state finite; should rounding ever not, the
                    // joint starts over rather than stay stuck.
                    *est = JointEstimator::new(j.kind, j.axis_parent, j.axis_child, self.params);
                }
            } else {
                est.hold();
            }
            self.corrections[j.child] = (self.corrections[j.parent] * est.correction()).normalized();
        }
        for (s, q) in sensors.iter().enumerate() {
            self.raw[s] = q.normalized();
        }
        self.updated = true;
        self.derive_outputs();
        Ok(())
    }

    /// [`Joints::update`] from the filters themselves (`filters[s]` took `samples[s]`): a
    /// filter that learns no bias in motion ([`Filter::learns_bias_in_motion`]) leaves
    /// its residual bias's horizontal part to the joints.
    pub fn update_from(&mut self, filters: &[&Filter], samples: &[Sample]) -> Result<(), JointError> {
        if filters.len() != self.segments() {
            return Err(JointError::WrongLength(filters.len()));
        }
        if samples.len() != self.segments() {
            return Err(JointError::WrongLength(samples.len()));
        }
        self.update_each(|s| (filters[s].sensor_quaternion(), samples[s], filters[s].learns_bias_in_motion()))
    }

    /// [`Joints::update`] with each segment's orientation, sample and whether its filter
    /// learns its bias in motion ([`Filter::learns_bias_in_motion`]) from `row(s)`, for a
    /// host whose rows are not slices; into buffers made with the joints, so that nothing
    /// is allocated here.
    pub fn update_each(
        &mut self,
        mut row: impl FnMut(usize) -> (Quat, Sample, bool),
    ) -> Result<(), JointError> {
        let mut b = core::mem::take(&mut self.scratch);
        for (s, ((q, x), l)) in
            b.sensors.iter_mut().zip(b.samples.iter_mut()).zip(b.learns.iter_mut()).enumerate()
        {
            (*q, *x, *l) = row(s);
        }
        let result = self.step(&b.sensors, &b.samples, |s| b.learns[s]);
        self.scratch = b;
        result
    }

    /// Segment `s`'s sensor orientation (sensor to earth) with the joints' correction.
    pub fn sensor_quaternion(&self, s: usize) -> Quat {
        self.sensors[s]
    }

    /// Segment `s`'s orientation (segment to earth), the bone rotation a host draws: the
    /// corrected sensor orientation with this rig's mounting `m` of the segment (given to
    /// [`Joints::new`]; a filter's own is not read) applied, `q_sensor ⊗ m⁻¹`.
    pub fn segment_quaternion(&self, s: usize) -> Quat {
        (self.sensors[s] * self.mountings[s].conj()).normalized()
    }

    /// Segment `s`'s correction (earth frame, applied on the left of its filter's
    /// orientation): the identity for a root.
    pub fn correction(&self, s: usize) -> Quat {
        self.corrections[s]
    }

    /// Joint `k`'s angles (rad) at the last update, zero in the reference pose (every
    /// segment's frame the same), positive by the right-hand rule about the joint's
    /// (refined) axes: a hinge gives `[θ, NaN]`, the child's turn about the axis; a 2-DoF
    /// joint `[α, β]`, the turn about `axis_parent` and then about `axis_child` that make
    /// up the child's orientation relative to its parent (exactly when the axes are
    /// true, the nearest such pair otherwise).
    pub fn angles(&self, k: usize) -> [f64; 2] {
        self.angles[k]
    }

    /// Joint `k`'s observability rating in [0, 1]: how much its constraints told about
    /// the relative heading over the last seconds (`rating_tau`). Near 0 at rest (when
    /// only the filters' measured drift moves the relative heading) and while a hinge's
    /// axis is vertical (when it is held on the drift estimate); near 1 for a horizontal
    /// axis in motion.
    pub fn rating(&self, k: usize) -> f64 {
        self.estimators[k].rating()
    }

    /// Joint `k`'s relative heading correction (rad, about the vertical): the turn added
    /// to the child's filter relative to its parent's.
    pub fn relative_heading(&self, k: usize) -> f64 {
        self.estimators[k].heading()
    }

    /// The standard deviation of [`Joints::relative_heading`] (rad).
    pub fn heading_std(&self, k: usize) -> f64 {
        self.estimators[k].heading_std()
    }

    /// The rate (rad/s) at which joint `k`'s relative heading correction turns to follow
    /// its two filters' headings as they drift apart on the vertical gyroscope bias each
    /// leaves: the child filter's heading drift relative to its parent's, negated.
    pub fn drift(&self, k: usize) -> f64 {
        self.estimators[k].drift()
    }

    /// Joint `k`'s axes as refined from motion (unit; parent's and child's sensor frame).
    pub fn axes(&self, k: usize) -> (Vec3, Vec3) {
        self.estimators[k].axes()
    }

    /// The tuning's field called `name` ([`JOINT_PARAMS`]); `None` for no such field.
    pub fn param(&self, name: &str) -> Option<f64> {
        self.params.get(name)
    }

    /// Sets the tuning's field called `name` ([`JOINT_PARAMS`]): every joint takes it from
    /// its next update on, and an initial standard deviation (`*_std0`) when its estimate
    /// next starts ([`Joints::reset`]; before the first update, at once; and while rows
    /// contradict a joint's estimate, which then widens its variances to the initial
    /// ones again, as from a start). The estimates
    /// are kept. A blob saved with another tuning no longer loads. `UnknownParam` or
    /// `ParamOutOfRange` change nothing.
    pub fn set_param(&mut self, name: &str, value: f64) -> Result<(), JointError> {
        let k = JOINT_PARAMS.iter().position(|s| s.name == name).ok_or(JointError::UnknownParam)?;
        if self.params.set(name, value) != Some(true) {
            return Err(JointError::ParamOutOfRange(k));
        }
        for e in &mut self.estimators {
            e.set_params(self.params);
        }
        if !self.updated && name.ends_with("_std0") {
            self.reset();
        }
        Ok(())
    }

    /// The size in bytes of this rig's joint state blob ([`Joints::save`]).
    pub fn state_size(&self) -> usize {
        let mut w = Writer { buf: None, pos: 0 };
        self.encode(&mut w);
        snapshot::HEADER + w.pos + snapshot::TRAILER
    }

    /// Saves the joints' estimates as a versioned, checksummed blob (the filters' snapshot
    /// format, its own kind byte) with the rig's description, so that only the same rig
    /// loads it: joints, axes as given, mountings and tuning. Returns its length;
    /// `BufferTooSmall` below [`Joints::state_size`]. Allocates nothing.
    pub fn save(&self, out: &mut [u8]) -> Result<usize, StateError> {
        let mut w = Writer { buf: None, pos: 0 };
        self.encode(&mut w);
        snapshot::seal(out, STATE_KIND, w.pos, |w| self.encode(w))
    }

    /// Restores a blob from [`Joints::save`] of the same rig: the estimates continue bit
    /// for bit. Refused, with nothing changed, when truncated, corrupted, of another
    /// format version, of a filter, of another rig, or holding a state no estimate could
    /// hold ([`estimator`]'s bounds). Allocates nothing: the blob is read twice, once to
    /// check it and once to take it.
    pub fn load(&mut self, blob: &[u8]) -> Result<(), StateError> {
        let size = self.state_size() - snapshot::HEADER - snapshot::TRAILER;
        let payload = snapshot::open(blob, STATE_KIND, size)?;
        if !self.decode(payload, false) {
            return Err(StateError::Corrupt);
        }
        let taken = self.decode(payload, true);
        debug_assert!(taken);
        // What the update derives: the corrections down the tree, the outputs.
        self.corrections.fill(Quat::IDENTITY);
        for &k in &self.order {
            let j = self.specs[k];
            self.corrections[j.child] =
                (self.corrections[j.parent] * self.estimators[k].correction()).normalized();
        }
        self.derive_outputs();
        Ok(())
    }

    /// The blob's payload: the rig's description (checked on load), each estimate, each
    /// segment's last sensor orientation, whether an update was taken. Values are copied
    /// out one at a time (the codec reads and writes through the same calls), so nothing
    /// is allocated.
    fn encode(&self, c: &mut dyn Codec) {
        let (mut segments, mut joints) = (self.mountings.len(), self.specs.len());
        c.usize(&mut segments);
        c.usize(&mut joints);
        for j in &self.specs {
            spec_codec(c, &mut j.clone());
        }
        for m in &self.mountings {
            c.quat(&mut m.clone());
        }
        params_codec(c, &mut self.params.clone());
        for e in &self.estimators {
            e.clone().codec(c);
        }
        for q in &self.raw {
            c.quat(&mut q.clone());
        }
        c.bool(&mut self.updated.clone());
    }

    /// Reads a payload: true when it is this rig's and every value one it could hold;
    /// with `take`, into the joints (after a pass without, which found it so).
    fn decode(&mut self, payload: &[u8], take: bool) -> bool {
        let mut r = Reader { buf: payload, pos: 0, ok: true };
        let (mut segments, mut joints) = (0, 0);
        r.usize(&mut segments);
        r.usize(&mut joints);
        if (segments, joints) != (self.mountings.len(), self.specs.len()) {
            return false;
        }
        let mut same = true;
        for k in 0..joints {
            let mut j = hinge_placeholder();
            spec_codec(&mut r, &mut j);
            same &= j == self.specs[k];
        }
        for s in 0..segments {
            let mut m = Quat::IDENTITY;
            r.quat(&mut m);
            same &= same_bits(m, self.mountings[s]);
        }
        let mut p = self.params;
        params_codec(&mut r, &mut p);
        same &= p == self.params;
        for k in 0..joints {
            let mut e = self.estimators[k].clone();
            e.codec(&mut r);
            same &= e.holds();
            if take {
                self.estimators[k] = e;
            }
        }
        for s in 0..segments {
            let mut q = Quat::IDENTITY;
            r.quat(&mut q);
            same &= estimator::is_unit(q);
            if take {
                self.raw[s] = q;
            }
        }
        let mut updated = false;
        r.bool(&mut updated);
        if take {
            self.updated = updated;
        }
        same && r.ok && r.pos == payload.len()
    }

    fn joint_angles(&self, k: usize) -> [f64; 2] {
        let j = &self.specs[k];
        let (a, b) = self.axes(k);
        angles(
            j.kind,
            a,
            b,
            self.mountings[j.parent],
            self.mountings[j.child],
            self.sensors[j.parent],
            self.sensors[j.child],
        )
    }
}

const UNIT_X: Vec3 = Vec3::new(1.0, 0.0, 0.0);

fn hinge_placeholder() -> JointSpec {
    JointSpec { kind: JointKind::Hinge, parent: 0, child: 0, axis_parent: UNIT_X, axis_child: UNIT_X }
}

/// A joint's description in a blob; a kind number that is neither fails the read.
fn spec_codec(c: &mut dyn Codec, j: &mut JointSpec) {
    let mut kind = j.kind as u32;
    c.u32(&mut kind);
    j.kind = match kind {
        0 => JointKind::Hinge,
        1 => JointKind::TwoDof,
        _ => {
            c.fail();
            JointKind::Hinge
        }
    };
    c.usize(&mut j.parent);
    c.usize(&mut j.child);
    c.vec3(&mut j.axis_parent);
    c.vec3(&mut j.axis_child);
}

/// The tuning in a blob, in [`JOINT_PARAMS`]' order.
fn params_codec(c: &mut dyn Codec, p: &mut JointParams) {
    for v in p.fields_mut() {
        c.f64(v);
    }
}

/// The snapshot kind byte of a rig's joints (the filters' are 1 to 6).
pub(crate) const STATE_KIND: u8 = 0x4a;

fn same_bits(a: Quat, b: Quat) -> bool {
    [a.w, a.x, a.y, a.z].map(f64::to_bits) == [b.w, b.x, b.y, b.z].map(f64::to_bits)
}

/// The twist of `q` about the unit axis `n`: the angle (rad, in (-π, π]) of the rotation
/// about `n` in the swing-twist decomposition `q = swing ⊗ twist`.
pub fn twist_angle(q: Quat, n: Vec3) -> f64 {
    let p = q.vector().dot(n);
    let a = 2.0 * libm::atan2(p, q.w);
    if a > core::f64::consts::PI {
        a - 2.0 * core::f64::consts::PI
    } else if a <= -core::f64::consts::PI {
        a + 2.0 * core::f64::consts::PI
    } else {
        a
    }
}

/// A joint's angles ([`Joints::angles`]) from its axes `a` (parent sensor frame) and `b`
/// (child's), the mountings `m_p`, `m_c` (sensor to segment) and the sensor orientations
/// `q_p`, `q_c` (sensor to earth).
pub fn angles(kind: JointKind, a: Vec3, b: Vec3, m_p: Quat, m_c: Quat, q_p: Quat, q_c: Quat) -> [f64; 2] {
    // The child sensor's orientation relative to the parent's in the reference pose, and
    // the joint's rotation in the parent sensor's frame.
    let r0 = m_p.conj() * m_c;
    let rot = (q_p.conj() * q_c * r0.conj()).normalized();
    match kind {
        JointKind::Hinge => [twist_angle(rot, a), f64::NAN],
        JointKind::TwoDof => {
            let b = r0.rotate(b);
            let rb = rot.rotate(b);
            let (u, v) = (b - a * b.dot(a), rb - a * rb.dot(a));
            let alpha = libm::atan2(a.dot(u.cross(v)), u.dot(v));
            let rest = Quat::from_axis_angle(a, -alpha) * rot;
            [alpha, twist_angle(rest, b)]
        }
    }
}

#[cfg(test)]
mod tests;
