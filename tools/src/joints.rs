//! The library's joints ([`orient::joints`]) as a rig run's stage: the rig description's
//! joints and mountings handed to [`orient::joints::Joints`], which corrects every
//! sensor's orientation from the row where the headings were aligned on.

use crate::rig::{JointStage, RigSpec};
use orient::joints::{self, JointSpec};
use orient::{Quat, Sample};

pub use orient::joints::JointParams;

/// The joint stage of a rig run.
pub struct Joints {
    /// The library's estimator, the spec's joints in the spec's order.
    pub joints: joints::Joints,
    /// The first row estimated (headings aligned there).
    start: usize,
}

impl Joints {
    /// Estimators for every joint of `spec`, from row `start` (where the headings were
    /// aligned) on.
    pub fn new(spec: &RigSpec, start: usize, params: JointParams) -> Joints {
        let specs: Vec<JointSpec> = spec
            .joints
            .iter()
            .map(|j| JointSpec {
                kind: j.kind,
                parent: j.parent,
                child: j.child,
                axis_parent: j.axis_parent,
                axis_child: j.axis_child,
            })
            .collect();
        let mountings: Vec<Quat> = spec.sensors.iter().map(|s| s.mounting).collect();
        let joints = joints::Joints::new(spec.sensors.len(), &specs, &mountings, params)
            .expect("RigSpec::parse checked the tree");
        Joints { joints, start }
    }
}

impl JointStage for Joints {
    fn update(&mut self, row: usize, samples: &[Sample], learns: &[bool], sensors: &mut [Quat]) {
        if row < self.start {
            return;
        }
        // A row the library refuses (a reading that is not finite) leaves the last
        // corrections in place.
        let _ = self.joints.update_each(|s| (sensors[s], samples[s], learns[s]));
        for (s, q) in sensors.iter_mut().enumerate() {
            *q = (self.joints.correction(s) * *q).normalized();
        }
    }
}
