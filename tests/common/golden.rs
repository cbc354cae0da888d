//! The golden-vector file format shared by the Rust, C, C++ and C# tests.
//!
//! Text, one record per line, every double written as the 16 hex digits of its IEEE-754
//! bit pattern (so every language reads back the exact value):
//!
//! ```text
//! # comment
//! case NAME KIND FRAME INIT QW QX QY QZ NPARAMS (ID VALUE)*
//! s DT GX GY GZ AX AY AZ MX MY MZ FLAGS QW QX QY QZ
//! end
//! ```
//!
//! KIND, FRAME, INIT, FLAGS and ID are decimal and use the C header's numbers
//! (ORIENT_KIND_*, ORIENT_FRAME_*, ORIENT_INIT_*, ORIENT_SAMPLE_*, ORIENT_PARAM_*).
//! QW..QZ on a `case` line are the initial quaternion for ORIENT_INIT_GIVEN; on an `s`
//! line, the filter's quaternion after that sample.
#![allow(dead_code)]

use orient::{Config, Frame, Init, Kind, Quat, Sample, Vec3};

pub const SAMPLE_GYRO: u32 = 1;
pub const SAMPLE_ACCEL: u32 = 2;
pub const SAMPLE_MAG: u32 = 4;

#[derive(Clone, Debug)]
pub struct Case {
    pub name: String,
    pub kind: i32,
    pub frame: i32,
    pub init: i32,
    pub initial: Quat,
    pub params: Vec<(u32, f64)>,
    pub rows: Vec<Row>,
}

#[derive(Clone, Debug)]
pub struct Row {
    pub dt: f64,
    pub gyro: Vec3,
    pub accel: Vec3,
    pub mag: Vec3,
    pub flags: u32,
    pub expected: Quat,
}

impl Row {
    pub fn sample(&self) -> Sample {
        let has = |bit: u32, v: Vec3| (self.flags & bit != 0).then_some(v);
        Sample {
            dt: self.dt,
            gyro: has(SAMPLE_GYRO, self.gyro),
            accel: has(SAMPLE_ACCEL, self.accel),
            mag: has(SAMPLE_MAG, self.mag),
        }
    }
}

pub fn kind_from(k: i32) -> Kind {
    Kind::ALL.into_iter().find(|x| kind_to(*x) == k).unwrap()
}

pub fn kind_to(k: Kind) -> i32 {
    orient::ffi::OrientKind::from(k) as i32
}

pub fn frame_from(f: i32) -> Frame {
    [Frame::Enu, Frame::Ned, Frame::Nwu][f as usize]
}

pub fn frame_to(f: Frame) -> i32 {
    [Frame::Enu, Frame::Ned, Frame::Nwu].iter().position(|x| *x == f).unwrap() as i32
}

impl Case {
    /// The Rust configuration this case describes.
    pub fn config(&self) -> Config {
        let mut c = Config::new(kind_from(self.kind)).expect("supported kind");
        c.frame = frame_from(self.frame);
        c.init = match self.init {
            0 => Init::AccMag,
            1 => Init::Identity,
            _ => Init::Given(self.initial),
        };
        for (id, v) in &self.params {
            c.set_param(*id, *v).expect("valid parameter");
        }
        c
    }
}

pub fn hex(v: f64) -> String {
    format!("{:016x}", v.to_bits())
}

fn unhex(s: &str) -> f64 {
    f64::from_bits(u64::from_str_radix(s, 16).unwrap_or_else(|_| panic!("bad hex '{s}'")))
}

pub fn write(cases: &[Case]) -> String {
    let mut out = String::new();
    out.push_str("# orient golden vectors, format v1 (tests/common/golden.rs).\n");
    out.push_str("# Regenerate after an intended algorithm change: cargo run --bin make_golden\n");
    for c in cases {
        let q = c.initial;
        out.push_str(&format!(
            "case {} {} {} {} {} {} {} {} {}",
            c.name,
            c.kind,
            c.frame,
            c.init,
            hex(q.w),
            hex(q.x),
            hex(q.y),
            hex(q.z),
            c.params.len()
        ));
        for (id, v) in &c.params {
            out.push_str(&format!(" {} {}", id, hex(*v)));
        }
        out.push('\n');
        for r in &c.rows {
            let v = |v: Vec3| format!("{} {} {}", hex(v.x), hex(v.y), hex(v.z));
            let e = r.expected;
            out.push_str(&format!(
                "s {} {} {} {} {} {} {} {} {}\n",
                hex(r.dt),
                v(r.gyro),
                v(r.accel),
                v(r.mag),
                r.flags,
                hex(e.w),
                hex(e.x),
                hex(e.y),
                hex(e.z)
            ));
        }
        out.push_str("end\n");
    }
    out
}

pub fn parse(text: &str) -> Vec<Case> {
    let mut cases = Vec::new();
    let mut current: Option<Case> = None;
    for line in text.lines() {
        let t: Vec<&str> = line.split_whitespace().collect();
        match t.first().copied() {
            None | Some("#") => {}
            Some("case") => {
                let n: usize = t[9].parse().unwrap();
                let params = (0..n).map(|i| (t[10 + 2 * i].parse().unwrap(), unhex(t[11 + 2 * i]))).collect();
                current = Some(Case {
                    name: t[1].to_string(),
                    kind: t[2].parse().unwrap(),
                    frame: t[3].parse().unwrap(),
                    init: t[4].parse().unwrap(),
                    initial: Quat::new(unhex(t[5]), unhex(t[6]), unhex(t[7]), unhex(t[8])),
                    params,
                    rows: Vec::new(),
                });
            }
            Some("s") => {
                let f = |i: usize| unhex(t[i]);
                current.as_mut().expect("sample outside a case").rows.push(Row {
                    dt: f(1),
                    gyro: Vec3::new(f(2), f(3), f(4)),
                    accel: Vec3::new(f(5), f(6), f(7)),
                    mag: Vec3::new(f(8), f(9), f(10)),
                    flags: t[11].parse().unwrap(),
                    expected: Quat::new(f(12), f(13), f(14), f(15)),
                });
            }
            Some("end") => cases.push(current.take().expect("end outside a case")),
            Some(other) if other.starts_with('#') => {}
            Some(other) => panic!("unknown record '{other}'"),
        }
    }
    cases
}

pub const PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/golden/filters.golden");
