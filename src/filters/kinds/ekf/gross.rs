//! Gross innovations: the normalised-innovation tests of the gyroscope and gravity rows,
//! and what they re-initialise (the rate, the drift) or inflate (the attitude).

use super::*;

/// The NIS bound of the gravity measurement (13): an innovation whose power exceeds this
/// many times the power the model predicts for it (`tr(H P Hᵀ) + 3 r`, r the noise and
/// linear-acceleration variance per axis) is a gross inconsistency, one the model's
/// noise does not explain (4 standard deviations of its RMS).
pub(super) const GROSS_NIS: f64 = 16.0;

/// The time constant (s) of the running mean of the gravity innovation whose length the
/// reported inclination σ is at least ([`Ekf::attitude_sigmas`]): 0.5-2 s all cover the
/// recovery property (min. 98.7 %, 97.1 %, 95.0 % of still samples), and a longer mean
/// starts later after a jump.
pub(super) const EXCESS_TAU: f64 = 1.0;

/// Covariance inflation: P_qq ← P_qq + (σ²/4)(I − q qᵀ), an attitude error of variance σ²
/// (rad²) about each axis (`I − q qᵀ = Σ_k (q ⊗ e_k)(q ⊗ e_k)ᵀ` for the three imaginary
/// units e_k, and δq = ½ q ⊗ (0, δθ)). A positive semi-definite addition, so P stays a
/// covariance; the cross-covariances with ω and δ are kept. Inlined, so that the AVX copy
/// keeps its lanes; it runs only on a gross inconsistency.
#[inline(always)]
pub(super) fn inflate_attitude<V: Lanes>(p: &mut Cov<V>, q: V, var: f64) {
    let t = q.token();
    let k = 0.25 * var;
    let qe = q.to_array();
    for (j, col) in p.qq.iter_mut().enumerate() {
        *col += (unit::<V>(t, j, 1.0) - q * V::splat(t, qe[j])) * V::splat(t, k);
    }
}

/// ω's axes whose gyroscope reading fails the NIS test (12): its innovation against the
/// predicted reading `a_ω ω_i + a_δ δ_i`, squared (`nu2`), beyond [`GROSS_NIS`] times its
/// predicted variance `a_ω² P_ωω + 2 a_ω a_δ P_ωδ + a_δ² P_δδ + q_ω + q_δ + r_g` (on the
/// diagonal, P before the prediction; `var` is `q_ω + q_δ + r_g`): a rate the model (9)
/// does not allow (a glitch, or a rate far beyond `omega_std` held for many correlation
/// times). The first three terms are the variance of `a_ω ω_i + a_δ δ_i`, at least zero;
/// a nearly singular ω-δ block can round them below, which counts as zero. So the
/// variance is at least `var`, and [`Ekf::update_in`] calls this only when some `nu2`
/// exceeds `GROSS_NIS · var` (with the usual motion, never).
#[cold]
#[inline(never)]
pub(super) fn rate_jumps(p: &Cov, nu2: [f64; 3], a: (f64, f64), var: f64) -> [bool; 3] {
    let (ww, wd, dd) = (in_place(&p.ww), in_place(&p.wd), in_place(&p.dd));
    let (aww, awd, add) = (a.0 * a.0, 2.0 * a.0 * a.1, a.1 * a.1);
    array(
        #[inline(always)]
        |i| {
            let predicted = ((aww * ww[i][i] + awd * wd[i][i]) + add * dd[i][i]).max(0.0);
            nu2[i] > GROSS_NIS * (predicted + var)
        },
    )
}

/// Why [`Ekf::update_in`] took no step (it then changed nothing).
pub(super) enum Stop {
    /// The step would not be finite.
    Refused,
    /// These axes' gyroscope readings failed the NIS test (12): ω is re-initialised
    /// from them first ([`reinit_rate`]).
    RateJump([bool; 3]),
}

/// Re-initialises the drift on axis `i` to `d`, independent of the other states with
/// variance `var` (P's row and column for δ_i set to zero but its diagonal, which keeps P
/// positive semi-definite).
#[cold]
#[inline(never)]
pub(super) fn reinit_drift(x: &mut Blocks, p: &mut Cov, i: usize, d: f64, var: f64) {
    x.d.as_array_mut()[i] = d;
    p.qd[i] = f64x4::splat(0.0);
    p.wd[i] = f64x4::splat(0.0);
    for j in 0..3 {
        p.dd[j].as_array_mut()[i] = 0.0;
        p.dd[i].as_array_mut()[j] = 0.0;
    }
    p.dd[i].as_array_mut()[i] = var;
}

/// Re-initialises ω on the `jumped` axes from the gyroscope (12): ω_i = ω_IMU,i − δ_i,
/// independent of the other states with variance `var` (P's row and column for ω_i set to
/// zero but its diagonal, which keeps P positive semi-definite).
#[cold]
#[inline(never)]
pub(super) fn reinit_rate(
    x: &mut Blocks,
    p: &mut Cov,
    gyro: Vec3,
    jumped: [bool; 3],
    var: f64,
    a: (f64, f64),
) {
    let g = [gyro.x, gyro.y, gyro.z];
    for i in (0..3).filter(|&i| jumped[i]) {
        // Before the prediction: ω_i such that the predicted a_ω ω_i + a_δ δ_i is the reading.
        // With a_ω = 0 (dt ≫ τ_ω) the prediction forgets ω: any value will do.
        let d = x.d.as_array_ref()[i];
        let w = (g[i] - a.1 * d) / a.0;
        x.w.as_array_mut()[i] = if w.is_finite() { w } else { 0.0 };
        p.qw[i] = f64x4::splat(0.0);
        for j in 0..3 {
            p.ww[j].as_array_mut()[i] = 0.0;
            p.ww[i].as_array_mut()[j] = 0.0;
            p.wd[j].as_array_mut()[i] = 0.0;
        }
        p.ww[i].as_array_mut()[i] = if var.is_finite() { var } else { 0.0 };
    }
}
