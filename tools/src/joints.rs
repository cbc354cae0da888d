//! Joint-constraint heading estimation for a rig of 6D filters (issue 42, deliverables 1
//! and 3): online, sample by sample, bounded memory, no allocation per update. A
//! prototype in the tools crate, plugged into [`run_rig`](crate::rig::run_rig) as a
//! [`JointStage`]; the library takes the algorithm over from here.
//!
//! # The model
//!
//! Every sensor runs its own 6D filter; its heading is free and drifts. For each joint
//! the child's orientation is corrected by a rotation about the vertical,
//! `q'_c = R_z(ψ_c) ⊗ q_c`, with `ψ_c = ψ_p + Δ` (the root has `ψ = 0`): `Δ` is the
//! child's heading relative to its parent, estimated from the uncorrected 6D estimates
//! `q_p`, `q_c` of the two sensors (a common turn about the vertical leaves every
//! constraint unchanged, so the parent's own correction does not enter).
//!
//! Per joint an extended Kalman filter with the state
//! `x = [Δ, b, u_p1, u_p2, u_c1, u_c2]`:
//! - `Δ` the relative heading (rad), `b = dΔ/dt` the relative heading drift (rad/s): the
//!   difference of the two sensors' vertical gyro-bias residuals that their filters
//!   leave, which the constraint reveals by the trend of `Δ`;
//! - `u` the axis corrections (rad): `j = normalize(j₀ + u₁ b₁ + u₂ b₂)` with `b₁, b₂` a
//!   basis perpendicular to the axis (error state, folded into `j` after each update and
//!   the basis carried along, `b₁ ← normalize(b₁ − j (j·b₁))`, `b₂ = j × b₁`).
//!
//! Prediction over `dt` (only while moving; at rest both filters hold, and so does the
//! joint): `Δ ← Δ + b dt`, `P ← F P Fᵀ + Q dt`, `F = I + dt E₀₁`,
//! `Q = diag(q_Δ, q_b, q_j, q_j, q_j, q_j)`.
//!
//! Measurements, earth-frame axes `e_p = R(q_p) j_p`, `e_c = R_z(Δ) R(q_c) j_c`:
//! - hinge: `r = e_p − e_c = 0` (three components, processed as scalar updates): the axis
//!   seen from both sides coincides. `∂r/∂Δ = −ẑ × e_c`, `∂r/∂u_pk = R(q_p) b_pk`,
//!   `∂r/∂u_ck = −R_z(Δ) R(q_c) b_ck`. The horizontal part fixes `Δ` (gain ∝ the axis'
//!   horizontal length), the vertical part the axes' tilt.
//! - 2-DoF: `f = e_p · e_c = 0` (Laidig, Weygers, Seel 2022: the first axis, fixed in the
//!   parent, stays perpendicular to the second, fixed in the child).
//!   `∂f/∂Δ = e_p · (ẑ × e_c)`, `∂f/∂u_pk = (R(q_p) b_pk) · e_c`,
//!   `∂f/∂u_ck = e_p · (R_z(Δ) R(q_c) b_ck)`.
//!
//! Each scalar update: `S = h P hᵀ + R`, with `R = r_c / dt` (the residuals' errors,
//! laxity, soft tissue and the filters' inclination errors, are correlated over a fraction
//! of a second: `r_c` is their variance times their correlation time, so the gain does not
//! depend on the rate); an innovation beyond `gate·√S` is down-weighted (`R` scaled by
//! `ν²/(gate² S)`, Huber); `K = P hᵀ / S`, `δx += K (ν − h δx)`, `P ← (I − K h) P`. The
//! step applied to `Δ` is limited to `max_rate · dt` (never a jump).
//!
//! The observability rating per joint is the information the constraint gave about `Δ`,
//! `h_Δ² / R` per unit time, low-passed (time constant [`JointParams::rating_tau`]) and
//! scaled to [0, 1] by its value for a horizontal axis: near 0 while the axis is vertical
//! (a hinge) or the 2-DoF axes leave the heading free, 0 at rest.

// Index loops over the state layout read like the equations.
#![allow(clippy::needless_range_loop)]

use crate::rig::{joint_angles, JointKind, JointStage, RigJoint, RigSpec};
use orient::{Quat, Sample, Vec3};

const UP: Vec3 = Vec3::new(0.0, 0.0, 1.0);
/// Number of states: Δ, β_p (3), β_c (3), u_p (2), u_c (2), o_p (3), o_c (3).
const N: usize = 19;
/// The child's tilt correction (rad, about the earth's x and y), after the heading.
const TX: usize = 17;
const OP: usize = 11;
const OC: usize = 14;
const BP: usize = 1;
const BC: usize = 4;
const UP_: usize = 7;
const UC: usize = 9;

/// Tuning of the joint estimator (continuous-time densities, so independent of the rate).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointParams {
    /// Hinge residual noise density per component, rad²·s.
    pub r_hinge: f64,
    /// 2-DoF residual noise density, rad²·s.
    pub r_2dof: f64,
    /// Random walk of the relative heading, rad²/s.
    pub q_heading: f64,
    /// Random walk of the relative drift rate, rad²/s³ (0 and `rate_std0` 0: no rate state).
    pub q_rate: f64,
    /// Random walk of each axis direction component, rad²/s (0 and `axis_std0` 0: axes fixed).
    pub q_axis: f64,
    /// Initial standard deviations: heading (rad), drift rate (rad/s), axes (rad).
    pub heading_std0: f64,
    pub rate_std0: f64,
    pub axis_std0: f64,
    /// Largest correction of `Δ` per second, rad/s.
    pub max_rate: f64,
    /// Rest: both gyros below this norm (rad/s) for `rest_time` seconds.
    pub rest_gyro: f64,
    pub rest_time: f64,
    /// Joint-centre acceleration residual noise density per component, (m/s²)²·s (0: no
    /// acceleration constraint).
    pub r_acc: f64,
    /// Initial standard deviation (m) and random walk (m²/s) of the joint centre in each sensor frame.
    pub lever_std0: f64,
    pub q_lever: f64,
    /// Initial standard deviation (rad) and random walk (rad²/s) of the relative tilt
    /// correction (0 and 0: heading only).
    pub tilt_std0: f64,
    pub q_tilt: f64,
    /// Innovations beyond this many standard deviations are down-weighted.
    pub gate: f64,
    /// Time constant of the rating's low-pass, s.
    pub rating_tau: f64,
}

impl Default for JointParams {
    fn default() -> JointParams {
        let d = 1f64.to_radians();
        JointParams {
            r_hinge: 0.05f64.powi(2) * 0.5,
            r_2dof: 0.08f64.powi(2) * 0.5,
            q_heading: (0.1 * d).powi(2),
            q_rate: 3e-7,
            q_axis: 0.0,
            heading_std0: 1.0 * d,
            rate_std0: 0.5 * d,
            axis_std0: 0.09,
            max_rate: 5.0 * d,
            rest_gyro: 0.15,
            rest_time: 0.3,
            r_acc: 0.003,
            lever_std0: 0.05,
            q_lever: 1e-10,
            tilt_std0: 0.0,
            q_tilt: 3e-5,
            gate: 3.0,
            rating_tau: 2.0,
        }
    }
}

/// An axis with its perpendicular basis (carried along as the axis is refined).
#[derive(Clone, Copy, Debug)]
struct Axis {
    j: Vec3,
    b1: Vec3,
    b2: Vec3,
}

impl Axis {
    fn new(j: Vec3) -> Axis {
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

    fn fold(&mut self, u1: f64, u2: f64) {
        self.j = (self.j + self.b1 * u1 + self.b2 * u2).normalized();
        self.b1 = (self.b1 - self.j * self.j.dot(self.b1)).normalized();
        self.b2 = self.j.cross(self.b1);
    }
}

/// One joint's estimator: the relative heading of the child, its drift, refined axes.
#[derive(Clone, Debug)]
pub struct JointEstimator {
    pub kind: JointKind,
    p_axis: Axis,
    c_axis: Axis,
    x: [f64; N],
    p: [[f64; N]; N],
    params: JointParams,
    still: f64,
    /// The vertical in the parent's and the child's sensor frame at the last sample.
    g: [Vec3; 2],
    /// The previous gyroscope readings (parent, child), for the angular accelerations.
    prev_gyr: Option<(Vec3, Vec3)>,
    rating: f64,
    /// `h_Δ²/R·dt` for a horizontal axis: the rating's scale.
    info_scale: f64,
}

fn rot_z(psi: f64) -> Quat {
    Quat::new(libm::cos(0.5 * psi), 0.0, 0.0, libm::sin(0.5 * psi))
}

impl JointEstimator {
    pub fn new(kind: JointKind, axis_parent: Vec3, axis_child: Vec3, params: JointParams) -> JointEstimator {
        let mut p = [[0.0; N]; N];
        p[0][0] = params.heading_std0.powi(2);
        for k in BP..UP_ {
            p[k][k] = params.rate_std0.powi(2);
        }
        for k in UP_..OP {
            p[k][k] = params.axis_std0.powi(2);
        }
        for k in OP..TX {
            p[k][k] = params.lever_std0.powi(2);
        }
        for k in TX..N {
            p[k][k] = params.tilt_std0.powi(2);
        }
        JointEstimator {
            kind,
            p_axis: Axis::new(axis_parent),
            c_axis: Axis::new(axis_child),
            x: [0.0; N],
            p,
            params,
            still: 0.0,
            g: [Vec3::ZERO; 2],
            prev_gyr: None,
            rating: 0.0,
            info_scale: 1.0,
        }
    }

    /// The relative heading Δ (rad): turn the child's 6D estimate by `R_z(Δ)` relative to its parent's.
    pub fn heading(&self) -> f64 {
        self.x[0]
    }
    /// The relative heading drift (rad/s) at the last sample:
    /// `dΔ/dt = g_c·β_c − g_p·β_p`.
    pub fn drift(&self) -> f64 {
        let v = |o: usize| Vec3::new(self.x[o], self.x[o + 1], self.x[o + 2]);
        self.g[1].dot(v(BC)) - self.g[0].dot(v(BP))
    }
    /// The child's whole correction (earth frame), `T(φ) ⊗ R_z(Δ)`: the tilt part is
    /// identity unless [`JointParams::tilt_std0`] or `q_tilt` is set.
    pub fn correction(&self) -> Quat {
        let t = Vec3::new(self.x[TX], self.x[TX + 1], 0.0);
        let a = t.norm();
        let tq = if a > 1e-12 { Quat::from_axis_angle(t, a) } else { Quat::IDENTITY };
        tq * rot_z(self.x[0])
    }
    /// The standard deviation of Δ (rad).
    pub fn heading_std(&self) -> f64 {
        self.p[0][0].max(0.0).sqrt()
    }
    /// The observability rating in [0, 1].
    pub fn rating(&self) -> f64 {
        self.rating
    }
    /// The axes as refined (sensor frames).
    pub fn axes(&self) -> (Vec3, Vec3) {
        (self.p_axis.j, self.c_axis.j)
    }

    /// One sample: the two sensors' 6D orientations (sensor to earth, uncorrected) and
    /// gyroscope readings (rad/s), the interval `dt` (s). Returns Δ.
    #[allow(clippy::too_many_arguments)]
    pub fn update(
        &mut self,
        q_p: Quat,
        q_c: Quat,
        gyr_p: Vec3,
        gyr_c: Vec3,
        acc_p: Vec3,
        acc_c: Vec3,
        dt: f64,
    ) -> f64 {
        let prm = self.params;
        if !(dt > 0.0 && dt < 1.0) {
            return self.x[0];
        }
        let prev = self.prev_gyr.replace((gyr_p, gyr_c));
        let moving = gyr_p.norm_squared().max(gyr_c.norm_squared()) > prm.rest_gyro * prm.rest_gyro;
        self.still = if moving { 0.0 } else { self.still + dt };
        let alpha = dt / (prm.rating_tau + dt);
        let rest = self.still >= prm.rest_time;
        for k in TX..N {
            self.p[k][k] += prm.q_tilt * dt;
        }
        if rest {
            self.rating -= alpha * self.rating;
        } else {
            self.g = [q_p.rotate_inverse(UP), q_c.rotate_inverse(UP)];
            self.predict(dt);
        }
        // The child's correction, earth frame: T(φ) R_z(Δ).
        let rz = self.correction();
        let tilt = |v: Vec3, h: &mut [f64; N], i: usize| {
            let comp = |v: Vec3| [v.x, v.y, v.z][i];
            h[TX] = comp(Vec3::new(1.0, 0.0, 0.0).cross(v));
            h[TX + 1] = comp(Vec3::new(0.0, 1.0, 0.0).cross(v));
        };
        let e_p = q_p.rotate(self.p_axis.j);
        let e_c = rz.rotate(q_c.rotate(self.c_axis.j));
        let dp = [q_p.rotate(self.p_axis.b1), q_p.rotate(self.p_axis.b2)];
        let dc = [rz.rotate(q_c.rotate(self.c_axis.b1)), rz.rotate(q_c.rotate(self.c_axis.b2))];
        let mut dx = [0.0; N];
        let mut info = 0.0;
        let kind = if rest { None } else { Some(self.kind) };
        match kind {
            None => {}
            Some(JointKind::Hinge) => {
                let r = e_p - e_c;
                let d_delta = -UP.cross(e_c);
                let comp = |v: Vec3, i: usize| [v.x, v.y, v.z][i];
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
                    self.scalar_update(&h, -comp(r, i), rr, &mut dx);
                }
                self.info_scale = 1.0 / rr;
            }
            Some(JointKind::TwoDof) => {
                let f = e_p.dot(e_c);
                let mut h = [0.0; N];
                h[0] = e_p.dot(UP.cross(e_c));
                h[UP_] = dp[0].dot(e_c);
                h[UP_ + 1] = dp[1].dot(e_c);
                h[UC] = e_p.dot(dc[0]);
                h[UC + 1] = e_p.dot(dc[1]);
                // ∂(e_p·T e_c)/∂φ = e_p·(x̂ × e_c), e_p·(ŷ × e_c).
                h[TX] = e_p.dot(Vec3::new(1.0, 0.0, 0.0).cross(e_c));
                h[TX + 1] = e_p.dot(Vec3::new(0.0, 1.0, 0.0).cross(e_c));
                let rr = prm.r_2dof / dt;
                info += h[0] * h[0] / rr;
                self.scalar_update(&h, -f, rr, &mut dx);
                self.info_scale = 1.0 / rr;
            }
        }
        if let (true, Some((gp0, gc0))) = (prm.r_acc > 0.0, prev) {
            // The joint centre's specific force seen from both sides:
            // r = R_p (a_p + M_p o_p) − R_z(Δ) R_c (a_c + M_c o_c), M o = ω×(ω×o) + ω̇×o.
            let (wp, wc) = (gyr_p, gyr_c);
            let (dwp, dwc) = ((gyr_p - gp0) * (1.0 / dt), (gyr_c - gc0) * (1.0 / dt));
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
            let comp = |v: Vec3, i: usize| [v.x, v.y, v.z][i];
            let rr = prm.r_acc / dt;
            for i in 0..3 {
                let mut h = [0.0; N];
                h[0] = comp(d_delta, i);
                for k in 0..3 {
                    h[OP + k] = comp(cp[k], i);
                    h[OC + k] = -comp(cc[k], i);
                }
                tilt(-fc, &mut h, i);
                self.scalar_update(&h, -comp(r, i), rr, &mut dx);
            }
        }
        self.rating += alpha * ((info / self.info_scale).min(1.0) - self.rating);
        let step = prm.max_rate * dt;
        self.x[0] += dx[0].clamp(-step, step);
        for k in BP..UP_ {
            self.x[k] += dx[k];
        }
        self.p_axis.fold(dx[UP_], dx[UP_ + 1]);
        self.c_axis.fold(dx[UC], dx[UC + 1]);
        for k in OP..TX {
            self.x[k] += dx[k];
        }
        for k in TX..N {
            self.x[k] += dx[k].clamp(-step, step);
        }
        self.x[0]
    }

    fn predict(&mut self, dt: f64) {
        let prm = &self.params;
        // dΔ/dt = f·x with f = [0, −g_p, g_c, 0, 0, 0, 0]; F = I + dt e₀ fᵀ.
        let mut f = [0.0; N];
        for (k, (gp, gc)) in
            [(self.g[0].x, self.g[1].x), (self.g[0].y, self.g[1].y), (self.g[0].z, self.g[1].z)]
                .into_iter()
                .enumerate()
        {
            f[BP + k] = -gp;
            f[BC + k] = gc;
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

    /// A scalar measurement `0 = z_pred + h δx + v`, innovation `nu` (before δx).
    fn scalar_update(&mut self, h: &[f64; N], nu: f64, r: f64, dx: &mut [f64; N]) {
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
        if s.is_nan() || s <= 0.0 {
            return;
        }
        for i in 0..N {
            dx[i] += ph[i] / s * nu;
        }
        for i in 0..N {
            for k in 0..N {
                self.p[i][k] -= ph[i] * ph[k] / s;
            }
        }
    }
}

/// The joint stage of a rig run: one [`JointEstimator`] per joint, children after their
/// parents, corrections applied down the tree.
pub struct Joints {
    /// (parent, child, estimator) in an order where every parent comes before its children.
    pub joints: Vec<(usize, usize, JointEstimator)>,
    /// Each sensor's correction (earth frame), the product of its chain's.
    correction: Vec<Quat>,
    /// The first row estimated (headings aligned there).
    start: usize,
    /// Index into `joints` for each of the spec's joints.
    order: Vec<usize>,
}

impl Joints {
    /// Estimators for every joint of `spec`, starting at row `start` (the row at which the
    /// headings were aligned).
    pub fn new(spec: &RigSpec, start: usize, params: JointParams) -> Joints {
        let n = spec.sensors.len();
        // Depth of each sensor in the tree, for the order.
        let depth = |mut s: usize| {
            let mut d = 0;
            while let Some(j) = spec.joints.iter().find(|j| j.child == s) {
                s = j.parent;
                d += 1;
            }
            d
        };
        let mut idx: Vec<usize> = (0..spec.joints.len()).collect();
        idx.sort_by_key(|&k| depth(spec.joints[k].child));
        let joints: Vec<(usize, usize, JointEstimator)> = idx
            .iter()
            .map(|&k| {
                let j = &spec.joints[k];
                (j.parent, j.child, JointEstimator::new(j.kind, j.axis_parent, j.axis_child, params))
            })
            .collect();
        let mut order = vec![0; spec.joints.len()];
        for (pos, &k) in idx.iter().enumerate() {
            order[k] = pos;
        }
        Joints { joints, correction: vec![Quat::IDENTITY; n], start, order }
    }

    /// The estimator of the spec's joint `k`.
    pub fn estimator(&self, k: usize) -> &JointEstimator {
        &self.joints[self.order[k]].2
    }

    /// Joint `k`'s angles (rad) from corrected sensor orientations, with the refined axes.
    pub fn angles(&self, spec: &RigSpec, k: usize, q_parent: Quat, q_child: Quat) -> (f64, f64) {
        let (a, b) = self.estimator(k).axes();
        let j = RigJoint { axis_parent: a, axis_child: b, ..spec.joints[k].clone() };
        joint_angles(spec, &j, q_parent, q_child)
    }
}

impl JointStage for Joints {
    fn update(&mut self, row: usize, samples: &[Sample], sensors: &mut [Quat]) {
        if row < self.start {
            return;
        }
        for (p, c, est) in self.joints.iter_mut() {
            let s = (&samples[*p], &samples[*c]);
            let (Some(gp), Some(gc), Some(ap), Some(ac)) = (s.0.gyro, s.1.gyro, s.0.accel, s.1.accel) else {
                continue;
            };
            let d = est.update(sensors[*p], sensors[*c], gp, gc, ap, ac, s.1.dt);
            let _ = d;
            self.correction[*c] = (self.correction[*p] * est.correction()).normalized();
        }
        for (_, c, _) in &self.joints {
            sensors[*c] = self.correction[*c] * sensors[*c];
        }
    }
}

/// The batch estimate of a hinge's axes from gyroscope readings alone (Seel, Schauer,
/// Raisch 2012): the axis `j_p` (parent sensor frame) and `j_c` (child's) minimising
/// `Σ (|ω_p × j_p| − |ω_c × j_c|)²` (the angular velocity perpendicular to the axis is
/// the same on both sides of a hinge), by Levenberg-Marquardt over the spherical
/// coordinates of both axes, started from `guess`. Returns the axes (signs as in the
/// guess) and the quality figure: the RMS residual over the RMS of `|ω_p × j_p|`
/// (0 for an ideal hinge; a few per cent for laxity and noise; near 1 when the motion
/// did not excite the axes or the joint is not a hinge).
pub fn estimate_hinge_axes(gyr_p: &[Vec3], gyr_c: &[Vec3], guess: (Vec3, Vec3)) -> (Vec3, Vec3, f64) {
    let sph = |v: Vec3| [libm::asin(v.z.clamp(-1.0, 1.0)), libm::atan2(v.y, v.x)];
    let axis =
        |a: f64, b: f64| Vec3::new(libm::cos(a) * libm::cos(b), libm::cos(a) * libm::sin(b), libm::sin(a));
    let resid = |x: &[f64; 4], i: usize| {
        gyr_p[i].cross(axis(x[0], x[1])).norm() - gyr_c[i].cross(axis(x[2], x[3])).norm()
    };
    let cost = |x: &[f64; 4]| (0..gyr_p.len()).map(|i| resid(x, i).powi(2)).sum::<f64>();
    let (g0, g1) = (sph(guess.0.normalized()), sph(guess.1.normalized()));
    let mut x = [g0[0], g0[1], g1[0], g1[1]];
    let mut lambda = 1e-3;
    let mut c = cost(&x);
    for _ in 0..50 {
        let mut jtj = [[0.0; 4]; 4];
        let mut jtr = [0.0; 4];
        for i in 0..gyr_p.len() {
            let r = resid(&x, i);
            let mut jac = [0.0; 4];
            for k in 0..4 {
                let mut xp = x;
                xp[k] += 1e-6;
                jac[k] = (resid(&xp, i) - r) / 1e-6;
            }
            for a in 0..4 {
                jtr[a] += jac[a] * r;
                for b in 0..4 {
                    jtj[a][b] += jac[a] * jac[b];
                }
            }
        }
        let mut a = jtj;
        for k in 0..4 {
            a[k][k] *= 1.0 + lambda;
        }
        let Some(step) = solve4(a, jtr) else { break };
        let xn = [x[0] - step[0], x[1] - step[1], x[2] - step[2], x[3] - step[3]];
        let cn = cost(&xn);
        if cn < c {
            let done = (c - cn) < 1e-12 * c;
            x = xn;
            c = cn;
            lambda *= 0.3;
            if done {
                break;
            }
        } else {
            lambda *= 10.0;
        }
    }
    let (mut jp, mut jc) = (axis(x[0], x[1]), axis(x[2], x[3]));
    if jp.dot(guess.0) < 0.0 {
        jp = -jp;
    }
    if jc.dot(guess.1) < 0.0 {
        jc = -jc;
    }
    let n = gyr_p.len().max(1) as f64;
    let scale = (gyr_p.iter().map(|w| w.cross(jp).norm_squared()).sum::<f64>() / n).sqrt();
    (jp, jc, (c / n).sqrt() / scale.max(1e-12))
}

/// Solves a 4×4 system by Gaussian elimination with partial pivoting.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for col in 0..4 {
        let piv = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, piv);
        b.swap(col, piv);
        for row in col + 1..4 {
            let f = a[row][col] / a[col][col];
            for k in col..4 {
                a[row][k] -= f * a[col][k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; 4];
    for row in (0..4).rev() {
        x[row] = (b[row] - (row + 1..4).map(|k| a[row][k] * x[k]).sum::<f64>()) / a[row][row];
    }
    Some(x)
}
