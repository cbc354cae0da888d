//! What the trust values of Appendix B are computed from: the running minimum of μ over
//! its window (Appendix B.2) and the regression over a static run.

use super::*;

pub(super) const WINDOW_SLOTS: usize = 1024;

/// Running minimum over a time window: a monotonic queue in a fixed ring buffer.
/// Entries closer than window/1000 in time share a slot, so the buffer never overflows
/// and the window is exact to that resolution.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct MinWindow {
    pub(super) t: [f64; WINDOW_SLOTS],
    pub(super) v: [f64; WINDOW_SLOTS],
    pub(super) head: usize,
    pub(super) len: usize,
}

impl MinWindow {
    pub(super) fn new() -> MinWindow {
        MinWindow { t: [0.0; WINDOW_SLOTS], v: [0.0; WINDOW_SLOTS], head: 0, len: 0 }
    }

    pub(super) fn back(&self) -> usize {
        (self.head + self.len - 1) % WINDOW_SLOTS
    }

    /// The minimum over `(now − window, now]` if `value` were added at `now`, without
    /// adding it.
    pub(super) fn peek(&self, now: f64, value: f64, window: f64) -> f64 {
        (0..self.len)
            .map(|k| (self.head + k) % WINDOW_SLOTS)
            .find(|&i| self.t[i] > now - window)
            .map_or(value, |i| self.v[i].min(value))
    }

    /// Adds `value` at time `now` and returns the minimum over `(now − window, now]`.
    pub(super) fn push(&mut self, now: f64, value: f64, window: f64) -> f64 {
        while self.len > 0 && self.t[self.head] <= now - window {
            self.head = (self.head + 1) % WINDOW_SLOTS;
            self.len -= 1;
        }
        while self.len > 0 && self.v[self.back()] >= value {
            self.len -= 1;
        }
        let resolution = window / 1000.0;
        let merge = self.len > 0 && now - self.t[self.back()] < resolution;
        if !merge {
            if self.len == WINDOW_SLOTS {
                // Unreachable with the resolution above; keep the newest if it happens.
                self.head = (self.head + 1) % WINDOW_SLOTS;
                self.len -= 1;
            }
            let i = (self.head + self.len) % WINDOW_SLOTS;
            self.t[i] = now;
            self.v[i] = value;
            self.len += 1;
        }
        self.v[self.head]
    }
}

/// Least-squares line through (t, ω) per axis, by running sums.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Regression {
    pub(super) n: f64,
    pub(super) t0: f64,
    pub(super) st: f64,
    pub(super) stt: f64,
    pub(super) sy: Vec3,
    pub(super) sty: Vec3,
    pub(super) last_t: f64,
}

impl Regression {
    pub(super) fn add(&mut self, t: f64, y: Vec3) {
        if self.n == 0.0 {
            self.t0 = t;
        }
        let t = t - self.t0;
        self.n += 1.0;
        self.st += t;
        self.stt += t * t;
        self.sy = self.sy + y;
        self.sty = self.sty + y * t;
        self.last_t = t;
    }

    pub(super) fn duration(&self) -> f64 {
        if self.n == 0.0 {
            0.0
        } else {
            self.last_t
        }
    }

    /// The fitted value at the last sample time.
    pub(super) fn value_at_end(&self) -> Vec3 {
        let d = self.n * self.stt - self.st * self.st;
        if self.n < 2.0 || d.abs() < 1e-300 {
            return self.sy * (1.0 / self.n);
        }
        let slope = (self.sty * self.n - self.sy * self.st) * (1.0 / d);
        let intercept = (self.sy - slope * self.st) * (1.0 / self.n);
        intercept + slope * self.last_t
    }
}
