//! A hinge's axes from a few seconds of motion, gyroscopes alone.

use crate::math::Vec3;

/// A hinge's axes estimated from motion ([`estimate_hinge_axes`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HingeAxes {
    /// The axis in the parent sensor's frame (unit, on the side of the guess).
    pub axis_parent: Vec3,
    /// The axis in the child sensor's frame.
    pub axis_child: Vec3,
    /// The RMS residual over the RMS angular rate perpendicular to the axis: 0 for an
    /// ideal hinge, a few hundredths with laxity and noise, near 1 when the motion did not
    /// turn the joint or the joint is no hinge. Below 0.1 the axes can be trusted.
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
) -> Option<HingeAxes> {
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
) -> Option<HingeAxes> {
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
    let (g0, g1) = (sph(guess.0.normalized()), sph(guess.1.normalized()));
    let mut x = [g0[0], g0[1], g1[0], g1[1]];
    let mut lambda = 1e-3;
    let mut c = cost(&x);
    for _ in 0..50 {
        let mut jtj = [[0.0; 4]; 4];
        let mut jtr = [0.0; 4];
        for i in 0..n {
            let r = resid(&x, i);
            let mut jac = [0.0; 4];
            for (k, d) in jac.iter_mut().enumerate() {
                let mut xp = x;
                xp[k] += 1e-6;
                *d = (resid(&xp, i) - r) / 1e-6;
            }
            for a in 0..4 {
                jtr[a] += jac[a] * r;
                for b in 0..4 {
                    jtj[a][b] += jac[a] * jac[b];
                }
            }
        }
        let mut a = jtj;
        for (k, row) in a.iter_mut().enumerate() {
            row[k] *= 1.0 + lambda;
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
    let n = n as f64;
    let scale = ((0..n as usize).map(|i| gyro_parent(i).cross(jp).norm_squared()).sum::<f64>() / n).sqrt();
    let quality = ((c / n).sqrt() / scale.max(1e-12)).min(1.0);
    Some(HingeAxes { axis_parent: jp, axis_child: jc, quality })
}

/// Solves a 4×4 system by Gaussian elimination with partial pivoting.
#[allow(clippy::needless_range_loop)]
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for col in 0..4 {
        let piv = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() < 1e-300 || a[piv][col].is_nan() {
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
    x.iter().all(|v| v.is_finite()).then_some(x)
}
