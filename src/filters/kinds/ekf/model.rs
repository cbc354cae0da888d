//! The process and measurement models: the quaternion exponential of the rate state and
//! its Jacobian, the gravity model h(q) and its Jacobian, and the covariance check.

use super::*;

/// True for a symmetric positive semi-definite matrix, to rounding: the Cholesky
/// factorisation of `m + ε I` with `ε = 1e-9 · max(diag m)` succeeds.
#[allow(clippy::needless_range_loop)] // index notation, as in the textbook algorithm
pub(super) fn covariance(m: &[[f64; 10]; 10]) -> bool {
    let scale = (0..10).map(|i| m[i][i]).fold(0.0, f64::max);
    let eps = 1e-9 * scale.max(f64::MIN_POSITIVE);
    if (0..10).any(|i| m[i][i] < -eps) || scale > 1e200 {
        return false;
    }
    for i in 0..10 {
        for j in 0..i {
            if (m[i][j] - m[j][i]).abs() > 1e-9 * scale {
                return false;
            }
        }
    }
    let mut l = [[0.0; 10]; 10];
    for j in 0..10 {
        let d = m[j][j] + eps - (0..j).map(|k| l[j][k] * l[j][k]).sum::<f64>();
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        l[j][j] = d.sqrt();
        for i in j + 1..10 {
            l[i][j] = (m[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>()) / l[j][j];
        }
    }
    true
}

/// `L(q)`: `q ⊗ e = L(q) e`.
#[cfg(test)]
pub(super) fn left(q: Quat) -> Matrix4<f64> {
    Matrix4::new(q.w, -q.x, -q.y, -q.z, q.x, q.w, -q.z, q.y, q.y, q.z, q.w, -q.x, q.z, -q.y, q.x, q.w)
}

/// `R(e)`: `q ⊗ e = R(e) q`.
pub(super) fn right(e: Quat) -> Matrix4<f64> {
    Matrix4::new(e.w, -e.x, -e.y, -e.z, e.x, e.w, e.z, -e.y, e.y, -e.z, e.w, e.x, e.z, e.y, -e.x, e.w)
}

/// `exp(ω h)` as a quaternion, `h = dt/2`, and its derivative with respect to ω (4×3).
pub fn exp_and_jacobian(omega: Vec3, h: f64) -> (Quat, Matrix4x3<f64>) {
    let n = omega.norm();
    let theta = n * h;
    let w = Vector3::new(omega.x, omega.y, omega.z);
    let mut j = Matrix4x3::zeros();
    if theta < 1e-8 {
        // Series to second order: e ≈ [1 − θ²/2, h ω].
        let e = Quat::new(1.0 - 0.5 * theta * theta, h * omega.x, h * omega.y, h * omega.z);
        j.fixed_view_mut::<1, 3>(0, 0).copy_from(&(-(h * h) * w.transpose()));
        j.fixed_view_mut::<3, 3>(1, 0).copy_from(&(Matrix3::identity() * h));
        return (e.normalized(), j);
    }
    let (s, c) = libm::sincos(theta); // sin's and cos's bits (a test in `math` checks it)
    let u = w / n;
    let uut = u * u.transpose();
    j.fixed_view_mut::<1, 3>(0, 0).copy_from(&(-s * h * u.transpose()));
    j.fixed_view_mut::<3, 3>(1, 0).copy_from(&(uut * (c * h) + (Matrix3::identity() - uut) * (s / n)));
    (Quat::new(c, s * u.x, s * u.y, s * u.z), j)
}

/// `exp(ω h)` as [`exp_and_jacobian`] gives it, and `D = ∂(q ⊗ exp(ω h))/∂ω = L(q) J` (4×3,
/// J that function's Jacobian) by its columns, multiplied out: with `n = |ω|`, `u = ω/n`,
/// `θ = n h`, `(s, c) = (sin θ, cos θ)` and `L_v` the last three columns of `L(q)`
/// (`q ⊗ i`, `q ⊗ j`, `q ⊗ k`),
/// `D = (s/n) L_v + w uᵀ` with `w = (c h − s/n) q ⊗ (0, u) − s h q`. Three columns of a
/// rank-one update instead of a 4×4 by 4×3 product (a test compares the two).
///
/// For the usual step, `θ² ≤ 1/256`, the same in `θ²` alone, with `A = sin θ/θ`,
/// `C = cos θ` ([`cos_and_sinc`]) and `B = (cos θ − sin θ/θ)/θ²`
/// ([`cos_minus_sinc_over_x2`]): `e = (C, h A ω)` and
/// `D = h A L_v + (h³ B q ⊗ (0, ω) − h² A q) ωᵀ` (`s/n = h A`, `(c h − s/n)/n² = h³ B`):
/// no root, no division and no `sincos`, and no branch for `θ → 0`. Larger angles take
/// the sine and cosine.
#[inline(always)]
pub(super) fn exp_and_d<V: Lanes>(t: V::Token, q: Quat, omega: Vec3, h: f64) -> (Quat, Cols<3, V>) {
    let theta2 = omega.norm_squared() * (h * h);
    let l_v = [
        V::new(t, [-q.x, q.w, q.z, -q.y]),
        V::new(t, [-q.y, -q.z, q.w, q.x]),
        V::new(t, [-q.z, q.y, -q.x, q.w]),
    ];
    // D = a L_v + w vᵀ.
    let (e, a, w, v) = if theta2 <= 1.0 / 256.0 {
        let ((c, sinc), b) = (cos_and_sinc(theta2), cos_minus_sinc_over_x2(theta2));
        let ha = h * sinc;
        let w = vector_of::<V>(t, q.mul_pure(omega)) * V::splat(t, h * h * h * b)
            - vector_of::<V>(t, q) * V::splat(t, h * ha);
        (Quat::new(c, ha * omega.x, ha * omega.y, ha * omega.z), ha, w, omega)
    } else {
        let n = omega.norm();
        let (s, c) = libm::sincos(n * h); // sin's and cos's bits (a test in `math` checks it)
        let u = Vec3::new(omega.x / n, omega.y / n, omega.z / n);
        let sn = s / n;
        let w = vector_of::<V>(t, q.mul_pure(u)) * V::splat(t, c * h - sn)
            - vector_of::<V>(t, q) * V::splat(t, s * h);
        (Quat::new(c, s * u.x, s * u.y, s * u.z), sn, w, u)
    };
    let (a, v) = (V::splat(t, a), [v.x, v.y, v.z]);
    (
        e,
        array(
            #[inline(always)]
            |j| l_v[j] * a + w * V::splat(t, v[j]),
        ),
    )
}

/// Eq. (13): the accelerometer reading predicted by q, and its Jacobian (3×4).
pub fn gravity_model(q: Quat, g: f64) -> (Vec3, Matrix3x4<f64>) {
    let Quat { w: q0, x: q1, y: q2, z: q3 } = q;
    let f = Vec3::new(
        g * (2.0 * q0 * q2 - 2.0 * q1 * q3),
        g * (-2.0 * q0 * q1 - 2.0 * q2 * q3),
        g * (-q0 * q0 + q1 * q1 + q2 * q2 - q3 * q3),
    );
    // ∂f/∂q: each entry ±2 q_k g, formed as ±q_k (2g) (doubling is exact: the same bits
    // as (±2 q_k) g, one multiplication fewer).
    let h = Matrix3x4::new(q2, -q3, q0, -q1, -q1, -q0, -q3, -q2, -q0, q1, q2, -q3) * (2.0 * g);
    (f, h)
}

pub(super) fn quat_of<V: Lanes>(v: V) -> Quat {
    let [w, x, y, z] = v.to_array();
    Quat::new(w, x, y, z)
}

pub(super) fn vector_of<V: Lanes>(t: V::Token, q: Quat) -> V {
    V::new(t, [q.w, q.x, q.y, q.z])
}
