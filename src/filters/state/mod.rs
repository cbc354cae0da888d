//! State snapshots: a versioned byte blob that restores a filter exactly.
//!
//! Layout (little-endian):
//!
//! ```text
//! offset  size  field
//! 0       4     magic "ORST"
//! 4       2     format version ([`VERSION`])
//! 6       1     kind (1 Madgwick .. 5 GMVDK)
//! 7       1     reserved, 0
//! 8       4     payload length P
//! 12      P     payload: configuration (frame, init, initial quaternion, every
//!               parameter slot), filter flags, last accelerometer reading, mounting, heading offset,
//!               declination, then the
//!               kind's state, each value as its exact bit pattern
//! 12+P    8     FNV-1a 64 of bytes 0 .. 12+P
//! ```
//!
//! Loading checks everything before it changes anything: magic, version, kind, length,
//! checksum, and that every decoded value is one the filter could hold.

pub(crate) mod holds;

use crate::math::{Quat, Vec3};

pub const MAGIC: [u8; 4] = *b"ORST";
pub const VERSION: u16 = 10;
pub const HEADER: usize = 12;
pub const TRAILER: usize = 8;

/// Why a blob was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StateError {
    /// Shorter than its header says, or than the header itself.
    Truncated,
    /// Not a state blob (magic), or a length that does not fit this kind.
    Corrupt,
    /// The checksum does not match the content.
    Checksum,
    /// Written by another format version.
    Version(u16),
    /// Written by another kind of filter.
    Kind(u8),
    /// The output buffer is too small for the blob.
    BufferTooSmall(usize),
}

impl core::fmt::Display for StateError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            StateError::Truncated => write!(f, "state blob is truncated"),
            StateError::Corrupt => write!(
                f,
                "state blob does not fit what loads it (bad magic, length or value; for joints, another rig's)"
            ),
            StateError::Checksum => write!(f, "state blob checksum mismatch (corrupted)"),
            StateError::Version(v) => {
                write!(f, "state blob format version {v}, this library reads {VERSION}")
            }
            StateError::Kind(crate::joints::STATE_KIND) => {
                write!(f, "state blob is of joints: it loads only into the joints of the same rig")
            }
            StateError::Kind(k) => write!(f, "state blob is of filter kind {k}: it loads only into a filter of that kind"),
            StateError::BufferTooSmall(n) => write!(f, "buffer too small: the state needs {n} bytes"),
        }
    }
}

/// FNV-1a, 64 bit.
pub fn checksum(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= *b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// Both directions of the encoding with one description per type: `Writer` reads the
/// values and appends their bytes, `Reader` overwrites them from the bytes.
pub trait Codec {
    fn u64(&mut self, v: &mut u64);

    fn f64(&mut self, v: &mut f64) {
        let mut bits = v.to_bits();
        self.u64(&mut bits);
        *v = f64::from_bits(bits);
    }

    fn u32(&mut self, v: &mut u32) {
        let mut w = *v as u64;
        self.u64(&mut w);
        *v = w as u32;
        if w > u32::MAX as u64 {
            self.fail();
        }
    }

    fn usize(&mut self, v: &mut usize) {
        let mut w = *v as u64;
        self.u64(&mut w);
        *v = w as usize;
        if w > usize::MAX as u64 {
            self.fail();
        }
    }

    fn bool(&mut self, v: &mut bool) {
        let mut w = *v as u64;
        self.u64(&mut w);
        *v = w == 1;
        if w > 1 {
            self.fail();
        }
    }

    fn vec3(&mut self, v: &mut Vec3) {
        self.f64(&mut v.x);
        self.f64(&mut v.y);
        self.f64(&mut v.z);
    }

    fn quat(&mut self, q: &mut Quat) {
        self.f64(&mut q.w);
        self.f64(&mut q.x);
        self.f64(&mut q.y);
        self.f64(&mut q.z);
    }

    fn opt_vec3(&mut self, v: &mut Option<Vec3>) {
        let mut present = v.is_some();
        self.bool(&mut present);
        let mut value = v.unwrap_or_default();
        self.vec3(&mut value);
        *v = present.then_some(value);
    }

    fn opt_f64(&mut self, v: &mut Option<f64>) {
        let mut present = v.is_some();
        self.bool(&mut present);
        let mut value = v.unwrap_or_default();
        self.f64(&mut value);
        *v = present.then_some(value);
    }

    /// Marks the decoded data as invalid (reading only).
    fn fail(&mut self);
}

/// Appends values; counts the size when given no buffer.
pub struct Writer<'a> {
    pub buf: Option<&'a mut [u8]>,
    pub pos: usize,
}

impl Codec for Writer<'_> {
    fn u64(&mut self, v: &mut u64) {
        if let Some(buf) = self.buf.as_deref_mut() {
            buf[self.pos..self.pos + 8].copy_from_slice(&v.to_le_bytes());
        }
        self.pos += 8;
    }

    fn fail(&mut self) {}
}

/// Overwrites values from bytes; `ok` turns false on any inconsistency.
pub struct Reader<'a> {
    pub buf: &'a [u8],
    pub pos: usize,
    pub ok: bool,
}

impl Codec for Reader<'_> {
    /// No state holds NaN or infinity: such a value marks the blob invalid.
    fn f64(&mut self, v: &mut f64) {
        let mut bits = 0;
        self.u64(&mut bits);
        *v = f64::from_bits(bits);
        if !v.is_finite() {
            self.ok = false;
        }
    }

    fn u64(&mut self, v: &mut u64) {
        match self.buf.get(self.pos..self.pos + 8) {
            Some(b) => {
                let mut a = [0u8; 8];
                a.copy_from_slice(b);
                *v = u64::from_le_bytes(a);
            }
            None => self.ok = false,
        }
        self.pos += 8;
    }

    fn fail(&mut self) {
        self.ok = false;
    }
}

/// Writes the header and checksum around a payload of `payload_len` bytes produced by
/// `write` into `out`; returns the blob's length.
pub fn seal(
    out: &mut [u8],
    kind: u8,
    payload_len: usize,
    write: impl FnOnce(&mut Writer<'_>),
) -> Result<usize, StateError> {
    let total = HEADER + payload_len + TRAILER;
    if out.len() < total {
        return Err(StateError::BufferTooSmall(total));
    }
    out[0..4].copy_from_slice(&MAGIC);
    out[4..6].copy_from_slice(&VERSION.to_le_bytes());
    out[6] = kind;
    out[7] = 0;
    out[8..12].copy_from_slice(&(payload_len as u32).to_le_bytes());
    let mut w = Writer { buf: Some(&mut out[HEADER..HEADER + payload_len]), pos: 0 };
    write(&mut w);
    debug_assert_eq!(w.pos, payload_len);
    let sum = checksum(&out[..HEADER + payload_len]);
    out[HEADER + payload_len..total].copy_from_slice(&sum.to_le_bytes());
    Ok(total)
}

/// Checks a blob's frame for `kind` and returns its payload.
pub fn open(blob: &[u8], kind: u8, payload_len: usize) -> Result<&[u8], StateError> {
    if blob.len() < HEADER {
        return Err(StateError::Truncated);
    }
    if blob[0..4] != MAGIC {
        return Err(StateError::Corrupt);
    }
    let version = u16::from_le_bytes([blob[4], blob[5]]);
    let len = u32::from_le_bytes([blob[8], blob[9], blob[10], blob[11]]) as usize;
    // On a 32-bit target HEADER + len + TRAILER can overflow: no blob is that long.
    let Some(total) = len.checked_add(HEADER + TRAILER) else {
        return Err(StateError::Truncated);
    };
    if blob.len() < total {
        return Err(StateError::Truncated);
    }
    if blob.len() > total || blob[7] != 0 {
        return Err(StateError::Corrupt);
    }
    let mut sum = [0u8; 8];
    sum.copy_from_slice(&blob[HEADER + len..]);
    if u64::from_le_bytes(sum) != checksum(&blob[..HEADER + len]) {
        return Err(StateError::Checksum);
    }
    if version != VERSION {
        return Err(StateError::Version(version));
    }
    if blob[6] != kind {
        return Err(StateError::Kind(blob[6]));
    }
    if len != payload_len {
        return Err(StateError::Corrupt);
    }
    Ok(&blob[HEADER..HEADER + len])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refusals_name_what_the_blob_is() {
        let joints = StateError::Kind(crate::joints::STATE_KIND).to_string();
        assert!(joints.contains("of joints") && !joints.contains("filter kind"), "{joints}");
        assert!(StateError::Kind(3).to_string().contains("of filter kind 3"));
        assert!(StateError::Corrupt.to_string().contains("another rig"));
    }

    #[test]
    fn values_round_trip_bit_for_bit() {
        let mut vals =
            (1e300, -0.0f64, Some(Vec3::new(1.0, f64::MIN_POSITIVE, -3.5)), None::<Vec3>, true, 7u32);
        let encode = |c: &mut dyn Codec, v: &mut (f64, f64, Option<Vec3>, Option<Vec3>, bool, u32)| {
            c.f64(&mut v.0);
            c.f64(&mut v.1);
            c.opt_vec3(&mut v.2);
            c.opt_vec3(&mut v.3);
            c.bool(&mut v.4);
            c.u32(&mut v.5);
        };
        let mut counter = Writer { buf: None, pos: 0 };
        encode(&mut counter, &mut vals);
        let mut buf = vec![0u8; counter.pos];
        encode(&mut Writer { buf: Some(&mut buf), pos: 0 }, &mut vals);
        let mut back = (0.0, 0.0, None, Some(Vec3::ZERO), false, 0u32);
        let mut r = Reader { buf: &buf, pos: 0, ok: true };
        encode(&mut r, &mut back);
        assert!(r.ok);
        assert_eq!(back.0.to_bits(), vals.0.to_bits());
        assert_eq!(back.1.to_bits(), vals.1.to_bits());
        assert_eq!((back.2, back.3, back.4, back.5), (vals.2, vals.3, vals.4, vals.5));
    }

    #[test]
    fn frame_rejects_every_kind_of_damage() {
        let payload = [7u8; 16];
        let mut blob = vec![0u8; HEADER + 16 + TRAILER];
        let n = seal(&mut blob, 3, 16, |w| {
            for chunk in payload.chunks(8) {
                let mut v = u64::from_le_bytes(chunk.try_into().unwrap());
                w.u64(&mut v);
            }
        })
        .unwrap();
        assert_eq!(open(&blob[..n], 3, 16).unwrap(), &payload);
        assert_eq!(open(&blob[..n - 1], 3, 16), Err(StateError::Truncated));
        assert_eq!(open(&blob[..5], 3, 16), Err(StateError::Truncated));
        assert_eq!(open(&blob, 2, 16), Err(StateError::Kind(3)));
        for i in 0..n {
            let mut bad = blob.clone();
            bad[i] ^= 0x10;
            assert!(open(&bad, 3, 16).is_err(), "flipped byte {i} accepted");
        }
        let mut small = vec![0u8; 10];
        assert_eq!(seal(&mut small, 3, 16, |_| {}), Err(StateError::BufferTooSmall(HEADER + 16 + TRAILER)));
    }
}
