//! The paper's arithmetic alone, the floor under a filter's update time (the bench times
//! it beside the filters): the operations of [`Madgwick::update`] and [`Mahony::update`]
//! with their default settings, in the same order, so the same bits ([`check`], which
//! the bench runs before timing and `tests/floor.rs` runs in the tests), and nothing
//! else: no sample checks, no `Option`, no kind dispatch, no finiteness tests, no failure
//! path. Each update still waits for the previous one's quaternion, as every filter's
//! must.

use orient::filters::madgwick::{
    half_gradient_imu, half_gradient_marg, reference_field, Madgwick, MadgwickSettings,
};
use orient::filters::mahony::{Mahony, MahonySettings};
use orient::math::inv_sqrt;
use orient::{Kind, Quat, Sample, Vec3};
use std::hint::black_box;

/// Madgwick eqs. (29)-(30), IMU (12)-(13) or MARG (18)-(19) with (31)-(32).
#[inline(always)]
pub fn madgwick(q: Quat, s: &Sample, marg: bool) -> Quat {
    let (dt, gyro, a) = (s.dt, s.gyro.unwrap_or_default(), s.accel.unwrap_or_default().normalized());
    let p = q + q.mul_pure(gyro).scale(0.5 * dt);
    let (gradient, beta) = if marg {
        let m = s.mag.unwrap_or_default().normalized();
        let (bx, bz) = reference_field(q, m);
        (half_gradient_marg(q, a, bx, bz, m), MadgwickSettings::default().beta_marg)
    } else {
        (half_gradient_imu(q, a), MadgwickSettings::default().beta_imu)
    };
    let next = p - gradient.scale(beta * dt * inv_sqrt(gradient.norm_squared()));
    next.scale(inv_sqrt(next.norm_squared()))
}

/// Mahony's update with its default gains (`k_i = 0`, so the bias stays zero).
#[inline(always)]
pub fn mahony(q: Quat, s: &Sample, marg: bool) -> Quat {
    let (dt, gyro, a) = (s.dt, s.gyro.unwrap_or_default(), s.accel.unwrap_or_default().normalized());
    let [r0, r1, up] = q.rows();
    let e = if marg {
        let m = s.mag.unwrap_or_default().normalized();
        let h = Vec3::new(r0.dot(m), r1.dot(m), up.dot(m));
        // East-North-Up: the reference [0, b_y, b_z].
        let by = (h.x * h.x + h.y * h.y).sqrt();
        (a + m * h.z).cross(up) + m.cross(r1) * by
    } else {
        a.cross(up)
    };
    let omega = (gyro - Vec3::ZERO) + e * MahonySettings::default().kp;
    let h = 0.5 * dt;
    let n2 = q.norm_squared() * (1.0 + h * h * omega.norm_squared());
    q.plus_mul_pure_scaled(omega, h).scale(inv_sqrt(n2))
}

/// [`check`] for both floors, IMU (the magnetometer readings dropped) and MARG.
pub fn check_all(samples: &[Sample]) {
    for kind in [Kind::Madgwick, Kind::Mahony] {
        for marg in [false, true] {
            let mut samples = samples.to_vec();
            if !marg {
                samples.iter_mut().for_each(|s| s.mag = None);
            }
            check(kind, marg, &samples);
        }
    }
}

/// Panics unless the floor of `kind` (Madgwick, else Mahony) computes what the core
/// computes on `samples`, from the identity.
pub fn check(kind: Kind, marg: bool, samples: &[Sample]) {
    let (mut a, mut b) = (Madgwick::new(MadgwickSettings::default()), Mahony::new(MahonySettings::default()));
    let mut q = Quat::IDENTITY;
    for s in samples {
        run(kind, marg, &mut q, std::slice::from_ref(s), false);
        let core_q = if kind == Kind::Madgwick {
            a.update(s.dt, s.gyro.unwrap(), s.accel, s.mag).unwrap();
            a.quaternion()
        } else {
            b.update(s.dt, s.gyro.unwrap(), s.accel, s.mag).unwrap();
            b.quaternion()
        };
        assert_eq!(q, core_q, "the floor of {kind:?} (MARG {marg}) must compute the core's numbers");
    }
}

/// Steps `q` through `samples` with the floor of `kind` (Madgwick, else Mahony): one
/// loop per case, so that each is compiled with its update inlined. With `in_memory`
/// every step reads the quaternion from memory and writes it back (`black_box` on its
/// address keeps the compiler from holding it in registers), as an update behind a
/// call must: the next call's chain then starts with a load that waits for the
/// store. Without it the quaternion stays in registers from one step to the next.
pub fn run(kind: Kind, marg: bool, q: &mut Quat, samples: &[Sample], in_memory: bool) {
    let mut cell = *q;
    macro_rules! each {
        ($step:ident, $marg:expr) => {
            if in_memory {
                for s in samples {
                    let c = black_box(&mut cell);
                    *c = $step(*c, s, $marg);
                }
            } else {
                let mut r = cell;
                for s in samples {
                    r = $step(r, s, $marg);
                }
                cell = r;
            }
        };
    }
    match (kind == Kind::Madgwick, marg) {
        (true, false) => each!(madgwick, false),
        (true, true) => each!(madgwick, true),
        (false, false) => each!(mahony, false),
        (false, true) => each!(mahony, true),
    }
    *q = cell;
}
