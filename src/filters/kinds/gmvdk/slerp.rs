//! SLERP, eqs. (15)-(16), and the rotations between two vectors, eqs. (10)-(12) and (19),
//! with the series forms the usual step takes and the readable forms tests compare them
//! with.

use super::*;

/// `SLERP(q1, q2, h)`, eqs. (15)-(16), along the shorter arc; linear interpolation
/// (normalised) when the two are within 1e-6 rad.
///
/// The weights are `sin((1 − h)ω)/sin ω` and `sin(hω)/sin ω` with `cos ω = q1·q2`. For
/// `sin ω < 1/20` and `(hω)² < 1/256` (the usual filter step, whose corrections are
/// small, with `h` in [0, 1]) they come from
/// series in `sin²ω = (1 − cos ω)(1 + cos ω)` alone: `ω = sin ω · asin(s)/s`
/// ([`asin_over`]), `sin(hω)/sin ω = h · asin(s)/s · sin(hω)/(hω)` and `cos(hω)`
/// ([`cos_and_sinc`]), with no arccosine, sine, root or division. Larger angles take
/// `slerp_weights_by_acos`, the readable form, which a test compares the series with.
#[inline(always)]
pub fn slerp(q1: Quat, q2: Quat, h: f64) -> Quat {
    let mut cos = q1.dot(q2);
    let mut q2 = q2;
    if cos < 0.0 {
        cos = -cos;
        q2 = q2.scale(-1.0);
    }
    if cos > 1.0 - 1e-12 {
        return (q1.scale(1.0 - h) + q2.scale(h)).normalized();
    }
    let (w1, w2) = slerp_weights(cos, h);
    (q1.scale(w1) + q2.scale(w2)).normalized()
}

/// (10)-(12): `Δq = H(q₀, Δ)` with `Δ = v₀ × v̂` (11) and `q₀ = |v₀||v̂| + v₀·v̂` (12),
/// normalised: the rotation that takes the reading `v₀` onto the prediction `v̂`
/// ((9)'s `a(q_G)`, or the magnetometer's), so that `q_G ⊗ Δq` maps the initial vector
/// onto the reading (13). The same rotation as [`Quat::from_two_vectors`]`(v₀, v̂)`,
/// which normalises both vectors first: two divisions more (a test compares them).
///
/// `|Δq|² = q₀² + |Δ|² = 2 |v₀||v̂| q₀`: the normalisation takes that product, not Δq's
/// four squares. Its relative error is q₀'s, about 2⁻⁵³ |v₀||v̂| / q₀, plus up to twice
/// that of the norms passed (the update passes the reference's stored norm, a few ulp
/// from the rotated prediction's). It is used while `q₀ > |v₀||v̂| / 2` (the reading
/// within 120° of the prediction), where that is a few ulp; the SLERPs that take Δq
/// normalise their results. Readings farther off (the last of them pointing opposite,
/// with no unique axis), or so small or large that `|Δq|²` leaves `inv_sqrt`'s fast
/// range, go to `from_two_vectors`, out of line. Taking the product costs GMVDK's MARG
/// update fewer instructions than normalising by the four squares (docs/PERFORMANCE.md).
#[inline(always)]
pub fn eq10_to_12(v0: Vec3, v: Vec3) -> Quat {
    eq10_to_12_with_norms(v0, v0.norm(), v, v.norm())
}

/// [`eq10_to_12`] with the norms given: the update has the reading's already (α's
/// accelerometer term, or for the magnetometer the `|m0|` that (19)-(22) use), and the
/// prediction `v̂ = q_G* ⊗ v_ref ⊗ q_G` (9) has the norm of
/// its reference `v_ref`, which [`Reference`] keeps; the update passes those instead of
/// two more square roots each step (equal to rounding; a test compares).
#[inline(always)]
pub(super) fn eq10_to_12_with_norms(v0: Vec3, v0_norm: f64, v: Vec3, v_norm: f64) -> Quat {
    let nn = v0_norm * v_norm;
    let q0 = nn + v0.dot(v);
    if q0 > 0.5 * nn {
        if let Some(r) = inv_sqrt_fast(2.0 * nn * q0) {
            let d = v0.cross(v);
            return Quat::new(q0, d.x, d.y, d.z).scale(r);
        }
    }
    from_two_vectors_outline(v0, v)
}

#[cold]
#[inline(never)]
pub(super) fn from_two_vectors_outline(v0: Vec3, v: Vec3) -> Quat {
    Quat::from_two_vectors(v0, v)
}

/// `SLERP(1, r, h)`: [`slerp`] from the identity, whose dot product with `r` is `r.w`
/// and whose terms are the weight alone. SLERP is left-invariant
/// (`SLERP(q ⊗ a, q ⊗ b, h) = q ⊗ SLERP(a, b, h)` for a unit `q`, since
/// `(q ⊗ a)·(q ⊗ b) = a·b`), so `SLERP(q_g, q_g ⊗ Δq, h) = q_g ⊗ SLERP(1, Δq, h)`; a test compares the
/// two sides. At exactly half a turn (`r.w = 0`) both arcs are shortest: this form
/// takes `r`'s, the paper's form whichever the rounding of `q_g·(q_g ⊗ Δq)` picks.
/// For a unit `r` and `h` in [0, 1] the result is unit before its normalisation, to
/// rounding, so that needs no range test.
#[inline(always)]
pub fn slerp_from_identity(r: Quat, h: f64) -> Quat {
    slerp_from_identity_terms(r, h).0.normalized_in_range()
}

/// [`slerp_from_identity`] before its normalisation, and whether that is the linear
/// interpolation of nearly equal ends (whose norm falls short of 1 by up to 2.5e-13),
/// not the weights' result (unit to rounding).
#[inline(always)]
pub(super) fn slerp_from_identity_terms(r: Quat, h: f64) -> (Quat, bool) {
    let r = if r.w < 0.0 { r.scale(-1.0) } else { r };
    let cos = r.w;
    if cos > 1.0 - 1e-12 {
        return (Quat::new((1.0 - h) + h * r.w, h * r.x, h * r.y, h * r.z), true);
    }
    let (w1, w2) = slerp_weights(cos, h);
    (Quat::new(w1 + w2 * r.w, w2 * r.x, w2 * r.y, w2 * r.z), false)
}

/// An end of (17)'s `SLERP(q_sm, q_sa, ½)`: [`slerp_from_identity`], normalised only where
/// it is not unit to rounding. [`slerp_half`] normalises the sum of its ends, so ends a
/// few ulps off unit move the result by rounding only: two normalisations fewer per step.
#[inline(always)]
pub(super) fn slerp_from_identity_for_half(r: Quat, h: f64) -> Quat {
    match slerp_from_identity_terms(r, h) {
        (q, true) => q.normalized_in_range(),
        (q, false) => q,
    }
}

/// [`slerp`]'s weights `(sin((1 − h)ω)/sin ω, sin(hω)/sin ω)` for `cos ω` in
/// `[0, 1 − 1e-12]`: the series, or [`slerp_weights_by_acos`].
#[inline(always)]
pub(super) fn slerp_weights(cos: f64, h: f64) -> (f64, f64) {
    let s2 = (1.0 - cos) * (1.0 + cos);
    if s2 < 1.0 / 400.0 {
        let a = asin_over(s2); // ω / sin ω
        let x2 = h * h * (s2 * (a * a)); // (hω)²: under 1/256 for h in [0, 1]
        if x2 < 1.0 / 256.0 {
            let (c_h, sinc_h) = cos_and_sinc(x2);
            let w2 = h * a * sinc_h;
            return (c_h - cos * w2, w2);
        }
    }
    slerp_weights_by_acos(cos, h)
}

/// [`slerp`]'s weights from `ω = acos(q1·q2)` and one `sincos`, for `q2` on the shorter
/// arc and `cos = q1·q2` under `1 − 1e-12`.
#[cold]
#[inline(never)]
pub(super) fn slerp_weights_by_acos(cos: f64, h: f64) -> (f64, f64) {
    let omega = libm::acos(cos);
    // sin ω from cos ω (ω in [0, π/2] after the flip): one square root instead of a
    // sine, and accurate near ω = 0 where it is formed as (1 − cos)(1 + cos).
    let r = inv_sqrt((1.0 - cos) * (1.0 + cos));
    // sin((1 − h)ω) = sin ω cos(hω) − cos ω sin(hω): both weights from one sincos. The
    // first, cos(hω) − cos ω sin(hω)/sin ω, is near 1 − h and loses nothing to
    // cancellation but absolutely, where its q1 term is that small anyway.
    let (s_h, c_h) = libm::sincos(h * omega);
    let w2 = s_h * r;
    (c_h - cos * w2, w2)
}

/// [`slerp`] by [`slerp_weights_by_acos`] whatever the angle: the readable form the
/// series is tested against.
#[cfg(test)]
pub(super) fn slerp_by_acos(q1: Quat, q2: Quat, cos: f64, h: f64) -> Quat {
    let (w1, w2) = slerp_weights_by_acos(cos, h);
    (q1.scale(w1) + q2.scale(w2)).normalized()
}

/// `SLERP(q1, q2, ½)`: the normalised sum along the shorter arc. Equal to [`slerp`] with
/// `h = ½`, whose two weights are then both `sin(ω/2)/sin ω`, without its arccosine and
/// sines. For unit `q1` and `q2`, `|q1 + q2|² = 2 + 2 q1·q2` is at least 2 on the shorter
/// arc, so the normalisation needs no range test.
pub fn slerp_half(q1: Quat, q2: Quat) -> Quat {
    let q2 = if q1.dot(q2) < 0.0 { q2.scale(-1.0) } else { q2 };
    (q1 + q2).normalized_in_range()
}

/// (19): `λ = acos(cos λ)`. For the small angles of an undisturbed field
/// (`s² = (1 − cos λ)/2` under 1/256: λ under 7.2°) as `2 asin(s)`, `s = sin(λ/2)`, by
/// [`asin_over`]'s series (`1 − cos λ` is exact there): a square root and the series
/// instead of libm's `acos`. Larger angles take `acos`, out of line; a test compares the
/// two forms.
#[inline(always)]
pub(super) fn eq19_lambda(cos_l: f64) -> f64 {
    let s2 = 0.5 * (1.0 - cos_l);
    if s2 < 1.0 / 256.0 {
        return 2.0 * s2.sqrt() * asin_over(s2);
    }
    acos_outline(cos_l)
}

#[cold]
#[inline(never)]
pub(super) fn acos_outline(c: f64) -> f64 {
    libm::acos(c)
}
