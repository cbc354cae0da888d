//! The library's joints ([`orient::joints`]) as a rig run's stage: the rig description's
//! joints and mountings handed to [`orient::joints::Joints`], which corrects every
//! sensor's orientation from the row where the headings were aligned on, or from the first
//! row with the headings unknown until they are aligned ([`Joints::until_aligned`]).

use crate::rig::{JointStage, RigSpec};
use orient::joints::{self, JointSpec};
use orient::{Quat, Sample};

pub use orient::joints::JointParams;

/// The joint stage of a rig run.
pub struct Joints {
    /// The library's estimator, the spec's joints in the spec's order.
    pub joints: joints::Joints,
    /// The first row estimated: with [`Joints::new`] where the headings were aligned, with
    /// [`Joints::until_aligned`] the first.
    start: usize,
    /// With [`Joints::until_aligned`]: the tuning the joints start over with at the
    /// alignment, and the tree to start them on.
    restart: Option<(JointParams, Vec<JointSpec>, Vec<Quat>)>,
}

impl Joints {
    /// Estimators for every joint of `spec`, from row `start` (where the headings were
    /// aligned) on.
    pub fn new(spec: &RigSpec, start: usize, params: JointParams) -> Joints {
        let (specs, mountings) = tree(spec);
        let joints = joints::Joints::new(spec.sensors.len(), &specs, &mountings, params)
            .expect("RigSpec::parse checked the tree");
        Joints { joints, start, restart: None }
    }

    /// Estimators for every joint of `spec` from the first row on, with `unknown` (the
    /// headings not aligned yet: its `heading_std0` large), until the run aligns the
    /// headings ([`JointStage::aligned`]): from that row on, new estimators with
    /// `aligned`, as [`Joints::new`] started there. A reference pose later in the
    /// recording, or one a sensor has no readings in (the alignment fails), leaves no row
    /// without joints.
    pub fn until_aligned(spec: &RigSpec, unknown: JointParams, aligned: JointParams) -> Joints {
        let mut j = Joints::new(spec, 0, unknown);
        let (specs, mountings) = tree(spec);
        j.restart = Some((aligned, specs, mountings));
        j
    }
}

/// The rig description's joints and mountings as the library takes them.
fn tree(spec: &RigSpec) -> (Vec<JointSpec>, Vec<Quat>) {
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
    (specs, mountings)
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

    fn aligned(&mut self, _row: usize) {
        if let Some((params, specs, mountings)) = self.restart.take() {
            self.joints = joints::Joints::new(mountings.len(), &specs, &mountings, params)
                .expect("RigSpec::parse checked the tree");
        }
    }
}
