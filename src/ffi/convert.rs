//! Conversions between the C types and the core's, and the host sample read in place.

use super::*;

/// An output that needs an accelerometer reading, or NO_DATA.
pub(crate) fn measured(value: Option<Vec3>) -> Result<OrientVec3, OrientStatus> {
    let v = value.ok_or_else(|| fail(OrientStatus::NoData, format_args!("no accelerometer reading yet")))?;
    Ok(vec_to(v))
}

pub(crate) fn kind_from(kind: i32) -> Result<Kind, OrientStatus> {
    Kind::ALL
        .into_iter()
        .find(|k| OrientKind::from(*k) as i32 == kind)
        .ok_or_else(|| fail(OrientStatus::InvalidArgument, format_args!("unknown filter kind {kind}")))
}

pub(crate) fn kind_to(kind: Kind) -> i32 {
    OrientKind::from(kind) as i32
}

pub(crate) fn frame_from(frame: i32) -> Result<Frame, OrientStatus> {
    match frame {
        0 => Ok(Frame::Enu),
        1 => Ok(Frame::Ned),
        2 => Ok(Frame::Nwu),
        _ => Err(fail(OrientStatus::InvalidArgument, format_args!("unknown frame {frame}"))),
    }
}

pub(crate) fn frame_to(frame: Frame) -> i32 {
    (match frame {
        Frame::Enu => OrientFrame::Enu,
        Frame::Ned => OrientFrame::Ned,
        Frame::Nwu => OrientFrame::Nwu,
    }) as i32
}

pub(crate) fn vec_from(v: OrientVec3) -> Vec3 {
    Vec3::new(v.x, v.y, v.z)
}

pub(crate) fn vec_to(v: Vec3) -> OrientVec3 {
    OrientVec3 { x: v.x, y: v.y, z: v.z }
}

pub(crate) fn quat_from(q: OrientQuaternion) -> Quat {
    Quat::new(q.w, q.x, q.y, q.z)
}

pub(crate) fn quat_to(q: Quat) -> OrientQuaternion {
    OrientQuaternion { w: q.w, x: q.x, y: q.y, z: q.z }
}

pub(crate) const SAMPLE_ALL: u32 = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG;

/// A host's sample whose flags and reserved field have been checked, read in place.
#[derive(Clone, Copy)]
pub(crate) struct HostSample<'a>(&'a OrientSample);

impl HostSample<'_> {
    #[inline(always)]
    fn has(&self, bit: u32, v: &OrientVec3) -> Option<Vec3> {
        (self.0.flags & bit != 0).then(|| vec_from(*v))
    }
}

impl SampleView for HostSample<'_> {
    #[inline(always)]
    fn dt(&self) -> f64 {
        self.0.dt
    }
    #[inline(always)]
    fn gyro(&self) -> Option<Vec3> {
        self.has(ORIENT_SAMPLE_GYRO, &self.0.gyro)
    }
    #[inline(always)]
    fn accel(&self) -> Option<Vec3> {
        self.has(ORIENT_SAMPLE_ACCEL, &self.0.accel)
    }
    #[inline(always)]
    fn mag(&self) -> Option<Vec3> {
        self.has(ORIENT_SAMPLE_MAG, &self.0.mag)
    }
}

/// Checks a host's sample's flags and reserved field.
#[inline(always)]
pub(crate) fn host_sample(s: &OrientSample) -> Result<HostSample<'_>, OrientStatus> {
    if s.flags & !SAMPLE_ALL != 0 || s.reserved != 0 {
        return Err(fail(
            OrientStatus::InvalidArgument,
            format_args!("unknown sample flag bits {:#x} or non-zero reserved field", s.flags & !SAMPLE_ALL),
        ));
    }
    Ok(HostSample(s))
}

pub(crate) fn config_to(c: &Config) -> OrientConfig {
    let (init, initial) = match c.init {
        Init::AccMag => (OrientInit::AccMag, Quat::IDENTITY),
        Init::Identity => (OrientInit::Identity, Quat::IDENTITY),
        Init::Given(q) => (OrientInit::Given, q),
    };
    OrientConfig {
        struct_size: core::mem::size_of::<OrientConfig>() as u32,
        kind: kind_to(c.kind()),
        frame: frame_to(c.frame),
        init: init as i32,
        initial: quat_to(initial),
        params: *c.slots(),
    }
}

/// Checks a C configuration and turns it into a core one.
pub(crate) unsafe fn config_from(c: *const OrientConfig) -> Result<Config, OrientStatus> {
    if c.is_null() {
        return Err(null());
    }
    // Read the size first: an older or newer caller's struct may be shorter or longer.
    let size = core::ptr::addr_of!((*c).struct_size).read();
    if size as usize != core::mem::size_of::<OrientConfig>() {
        return Err(fail(
            OrientStatus::VersionMismatch,
            format_args!(
                "OrientConfig.struct_size is {size}, this library's is {}",
                core::mem::size_of::<OrientConfig>()
            ),
        ));
    }
    let c = &*c;
    let kind = kind_from(c.kind)?;
    let frame = frame_from(c.frame)?;
    let init = match c.init {
        0 => Init::AccMag,
        1 => Init::Identity,
        2 => Init::Given(quat_from(c.initial)),
        other => return Err(fail(OrientStatus::InvalidArgument, format_args!("unknown init mode {other}"))),
    };
    Config::from_slots(kind, frame, init, &c.params).map_err(from_core)
}

pub(crate) fn uncertainty_to(u: &crate::filters::Uncertainty) -> OrientUncertainty {
    let bit = |v: Option<f64>, b: u32| if v.is_some() { b } else { 0 };
    OrientUncertainty {
        present: bit(u.heading, ORIENT_UNCERTAINTY_HEADING)
            | bit(u.inclination, ORIENT_UNCERTAINTY_INCLINATION),
        reserved: 0,
        heading: u.heading.unwrap_or(f64::NAN),
        inclination: u.inclination.unwrap_or(f64::NAN),
    }
}

pub(crate) fn diagnostics_to(d: &crate::filters::Diagnostics) -> OrientDiagnostics {
    OrientDiagnostics {
        present: d.present,
        reserved: 0,
        gyro_bias: vec_to(d.gyro_bias),
        rest: d.rest,
        alpha: d.alpha,
        mu_ka: d.mu_ka,
        mu_km: d.mu_km,
        mu_k: d.mu_k,
        rate: vec_to(d.rate),
        covariance: d.covariance,
    }
}
