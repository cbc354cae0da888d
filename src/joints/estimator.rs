//! One joint's estimator: the child's heading relative to its parent, from the two
//! sensors' own (6D or 9D) orientation estimates and readings.
//!
//! Every sensor runs its own filter, whose heading is free and drifts without a
//! magnetometer. The child's orientation is corrected by a rotation about the vertical,
//! then by a small tilt, `q'_c = T(φ) ⊗ R_z(Δ) ⊗ q_c`: `Δ` is the child's heading
//! relative to its parent (a common turn about the vertical leaves every constraint
//! unchanged, so the parent's own correction does not enter). An extended Kalman filter
//! per joint estimates the error state
//!
//! `x = [Δ, β_p (3), β_c (3), u_p (2), u_c (2), o_p (3), o_c (3), φ (2)]`:
//! - `Δ`: the relative heading (rad);
//! - `β_p`, `β_c`: what remains of each sensor's gyroscope bias after its filter, negated
//!   (rad/s, sensor frame: a residual bias `b` turns a filter's heading at `g·b`, which
//!   the correction undoes); the correction drifts at `dΔ/dt = g_c·β_c − g_p·β_p`, with
//!   `g` the vertical in each sensor's frame, so the drift seen while the sensors turn
//!   reveals the vertical bias of each;
//! - `u_p`, `u_c`: the axis corrections (rad): `j = normalize(j₀ + u₁ b₁ + u₂ b₂)` with
//!   `b₁, b₂` a basis perpendicular to the axis, folded into `j` after each update (the
//!   axes a host gives are off by a few degrees; they are refined from motion);
//! - `o_p`, `o_c`: the joint centre in each sensor's frame (m), the lever arms;
//! - `φ`: the child's tilt correction about the earth's x and y (rad).
//!
//! Prediction and the constraints below only while a sensor turns: at rest the joint holds
//! (the constraints' errors, laxity and soft tissue, are then the same row after row, and
//! the joint centre's force is gravity on both sides, which says nothing about heading)
//! and measures the filters' drift instead (the last item below). Prediction over `dt`:
//! `Δ ← Δ + dt (g_c·β_c − g_p·β_p)`; the residual bias of each filter that learns its bias
//! in motion ([`crate::Filter::learns_bias_in_motion`]) loses its horizontal part at the
//! rate `λ` (`bias_learn_rate`) at which the filter learns that part of its own bias
//! from gravity (the inclination correction measures it), while the vertical part,
//! which gravity does not show, stays: `β ← A β` with `A = I − l (I − g gᵀ)`, `l = 1 −
//! e^(−λ dt)` the share learned over `dt`; `P ← T F P Fᵀ Tᵀ + Q dt` (`F` moves `Δ` with the
//! biases before the step, `T` is `A` on each bias's block); then each variance is held to
//! the square of the largest initial standard deviation [`JOINT_PARAMS`] accepts for its
//! state (4 rad for `Δ`) by `P ← D P D`: a state nothing observes for hours keeps a
//! covariance a blob loads with.
//!
//! Measurements, with the earth-frame axes `e_p = R(q_p) j_p` and
//! `e_c = R(T R_z(Δ)) R(q_c) j_c`:
//! - a hinge: `e_p − e_c = 0`, three scalar updates: the axis seen from both sides is one
//!   line. `∂/∂Δ = −ẑ × e_c`; its horizontal part fixes `Δ` (the gain grows with the
//!   axis' horizontal length: a vertical hinge says nothing about heading), its vertical
//!   part the axes' tilt (Laidig, Lehmann, Bégin, Seel, EMBC 2019);
//! - a 2-DoF joint: `e_p · e_c = 0`: the first axis, fixed in the parent, stays
//!   perpendicular to the second, fixed in the child (Laidig, Weygers, Seel, Sensors
//!   2022);
//! - every joint: the joint centre's specific force seen from both sides is one vector,
//!   `R(q_p)(a_p + M_p o_p) − R(T R_z(Δ) q_c)(a_c + M_c o_c) = 0` with
//!   `M o = ω × (ω × o) + ω̇ × o`: while the rig accelerates horizontally it fixes `Δ`
//!   whatever the axes' direction. Its residual's errors (soft tissue on the lever arms,
//!   the laxity, the finite-difference `ω̇`) grow with the motion: its `r` is
//!   `r_acc (1 + (|ω_p|² + |ω_c|²) / ω_s² + (|ω̇_p|² + |ω̇_c|²) / α_s²)`, `ω_s` =
//!   `acc_rate_scale`, `α_s` = `acc_accel_scale`;
//! - at rest, the drift: each filter's heading then turns only at its residual bias,
//!   `ψ̇ = −g·β`, so the difference of the two filters' heading rates (from their
//!   orientations at consecutive rows) measures `g_p·β_p − g_c·β_c` with noise density
//!   `r_drift`: the residual biases as the filters leave them after learning the biases
//!   at rest, which they would otherwise carry into the next motion.
//!
//! Each scalar update: `S = h P hᵀ + R` with `R = r / dt` (the residuals' errors, laxity,
//! soft tissue and the filters' inclination errors, are correlated over a fraction of a
//! second: `r` is their variance times their correlation time, so the gain does not
//! depend on the rate); an innovation beyond `gate √S` is down-weighted (Huber);
//! `K = P hᵀ / S`, `δx ← δx + K (ν − h δx)`, `P ← P − K h P`. The step applied to `Δ` and
//! to `φ` by the measurements is at most `max_rate · dt` a sample (the prediction adds the
//! drift): the heading never jumps. An update the bound cuts to a fraction `f` of its
//! step takes the gain `f K` in every state and removes from `P` only what that gain
//! does, `(2f − f²) P hᵀ h P / S` (Joseph's form for any gain): the estimate stays as
//! uncertain as the step it did not take and goes on at the bound. A joint started with
//! its headings unknown (`heading_std0` above 45°: not aligned at a reference pose, up
//! to 180° apart) takes the bound at 1 rad/s instead for its first
//! 60 seconds of motion: the joint centre's acceleration and the axes then
//! bring a heading 150° off within a degree within 30 s, where `max_rate` took minutes.
//!
//! Input no rig gives (rates that disagree with the orientations, forces no joint centre
//! feels), for minutes, must not leave a joint that good rows cannot bring back: each
//! residual bias, lever-arm and tilt component is held within the largest initial standard
//! deviation [`JOINT_PARAMS`] accepts for it, and while the innovations, low-passed over
//! 10 s, are far beyond what the model's noise explains, every variance is held at least
//! at its initial value, so that the estimate learns again as from a start.
//!
//! The observability rating is the information the constraints gave about `Δ`,
//! `h_Δ² / R`, low-passed over `rating_tau` and scaled to [0, 1] by its value for a
//! horizontal axis: 0 at rest and while a hinge's axis is vertical.

// Index loops over the state layout read like the equations.
#![allow(clippy::needless_range_loop)]

use super::JointKind;
use crate::filters::params::ParamSpec;
use crate::filters::MIN_DT;
use crate::math::{Quat, Vec3};

const UP: Vec3 = Vec3::new(0.0, 0.0, 1.0);
/// The state's size and layout (see the module doc).
const N: usize = 19;
const BP: usize = 1;
const BC: usize = 4;
const UP_: usize = 7;
const UC: usize = 9;
const OP: usize = 11;
const OC: usize = 14;
const TX: usize = 17;
/// A joint started with its relative heading unknown, `heading_std0` above
/// [`ACQUIRE_STD`] (45°; the headings were not aligned at a reference pose), corrects it
/// and its tilt at up to [`ACQUIRE_RATE`] (rad/s, the largest `max_rate` accepts) for
/// its first [`ACQUIRE_TIME`] seconds of motion (rest does not count), then within
/// `max_rate`: it acquires a heading up to 180° off within about a minute instead of
/// several (orient: simulated gloves without a reference pose, docs/ACCURACY.md). A joint
/// that reopens its variances (rows that contradict it for long) acquires again.
pub(crate) const ACQUIRE_STD: f64 = core::f64::consts::FRAC_PI_4;
pub(crate) const ACQUIRE_RATE: f64 = 1.0;
pub(crate) const ACQUIRE_TIME: f64 = 60.0;

/// The consistency check ([`JointEstimator::inconsistent`]): the normalized innovations'
/// low-pass time constant (s), the bound of each normalized innovation, and the limit of
/// a low-passed one's square in units of its variance under the model.
const CONSISTENCY_TAU: f64 = 10.0;
const CONSISTENCY_MAX_NU: f64 = 100.0;
const CONSISTENCY_LIMIT: f64 = 1000.0;

/// The joint estimator's tuning: noise densities in continuous time, so that none depends
/// on the sample rate. The defaults were chosen on simulated gloves (seeds 1-3 of the
/// tools' `rigsim`) and held on others (seeds 4-9): `rig_joints` in the tools. Each
/// field's unit, meaning, default and range, as hosts see them: [`JOINT_PARAMS`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointParams {
    /// Hinge residual noise density per component (rad²·s).
    pub r_hinge: f64,
    /// 2-DoF residual noise density (rad²·s).
    pub r_2dof: f64,
    /// Random walk of the relative heading (rad²/s).
    pub q_heading: f64,
    /// Random walk of each residual bias component (rad²/s³).
    pub q_rate: f64,
    /// Random walk of each axis correction (rad²/s); 0 with `axis_std0` 0 keeps the axes.
    pub q_axis: f64,
    /// Initial standard deviations: relative heading (rad), residual bias (rad/s), axes
    /// (rad).
    pub heading_std0: f64,
    pub rate_std0: f64,
    pub axis_std0: f64,
    /// The largest correction of the relative heading (and of the tilt) per second
    /// (rad/s, above zero): an update that would turn them faster takes a fraction of its
    /// gain in every state.
    pub max_rate: f64,
    /// Rest: both gyroscopes below this norm (rad/s) for `rest_time` seconds.
    pub rest_gyro: f64,
    pub rest_time: f64,
    /// Joint centre specific-force residual noise density per component ((m/s²)²·s) at
    /// rest; 0 leaves the constraint out.
    pub r_acc: f64,
    /// The angular rate (rad/s, of either sensor, summed in squares) and the angular
    /// acceleration (rad/s²) at which `r_acc` has doubled: above zero.
    pub acc_rate_scale: f64,
    pub acc_accel_scale: f64,
    /// Initial standard deviation (m) and random walk (m²/s) of each lever-arm component.
    pub lever_std0: f64,
    pub q_lever: f64,
    /// Initial standard deviation (rad) and random walk (rad²/s) of the tilt correction.
    pub tilt_std0: f64,
    pub q_tilt: f64,
    /// Innovations beyond this many standard deviations are down-weighted.
    pub gate: f64,
    /// The rating's low-pass time constant (s).
    pub rating_tau: f64,
    /// Noise density (rad²/s) of the two filters' relative heading drift measured at
    /// rest; 0 leaves the measurement out.
    pub r_drift: f64,
    /// The rate (1/s) at which each sensor's filter learns the horizontal part of its
    /// gyroscope bias in motion, for the filters that do ([`crate::Filter::learns_bias_in_motion`]);
    /// 0 for none.
    pub bias_learn_rate: f64,
}

impl Default for JointParams {
    /// The defaults of [`JOINT_PARAMS`].
    fn default() -> JointParams {
        let mut p = JointParams {
            r_hinge: 0.0,
            r_2dof: 0.0,
            q_heading: 0.0,
            q_rate: 0.0,
            q_axis: 0.0,
            heading_std0: 0.0,
            rate_std0: 0.0,
            axis_std0: 0.0,
            max_rate: 0.0,
            rest_gyro: 0.0,
            rest_time: 0.0,
            r_acc: 0.0,
            acc_rate_scale: 0.0,
            acc_accel_scale: 0.0,
            lever_std0: 0.0,
            q_lever: 0.0,
            tilt_std0: 0.0,
            q_tilt: 0.0,
            gate: 0.0,
            rating_tau: 0.0,
            r_drift: 0.0,
            bias_learn_rate: 0.0,
        };
        for (spec, v) in JOINT_PARAMS.iter().zip(p.fields_mut()) {
            *v = spec.default;
        }
        p
    }
}

/// Each [`JointParams`] field as a host sees it: the name, unit, meaning, default and
/// accepted range, in the order of [`JointParams::fields_mut`] (and of a joint blob).
/// The C ABI's `orient_joint_param_info`, `orient_joints_set_param` and the bindings
/// read this table, and [`JointParams::default`] takes its defaults.
pub const JOINT_PARAMS: [ParamSpec; 22] = [
    spec(
        0,
        "r_hinge",
        "rad^2 s",
        "Hinge residual noise density per component: how far the axis seen from \
        the two sensors may disagree (laxity, soft tissue, the filters' inclination), as variance times \
        correlation time; default 0.00125 (orient: chosen on simulated gloves).",
        0.00125,
        1e-12,
        1e3,
    ),
    spec(
        1,
        "r_2dof",
        "rad^2 s",
        "2-DoF residual noise density (the two axes' perpendicularity); default \
        0.0032 (orient: chosen on simulated gloves).",
        0.0032,
        1e-12,
        1e3,
    ),
    spec(
        2,
        "q_heading",
        "rad^2/s",
        "Random walk of the relative heading (what the two filters' headings do \
        that no residual bias explains); default 3.046e-6 (0.1 deg/sqrt(s)) (orient: simulated gloves).",
        Q_HEADING,
        0.0,
        1e-2,
    ),
    spec(
        3,
        "q_rate",
        "rad^2/s^3",
        "Random walk of each residual gyroscope bias component (how fast the \
        biases the filters leave move); default 6e-7 (orient: simulated gloves with drifting biases).",
        6e-7,
        0.0,
        1e-3,
    ),
    spec(
        4,
        "q_axis",
        "rad^2/s",
        "Random walk of each axis correction; default 0: the axes settle (with \
        axis_std0 0 too, the given axes are kept) (orient: simulated gloves).",
        0.0,
        0.0,
        1e-2,
    ),
    spec(
        5,
        "heading_std0",
        "rad",
        "Initial standard deviation of the relative heading, taken when the \
        estimate starts (the joints made, or reset): 1 deg by default, for filters whose headings were \
        aligned at a reference pose (orient_rig_align_heading); as far apart as they may be when they \
        were not (a hinge finds 30 deg within a degree in a minute of motion); above 45 deg (pi: \
        unknown) the joint corrects its heading and tilt at up to 1 rad/s for its first 60 s of \
        motion (orient: simulated gloves).",
        DEG,
        0.0,
        4.0,
    ),
    spec(
        6,
        "rate_std0",
        "rad/s",
        "Initial standard deviation of each residual bias component, taken when \
        the estimate starts; default 0.5 deg/s (orient: simulated gloves).",
        0.5 * DEG,
        0.0,
        0.1,
    ),
    spec(
        7,
        "axis_std0",
        "rad",
        "Initial standard deviation of each axis correction (how far off the \
        given axes may be), taken when the estimate starts; default 0.09 (about 5 deg) (orient: simulated gloves).",
        0.09,
        0.0,
        0.5,
    ),
    spec(
        8,
        "max_rate",
        "rad/s",
        "The largest correction of a relative heading and tilt per second: the \
        outputs never jump (but while a joint started with heading_std0 above 45 deg acquires its \
        heading: 1 rad/s for its first 60 s of motion); default 5 deg/s (orient: simulated gloves).",
        5.0 * DEG,
        1e-6,
        1.0,
    ),
    spec(
        9,
        "rest_gyro",
        "rad/s",
        "Rest, when the joint leaves its constraints out and measures the filters' drift \
        instead (r_drift): both gyroscopes below this norm for \
        rest_time; default 0.15 (orient: simulated gloves).",
        0.15,
        0.0,
        100.0,
    ),
    spec(
        10,
        "rest_time",
        "s",
        "How long both gyroscopes stay below rest_gyro before the joint rests; \
        default 0.3 (orient: simulated gloves).",
        0.3,
        0.0,
        1e3,
    ),
    spec(
        11,
        "r_acc",
        "(m/s^2)^2 s",
        "Joint centre specific-force residual noise density per component at \
        rest (it grows with the motion: acc_rate_scale, acc_accel_scale); 0 leaves the constraint out; \
        default 0.001 (orient: chosen on simulated gloves).",
        0.001,
        0.0,
        1e6,
    ),
    spec(
        12,
        "acc_rate_scale",
        "rad/s",
        "The angular rate (both sensors', summed in squares) at which \
        r_acc has doubled; default 1 (orient: simulated gloves).",
        1.0,
        1e-6,
        1e6,
    ),
    spec(
        13,
        "acc_accel_scale",
        "rad/s^2",
        "The angular acceleration (both sensors', summed in squares) at \
        which r_acc has doubled; default 20 (orient: simulated gloves).",
        20.0,
        1e-6,
        1e6,
    ),
    spec(
        14,
        "lever_std0",
        "m",
        "Initial standard deviation of each lever-arm component (the joint centre \
        in each sensor's frame), taken when the estimate starts; default 0.05 (orient: simulated gloves).",
        0.05,
        0.0,
        1.0,
    ),
    spec(15, "q_lever", "m^2/s", "Random walk of each lever-arm component; default 1e-10 (orient: simulated gloves).", 1e-10, 0.0, 1e-4),
    spec(
        16,
        "tilt_std0",
        "rad",
        "Initial standard deviation of the child's tilt correction, taken when \
        the estimate starts; default 0 (orient: simulated gloves).",
        0.0,
        0.0,
        0.5,
    ),
    spec(
        17,
        "q_tilt",
        "rad^2/s",
        "Random walk of the child's tilt correction (what the two filters' \
        inclinations do); default 3e-5 (orient: simulated gloves).",
        3e-5,
        0.0,
        1e-2,
    ),
    spec(
        18,
        "gate",
        "1",
        "Innovations beyond this many standard deviations are down-weighted (Huber); \
        default 3 (orient: simulated gloves).",
        3.0,
        0.1,
        1e3,
    ),
    spec(19, "rating_tau", "s", "The rating's low-pass time constant; default 2 (orient: simulated gloves).", 2.0, 1e-3, 1e3),
    spec(
        20,
        "r_drift",
        "rad^2/s",
        "Noise density of the relative heading drift measured at rest (each filter's \
        heading turns at its residual gyroscope bias while its sensor is still; rest is both \
        gyroscopes below rest_gyro, so a slow relative turn about the vertical within it is taken \
        for drift, and \
        so is a 9D filter's magnetometer correction); 0 leaves the measurement out; default \
        1e-7 (orient: about a MEMS gyroscope's noise density squared, chosen on simulated \
        gloves).",
        1e-7,
        0.0,
        1.0,
    ),
    spec(
        21,
        "bias_learn_rate",
        "1/s",
        "The rate at which each sensor's filter learns the horizontal part of its own \
        gyroscope bias in motion (the part gravity shows it): the joint's residual biases lose \
        their horizontal part at this rate and keep their vertical part. Applied to the filters \
        whose kind, with their settings, learns in motion (the recommended kind unless its \
        bias_sigma_motion, bias_walk or bias_sigma is 0, the EKF, Mahony with ki above 0; \
        Madgwick, Mahony without ki, the complementary filter and GMVDK learn theirs at rest, in \
        still runs, or not at all): orient_joints_update \
        reads it from each filter; 0 for none; default 0.1 (orient: fitted on simulated gloves \
        and a leg with the recommended kind under orient_config_for_joints()).",
        0.1,
        0.0,
        10.0,
    ),
];

pub(super) const DEG: f64 = core::f64::consts::PI / 180.0;
const Q_HEADING: f64 = (0.1 * DEG) * (0.1 * DEG);

const fn spec(
    id: u32,
    name: &'static str,
    unit: &'static str,
    doc: &'static str,
    default: f64,
    min: f64,
    max: f64,
) -> ParamSpec {
    ParamSpec { id, name, unit, doc, default, min, max, zero_off: false }
}

impl JointParams {
    /// Every field in [`JOINT_PARAMS`]' order.
    pub fn fields_mut(&mut self) -> [&mut f64; 22] {
        let p = self;
        [
            &mut p.r_hinge,
            &mut p.r_2dof,
            &mut p.q_heading,
            &mut p.q_rate,
            &mut p.q_axis,
            &mut p.heading_std0,
            &mut p.rate_std0,
            &mut p.axis_std0,
            &mut p.max_rate,
            &mut p.rest_gyro,
            &mut p.rest_time,
            &mut p.r_acc,
            &mut p.acc_rate_scale,
            &mut p.acc_accel_scale,
            &mut p.lever_std0,
            &mut p.q_lever,
            &mut p.tilt_std0,
            &mut p.q_tilt,
            &mut p.gate,
            &mut p.rating_tau,
            &mut p.r_drift,
            &mut p.bias_learn_rate,
        ]
    }

    /// The field called `name` ([`JOINT_PARAMS`]); `None` for no such field.
    pub fn get(&self, name: &str) -> Option<f64> {
        let k = JOINT_PARAMS.iter().position(|s| s.name == name)?;
        let mut p = *self;
        let v = *p.fields_mut()[k];
        Some(v)
    }

    /// Sets the field called `name` when [`JOINT_PARAMS`] accepts `value` for it: `None`
    /// for no such field, `Some(false)` (nothing changed) for a value out of its range.
    pub fn set(&mut self, name: &str, value: f64) -> Option<bool> {
        let k = JOINT_PARAMS.iter().position(|s| s.name == name)?;
        let ok = JOINT_PARAMS[k].accepts(value);
        if ok {
            *self.fields_mut()[k] = value;
        }
        Some(ok)
    }

    /// Every field within its range in [`JOINT_PARAMS`].
    pub(crate) fn is_valid(&self) -> bool {
        let mut p = *self;
        let ok = JOINT_PARAMS.iter().zip(p.fields_mut()).all(|(s, v)| s.accepts(*v));
        ok
    }
}

/// An axis with a perpendicular basis (the directions of its small turns), carried along
/// as the axis is refined.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Axis {
    pub(crate) j: Vec3,
    pub(crate) b1: Vec3,
    pub(crate) b2: Vec3,
}

impl Axis {
    pub(crate) fn new(j: Vec3) -> Axis {
        let j = j.normalized();
        let helper = if j.x.abs() <= j.y.abs() && j.x.abs() <= j.z.abs() {
            Vec3::new(1.0, 0.0, 0.0)
        } else if j.y.abs() <= j.z.abs() {
            Vec3::new(0.0, 1.0, 0.0)
        } else {
            UP
        };
        let b1 = j.cross(helper).normalized();
        Axis { j, b1, b2: j.cross(b1) }
    }

    /// The axis turned by `u1` towards `b1` and `u2` towards `b2` (rad, small).
    pub(crate) fn fold(&mut self, u1: f64, u2: f64) {
        self.j = (self.j + self.b1 * u1 + self.b2 * u2).normalized();
        self.b1 = (self.b1 - self.j * self.j.dot(self.b1)).normalized();
        self.b2 = self.j.cross(self.b1);
    }
}

/// The [`JOINT_PARAMS`] index of state `i`'s initial standard deviation (`heading_std0`,
/// `rate_std0`, `axis_std0`, `lever_std0`, `tilt_std0`).
fn std0_param(i: usize) -> usize {
    match i {
        0 => 5,
        _ if i < UP_ => 6,
        _ if i < OP => 7,
        _ if i < TX => 14,
        _ => 16,
    }
}

/// State `i`'s initial standard deviation in the tuning `p`.
fn initial_std(p: &JointParams, i: usize) -> f64 {
    let mut p = *p;
    *p.fields_mut()[std0_param(i)]
}

/// The largest initial standard deviation [`JOINT_PARAMS`] accepts for state `i`'s group
/// (the maximum of its `*_std0`): each variance is held to its square
/// ([`JointEstimator::bound_variances`]), and each residual bias, lever-arm and tilt
/// component to it ([`JointEstimator::bound_states`]).
fn largest_std(i: usize) -> f64 {
    JOINT_PARAMS[std0_param(i)].max
}

/// The states [`JointEstimator::bound_states`] holds within [`largest_std`]: the residual
/// biases, the lever arms and the tilt (the relative heading is free and the axis
/// corrections are folded into the axes after every update).
fn bounded(i: usize) -> bool {
    (BP..UP_).contains(&i) || (OP..N).contains(&i)
}

/// A quaternion a blob may hold where the joints keep unit ones (a filter's orientation).
pub(crate) fn is_unit(q: Quat) -> bool {
    (q.norm_squared() - 1.0).abs() < 1e-9
}

fn comp(v: Vec3, i: usize) -> f64 {
    [v.x, v.y, v.z][i]
}

fn rot_z(psi: f64) -> Quat {
    Quat::new(libm::cos(0.5 * psi), 0.0, 0.0, libm::sin(0.5 * psi))
}

/// One joint's estimator (see the module doc). Fixed size: no update allocates.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointEstimator {
    kind: JointKind,
    p_axis: Axis,
    c_axis: Axis,
    x: [f64; N],
    p: [[f64; N]; N],
    params: JointParams,
    /// How long both sensors have been still (s).
    still: f64,
    /// The vertical in the parent's and the child's sensor frame at the last motion.
    g: [Vec3; 2],
    /// The previous gyroscope readings (parent, child), for the angular accelerations.
    prev_gyro: Option<(Vec3, Vec3)>,
    /// The two filters' orientations at the previous row (parent, child), for their
    /// heading drift at rest.
    prev_q: Option<(Quat, Quat)>,
    rating: f64,
    /// `h_Δ² / R` for a horizontal axis: the rating's scale.
    info_scale: f64,
    /// Each channel's normalized innovation (the constraint's up to three components, then
    /// the joint centre's three), low-passed, and the variance the low-pass has under the
    /// model ([`JointEstimator::inconsistent`]).
    consistency: [f64; 6],
    consistency_var: [f64; 6],
    /// Seconds of motion left with the acquisition's step bound ([`ACQUIRE_TIME`]).
    acquiring: f64,
}

impl JointEstimator {
    pub(crate) fn new(kind: JointKind, axis_parent: Vec3, axis_child: Vec3, params: JointParams) -> Self {
        let mut p = [[0.0; N]; N];
        for k in 0..N {
            p[k][k] = initial_std(&params, k) * initial_std(&params, k);
        }
        JointEstimator {
            kind,
            p_axis: Axis::new(axis_parent),
            c_axis: Axis::new(axis_child),
            x: [0.0; N],
            p,
            params,
            acquiring: if params.heading_std0 > ACQUIRE_STD { ACQUIRE_TIME } else { 0.0 },
            still: 0.0,
            g: [Vec3::ZERO; 2],
            prev_gyro: None,
            prev_q: None,
            rating: 0.0,
            info_scale: 1.0,
            consistency: [0.0; 6],
            consistency_var: [0.0; 6],
        }
    }

    /// Takes another tuning from the next update on.
    pub(crate) fn set_params(&mut self, params: JointParams) {
        self.params = params;
    }

    /// Every state and covariance entry is finite.
    pub(crate) fn is_finite(&self) -> bool {
        self.x
            .iter()
            .chain(self.p.iter().flatten())
            .chain(&self.consistency)
            .chain(&self.consistency_var)
            .all(|v| v.is_finite())
            && self.p_axis.j.is_finite()
            && self.c_axis.j.is_finite()
    }

    /// A row without both sensors' readings: the estimate holds, and the next row takes
    /// neither its angular acceleration nor the filters' drift across the gap.
    pub(crate) fn hold(&mut self) {
        self.prev_gyro = None;
        self.prev_q = None;
    }

    /// The relative heading `Δ` (rad).
    pub(crate) fn heading(&self) -> f64 {
        self.x[0]
    }

    /// The correction's drift at the last motion (rad/s): `g_c·β_c − g_p·β_p`.
    pub(crate) fn drift(&self) -> f64 {
        let v = |o: usize| Vec3::new(self.x[o], self.x[o + 1], self.x[o + 2]);
        self.g[1].dot(v(BC)) - self.g[0].dot(v(BP))
    }

    /// The child's correction, earth frame: `T(φ) ⊗ R_z(Δ)`.
    pub(crate) fn correction(&self) -> Quat {
        let t = Vec3::new(self.x[TX], self.x[TX + 1], 0.0);
        let a = t.norm();
        let tilt = if a > 1e-12 { Quat::from_axis_angle(t, a) } else { Quat::new(1.0, 0.0, 0.0, 0.0) };
        tilt * rot_z(self.x[0])
    }

    /// The standard deviation of `Δ` (rad).
    pub(crate) fn heading_std(&self) -> f64 {
        self.p[0][0].max(0.0).sqrt()
    }

    /// The observability rating in [0, 1].
    pub(crate) fn rating(&self) -> f64 {
        self.rating
    }

    /// The axes as refined (unit, sensor frames).
    pub(crate) fn axes(&self) -> (Vec3, Vec3) {
        (self.p_axis.j, self.c_axis.j)
    }

    /// One sample: the two sensors' orientations (sensor to earth, the child's without
    /// this joint's correction), their gyroscope (rad/s) and accelerometer (m/s²)
    /// readings, and the interval `dt` (s). A `dt` outside [`MIN_DT`, 1) s (1 ns, the
    /// filters' smallest) holds the estimate, as a row without readings does
    /// ([`JointEstimator::hold`]).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn update(
        &mut self,
        q_p: Quat,
        q_c: Quat,
        gyro_p: Vec3,
        gyro_c: Vec3,
        acc_p: Vec3,
        acc_c: Vec3,
        dt: f64,
        learns: [bool; 2],
    ) {
        let prm = self.params;
        if !(MIN_DT..1.0).contains(&dt) {
            self.hold();
            return;
        }
        let prev = self.prev_gyro.replace((gyro_p, gyro_c));
        let moving = gyro_p.norm_squared().max(gyro_c.norm_squared()) > prm.rest_gyro * prm.rest_gyro;
        self.still = if moving { 0.0 } else { self.still + dt };
        let alpha = dt / (prm.rating_tau + dt);
        let rest = !moving && self.still >= prm.rest_time;
        for k in TX..N {
            self.p[k][k] += prm.q_tilt * dt;
        }
        if !rest {
            self.g = [q_p.rotate_inverse(UP), q_c.rotate_inverse(UP)];
            self.predict(dt, learns);
        }
        self.bound_variances();
        let rz = self.correction();
        let tilt = |v: Vec3, h: &mut [f64; N], i: usize| {
            h[TX] = comp(Vec3::new(1.0, 0.0, 0.0).cross(v), i);
            h[TX + 1] = comp(Vec3::new(0.0, 1.0, 0.0).cross(v), i);
        };
        let e_p = q_p.rotate(self.p_axis.j);
        let e_c = rz.rotate(q_c.rotate(self.c_axis.j));
        let dp = [q_p.rotate(self.p_axis.b1), q_p.rotate(self.p_axis.b2)];
        let dc = [rz.rotate(q_c.rotate(self.c_axis.b1)), rz.rotate(q_c.rotate(self.c_axis.b2))];
        let mut dx = [0.0; N];
        let rate = if self.acquiring > 0.0 && !rest { prm.max_rate.max(ACQUIRE_RATE) } else { prm.max_rate };
        let step = rate * dt;
        if !rest {
            self.acquiring = (self.acquiring - dt).max(0.0);
        }
        let mut info = 0.0;
        let mut n = [None; 6];
        match (rest, self.kind) {
            (true, _) => {
                if let (Some((qp0, qc0)), true) = (self.prev_q, prm.r_drift > 0.0) {
                    self.drift_update(q_p, q_c, qp0, qc0, dt, &mut dx, step);
                }
            }
            (false, JointKind::Hinge) => {
                let r = e_p - e_c;
                let d_delta = -UP.cross(e_c);
                let rr = prm.r_hinge / dt;
                for i in 0..3 {
                    let mut h = [0.0; N];
                    h[0] = comp(d_delta, i);
                    h[UP_] = comp(dp[0], i);
                    h[UP_ + 1] = comp(dp[1], i);
                    h[UC] = -comp(dc[0], i);
                    h[UC + 1] = -comp(dc[1], i);
                    tilt(-e_c, &mut h, i);
                    info += h[0] * h[0] / rr;
                    n[i] = self.scalar_update(&h, -comp(r, i), rr, &mut dx, step);
                }
                self.info_scale = 1.0 / rr;
            }
            (false, JointKind::TwoDof) => {
                let f = e_p.dot(e_c);
                let mut h = [0.0; N];
                h[0] = e_p.dot(UP.cross(e_c));
                h[UP_] = dp[0].dot(e_c);
                h[UP_ + 1] = dp[1].dot(e_c);
                h[UC] = e_p.dot(dc[0]);
                h[UC + 1] = e_p.dot(dc[1]);
                h[TX] = e_p.dot(Vec3::new(1.0, 0.0, 0.0).cross(e_c));
                h[TX + 1] = e_p.dot(Vec3::new(0.0, 1.0, 0.0).cross(e_c));
                let rr = prm.r_2dof / dt;
                info += h[0] * h[0] / rr;
                n[0] = self.scalar_update(&h, -f, rr, &mut dx, step);
                self.info_scale = 1.0 / rr;
            }
        }
        if let (true, false, Some((gp0, gc0))) = (prm.r_acc > 0.0, rest, prev) {
            let (wp, wc) = (gyro_p, gyro_c);
            let (dwp, dwc) = ((gyro_p - gp0) * (1.0 / dt), (gyro_c - gc0) * (1.0 / dt));
            let m = |w: Vec3, dw: Vec3, o: Vec3| w.cross(w.cross(o)) + dw.cross(o);
            let vec = |o: usize| Vec3::new(self.x[o], self.x[o + 1], self.x[o + 2]);
            let (op, oc) = (vec(OP), vec(OC));
            let fp = q_p.rotate(acc_p + m(wp, dwp, op));
            let fc = rz.rotate(q_c.rotate(acc_c + m(wc, dwc, oc)));
            let r = fp - fc;
            let d_delta = -UP.cross(fc);
            let unit = [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), UP];
            let cp = unit.map(|e| q_p.rotate(m(wp, dwp, e)));
            let cc = unit.map(|e| rz.rotate(q_c.rotate(m(wc, dwc, e))));
            let (ws, als) = (prm.acc_rate_scale, prm.acc_accel_scale);
            let motion = (wp.dot(wp) + wc.dot(wc)) / (ws * ws) + (dwp.dot(dwp) + dwc.dot(dwc)) / (als * als);
            let rr = prm.r_acc / dt * (1.0 + motion);
            for i in 0..3 {
                let mut h = [0.0; N];
                h[0] = comp(d_delta, i);
                for k in 0..3 {
                    h[OP + k] = comp(cp[k], i);
                    h[OC + k] = -comp(cc[k], i);
                }
                tilt(-fc, &mut h, i);
                n[3 + i] = self.scalar_update(&h, -comp(r, i), rr, &mut dx, step);
            }
        }
        if self.inconsistent(&n, dt) {
            self.reopen();
        }
        // At rest `info` is 0: the rating decays with the low-pass's time constant.
        self.rating += alpha * ((info / self.info_scale).min(1.0) - self.rating);
        // Each update kept the steps within the bound but for rounding.
        for k in [0, TX, TX + 1] {
            dx[k] = dx[k].clamp(-step, step);
        }
        self.x[0] += dx[0];
        for k in BP..UP_ {
            self.x[k] += dx[k];
        }
        self.p_axis.fold(dx[UP_], dx[UP_ + 1]);
        self.c_axis.fold(dx[UC], dx[UC + 1]);
        for k in OP..TX {
            self.x[k] += dx[k];
        }
        for k in TX..N {
            self.x[k] += dx[k];
        }
        self.bound_states();
        self.prev_q = Some((q_p, q_c));
    }

    /// At rest each filter's heading turns only at its residual gyroscope bias, `ψ̇ =
    /// −g·β` (sensor still: the gyroscope reads the bias, the filter turns by what it did
    /// not subtract), so the difference of the two filters' heading rates measures the
    /// relative drift: `ψ̇_c − ψ̇_p = g_p·β_p − g_c·β_c`, with noise density `r_drift`.
    /// The rates come from the filters' orientations at this row and the last, `ψ̇ = 2
    /// (q q₀*)_z / dt` (the vertical part of the earth-frame turn). A turn of the two
    /// sensors together cancels; a difference faster than twice `rest_gyro` is no drift of
    /// still sensors but the host turning a filter (a heading alignment) and is left out.
    #[allow(clippy::too_many_arguments)]
    fn drift_update(
        &mut self,
        q_p: Quat,
        q_c: Quat,
        qp0: Quat,
        qc0: Quat,
        dt: f64,
        dx: &mut [f64; N],
        step: f64,
    ) {
        let yaw_rate = |q: Quat, q0: Quat| {
            let d = q * q0.conj();
            2.0 * if d.w < 0.0 { -d.z } else { d.z } / dt
        };
        let measured = yaw_rate(q_c, qc0) - yaw_rate(q_p, qp0);
        // (NaN cannot arise: the orientations are unit and dt at least 1 ns.)
        if measured.abs() > 2.0 * self.params.rest_gyro {
            return;
        }
        let (g_p, g_c) = (q_p.rotate_inverse(UP), q_c.rotate_inverse(UP));
        let mut h = [0.0; N];
        for k in 0..3 {
            h[BP + k] = comp(g_p, k);
            h[BC + k] = -comp(g_c, k);
        }
        let predicted: f64 = (0..N).map(|k| h[k] * self.x[k]).sum();
        let _ = self.scalar_update(&h, measured - predicted, self.params.r_drift / dt, dx, step);
    }

    /// Low-passes each channel's normalized innovation `n = ν / √S` over
    /// [`CONSISTENCY_TAU`] (`c ← c + a (n − c)`, `a = dt / (τ + dt)`), with the variance
    /// `v` that `c` has under the model, where `n` has unit variance from row to row
    /// (`v ← (1 − a)² v + a²`, about `dt / (2τ)`), and tells whether the largest `c² / v`
    /// is beyond [`CONSISTENCY_LIMIT`]. The model's noise is a density (`R = r / dt`), so
    /// `v` is what a consistent channel's `c²` stays near whatever the rows' `dt`: a short
    /// row moves both little. Once `v` has settled (after a few τ; then `c² / v` is
    /// `c² 2τ / dt` within 0.1 % at 100 Hz), on the simulated gloves and leg
    /// (`rig_joints`, seeds 1-6, every case) it stays below 300 (7 but for the biases to
    /// 3°/s and the leg, while their filters learn the biases); in the first rows after a
    /// start it is `n²` and larger, where a widening changes little. Rows that contradict the estimate grossly (a
    /// sensor that slipped in its strap, readings no rig gives) pass the limit, 1000,
    /// within a few rows; a steady disagreement `e` when `e²` passes about `500 r / τ` (a
    /// hinge's axes with the defaults: 14°).
    fn inconsistent(&mut self, n: &[Option<f64>; 6], dt: f64) -> bool {
        let a = dt / (CONSISTENCY_TAU + dt);
        let mut worst: f64 = 0.0;
        for c in 0..6 {
            if let Some(n) = n[c] {
                self.consistency[c] += a * (n - self.consistency[c]);
                self.consistency_var[c] = (1.0 - a) * (1.0 - a) * self.consistency_var[c] + a * a;
                worst = worst.max(self.consistency[c] * self.consistency[c] / self.consistency_var[c]);
            }
        }
        worst > CONSISTENCY_LIMIT
    }

    /// While the joint's rows contradict its estimate ([`JointEstimator::inconsistent`]),
    /// each variance is held at least at its initial value in the current tuning (a
    /// partial start: a `*_std0` set since applies here too), `P ← P + diag(max(0, σ₀ᵢ² −
    /// Pᵢᵢ))` (positive semi-definite and symmetric as before): an estimate sure of a wrong
    /// state (axes turned by contradicting rows, with `q_axis` 0 nothing widens them
    /// again) would otherwise down-weight the good rows that follow and take hours to
    /// come back; re-opened, it comes back as from a start (within 2 degrees in two
    /// minutes, `contradicting_rows_leave_a_joint_good_rows_bring_back`).
    fn reopen(&mut self) {
        for i in 0..N {
            let std0 = initial_std(&self.params, i);
            self.p[i][i] = self.p[i][i].max(std0 * std0);
        }
        // As from a start: with the headings unknown, acquired again.
        if self.params.heading_std0 > ACQUIRE_STD {
            self.acquiring = ACQUIRE_TIME;
        }
    }

    /// Input that no rig could give, for long (readings that contradict the orientations,
    /// the joint's axes or each other), drives some states without end: a residual bias
    /// of radians a second, a tilt that turns the child upside down, from which good rows
    /// never bring the joint back and whose blob no longer loads. Each residual bias,
    /// lever-arm and tilt component is held within the largest initial standard deviation
    /// [`JOINT_PARAMS`] accepts for it (0.1 rad/s, 1 m, 0.5 rad): beyond every rig the
    /// table describes, so a working rig never meets the bound.
    fn bound_states(&mut self) {
        for k in (0..N).filter(|&k| bounded(k)) {
            self.x[k] = self.x[k].clamp(-largest_std(k), largest_std(k));
        }
    }

    /// A state nothing has told about for long (a vertical hinge for hours, a tilt at
    /// rest) would see its variance grow without end, until a blob of it no longer loads
    /// ([`JointEstimator::holds`]): each variance is held to the square of its initial
    /// standard deviation's largest value in [`JOINT_PARAMS`] by `P ← D P D`,
    /// `D_ii = min(1, √(c_i / P_ii))`, which keeps the correlations and `P` positive
    /// semi-definite (and symmetric bit for bit: each entry is scaled by `D_ii D_kk`).
    fn bound_variances(&mut self) {
        let mut d = [1.0; N];
        let mut any = false;
        for i in 0..N {
            let c = largest_std(i) * largest_std(i);
            if self.p[i][i] > c {
                d[i] = (c / self.p[i][i]).sqrt();
                any = true;
            }
        }
        if any {
            for i in 0..N {
                for k in 0..N {
                    let s = d[i] * d[k];
                    self.p[i][k] *= s;
                }
            }
        }
    }

    /// `Δ ← Δ + dt fᵀx`, `P ← F P Fᵀ + Q dt` with `F = I + dt e₀ fᵀ`,
    /// `f = [0, −g_p, g_c, 0 …]`, the filters' learning ([`JointEstimator::learn`]) between
    /// the two.
    fn predict(&mut self, dt: f64, learns: [bool; 2]) {
        let prm = self.params;
        let mut f = [0.0; N];
        for k in 0..3 {
            f[BP + k] = -comp(self.g[0], k);
            f[BC + k] = comp(self.g[1], k);
        }
        self.x[0] += dt * (0..N).map(|k| f[k] * self.x[k]).sum::<f64>();
        // F P Fᵀ = P + dt (e₀ vᵀ + v e₀ᵀ) + dt² (fᵀ P f) e₀ e₀ᵀ, v = P f.
        let mut v = [0.0; N];
        for (i, vi) in v.iter_mut().enumerate() {
            *vi = (0..N).map(|k| self.p[i][k] * f[k]).sum();
        }
        let fpf: f64 = (0..N).map(|k| f[k] * v[k]).sum();
        for k in 0..N {
            self.p[0][k] += dt * v[k];
            self.p[k][0] += dt * v[k];
        }
        self.p[0][0] += dt * dt * fpf + prm.q_heading * dt;
        if prm.bias_learn_rate > 0.0 {
            // The share learned over dt, exactly: 1 − e^(−λ dt), in [0, 1) for every rate
            // and step the table and the update accept (λ ≤ 10, dt < 1 s).
            let l = -libm::expm1(-prm.bias_learn_rate * dt);
            if learns[0] {
                self.learn(BP, self.g[0], l);
            }
            if learns[1] {
                self.learn(BC, self.g[1], l);
            }
        }
        for k in BP..UP_ {
            self.p[k][k] += prm.q_rate * dt;
        }
        for k in UP_..OP {
            self.p[k][k] += prm.q_axis * dt;
        }
        for k in OP..TX {
            self.p[k][k] += prm.q_lever * dt;
        }
    }

    /// A filter's learning over one step for the residual bias at `o`, `g` the vertical in
    /// its sensor's frame and `l = 1 − e^(−λ dt)` the share learned: `β ← A β`,
    /// `P ← T P Tᵀ` with `T` the identity but for `A = I − l (I − g gᵀ)` on the bias's
    /// three states.
    fn learn(&mut self, o: usize, g: Vec3, l: f64) {
        let mut a = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                let id = if i == j { 1.0 } else { 0.0 };
                a[i][j] = id - l * (id - comp(g, i) * comp(g, j));
            }
        }
        let times_a =
            |v: [f64; 3]| -> [f64; 3] { core::array::from_fn(|i| (0..3).map(|j| a[i][j] * v[j]).sum()) };
        let beta = times_a([self.x[o], self.x[o + 1], self.x[o + 2]]);
        self.x[o..o + 3].copy_from_slice(&beta);
        for c in 0..N {
            let col = times_a([self.p[o][c], self.p[o + 1][c], self.p[o + 2][c]]);
            for i in 0..3 {
                self.p[o + i][c] = col[i];
            }
        }
        for row in self.p.iter_mut() {
            let r = times_a([row[o], row[o + 1], row[o + 2]]);
            row[o..o + 3].copy_from_slice(&r);
        }
        // The block's own entries rounded differently on the two sides: symmetric again.
        for i in o..o + 3 {
            for c in 0..N {
                self.p[c][i] = self.p[i][c];
            }
        }
    }

    /// A scalar measurement `0 = z + h δx + v` with innovation `nu` before `δx` and noise
    /// variance `r`, the step of `Δ` and of `φ` this sample kept within `±step`. Where the
    /// bound cuts the step to a fraction `f` of the gain's, the whole update takes the
    /// gain `f K`, and the covariance what that gain removes (Joseph's form,
    /// `P ← P − (2f − f²) P hᵀ h P / S`): the estimate stays as uncertain as the step it
    /// did not take, and goes on at the bound.
    fn scalar_update(&mut self, h: &[f64; N], nu: f64, r: f64, dx: &mut [f64; N], step: f64) -> Option<f64> {
        let mut ph = [0.0; N];
        for i in 0..N {
            ph[i] = (0..N).map(|k| self.p[i][k] * h[k]).sum();
        }
        let hph: f64 = (0..N).map(|k| h[k] * ph[k]).sum();
        let nu = nu - (0..N).map(|k| h[k] * dx[k]).sum::<f64>();
        let mut s = hph + r;
        let g2 = self.params.gate * self.params.gate;
        if nu * nu > g2 * s {
            s = hph + r * nu * nu / (g2 * s);
        }
        if !(s.is_finite() && s > 0.0 && nu.is_finite()) {
            return None;
        }
        let normalized = (nu / (hph + r).sqrt()).clamp(-CONSISTENCY_MAX_NU, CONSISTENCY_MAX_NU);
        let mut f: f64 = 1.0;
        for k in [0, TX, TX + 1] {
            let change = ph[k] / s * nu;
            let to = dx[k] + change;
            if to.abs() > step && change != 0.0 {
                f = f.min(((step.copysign(change) - dx[k]) / change).clamp(0.0, 1.0));
            }
        }
        for i in 0..N {
            dx[i] += f * ph[i] / s * nu;
        }
        let taken = (2.0 * f - f * f) / s;
        for i in 0..N {
            for k in 0..N {
                self.p[i][k] -= ph[i] * ph[k] * taken;
            }
        }
        // A measurement that all but fixes a state (a lever arm under fast rotation) leaves
        // its variance at rounding level, which can fall below zero: it is zero.
        for i in 0..N {
            self.p[i][i] = self.p[i][i].max(0.0);
        }
        Some(normalized)
    }
}

impl JointEstimator {
    /// The estimate's state, both directions ([`crate::filters::state::Codec`]); the kind
    /// and the tuning are the rig's (checked by [`super::Joints::load`]).
    pub(crate) fn codec(&mut self, c: &mut dyn crate::filters::state::Codec) {
        for axis in [&mut self.p_axis, &mut self.c_axis] {
            c.vec3(&mut axis.j);
            c.vec3(&mut axis.b1);
            c.vec3(&mut axis.b2);
        }
        for v in self.x.iter_mut().chain(self.p.iter_mut().flatten()) {
            c.f64(v);
        }
        c.f64(&mut self.still);
        c.f64(&mut self.acquiring);
        c.vec3(&mut self.g[0]);
        c.vec3(&mut self.g[1]);
        let mut moving = self.prev_gyro.is_some();
        c.bool(&mut moving);
        let (mut a, mut b) = self.prev_gyro.unwrap_or((Vec3::ZERO, Vec3::ZERO));
        c.vec3(&mut a);
        c.vec3(&mut b);
        self.prev_gyro = moving.then_some((a, b));
        let mut had = self.prev_q.is_some();
        c.bool(&mut had);
        let (mut qp, mut qc) = self.prev_q.unwrap_or((Quat::IDENTITY, Quat::IDENTITY));
        c.quat(&mut qp);
        c.quat(&mut qc);
        self.prev_q = had.then_some((qp, qc));
        c.f64(&mut self.rating);
        c.f64(&mut self.info_scale);
        for v in self.consistency.iter_mut().chain(&mut self.consistency_var) {
            c.f64(v);
        }
    }

    /// For tests: the variance of state `i`.
    #[cfg(test)]
    pub(crate) fn variance(&self, i: usize) -> f64 {
        self.p[i][i]
    }

    /// Seconds of motion left with the acquisition's bound.
    #[cfg(test)]
    pub(crate) fn acquiring(&self) -> f64 {
        self.acquiring
    }

    /// For tests: states no estimate could hold, each finite (so that only `holds`
    /// refuses them): a negative variance, a tilt beyond its bound, an indefinite
    /// covariance (a correlation of 1.004), an asymmetric one, a residual bias, a
    /// low-passed innovation and its variance just beyond their bounds, more acquisition
    /// time left than [`ACQUIRE_TIME`], a previous orientation that is not unit.
    #[cfg(test)]
    pub(crate) fn corrupt_for_test(&mut self, how: usize) {
        match how {
            0 => self.p[3][3] = -1.0,
            1 => self.x[TX] = 1e200,
            2 => {
                let c = 1.004 * (self.p[UP_][UP_] * self.p[UP_ + 1][UP_ + 1]).sqrt();
                self.p[UP_][UP_ + 1] = c;
                self.p[UP_ + 1][UP_] = c;
            }
            3 => self.p[0][5] += 1e-9,
            // Just beyond the bounds `bound_states` and the consistency check keep.
            4 => self.x[BP] = largest_std(BP) * (1.0 + 1e-15),
            5 => self.consistency[3] = -CONSISTENCY_MAX_NU * (1.0 + 1e-15),
            6 => self.consistency_var[0] = 1.0 + 1e-15,
            7 => self.acquiring = ACQUIRE_TIME * (1.0 + 1e-15),
            _ => self.prev_q = Some((Quat::new(1.0, 1e-4, 0.0, 0.0), Quat::IDENTITY)),
        }
    }

    /// A state this estimator could hold (a loaded blob's): unit, orthogonal axes with
    /// their bases; states within their bounds (relative heading 1e9 rad, which a heading
    /// turning at the largest `max_rate` for decades does not reach; the residual biases,
    /// lever arms and tilt within those [`JointEstimator::bound_states`] holds them to;
    /// the axis corrections, folded into the axes after each update, 1 rad); an exactly symmetric covariance (every
    /// update keeps it so) that is positive semi-definite to rounding (a Cholesky
    /// factorisation of P + 1e-9 max(P_ii) I), with variances up to 1e6: anything else
    /// could make an innovation's variance negative, and the joint skip every update; a
    /// rating in [0, 1], a rest time not negative, acquisition time left within [0,
    /// [`ACQUIRE_TIME`]], a positive information scale, the
    /// low-passed normalized innovations within their bound ([`CONSISTENCY_MAX_NU`]) and
    /// their variances in [0, 1], unit previous orientations, and a finite correction.
    pub(crate) fn holds(&self) -> bool {
        let unit = |v: Vec3| (v.norm_squared() - 1.0).abs() < 1e-9;
        let axes = [self.p_axis, self.c_axis].iter().all(|a| {
            unit(a.j) && unit(a.b1) && unit(a.b2) && a.j.dot(a.b1).abs() < 1e-9 && a.j.dot(a.b2).abs() < 1e-9
        });
        let states = self.x[0].abs() <= 1e9
            && (UP_..OP).all(|k| self.x[k].abs() <= 1.0)
            && (0..N).filter(|&k| bounded(k)).all(|k| self.x[k].abs() <= largest_std(k));
        self.is_finite()
            && axes
            && states
            && self.covariance_holds()
            && (0.0..=1.0).contains(&self.rating)
            && self.still >= 0.0
            && (0.0..=ACQUIRE_TIME).contains(&self.acquiring)
            && self.info_scale > 0.0
            && self.consistency.iter().all(|c| c.abs() <= CONSISTENCY_MAX_NU)
            && self.consistency_var.iter().all(|v| (0.0..=1.0).contains(v))
            && self.prev_q.map_or(true, |(a, b)| is_unit(a) && is_unit(b))
            && self.correction().is_finite()
    }

    /// P symmetric bit for bit, its diagonal in [0, 1e6], and P + 1e-9 max(P_ii) I
    /// positive definite (Cholesky).
    fn covariance_holds(&self) -> bool {
        let p = &self.p;
        let symmetric = (0..N).all(|i| (0..i).all(|k| p[i][k].to_bits() == p[k][i].to_bits()));
        if !symmetric || !(0..N).all(|i| (0.0..=1e6).contains(&p[i][i])) {
            return false;
        }
        let jitter = 1e-9 * (0..N).map(|i| p[i][i]).fold(1e-300, f64::max);
        let mut l = [[0.0; N]; N];
        for i in 0..N {
            for k in 0..=i {
                let sum: f64 = (0..k).map(|m| l[i][m] * l[k][m]).sum();
                if i == k {
                    let d = p[i][i] + jitter - sum;
                    if d.is_nan() || d <= 0.0 {
                        return false;
                    }
                    l[i][i] = d.sqrt();
                } else {
                    l[i][k] = (p[i][k] - sum) / l[k][k];
                }
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A heading measurement whose step the bound cuts: the state moves by the bound, and
    /// the covariance loses `(2f − f²) P hᵀ h P / S` (Joseph's form for the gain `f K`),
    /// not the full `P hᵀ h P / S`, so the heading stays uncertain.
    #[test]
    fn a_cut_step_takes_the_gain_f_k_and_its_covariance() {
        let params = JointParams { heading_std0: 0.5, ..JointParams::default() };
        let x = Vec3::new(1.0, 0.0, 0.0);
        let mut e = JointEstimator::new(JointKind::Hinge, x, x, params);
        let before = e.clone();
        let mut h = [0.0; N];
        h[0] = 1.0;
        h[UP_] = 0.3;
        let (nu, r, step) = (0.4, 1e-4, 1e-3);
        let mut dx = [0.0; N];
        e.scalar_update(&h, nu, r, &mut dx, step);
        // The readable form: P hᵀ, S = h P hᵀ + R, the gain's step K ν, its fraction f.
        let ph: Vec<f64> = (0..N).map(|i| (0..N).map(|k| before.p[i][k] * h[k]).sum()).collect();
        let s = (0..N).map(|k| h[k] * ph[k]).sum::<f64>() + r;
        assert!(nu * nu <= params.gate * params.gate * s, "inside the gate");
        let f = step / (ph[0] / s * nu);
        assert!(f > 0.0 && f < 0.01, "{f}");
        assert!((dx[0] - step).abs() <= 1e-18, "{}", dx[0]);
        for i in 0..N {
            assert!((dx[i] - f * ph[i] / s * nu).abs() <= 1e-15, "dx[{i}]");
            for k in 0..N {
                let want = before.p[i][k] - (2.0 * f - f * f) * ph[i] * ph[k] / s;
                assert!((e.p[i][k] - want).abs() <= 1e-15, "P[{i}][{k}]: {} vs {want}", e.p[i][k]);
            }
        }
        // Most of the heading's variance is left: the next samples go on at the bound.
        assert!(e.p[0][0] > 0.98 * before.p[0][0], "{} of {}", e.p[0][0], before.p[0][0]);
    }

    /// The filters' learning in the prediction, term by term: each residual bias keeps
    /// its vertical part `g (g·β)` and loses `1 − e^(−λ dt)` of its horizontal part, and
    /// the covariance is `T P Tᵀ` with `A = I − l (I − g gᵀ)` on each bias's block; the
    /// relative heading moves with the biases before the step, as without the learning.
    #[test]
    fn the_prediction_takes_the_filters_learning_of_their_horizontal_bias() {
        let x = Vec3::new(1.0, 0.0, 0.0);
        let (lambda, dt) = (0.5, 0.01);
        let run = |bias_learn_rate: f64| {
            let params = JointParams { bias_learn_rate, ..JointParams::default() };
            let mut e = JointEstimator::new(JointKind::Hinge, x, x, params);
            let b = [Vec3::new(0.01, -0.02, 0.03), Vec3::new(-0.004, 0.005, 0.006)];
            for (o, v) in [(BP, b[0]), (BC, b[1])] {
                e.x[o..o + 3].copy_from_slice(&[v.x, v.y, v.z]);
            }
            // A full covariance: every entry coupled to the biases.
            for i in 0..N {
                for k in 0..N {
                    e.p[i][k] += 1e-6 * (1.0 + ((i * k) % 7) as f64) * if i == k { 10.0 } else { 0.1 };
                }
            }
            e.g = [Vec3::new(0.3, -0.4, 0.5).normalized(), Vec3::new(-0.6, 0.0, 0.8)];
            let before = e.clone();
            e.predict(dt, [true, true]);
            (before, e)
        };
        let (b0, plain) = run(0.0);
        let (before, e) = run(lambda);
        let l = 1.0 - (-lambda * dt).exp();
        // T, the readable form: the identity but for A on each bias's block.
        let mut t = [[0.0; N]; N];
        for i in 0..N {
            t[i][i] = 1.0;
        }
        for (o, g) in [(BP, before.g[0]), (BC, before.g[1])] {
            let beta = Vec3::new(before.x[o], before.x[o + 1], before.x[o + 2]);
            let vertical = g * g.dot(beta);
            let want = vertical + (beta - vertical) * (1.0 - l);
            for i in 0..3 {
                assert!((e.x[o + i] - comp(want, i)).abs() <= 1e-15 * beta.norm(), "β[{}]", o + i);
                for j in 0..3 {
                    let id = if i == j { 1.0 } else { 0.0 };
                    t[o + i][o + j] = id - l * (id - comp(g, i) * comp(g, j));
                }
            }
        }
        assert!(e.covariance_holds());
        // Without the learning the prediction leaves the biases; Δ moves the same.
        assert_eq!(plain.x[BP..UP_], b0.x[BP..UP_]);
        assert_eq!(e.x[0].to_bits(), plain.x[0].to_bits());
        // P after the heading's step (the prediction without learning, less the biases'
        // random walk, which comes after the learning), then T P Tᵀ, then the walk.
        let walk = JointParams::default().q_rate * dt;
        let mut q = plain.p;
        for k in BP..UP_ {
            q[k][k] -= walk;
        }
        for i in 0..N {
            for k in 0..N {
                let mut want: f64 =
                    (0..N).map(|a| (0..N).map(|c| t[i][a] * q[a][c] * t[k][c]).sum::<f64>()).sum();
                if i == k && (BP..UP_).contains(&i) {
                    want += walk;
                }
                assert!((e.p[i][k] - want).abs() <= 1e-18, "P[{i}][{k}]: {} vs {want}", e.p[i][k]);
            }
        }
    }
}
