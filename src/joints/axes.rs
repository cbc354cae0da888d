//! A joint's axes from a few seconds of motion: a hinge's from the gyroscopes alone, a
//! 2-DoF joint's from the two sensors' 6D orientations.

use super::estimator::Axis;
use crate::math::{Quat, Vec3};

/// A joint's axes estimated from motion ([`estimate_hinge_axes`],
/// [`estimate_two_dof_axes`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointAxes {
    /// The (first) axis in the parent sensor's frame (unit, on the side of the guess).
    pub axis_parent: Vec3,
    /// The hinge's axis, or the 2-DoF joint's second axis, in the child sensor's frame.
    pub axis_child: Vec3,
    /// How far the motion bears the axes out, 0 to 1; below 0.1 they can be trusted. A
    /// hinge: the RMS residual over the RMS angular rate perpendicular to the axis (0
    /// for an ideal hinge, a few hundredths with laxity and noise, near 1 when the motion
    /// did not turn the joint or the joint is no hinge). A 2-DoF joint: the larger of the
    /// RMS residual (rad, how far from perpendicular the axes were seen) and three times
    /// the axes' standard error (rad, large when the motion did not turn the joint about
    /// both axes far enough, as a hinge's does not).
    pub quality: f64,
}

/// The axes `j_p` (parent sensor frame) and `j_c` (child's) of a hinge from gyroscope
/// readings taken at the same instants (rad/s), started from the host's `guess`: the pair
/// minimising `Σ (|ω_p × j_p| − |ω_c × j_c|)²`, since the angular rate perpendicular to a
/// hinge's axis is the same on both sides (Seel, Schauer, Raisch, IEEE Sensors 2012), by
/// Levenberg-Marquardt over the axes' spherical coordinates. A few seconds of the joint
/// turning while the segments move about other axes too are enough. `None` when the
/// slices' lengths differ or are zero, a reading or a guess is not finite, or a guess is
/// too short to normalise (its squared norm below the smallest normal double).
pub fn estimate_hinge_axes(
    gyro_parent: &[Vec3],
    gyro_child: &[Vec3],
    guess: (Vec3, Vec3),
) -> Option<JointAxes> {
    if gyro_parent.len() != gyro_child.len() {
        return None;
    }
    estimate_hinge_axes_by(gyro_parent.len(), |i| (gyro_parent[i], gyro_child[i]), guess)
}

/// [`estimate_hinge_axes`] over `n` pairs of readings `reading(i)` (parent, child), for a
/// host whose readings are not two slices. `None` when `n` is 0, a reading or a guess is
/// not finite, or a guess's squared norm is below the smallest normal double.
pub fn estimate_hinge_axes_by(
    n: usize,
    reading: impl Fn(usize) -> (Vec3, Vec3),
    guess: (Vec3, Vec3),
) -> Option<JointAxes> {
    let usable =
        |v: Vec3| v.is_finite() && v.norm_squared().is_finite() && v.norm_squared() >= f64::MIN_POSITIVE;
    let finite = |i: usize| reading(i).0.is_finite() && reading(i).1.is_finite();
    if n == 0 || !(0..n).all(finite) || !(usable(guess.0) && usable(guess.1)) {
        return None;
    }
    let gyro_parent = |i: usize| reading(i).0;
    let gyro_child = |i: usize| reading(i).1;
    let sph = |v: Vec3| [libm::asin(v.z.clamp(-1.0, 1.0)), libm::atan2(v.y, v.x)];
    let axis =
        |a: f64, b: f64| Vec3::new(libm::cos(a) * libm::cos(b), libm::cos(a) * libm::sin(b), libm::sin(a));
    let resid = |x: &[f64; 4], i: usize| {
        gyro_parent(i).cross(axis(x[0], x[1])).norm() - gyro_child(i).cross(axis(x[2], x[3])).norm()
    };
    let cost = |x: &[f64; 4]| (0..n).map(|i| resid(x, i).powi(2)).sum::<f64>();
    // JᵀJ and Jᵀr by forward differences.
    let normal = |x: &[f64; 4]| {
        let (mut jtj, mut jtr) = ([[0.0; 4]; 4], [0.0; 4]);
        for i in 0..n {
            let r = resid(x, i);
            let mut jac = [0.0; 4];
            for (k, d) in jac.iter_mut().enumerate() {
                let mut xp = *x;
                xp[k] += 1e-6;
                *d = (resid(&xp, i) - r) / 1e-6;
            }
            accumulate(&mut jtj, &mut jtr, &jac, r);
        }
        (jtj, jtr)
    };
    let (g0, g1) = (sph(guess.0.normalized()), sph(guess.1.normalized()));
    let start = [g0[0], g0[1], g1[0], g1[1]];
    let (x, c) = levenberg_marquardt(start, n, cost, normal, |x, step| {
        [x[0] - step[0], x[1] - step[1], x[2] - step[2], x[3] - step[3]]
    });
    let (mut jp, mut jc) = (axis(x[0], x[1]), axis(x[2], x[3]));
    if jp.dot(guess.0) < 0.0 {
        jp = -jp;
    }
    if jc.dot(guess.1) < 0.0 {
        jc = -jc;
    }
    let n = n as f64;
    let scale = ((0..n as usize).map(|i| gyro_parent(i).cross(jp).norm_squared()).sum::<f64>() / n).sqrt();
    let quality = ((c / n).sqrt() / scale.max(1e-12)).min(1.0);
    Some(JointAxes { axis_parent: jp, axis_child: jc, quality })
}

/// Adds one residual `r` with its gradient `jac` to the normal equations `JᵀJ`, `Jᵀr`.
fn accumulate<const P: usize>(jtj: &mut [[f64; P]; P], jtr: &mut [f64; P], jac: &[f64; P], r: f64) {
    for a in 0..P {
        jtr[a] += jac[a] * r;
        for b in 0..P {
            jtj[a][b] += jac[a] * jac[b];
        }
    }
}

/// Levenberg-Marquardt from `start` over `n` residuals: `normal(x)` gives `JᵀJ` and `Jᵀr`,
/// `cost(x)` the sum of squared residuals, `moved(x, δ)` the state turned by `−δ`. The
/// damping is Marquardt's (`λ` times each diagonal entry, at least `10⁻¹² n`); a step
/// that lowers the cost is taken and `λ` shrinks, else `λ` grows; it stops after 100
/// iterations, when a step gains less than `10⁻¹²` of the cost, or when `λ` passes
/// `10¹²`. The state reached and its cost.
fn levenberg_marquardt<S: Copy, const P: usize>(
    start: S,
    n: usize,
    cost: impl Fn(&S) -> f64,
    normal: impl Fn(&S) -> ([[f64; P]; P], [f64; P]),
    moved: impl Fn(&S, &[f64; P]) -> S,
) -> (S, f64) {
    let (mut x, mut c, mut lambda) = (start, cost(&start), 1e-3);
    for _ in 0..100 {
        let (mut jtj, jtr) = normal(&x);
        for (k, row) in jtj.iter_mut().enumerate() {
            row[k] += lambda * row[k].max(1e-12 * n as f64);
        }
        let Some(step) = solve(jtj, jtr) else { break };
        let xn = moved(&x, &step);
        let cn = cost(&xn);
        if cn < c {
            let done = (c - cn) <= 1e-12 * c;
            (x, c) = (xn, cn);
            lambda *= 0.3;
            if done {
                break;
            }
        } else {
            lambda *= 10.0;
            if lambda > 1e12 {
                break;
            }
        }
    }
    (x, c)
}

/// Solves an N×N system by Gaussian elimination with partial pivoting.
#[allow(clippy::needless_range_loop)]
fn solve<const N: usize>(mut a: [[f64; N]; N], mut b: [f64; N]) -> Option<[f64; N]> {
    for col in 0..N {
        let piv = (col..N).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() < 1e-300 || a[piv][col].is_nan() {
            return None;
        }
        a.swap(col, piv);
        b.swap(col, piv);
        for row in col + 1..N {
            let f = a[row][col] / a[col][col];
            for k in col..N {
                a[row][k] -= f * a[col][k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; N];
    for row in (0..N).rev() {
        x[row] = (b[row] - (row + 1..N).map(|k| a[row][k] * x[k]).sum::<f64>()) / a[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The axes `j_1` (parent sensor frame) and `j_2` (child's) of a 2-DoF joint, and the
/// child's heading offset `δ`, from the two sensors' orientations `q_parent[i]`,
/// `q_child[i]` (sensor to earth; 6D estimates will do, whatever their headings, as long
/// as these hold still relative to each other over the window) taken at the same instants,
/// started from the host's `guess`: the pair minimising
/// `Σ ((R(q_p) j_1) · (R_z(δ) R(q_c) j_2))²`, since the first axis, fixed in the parent,
/// stays perpendicular to the second, fixed in the child (Laidig, Weygers, Seel, Sensors
/// 2022), by Levenberg-Marquardt over small turns of each axis and `δ`, from the guess at
/// the four offsets 0, ±90° and 180° (the lowest cost wins). A few seconds of the joint
/// turning about both axes while the segments move are enough. `None` when the slices'
/// lengths differ or are zero, a quaternion is not finite or is too short to normalise,
/// or a guess is not finite or too short to normalise (its squared norm below the
/// smallest normal double).
pub fn estimate_two_dof_axes(q_parent: &[Quat], q_child: &[Quat], guess: (Vec3, Vec3)) -> Option<JointAxes> {
    if q_parent.len() != q_child.len() {
        return None;
    }
    estimate_two_dof_axes_by(q_parent.len(), |i| (q_parent[i], q_child[i]), guess)
}

/// [`estimate_two_dof_axes`] over `n` pairs of orientations `pair(i)` (parent, child),
/// for a host whose orientations are not two slices. `None` as there.
pub fn estimate_two_dof_axes_by(
    n: usize,
    pair: impl Fn(usize) -> (Quat, Quat),
    guess: (Vec3, Vec3),
) -> Option<JointAxes> {
    let usable = |n2: f64| n2.is_finite() && n2 >= f64::MIN_POSITIVE;
    let good = |i: usize| {
        let (p, c) = pair(i);
        p.is_finite() && c.is_finite() && usable(p.norm_squared()) && usable(c.norm_squared())
    };
    let guess_ok = |v: Vec3| v.is_finite() && usable(v.norm_squared());
    if n == 0 || !(0..n).all(good) || !(guess_ok(guess.0) && guess_ok(guess.1)) {
        return None;
    }
    let up = Vec3::new(0.0, 0.0, 1.0);
    let rot_z = |d: f64| Quat::new(libm::cos(0.5 * d), 0.0, 0.0, libm::sin(0.5 * d));
    // The cost and, with `normal`, the normal equations at (j_1, j_2, δ): residual
    // r_i = e_p · e_c with e_p = R(q_p) j_1 and e_c = R_z(δ) R(q_c) j_2; its derivatives
    // along the axes' turns and δ.
    let eval = |a: &Axis, b: &Axis, d: f64, normal: Option<(&mut [[f64; 5]; 5], &mut [f64; 5])>| {
        let rz = rot_z(d);
        let mut cost = 0.0;
        let mut ne = normal;
        for i in 0..n {
            let (p, c) = pair(i);
            let (p, c) = (p.normalized(), (rz * c.normalized()).normalized());
            let (e_p, e_c) = (p.rotate(a.j), c.rotate(b.j));
            let r = e_p.dot(e_c);
            cost += r * r;
            if let Some((jtj, jtr)) = ne.as_mut() {
                let jac = [
                    p.rotate(a.b1).dot(e_c),
                    p.rotate(a.b2).dot(e_c),
                    e_p.dot(c.rotate(b.b1)),
                    e_p.dot(c.rotate(b.b2)),
                    e_p.dot(up.cross(e_c)),
                ];
                accumulate(jtj, jtr, &jac, r);
            }
        }
        cost
    };
    let fit = |d0: f64| {
        let start = (Axis::new(guess.0), Axis::new(guess.1), d0);
        let cost = |x: &(Axis, Axis, f64)| eval(&x.0, &x.1, x.2, None);
        let normal = |x: &(Axis, Axis, f64)| {
            let (mut jtj, mut jtr) = ([[0.0; 5]; 5], [0.0; 5]);
            eval(&x.0, &x.1, x.2, Some((&mut jtj, &mut jtr)));
            (jtj, jtr)
        };
        let ((a, b, d), c) = levenberg_marquardt(start, n, cost, normal, |x, step: &[f64; 5]| {
            let (mut a, mut b) = (x.0, x.1);
            a.fold(-step[0], -step[1]);
            b.fold(-step[2], -step[3]);
            (a, b, x.2 - step[4])
        });
        (c, a, b, d)
    };
    let quarter = core::f64::consts::FRAC_PI_2;
    let (c, a, b, d) =
        [0.0, quarter, -quarter, 2.0 * quarter].map(fit).into_iter().min_by(|x, y| x.0.total_cmp(&y.0))?;
    // The axes' standard error: the residuals' variance (at least (0.01 rad)², the level
    // of soft tissue and noise, so that motion that fits exactly but does not turn the
    // joint about both axes still shows), times the largest of the axes' diagonal entries
    // of (JᵀJ)⁻¹, times n over the effective number of independent residuals (soft
    // tissue and laxity make neighbours alike: n (1 − ρ) / (1 + ρ) for a lag-one
    // correlation ρ).
    let (mut jtj, mut jtr) = ([[0.0; 5]; 5], [0.0; 5]);
    eval(&a, &b, d, Some((&mut jtj, &mut jtr)));
    let rz = rot_z(d);
    let resid = |i: usize| {
        let (p, c) = pair(i);
        p.normalized().rotate(a.j).dot((rz * c.normalized()).normalized().rotate(b.j))
    };
    let floor = 1e-4;
    let variance = c / (n as f64 - 5.0).max(1.0);
    // The correlation of residuals above the floor only: what an exact fit leaves is
    // rounding, however smooth.
    let rho = if variance > floor {
        let lag1: f64 = (1..n).map(|i| resid(i - 1) * resid(i)).sum();
        (lag1 / c).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let n_eff = (n as f64 * (1.0 - rho) / (1.0 + rho)).max(1.0);
    let rms = (c / n as f64).sqrt();
    let s2 = variance.max(floor) * n as f64 / n_eff;
    let mut worst: f64 = 0.0;
    for k in 0..4 {
        let mut e = [0.0; 5];
        e[k] = 1.0;
        // A diagonal entry of the inverse that is not positive is rounding of a singular
        // JᵀJ: an axis the motion did not determine.
        let inverse = solve(jtj, e).map_or(f64::NAN, |x| x[k]);
        worst = worst.max(if inverse > 0.0 { inverse } else { f64::INFINITY });
    }
    let se = (s2 * worst).sqrt();
    let quality = if se.is_nan() { 1.0 } else { rms.max(3.0 * se).min(1.0) };
    let (mut jp, mut jc) = (a.j, b.j);
    if jp.dot(guess.0) < 0.0 {
        jp = -jp;
    }
    if jc.dot(guess.1) < 0.0 {
        jc = -jc;
    }
    Some(JointAxes { axis_parent: jp, axis_child: jc, quality })
}
