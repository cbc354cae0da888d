//! The field reference the heading correction accepts: its norm and dip, learned at
//! start, confirmed while the sensor turns, and replaced by a different field seen
//! consistently while turning (the reference was a disturbance, or the place changed).

use super::*;

/// Dip of an earth-frame (ENU) field: positive when it points down.
pub(super) fn dip(f: Vec3) -> f64 {
    libm::asin((-f.z / f.norm()).clamp(-1.0, 1.0))
}

/// A field counts towards confirming the reference, or towards a new one, only while the
/// sensor turns at least this fast (rad/s; VQF's `magNewMinGyr`, 20 °/s): turning is what
/// tells a field fixed in the room from a magnet fixed to the sensor.
pub(super) const MAG_NEW_MIN_GYRO: f64 = 20.0 * core::f64::consts::PI / 180.0;

/// Seconds of turning with the reference accepted that confirm it (VQF's
/// `magNewFirstTime`).
pub(super) const MAG_CONFIRM_TIME: f64 = 5.0;

/// Seconds a different, consistent field must be seen while turning before it replaces a
/// confirmed reference (VQF's `magNewTime`).
pub(super) const MAG_NEW_TIME: f64 = 20.0;

/// The same for a reference never confirmed by turning (learned at rest: it may be a
/// disturbance the sensor started in).
pub(super) const MAG_FIRST_TIME: f64 = 3.0;

impl Robust {
    /// Tracks a candidate field (norm and dip of the raw readings in E′, low-passed while
    /// consistent). When the readings are rejected and the candidate has stayed
    /// consistent while the sensor turned for [`MAG_NEW_TIME`] (or [`MAG_FIRST_TIME`]
    /// when the reference was never confirmed by turning), it becomes the reference: the
    /// reference was a disturbance (a start inside a magnet's field) or the place changed.
    /// A magnet attached to the sensor changes the norm and dip as the sensor turns, so
    /// it never becomes a consistent candidate. When the new field is far from the old
    /// reference the heading starts over from it as at start (averaging gain), since it
    /// came from a disturbance. `n`, `d`: norm and dip of the raw reading in E′.
    pub(super) fn new_field(&mut self, dt: f64, n: f64, d: f64, turning: bool) {
        let s = self.settings;
        if (n - self.cand_norm).abs() <= s.mag_norm_th * self.cand_norm
            && (d - self.cand_dip).abs() <= s.mag_dip_th
        {
            if turning {
                self.cand_clock += dt;
            }
            let k = lp_gain(dt, s.tau_mag);
            self.cand_norm += (n - self.cand_norm) * k;
            self.cand_dip += (d - self.cand_dip) * k;
        } else {
            self.cand_clock = 0.0;
            self.cand_norm = n;
            self.cand_dip = d;
        }
        let wait = if self.ref_confirmed >= MAG_CONFIRM_TIME { MAG_NEW_TIME } else { MAG_FIRST_TIME };
        if self.mag_disturbed && self.cand_clock >= wait {
            // A field far from the old reference (beyond twice the disturbance tests)
            // shows that the old one was a disturbance, and the heading learned from it
            // wrong; a nearby one is the same place seen better, and the heading stays.
            let far = (self.cand_norm - self.ref_norm).abs() > 2.0 * s.mag_norm_th * self.ref_norm
                || (self.cand_dip - self.ref_dip).abs() > 2.0 * s.mag_dip_th;
            self.ref_norm = self.cand_norm;
            self.ref_dip = self.cand_dip;
            self.ref_confirmed = 0.0;
            self.cand_clock = 0.0;
            if far {
                self.mag_count = 1;
                self.heading_var.lost();
                self.heading_var.forget_innovation();
            }
            self.hard_iron_on = false;
            self.hi_started = false;
            self.hi_clock = 0.0;
        }
    }

    pub(super) fn accepts(&self, f_e: Vec3) -> bool {
        self.accepts_norm_dip(f_e.norm(), dip(f_e))
    }

    /// The norm and dip tests against the reference.
    pub(super) fn accepts_norm_dip(&self, norm: f64, dip: f64) -> bool {
        let s = &self.settings;
        (norm - self.ref_norm).abs() <= s.mag_norm_th * self.ref_norm
            && (dip - self.ref_dip).abs() <= s.mag_dip_th
    }
}
