//! Writes tests/golden/filters.golden: deterministic synthetic input sequences and the
//! quaternion the Rust API produces after each sample, as exact bit patterns.
//!
//! Run it only when an algorithm changes on purpose, and say why in the commit:
//!     cargo run -p orient-tools --bin make_golden [OUT]
//! (OUT defaults to the committed tests/golden/filters.golden; give another path to
//! compare without touching it.)
//! The tests (Rust, C through the .so and the .a, and later C++ and C#) then require
//! every binding to reproduce these bits exactly.

#[path = "../../../tests/common/golden.rs"]
mod golden;

use golden::{Case, Row, SAMPLE_ACCEL, SAMPLE_GYRO, SAMPLE_MAG};
use orient::{Filter, Frame, Kind, Quat, Vec3};

/// xorshift64*: a tiny deterministic generator; uniform in [-1, 1).
struct Noise(u64);

impl Noise {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let r = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
        (r >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    fn vec(&mut self, scale: f64) -> Vec3 {
        Vec3::new(self.next() * scale, self.next() * scale, self.next() * scale)
    }
}

/// A sensor moving with a smooth angular velocity; readings with bias and noise,
/// written in the sensor frame (ENU earth frame, field 20 µT north, 40 µT down).
fn motion(seed: u64, n: usize, flags: impl Fn(usize) -> u32) -> Vec<Row> {
    motion_after_rest(seed, 0, n, flags)
}

/// [`motion`] that starts with `still` samples at rest (for start-up periods).
fn motion_after_rest(seed: u64, still: usize, n: usize, flags: impl Fn(usize) -> u32) -> Vec<Row> {
    let mut noise = Noise(seed);
    let mut truth = Quat::from_axis_angle(Vec3::new(0.2, -0.5, 1.0), 0.9);
    let bias = Vec3::new(0.01, -0.02, 0.015);
    let mut rows = Vec::with_capacity(n);
    for i in 0..n {
        let t = i as f64 * 0.01;
        let dt = 0.01 + 0.0005 * noise.next();
        let w = if i < still {
            Vec3::ZERO
        } else {
            Vec3::new(0.8 * (0.7 * t).sin(), 0.5 * (1.1 * t).cos(), 0.9 * (0.3 * t + 1.0).sin())
        };
        // The readable exp map (root, sincos, division), so that the inputs do not move
        // with the faster form the filters use.
        truth = (truth * orient::filters::complementary::rotation_of_by_sincos(w, dt)).normalized();
        let lin = if i < still {
            Vec3::ZERO
        } else {
            Vec3::new(0.3 * (2.0 * t).sin(), 0.2 * (1.5 * t).cos(), 0.1 * (3.0 * t).sin())
        };
        let accel = truth.rotate_inverse(Vec3::new(0.0, 0.0, 9.81) + lin) + noise.vec(0.05);
        let mag = truth.rotate_inverse(Vec3::new(0.0, 20.0, -40.0)) + noise.vec(0.3);
        rows.push(Row {
            dt,
            gyro: w + bias + noise.vec(0.005),
            accel,
            mag,
            flags: flags(i),
            expected: Quat::IDENTITY,
        });
    }
    rows
}

fn case(
    name: &str,
    kind: Kind,
    frame: Frame,
    init: i32,
    initial: Quat,
    params: Vec<(u32, f64)>,
    rows: Vec<Row>,
) -> Case {
    let mut c = Case {
        name: name.into(),
        kind: golden::kind_to(kind),
        frame: golden::frame_to(frame),
        init,
        initial,
        params,
        rows,
    };
    let mut f = Filter::new(&c.config()).expect("valid case");
    for r in &mut c.rows {
        f.update(&r.sample()).unwrap_or_else(|e| panic!("{name}: {e}"));
        r.expected = f.quaternion();
    }
    c
}

fn main() {
    use orient::filters::params::id;
    let imu = SAMPLE_GYRO | SAMPLE_ACCEL;
    let marg = imu | SAMPLE_MAG;
    let q0 = Quat::from_axis_angle(Vec3::new(1.0, 0.4, -0.3), 0.6);
    let cases = vec![
        case(
            "madgwick_imu_enu",
            Kind::Madgwick,
            Frame::Enu,
            0,
            Quat::IDENTITY,
            vec![],
            motion(1, 300, |_| imu),
        ),
        case(
            "madgwick_marg_enu",
            Kind::Madgwick,
            Frame::Enu,
            0,
            Quat::IDENTITY,
            vec![],
            motion(2, 300, |_| marg),
        ),
        case(
            "madgwick_marg_ned_given",
            Kind::Madgwick,
            Frame::Ned,
            2,
            q0,
            vec![(id::MADGWICK_BETA_IMU, 0.1), (id::MADGWICK_BETA_MARG, 0.08)],
            motion(3, 300, |_| marg),
        ),
        case(
            "madgwick_mixed_nwu_identity",
            Kind::Madgwick,
            Frame::Nwu,
            1,
            Quat::IDENTITY,
            vec![],
            // Magnetometer on every other sample, accelerometer missing on every fifth.
            motion(4, 300, |i| {
                SAMPLE_GYRO
                    | if i % 5 == 4 { 0 } else { SAMPLE_ACCEL }
                    | if i % 2 == 0 { SAMPLE_MAG } else { 0 }
            }),
        ),
        case(
            "mahony_marg_enu_ki",
            Kind::Mahony,
            Frame::Enu,
            0,
            Quat::IDENTITY,
            vec![(id::MAHONY_KI, 0.1)],
            motion(5, 300, |_| marg),
        ),
        case(
            "complementary_imu_enu",
            Kind::Complementary,
            Frame::Enu,
            0,
            Quat::IDENTITY,
            vec![(id::COMPLEMENTARY_INIT_DURATION, 0.5)],
            motion_after_rest(6, 80, 300, |_| imu),
        ),
        case("ekf_marg_ned", Kind::Ekf, Frame::Ned, 0, Quat::IDENTITY, vec![], motion(7, 300, |_| marg)),
        case("ekf_imu_enu_given", Kind::Ekf, Frame::Enu, 2, q0, vec![], motion(8, 300, |_| imu)),
        case(
            "gmvdk_marg_enu",
            Kind::Gmvdk,
            Frame::Enu,
            0,
            Quat::IDENTITY,
            vec![(id::GMVDK_INIT_DURATION, 0.5)],
            motion_after_rest(9, 80, 300, |_| marg),
        ),
        case(
            "robust_marg_enu",
            Kind::Robust,
            Frame::Enu,
            0,
            Quat::IDENTITY,
            vec![(id::ROBUST_REST_TIME, 0.3), (id::ROBUST_HARD_IRON_TIME, 0.5)],
            motion_after_rest(10, 80, 300, |_| marg),
        ),
        case(
            "robust_imu_ned_given",
            Kind::Robust,
            Frame::Ned,
            2,
            q0,
            vec![(id::ROBUST_BIAS_SIGMA_MOTION, 3e-4)],
            motion(11, 300, |_| imu),
        ),
        // Mahony's default (k_I = 0) IMU step in a frame other than its native one.
        case("mahony_imu_ned", Kind::Mahony, Frame::Ned, 0, Quat::IDENTITY, vec![], motion(12, 300, |_| imu)),
        // A given attitude: no start-up period, g0 from the first reading.
        case(
            "complementary_marg_enu_given",
            Kind::Complementary,
            Frame::Enu,
            2,
            q0,
            vec![],
            motion(13, 300, |_| marg),
        ),
        // The motion bias filter: it learns from two accelerometer time constants on (1 s
        // here), with three times the default walk and the bound under joints (the walk
        // of orient_config_for_joints when this case was made; it is five times now).
        case(
            "robust_imu_enu_motion_bias",
            Kind::Robust,
            Frame::Enu,
            0,
            Quat::IDENTITY,
            vec![
                (id::ROBUST_TAU_ACC, 0.5),
                (id::ROBUST_BIAS_WALK, 5.235_987_755_982_989e-4),
                (id::ROBUST_BIAS_LIMIT, 0.069_813_170_079_773_18),
            ],
            motion(14, 600, |_| imu),
        ),
    ];
    let out = std::env::args().nth(1).unwrap_or_else(|| {
        concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/golden/filters.golden").to_string()
    });
    std::fs::write(&out, golden::write(&cases)).expect("write golden file");
    let n: usize = cases.iter().map(|c| c.rows.len()).sum();
    println!("wrote {} cases, {n} samples to {out}", cases.len());
}
