//! The hard-iron estimate: the reading minus the reference field seen at the current
//! orientation, compensated once it has been consistent long enough.

use super::*;

impl Robust {
    /// One step of the hard-iron estimate: the reading minus the reference field seen at
    /// the current orientation. Switches compensation on once consistent long enough.
    pub(super) fn estimate_hard_iron(&mut self, dt: f64, m: Vec3, q_e: Quat) {
        let s = self.settings;
        if s.hard_iron_time <= 0.0 {
            return;
        }
        let (sd, cd) = libm::sincos(self.ref_dip);
        let reference = Vec3::new(0.0, self.ref_norm * cd, -self.ref_norm * sd);
        let inst = m - self.q.rotate_inverse(reference);
        if !self.hi_started {
            self.hi_lp = inst;
            self.hi_spread = 0.0;
            self.hi_started = true;
        }
        let k = lp_gain(dt, s.rest_tau.max(0.25 * s.hard_iron_time));
        self.hi_lp = self.hi_lp + (inst - self.hi_lp) * k;
        self.hi_spread += ((inst - self.hi_lp).norm_squared() - self.hi_spread) * k;
        if !(self.hi_lp.is_finite() && self.hi_spread.is_finite()) {
            // Only a reading beyond the runner's bounds (a core driven directly) gets here:
            // the estimate starts over at the next disturbed reading instead of keeping a
            // NaN that the orientation's guard would never see.
            self.hi_started = false;
            self.hi_lp = Vec3::ZERO;
            self.hi_spread = 0.0;
            self.hi_clock = 0.0;
            return;
        }
        let tol = 0.5 * s.mag_norm_th * self.ref_norm;
        if self.hi_spread.sqrt() < tol && self.accepts(q_e.rotate(m - self.hi_lp)) {
            self.hi_clock += dt;
            if self.hi_clock >= s.hard_iron_time {
                self.hard_iron = self.hi_lp;
                self.hard_iron_on = true;
            }
        } else {
            // A leaky clock: a single noisy reading does not start the wait over (which
            // would make the wait depend on the sample rate); a third of failing readings
            // or more keeps it from ever completing.
            self.hi_clock = (self.hi_clock - 2.0 * dt).max(0.0);
        }
    }
}
