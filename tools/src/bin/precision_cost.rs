//! What f32 would cost and gain on a board: the Madgwick MARG update (the library's
//! equations, written once over a float type) in f64 and in f32, on the demo recording.
//!
//!     cargo run --release --bin precision_cost                  accuracy of f32 vs f64
//!     cargo run --release --bin precision_cost -- f64 5000      run N updates only
//!
//! The second form exists to be counted: under qemu,
//! `qemu-aarch64 -one-insn-per-tb -d exec,nochain -D log BIN f32 5000` logs one line per
//! executed instruction (scripts/instruction-counts.sh subtracts a zero-update run).
//! The library itself stays f64: this example only measures the alternative.

use orient_tools::eval::Recording;
use std::ops::{Add, Div, Mul, Neg, Sub};

trait Float:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self>
{
    fn of(v: f64) -> Self;
    fn sqrt(self) -> Self;
    fn to_f64(self) -> f64;
}

impl Float for f64 {
    fn of(v: f64) -> Self {
        v
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn to_f64(self) -> f64 {
        self
    }
}

impl Float for f32 {
    fn of(v: f64) -> Self {
        v as f32
    }
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    fn to_f64(self) -> f64 {
        self as f64
    }
}

/// Madgwick 2010, eqs. (12)-(13), (16)-(17), (29)-(32) for one MARG step; q = [w x y z].
#[inline(never)]
fn madgwick<T: Float>(q: [T; 4], g: [T; 3], a: [T; 3], m: [T; 3], beta: T, dt: T) -> [T; 4] {
    let two = T::of(2.0);
    let half = T::of(0.5);
    let [q1, q2, q3, q4] = q;
    let inv = |v: [T; 3]| {
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        [v[0] / n, v[1] / n, v[2] / n]
    };
    let a = inv(a);
    let m = inv(m);
    // (31)-(32): h = q m q*, b = [sqrt(hx^2 + hy^2), 0, hz].
    let hx =
        two * (m[0] * (half - q3 * q3 - q4 * q4) + m[1] * (q2 * q3 - q1 * q4) + m[2] * (q2 * q4 + q1 * q3));
    let hy =
        two * (m[0] * (q2 * q3 + q1 * q4) + m[1] * (half - q2 * q2 - q4 * q4) + m[2] * (q3 * q4 - q1 * q2));
    let hz =
        two * (m[0] * (q2 * q4 - q1 * q3) + m[1] * (q3 * q4 + q1 * q2) + m[2] * (half - q2 * q2 - q3 * q3));
    let bx = (hx * hx + hy * hy).sqrt();
    let bz = hz;
    let f = [
        two * (q2 * q4 - q1 * q3) - a[0],
        two * (q1 * q2 + q3 * q4) - a[1],
        two * (half - q2 * q2 - q3 * q3) - a[2],
        two * bx * (half - q3 * q3 - q4 * q4) + two * bz * (q2 * q4 - q1 * q3) - m[0],
        two * bx * (q2 * q3 - q1 * q4) + two * bz * (q1 * q2 + q3 * q4) - m[1],
        two * bx * (q1 * q3 + q2 * q4) + two * bz * (half - q2 * q2 - q3 * q3) - m[2],
    ];
    let four = T::of(4.0);
    let j = [
        [-two * q3, two * q4, -two * q1, two * q2],
        [two * q2, two * q1, two * q4, two * q3],
        [T::of(0.0), -four * q2, -four * q3, T::of(0.0)],
        [-two * bz * q3, two * bz * q4, -four * bx * q3 - two * bz * q1, -four * bx * q4 + two * bz * q2],
        [
            -two * bx * q4 + two * bz * q2,
            two * bx * q3 + two * bz * q1,
            two * bx * q2 + two * bz * q4,
            -two * bx * q1 + two * bz * q3,
        ],
        [two * bx * q3, two * bx * q4 - four * bz * q2, two * bx * q1 - four * bz * q3, two * bx * q2],
    ];
    let mut grad = [T::of(0.0); 4];
    for (c, gc) in grad.iter_mut().enumerate() {
        for r in 0..6 {
            *gc = *gc + j[r][c] * f[r];
        }
    }
    let n = (grad[0] * grad[0] + grad[1] * grad[1] + grad[2] * grad[2] + grad[3] * grad[3]).sqrt();
    let qd = [
        half * (-q2 * g[0] - q3 * g[1] - q4 * g[2]) - beta * grad[0] / n,
        half * (q1 * g[0] + q3 * g[2] - q4 * g[1]) - beta * grad[1] / n,
        half * (q1 * g[1] - q2 * g[2] + q4 * g[0]) - beta * grad[2] / n,
        half * (q1 * g[2] + q2 * g[1] - q3 * g[0]) - beta * grad[3] / n,
    ];
    let r = [q1 + qd[0] * dt, q2 + qd[1] * dt, q3 + qd[2] * dt, q4 + qd[3] * dt];
    let rn = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]).sqrt();
    [r[0] / rn, r[1] / rn, r[2] / rn, r[3] / rn]
}

fn run<T: Float>(rec: &Recording, n: usize) -> Vec<[f64; 4]> {
    let mut q = [T::of(1.0), T::of(0.0), T::of(0.0), T::of(0.0)];
    let c = |v: orient::Vec3| [T::of(v.x), T::of(v.y), T::of(v.z)];
    let samples = rec.samples();
    let mut out = Vec::with_capacity(n.max(1));
    for i in 0..n {
        let s = &samples[i % samples.len()];
        q = madgwick(
            q,
            c(s.gyro.unwrap()),
            c(s.accel.unwrap()),
            c(s.mag.unwrap()),
            T::of(0.033),
            T::of(s.dt),
        );
        out.push([q[0].to_f64(), q[1].to_f64(), q[2].to_f64(), q[3].to_f64()]);
    }
    out
}

fn main() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/data/broad_01_excerpt.csv");
    let args: Vec<String> = std::env::args().collect();
    if args.len() == 3 {
        // Counting mode: the same 200 rows are parsed whatever N is, so that a run with
        // N = 0 measures everything but the updates.
        let n: usize = args[2].parse().expect("N");
        let text = std::fs::read_to_string(path).expect("recording");
        let head: String = text.lines().take(201).map(|l| format!("{l}\n")).collect();
        let rec = Recording::parse(&head, true).expect("csv");
        let last = match args[1].as_str() {
            "f32" => run::<f32>(&rec, n).last().copied(),
            _ => run::<f64>(&rec, n).last().copied(),
        };
        println!("{last:?}");
        return;
    }
    let rec = Recording::read(path.as_ref(), true).expect("recording");
    let a = run::<f64>(&rec, rec.len());
    let b = run::<f32>(&rec, rec.len());
    let mut worst: f64 = 0.0;
    let mut sum2 = 0.0;
    for (x, y) in a.iter().zip(&b) {
        let d = (x[0] * y[0] + x[1] * y[1] + x[2] * y[2] + x[3] * y[3]).abs().min(1.0);
        let angle = 2.0 * d.acos().to_degrees();
        worst = worst.max(angle);
        sum2 += angle * angle;
    }
    println!(
        "f32 vs f64 Madgwick MARG over {} samples: RMS difference {:.2e} deg, worst {:.2e} deg",
        a.len(),
        (sum2 / a.len() as f64).sqrt(),
        worst
    );
}
