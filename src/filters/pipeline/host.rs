//! What a host puts around a filter: the sensor's mounting on its body segment, a
//! heading offset, the magnetic declination, and rig calibration from a reference
//! posture.
//!
//! The filter estimates the sensor's orientation `q` (sensor to earth). A host that
//! models segments (a hand's bones, a suit's limbs) wants the segment's. With the
//! mounting `m` (sensor to segment: `v_segment = m v_sensor`), the heading offset `h`
//! and the declination `d`, every orientation output is
//!
//! ```text
//! out = Rz(h - s d) ⊗ q ⊗ m*        s = +1 when the frame's z is up (ENU, NWU), -1 (NED)
//! ```
//!
//! `Rz` is a rotation about the configured frame's z axis, which is vertical in every
//! frame, so `h` and `d` change only the heading (the Euler yaw): `h` adds to it, and
//! the declination (east positive) turns a magnetic heading into a true one. All three
//! are kept by [`Filter::reset`] and [`Filter::set_param`], and saved in snapshots.

use crate::filters::error::Error;
use crate::filters::error::Field;
use crate::filters::pipeline::estimator::twist_about;
use crate::filters::pipeline::filter::Filter;
use crate::math::{Quat, Vec3};

/// The host's frames around the filter (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Host {
    /// Sensor to segment (unit).
    pub mounting: Quat,
    /// Heading offset (rad, about the frame's z axis), in (-π, π].
    pub heading: f64,
    /// Magnetic declination (rad, east positive), in [-π, π].
    pub declination: f64,
    /// The earth-side rotation `Rz(h - s d)`, kept ready.
    left: Quat,
    /// True when everything is the identity: outputs are the filter's own bits.
    identity: bool,
}

impl Default for Host {
    fn default() -> Self {
        Host {
            mounting: Quat::IDENTITY,
            heading: 0.0,
            declination: 0.0,
            left: Quat::IDENTITY,
            identity: true,
        }
    }
}

/// An angle in (-π, π].
fn wrap(a: f64) -> f64 {
    let pi = core::f64::consts::PI;
    let r = libm::remainder(a, 2.0 * pi);
    if r <= -pi {
        r + 2.0 * pi
    } else {
        r
    }
}

/// The angle of a rotation about z (its twist about z), in (-π, π].
fn z_angle(q: Quat) -> f64 {
    wrap(2.0 * libm::atan2(q.z, q.w))
}

fn rz(angle: f64) -> Quat {
    Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), angle)
}

fn check_angle(a: f64) -> Result<(), Error> {
    if a.is_finite() {
        Ok(())
    } else {
        Err(Error::NonFinite(Field::Angle))
    }
}

impl Host {
    /// Recomputes the cached rotation; `up_z` is the frame's up vector's z (±1). A
    /// negative zero in the mounting, heading or declination becomes +0 (`x + 0.0`;
    /// every other value is kept bit for bit): the outputs are the same either way, and
    /// a filter whose host frames equal the defaults saves the bytes a filter loaded from
    /// its blob saves (a load keeps no host frames equal to the defaults, compared with
    /// `==`, which does not tell the zeros apart).
    pub(crate) fn refresh(&mut self, up_z: f64) {
        let m = self.mounting;
        self.mounting = Quat::new(m.w + 0.0, m.x + 0.0, m.y + 0.0, m.z + 0.0);
        self.heading += 0.0;
        self.declination += 0.0;
        let angle = self.heading - up_z * self.declination;
        self.left = if angle == 0.0 { Quat::IDENTITY } else { rz(angle) };
        self.identity = self.mounting == Quat::IDENTITY && angle == 0.0;
    }

    /// The segment's orientation for the sensor's `q` (configured frame).
    #[inline]
    pub(crate) fn output(&self, q: Quat) -> Quat {
        if self.identity {
            q
        } else {
            (self.left * q * self.mounting.conj()).normalized()
        }
    }

    /// The sensor's orientation for an output orientation `out` (the inverse of
    /// [`Host::output`]).
    pub(crate) fn sensor_for(&self, out: Quat) -> Quat {
        if self.identity {
            out
        } else {
            (self.left.conj() * out * self.mounting).normalized()
        }
    }

    /// A vector in the filter's earth frame, in the output's earth frame.
    #[inline]
    pub(crate) fn earth(&self, v: Vec3) -> Vec3 {
        if self.identity {
            v
        } else {
            self.left.rotate(v)
        }
    }

    /// True when the decoded values are ones a filter can hold.
    pub(crate) fn valid(&self) -> bool {
        let pi = core::f64::consts::PI;
        let m = self.mounting;
        m.is_finite()
            && (m.norm_squared() - 1.0).abs() < 1e-9
            && self.heading.is_finite()
            && self.heading > -pi
            && self.heading <= pi
            && self.declination.is_finite()
            && self.declination.abs() <= pi
    }
}

/// How [`Filter::calibrate_rig`] picks the heading offsets: one common value, given or
/// estimated, or each filter's own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RigHeading {
    /// The reference posture's frame is turned by this yaw (rad, about the frame's z
    /// axis) from the filters' earth frame: a subject facing that way. The outputs are
    /// then in the reference posture's frame.
    Given(f64),
    /// Estimated: the yaw that brings the sensors' headings nearest their segments' on
    /// average, which is the subject's when the mountings have no heading part on
    /// average (sensors strapped along their segments, tilted as they may be).
    Estimated,
    /// Each filter's own, for filters that share no earth frame (6D: each heading is
    /// its filter's): the yaw that brings its sensor's heading nearest its segment's,
    /// each sensor taken as strapped along its segment (no turn about the vertical at
    /// the pose, which 6D cannot see): each mounting found is the sensor's tilt on its
    /// segment (for a level segment, a turn about a horizontal axis). The outputs are
    /// then in the reference posture's frame.
    Each,
}

impl Filter {
    /// The frame's up vector's z component: +1 (ENU, NWU) or -1 (NED).
    fn up_z(&self) -> f64 {
        self.frame().up().z
    }

    /// Sets the mounting: the rotation from the sensor's frame to its segment's
    /// (`v_segment = m v_sensor`; normalised). The orientation outputs are the segment's
    /// from then on. NonFinite, ZeroVector or TooLarge for an unusable quaternion.
    pub fn set_mounting(&mut self, m: Quat) -> Result<(), Error> {
        crate::filters::pipeline::sample::check_quaternion(m)?;
        self.host_mut().mounting = m.normalized();
        let up = self.up_z();
        self.host_mut().refresh(up);
        Ok(())
    }

    /// The mounting (sensor to segment); the identity unless set.
    pub fn mounting(&self) -> Quat {
        self.host().mounting
    }

    /// The sensor's own orientation (sensor to earth) in the output's earth frame: the
    /// heading offset and declination applied, the mounting not. With the identity
    /// mounting it is [`Filter::quaternion`].
    pub fn sensor_quaternion(&self) -> Quat {
        let q = self.frame_quaternion();
        if self.host().identity {
            q
        } else {
            (self.host().left * q).normalized()
        }
    }

    /// Turns the outputs about the vertical so that the yaw of [`Filter::euler`] becomes
    /// `yaw` (rad, wrapped to (-π, π]); inclination and mounting are kept, and the
    /// filter's own estimate is not touched (a magnetometer does not undo it).
    /// NotInitialized before the filter has an orientation; NonFinite for a NaN or
    /// infinite `yaw`.
    pub fn set_heading(&mut self, yaw: f64) -> Result<(), Error> {
        check_angle(yaw)?;
        if !self.is_initialized() {
            return Err(Error::NotInitialized);
        }
        let now = self.quaternion().to_euler().yaw;
        self.host_mut().heading = wrap(self.host().heading + wrap(yaw - now));
        let up = self.up_z();
        self.host_mut().refresh(up);
        Ok(())
    }

    /// [`Filter::set_heading`] to 0: the segment faces the frame's x axis (east in ENU,
    /// north in NED and NWU), its inclination kept.
    pub fn reset_heading(&mut self) -> Result<(), Error> {
        self.set_heading(0.0)
    }

    /// The heading offset (rad, in (-π, π]) that [`Filter::set_heading`] and rig
    /// calibration maintain; 0 unless set.
    pub fn heading_offset(&self) -> f64 {
        self.host().heading
    }

    /// Sets the magnetic declination (rad, east positive, in [-π, π]): the angle from
    /// true north to magnetic north. The outputs' heading is then turned by it, so that
    /// a heading taken from the magnetometer reads against true north. NonFinite for a
    /// NaN or infinite value, TooLarge beyond ±π.
    pub fn set_declination(&mut self, declination: f64) -> Result<(), Error> {
        check_angle(declination)?;
        if declination.abs() > core::f64::consts::PI {
            return Err(Error::TooLarge(Field::Angle));
        }
        self.host_mut().declination = declination;
        let up = self.up_z();
        self.host_mut().refresh(up);
        Ok(())
    }

    /// The magnetic declination (rad); 0 unless set.
    pub fn declination(&self) -> f64 {
        self.host().declination
    }

    /// Rig calibration from a reference posture: while the rig's segments hold the known
    /// orientations `references[i]` (segment to reference frame; an N-pose, a T-pose, a
    /// hand flat on a table), sets every filter's heading offset to one common value (see
    /// [`RigHeading`]; [`RigHeading::Each`]: each its own) and its mounting so that
    /// `filters[i]` reads `references[i]` exactly now, and the segment's orientation from
    /// then on. With a common value the filters must share one earth frame (a
    /// magnetometer); 6D filters take [`RigHeading::Each`], or else each one's heading
    /// would go into its mounting. Each filter's declination is kept. On error nothing
    /// changes: `(i, error)` names the first bad filter or reference (NotInitialized, or an
    /// unusable quaternion); `(0, MissingSensor(Quaternion))` when the lengths differ or
    /// are 0.
    pub fn calibrate_rig(
        filters: &mut [&mut Filter],
        references: &[Quat],
        heading: RigHeading,
    ) -> Result<(), (usize, Error)> {
        check_rig(filters, references)?;
        if let RigHeading::Given(h) = heading {
            check_angle(h).map_err(|e| (0, e))?;
        }
        // Each filter's earth-side rotation without a heading offset: its declination.
        let bare = |f: &Filter| {
            let mut h = f.host();
            h.heading = 0.0;
            h.refresh(f.up_z());
            h.left
        };
        let common = match heading {
            RigHeading::Given(h) => Some(wrap(-h)),
            RigHeading::Each => None,
            RigHeading::Estimated => Some({
                // The mean of each segment's heading from its sensor's: rotations about
                // z, averaged as quaternions (signs aligned with the first).
                let mut sum = Quat::new(0.0, 0.0, 0.0, 0.0);
                for (f, r) in filters.iter().zip(references) {
                    let sensor = bare(f) * f.frame_quaternion();
                    let d = twist_about(r.normalized() * sensor.conj(), Vec3::new(0.0, 0.0, 1.0));
                    let d = if sum.dot(d) < 0.0 { d.scale(-1.0) } else { d };
                    sum = Quat::new(sum.w + d.w, sum.x + d.x, sum.y + d.y, sum.z + d.z);
                }
                sum.try_normalized().map_or(0.0, z_angle)
            }),
        };
        for (f, r) in filters.iter_mut().zip(references) {
            let up_z = f.up_z();
            // Each: the turn about the vertical from the sensor's bare output to its segment.
            let offset = common.unwrap_or_else(|| {
                let sensor = bare(f) * f.frame_quaternion();
                wrap(z_angle(twist_about(r.normalized() * sensor.conj(), Vec3::new(0.0, 0.0, 1.0))))
            });
            f.host_mut().heading = offset;
            f.host_mut().refresh(up_z);
            let sensor = f.host().left * f.frame_quaternion();
            f.host_mut().mounting = (r.normalized().conj() * sensor).normalized();
            f.host_mut().refresh(up_z);
        }
        Ok(())
    }

    /// Rig heading alignment: while the segments hold `references[i]`, turns each
    /// filter's heading offset so that its segment's heading is the reference's (the
    /// rotation about the vertical that brings the output nearest the reference);
    /// mountings and inclinations are kept. For rigs whose mountings are known (or
    /// calibrated before) and whose filters' headings drifted apart: IMU-only filters,
    /// or after a restart. Errors as [`Filter::calibrate_rig`]; on error nothing changes.
    pub fn align_rig_heading(filters: &mut [&mut Filter], references: &[Quat]) -> Result<(), (usize, Error)> {
        check_rig(filters, references)?;
        for (f, r) in filters.iter_mut().zip(references) {
            let d = twist_about(r.normalized() * f.quaternion().conj(), Vec3::new(0.0, 0.0, 1.0));
            f.host_mut().heading = wrap(f.host().heading + z_angle(d));
            let up_z = f.up_z();
            f.host_mut().refresh(up_z);
        }
        Ok(())
    }
}

/// The checks both rig calls make before changing anything.
fn check_rig(filters: &[&mut Filter], references: &[Quat]) -> Result<(), (usize, Error)> {
    if filters.is_empty() || filters.len() != references.len() {
        return Err((0, Error::MissingSensor(Field::Quaternion)));
    }
    for (i, (f, r)) in filters.iter().zip(references).enumerate() {
        crate::filters::pipeline::sample::check_quaternion(*r).map_err(|e| (i, e))?;
        if !f.is_initialized() {
            return Err((i, Error::NotInitialized));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
