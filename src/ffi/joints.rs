//! The C calls for a rig's joints (issue 42): the handle, its update from the filters'
//! orientations, and its outputs. See `crate::joints`.

use super::*;
use crate::filters::pipeline::sample::check_quaternion;
use crate::joints::{
    estimate_hinge_axes_by, estimate_two_dof_axes_by, JointError, JointKind, JointParams, JointSpec, Joints,
    JOINT_PARAMS,
};

/// OrientJoint.kind: one degree of freedom. The child turns about one axis,
/// `axis_parent` in the parent sensor's frame and `axis_child` in the child's, the same
/// line at every instant (an elbow, a knee, a finger's PIP and DIP joints).
pub const ORIENT_JOINT_HINGE: i32 = 0;
/// OrientJoint.kind: two degrees of freedom. The child turns about `axis_parent` (fixed
/// in the parent), then about `axis_child` (fixed in the child), the two perpendicular (a
/// wrist, a finger's MCP joint, an ankle).
pub const ORIENT_JOINT_TWO_DOF: i32 = 1;
/// OrientJoint.axes_frame: the axes are given in the sensors' frames.
pub const ORIENT_JOINT_AXES_SENSOR: u32 = 0;
/// OrientJoint.axes_frame: the axes are given in the segments' frames (a segment's
/// anatomical axes: a finger's flexion axis in its bone's frame), and turned into the
/// sensors' through the mountings (v_sensor = conj(m) v_segment m).
pub const ORIENT_JOINT_AXES_SEGMENT: u32 = 1;
/// The most joints one OrientJoints holds (two hands have 30, a suit 19).
pub const ORIENT_MAX_JOINTS: usize = 64;
const _: () = assert!(ORIENT_MAX_JOINTS == crate::joints::MAX_JOINTS);
/// The most segments one OrientJoints holds.
pub const ORIENT_MAX_SEGMENTS: usize = 256;

/// One joint of a rig: segment indices (a segment is one sensor with its filter, by its
/// index in the filters array of orient_joints_update) and axes in the sensors' frames
/// (normalised: any length whose square is a normal finite double).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct OrientJoint {
    /// ORIENT_JOINT_HINGE or ORIENT_JOINT_TWO_DOF.
    pub kind: i32,
    /// The parent segment.
    pub parent: u32,
    /// The child segment.
    pub child: u32,
    /// ORIENT_JOINT_AXES_SENSOR (0): the axes below are in the sensors' frames;
    /// ORIENT_JOINT_AXES_SEGMENT: in the segments' frames (anatomical axes), turned into
    /// the sensors' through orient_joints_new's mountings.
    pub axes_frame: u32,
    /// The (first) axis in the parent's frame.
    pub axis_parent: OrientVec3,
    /// The hinge's axis, or the second axis of a 2-DoF joint, in the child's frame.
    pub axis_child: OrientVec3,
}

/// A joint's axes estimated from motion (orient_estimate_hinge_axes,
/// orient_estimate_two_dof_axes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct OrientJointAxes {
    /// The (first) axis in the parent sensor's frame (unit, on the side of the guess).
    pub axis_parent: OrientVec3,
    /// The hinge's axis, or the 2-DoF joint's second axis, in the child sensor's frame
    /// (unit, on the side of the guess).
    pub axis_child: OrientVec3,
    /// How far the motion bears the axes out, 0 to 1; below 0.1 they can be trusted. A
    /// hinge: RMS residual over RMS angular rate perpendicular to the axis (0 for an
    /// ideal hinge, a few hundredths with laxity and noise, near 1 when the motion did
    /// not turn the joint or the joint is no hinge). A 2-DoF joint: the larger of the RMS
    /// residual (rad, how far from perpendicular the axes were seen) and three times the
    /// axes' standard error (rad, large when the motion did not turn the joint about both
    /// axes far enough, as a hinge's does not).
    pub quality: f64,
}

/// A rig's joints and their estimates (opaque to C): create with orient_joints_new,
/// release with orient_joints_free. Its address is its identity in the registry of live
/// handles, as a filter's is.
pub struct OrientJoints {
    pub(crate) joints: Joints,
}

/// The registry entry of a joints handle: its address with bit 1 set, which no filter's
/// address has (both are 8-byte aligned boxes), so neither kind of handle passes for the
/// other. A pointer that is not 8-byte aligned is no handle of either kind (its key would
/// be some handle's): refused before the lookup, here and in `handle`.
fn key(h: *const OrientJoints) -> Option<usize> {
    (h as usize & 7 == 0).then_some(h as usize | 2)
}

unsafe fn joints_ref<'a>(h: *const OrientJoints) -> Result<&'a OrientJoints, OrientStatus> {
    if h.is_null() {
        return Err(null());
    }
    if !key(h).is_some_and(|k| registry::HANDLES.contains(k)) {
        return Err(fail(OrientStatus::InvalidHandle, format_args!("not a live OrientJoints handle: {h:p}")));
    }
    Ok(&*h)
}

unsafe fn joints_mut<'a>(h: *mut OrientJoints) -> Result<&'a mut OrientJoints, OrientStatus> {
    joints_ref(h)?;
    Ok(&mut *h)
}

fn joint_error(e: JointError) -> OrientStatus {
    let status = match e {
        JointError::TooMany(_) | JointError::TooManySegments(_) => OrientStatus::CountTooLarge,
        JointError::OutOfMemory => OrientStatus::OutOfMemory,
        JointError::NoSuchSegment(_)
        | JointError::OwnParent(_)
        | JointError::TwoParents(_)
        | JointError::Cycle(_)
        | JointError::BadAxis(_) => OrientStatus::InvalidJoint,
        JointError::BadMounting(_) => OrientStatus::ZeroVector,
        JointError::BadParams | JointError::WrongLength(_) => OrientStatus::InvalidArgument,
        JointError::NonFinite(_) => OrientStatus::NonFinite,
        JointError::UnknownParam => OrientStatus::UnknownParam,
        JointError::ParamOutOfRange(_) => OrientStatus::ParamOutOfRange,
    };
    fail(status, format_args!("{e}"))
}

fn index(i: usize, n: usize, what: &str) -> Result<usize, OrientStatus> {
    if i < n {
        Ok(i)
    } else {
        Err(fail(OrientStatus::InvalidArgument, format_args!("{what} {i}: the rig has {n}")))
    }
}

/// orient_config_for_joints (`joint_settings.rs`, generated for its doc): the recommended
/// kind's settings under joints, only the slots they change written to `config`.
pub(super) unsafe fn config_for_joints(config: *mut OrientConfig) -> OrientStatus {
    guard(|| {
        let before = config_from(config)?;
        let mut c = before.clone();
        c.for_joints();
        // Only the slots set: the others stay as the caller's struct has them.
        for (i, (a, b)) in before.slots().iter().zip(c.slots()).enumerate() {
            if a.to_bits() != b.to_bits() {
                (*config).params[i] = *b;
            }
        }
        Ok(())
    })
}

/// Creates a rig's joints: `n_joints` joints (NULL only when 0) over `n_segments`
/// segments, with the sensors' `mountings` (sensor to segment, as
/// orient_filter_set_mounting; NULL for the identity everywhere, else `n_segments` of
/// them), which give the joint angles' zero: the reference pose, every segment's frame
/// the same. The joints form a forest (each segment the child of at most one joint, no
/// cycle); a segment that is no joint's child is a root, whose orientation is its
/// filter's. On success `*out` is a new handle; on failure it is set to NULL (when `out`
/// is not NULL). INVALID_JOINT for a joint that names a segment at or beyond
/// `n_segments`, whose child is its parent, whose child is already another joint's
/// child, that closes a cycle, or whose axis is NaN or infinite or has a squared norm
/// that is not a normal finite double (zero, too small or too large to normalise); the
/// detail names the joint. Axes given in the segments' frames (`axes_frame` ORIENT_JOINT_AXES_SEGMENT)
/// are turned into the sensors' through the mountings first. INVALID_ARGUMENT for an
/// unknown kind or axes_frame, or
/// `n_segments` 0; COUNT_TOO_LARGE for more than ORIENT_MAX_JOINTS joints or
/// ORIENT_MAX_SEGMENTS segments, or when the most handles the library holds are live; a
/// mounting is checked as orient_filter_set_quaternion checks its quaternion:
/// NON_FINITE, ZERO_VECTOR or TOO_LARGE. OUT_OF_MEMORY when the joints' memory (about 3.7
/// KiB a joint) cannot be allocated.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_new(
    joints: *const OrientJoint,
    n_joints: usize,
    n_segments: usize,
    mountings: *const OrientQuaternion,
    out: *mut *mut OrientJoints,
) -> OrientStatus {
    guard(|| {
        if out.is_null() {
            return Err(null());
        }
        out.write(core::ptr::null_mut());
        if n_joints > ORIENT_MAX_JOINTS {
            return Err(fail(
                OrientStatus::CountTooLarge,
                format_args!("{n_joints} joints: at most ORIENT_MAX_JOINTS ({ORIENT_MAX_JOINTS})"),
            ));
        }
        if n_segments == 0 || n_segments > ORIENT_MAX_SEGMENTS {
            let status =
                if n_segments == 0 { OrientStatus::InvalidArgument } else { OrientStatus::CountTooLarge };
            return Err(fail(
                status,
                format_args!("{n_segments} segments: from 1 to ORIENT_MAX_SEGMENTS ({ORIENT_MAX_SEGMENTS})"),
            ));
        }
        let given = items(joints, n_joints, "joints")?;
        let mut specs = [JointSpec {
            kind: JointKind::Hinge,
            parent: 0,
            child: 0,
            axis_parent: Vec3::ZERO,
            axis_child: Vec3::ZERO,
        }; ORIENT_MAX_JOINTS];
        for (k, (j, spec)) in given.iter().zip(specs.iter_mut()).enumerate() {
            let kind = match j.kind {
                ORIENT_JOINT_HINGE => JointKind::Hinge,
                ORIENT_JOINT_TWO_DOF => JointKind::TwoDof,
                other => {
                    return Err(fail(
                        OrientStatus::InvalidArgument,
                        format_args!("joint {k}: unknown kind {other}"),
                    ))
                }
            };
            if j.axes_frame > ORIENT_JOINT_AXES_SEGMENT {
                return Err(fail(
                    OrientStatus::InvalidArgument,
                    format_args!("joint {k}: unknown axes_frame {}", j.axes_frame),
                ));
            }
            *spec = JointSpec {
                kind,
                parent: j.parent as usize,
                child: j.child as usize,
                axis_parent: vec_from(j.axis_parent),
                axis_child: vec_from(j.axis_child),
            };
        }
        let mut m = [Quat::IDENTITY; ORIENT_MAX_SEGMENTS];
        if !mountings.is_null() {
            for (s, (q, into)) in
                items(mountings, n_segments, "mountings")?.iter().zip(m.iter_mut()).enumerate()
            {
                let q = quat_from(*q);
                check_quaternion(q).map_err(|e| {
                    let status = from_core(e);
                    fail(status, format_args!("mounting {s}: {e}"))
                })?;
                *into = q;
            }
        }
        // Axes given in the segments' frames, into the sensors' (a segment index the rig
        // does not have is left for Joints::new to name).
        for (j, spec) in given.iter().zip(specs.iter_mut()) {
            if j.axes_frame == ORIENT_JOINT_AXES_SEGMENT
                && spec.parent < n_segments
                && spec.child < n_segments
            {
                *spec = spec.in_sensor_frames(m[spec.parent], m[spec.child]);
            }
        }
        let j = Joints::new(n_segments, &specs[..n_joints], &m[..n_segments], JointParams::default())
            .map_err(joint_error)?;
        let h = Box::into_raw(Box::new(OrientJoints { joints: j }));
        if !key(h).is_some_and(|k| registry::HANDLES.insert(k)) {
            drop(Box::from_raw(h));
            return Err(fail(
                OrientStatus::CountTooLarge,
                format_args!("{} handles are live, the most this library holds at once", registry::CAPACITY),
            ));
        }
        out.write(h);
        Ok(())
    })
}

/// Releases a rig's joints (the filters are the host's and stay). NULL is a no-op
/// (ORIENT_STATUS_OK); a handle already freed, or any pointer orient_joints_new did not
/// return (an OrientFilter among them), is INVALID_HANDLE and nothing is read or freed
/// through it.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_free(joints: *mut OrientJoints) -> OrientStatus {
    guard(|| {
        if joints.is_null() {
            return Ok(());
        }
        if !key(joints).is_some_and(|k| registry::HANDLES.remove(k)) {
            return Err(fail(
                OrientStatus::InvalidHandle,
                format_args!("not a live OrientJoints handle: {joints:p}"),
            ));
        }
        drop(Box::from_raw(joints));
        Ok(())
    })
}

/// One row of the rig: after `filters[s]` took `samples[s]` (orient_filter_update or
/// orient_filters_update), for each of the `n` segments (`n` as given to
/// orient_joints_new), updates every joint from the filters' sensor orientations
/// (orient_filter_sensor_quaternion) and the samples' gyroscope and accelerometer
/// readings, and whether each filter learns its gyroscope bias in motion (by its kind and
/// settings: the joint parameter bias_learn_rate). A joint whose two samples do not both
/// have both readings holds its estimate this row; the child's dt is the joint's, and one
/// outside [1e-9, 1) s holds it too.
/// Allocates nothing. Every handle and sample is checked before anything changes:
/// INVALID_ARGUMENT for an `n` that is not the rig's segment count or a sample with
/// unknown flag bits or a non-zero reserved field, NULL_POINTER for a NULL array or
/// filter, INVALID_HANDLE for a `joints` or filter that is not live, NON_FINITE for a
/// NaN or infinite dt, gyroscope or accelerometer reading; the detail names the segment.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_update(
    joints: *mut OrientJoints,
    filters: *const *mut OrientFilter,
    samples: *const OrientSample,
    n: usize,
) -> OrientStatus {
    guard(|| {
        need(filters.is_null() || samples.is_null())?;
        let j = joints_mut(joints)?;
        let segments = j.joints.segments();
        if n != segments {
            return Err(fail(
                OrientStatus::InvalidArgument,
                format_args!("n = {n}: the rig has {segments} segments"),
            ));
        }
        let handles = items(filters, n, "filters")?;
        let rows = items(samples, n, "samples")?;
        for (s, (h, x)) in handles.iter().zip(rows).enumerate() {
            if h.is_null() {
                return Err(fail(OrientStatus::NullPointer, format_args!("filter {s} is NULL")));
            }
            handle(*h)
                .map_err(|status| fail(status, format_args!("filter {s}: not a live OrientFilter handle")))?;
            host_sample(x).map_err(|status| {
                fail(status, format_args!("sample {s}: unknown flag bits or reserved field"))
            })?;
        }
        let row = |s: usize| {
            // Checked above: every handle is live and every sample's flags are known.
            let f = &(*handles[s]).filter;
            (
                f.sensor_quaternion(),
                host_sample(&rows[s]).map(|x| x.to_sample()).unwrap_or_default(),
                f.learns_bias_in_motion(),
            )
        };
        j.joints.update_each(row).map_err(|e| match e {
            JointError::NonFinite(s) => {
                fail(OrientStatus::NonFinite, format_args!("segment {s}: a value is NaN or infinite"))
            }
            e => joint_error(e),
        })
    })
}

/// Segment `segment`'s orientation (segment to earth, the filters' earth frame) after
/// the last orient_joints_update: its sensor's orientation with the joints' correction and
/// the segment's mounting given to orient_joints_new applied, the bone rotation a host
/// draws (the filters' own mountings are not read: give orient_joints_new each filter's
/// orient_filter_mounting). Before the first update, the identity's rotation by the
/// mounting's inverse. INVALID_ARGUMENT for a segment at or beyond the rig's count.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_segment_quaternion(
    joints: *const OrientJoints,
    segment: usize,
    out: *mut OrientQuaternion,
) -> OrientStatus {
    guard(|| {
        put(out, || {
            let j = &joints_ref(joints)?.joints;
            Ok(quat_to(j.segment_quaternion(index(segment, j.segments(), "segment")?)))
        })
    })
}

/// Joint `joint`'s angles (radians) after the last orient_joints_update, in
/// `angles[0]` and `angles[1]` (room for 2): zero in the reference pose (every segment's frame the same, see
/// orient_joints_new's mountings), positive by the right-hand rule about the joint's axes
/// as refined from motion. A hinge: `angles[0]` its angle, `angles[1]` NaN. A 2-DoF joint:
/// the turn about `axis_parent`, then the turn about `axis_child` that make up the
/// child's orientation relative to its parent. 0 before the first update.
/// INVALID_ARGUMENT for a joint at or beyond the rig's count.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_angles(
    joints: *const OrientJoints,
    joint: usize,
    angles: *mut f64,
) -> OrientStatus {
    guard(|| {
        put(angles.cast::<[f64; 2]>(), || {
            let j = &joints_ref(joints)?.joints;
            Ok(j.angles(index(joint, j.specs().len(), "joint")?))
        })
    })
}

/// Joint `joint`'s observability rating in [0, 1]: how much its constraints told about
/// the child's heading relative to its parent over the last two seconds. Near 0 at rest
/// (when only the filters' measured drift moves the relative heading) and while a hinge's
/// axis is vertical (when it is held on the drift estimate); near 1 for a horizontal axis
/// in motion. INVALID_ARGUMENT for a joint at or beyond the rig's count.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_rating(
    joints: *const OrientJoints,
    joint: usize,
    rating: *mut f64,
) -> OrientStatus {
    guard(|| {
        put(rating, || {
            let j = &joints_ref(joints)?.joints;
            Ok(j.rating(index(joint, j.specs().len(), "joint")?))
        })
    })
}

/// Joint `joint`'s correction of its child's heading relative to its parent (radians,
/// about the vertical) and its standard deviation (4 at most, to rounding: a heading
/// nothing observes for long is held at that uncertainty). INVALID_ARGUMENT for a joint at or
/// beyond the rig's count. `sigma` may be NULL.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_relative_heading(
    joints: *const OrientJoints,
    joint: usize,
    heading: *mut f64,
    sigma: *mut f64,
) -> OrientStatus {
    guard(|| {
        need(heading.is_null())?;
        let j = &joints_ref(joints)?.joints;
        let k = index(joint, j.specs().len(), "joint")?;
        heading.write(j.relative_heading(k));
        if !sigma.is_null() {
            sigma.write(j.heading_std(k));
        }
        Ok(())
    })
}

/// Joint `joint`'s axes as refined from motion (unit; the parent sensor's and the child
/// sensor's frame). INVALID_ARGUMENT for a joint at or beyond the rig's count.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_axes(
    joints: *const OrientJoints,
    joint: usize,
    axis_parent: *mut OrientVec3,
    axis_child: *mut OrientVec3,
) -> OrientStatus {
    guard(|| {
        need(axis_parent.is_null() || axis_child.is_null())?;
        let j = &joints_ref(joints)?.joints;
        let (a, b) = j.axes(index(joint, j.specs().len(), "joint")?);
        axis_parent.write(vec_to(a));
        axis_child.write(vec_to(b));
        Ok(())
    })
}

/// Starts every joint's estimate over: no correction, the axes as given; the outputs are
/// then the last update's filter orientations, uncorrected. For a rig whose filters were
/// reset or whose headings were aligned again (orient_rig_align_heading).
#[no_mangle]
pub unsafe extern "C" fn orient_joints_reset(joints: *mut OrientJoints) -> OrientStatus {
    guard(|| {
        joints_mut(joints)?.joints.reset();
        Ok(())
    })
}

/// Size in bytes of this rig's joint state blob (orient_joints_save); constant for a rig.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_state_size(
    joints: *const OrientJoints,
    size: *mut usize,
) -> OrientStatus {
    guard(|| put(size, || Ok(joints_ref(joints)?.joints.state_size())))
}

/// Saves the joints' estimates, with the rig's description (joints, axes as given,
/// mountings), as a versioned, checksummed blob into `buffer` (`capacity` bytes);
/// `*written` receives its length. ORIENT_STATUS_BUFFER_TOO_SMALL when `capacity` is
/// below orient_joints_state_size(), COUNT_TOO_LARGE for a `capacity` no buffer can have.
/// Joints loaded with the blob continue bit for bit as these would, given the same
/// filters' states (orient_filter_save each).
#[no_mangle]
pub unsafe extern "C" fn orient_joints_save(
    joints: *const OrientJoints,
    buffer: *mut u8,
    capacity: usize,
    written: *mut usize,
) -> OrientStatus {
    guard(|| {
        need(buffer.is_null() || written.is_null())?;
        let j = joints_ref(joints)?;
        let n = j.joints.save(blob_out(buffer, capacity)?).map_err(from_state)?;
        written.write(n);
        Ok(())
    })
}

/// The number of joint parameters, the tuning every joint of a rig shares
/// (orient_joint_param_info lists them).
#[no_mangle]
pub unsafe extern "C" fn orient_joint_param_count(count: *mut u32) -> OrientStatus {
    guard(|| put(count, || Ok(JOINT_PARAMS.len() as u32)))
}

/// Describes joint parameter number `index` (0 <= index < orient_joint_param_count): its
/// name (what orient_joints_set_param takes), unit, meaning, default and accepted range;
/// `id` is `index` and `flags` 0. The strings are the library's, static.
/// INVALID_ARGUMENT for an index at or beyond the count.
#[no_mangle]
pub unsafe extern "C" fn orient_joint_param_info(index: u32, info: *mut OrientParamInfo) -> OrientStatus {
    guard(|| {
        need(info.is_null())?;
        let Some(spec) = JOINT_PARAMS.get(index as usize) else {
            return Err(fail(
                OrientStatus::InvalidArgument,
                format_args!("joint parameter index {index}: there are {}", JOINT_PARAMS.len()),
            ));
        };
        let text = strings::joint_param_text(index).ok_or_else(|| {
            fail(OrientStatus::Panic, format_args!("no strings for joint parameter {index}"))
        })?;
        put(info, || Ok(super::config::param_info(spec, text)))
    })
}

/// The table's name for the C string `name`; UNKNOWN_PARAM when no joint parameter has it.
unsafe fn joint_param(name: *const c_char) -> Result<&'static str, OrientStatus> {
    let name = CStr::from_ptr(name).to_str().unwrap_or("");
    JOINT_PARAMS
        .iter()
        .find(|s| s.name == name)
        .map(|s| s.name)
        .ok_or_else(|| fail(OrientStatus::UnknownParam, format_args!("no joint parameter '{name}'")))
}

/// Reads the joint parameter called `name` (NUL-terminated; orient_joint_param_info
/// lists them) of a rig's joints into `value`. INVALID_HANDLE for joints that are not
/// live, UNKNOWN_PARAM for a name no joint parameter has.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_get_param(
    joints: *const OrientJoints,
    name: *const c_char,
    value: *mut f64,
) -> OrientStatus {
    guard(|| {
        need(name.is_null() || value.is_null())?;
        let j = &joints_ref(joints)?.joints;
        let name = joint_param(name)?;
        let v = j.param(name).ok_or_else(|| fail(OrientStatus::Panic, format_args!("{name} unread")))?;
        value.write(v);
        Ok(())
    })
}

/// Sets the joint parameter called `name` (NUL-terminated; orient_joint_param_info lists
/// them with their ranges) for every joint of the rig, the estimates kept: taken from the
/// next orient_joints_update on, and an initial standard deviation (a name ending in
/// `_std0`) when the estimates next start (orient_joints_reset; before the first update,
/// at once; and while rows contradict a joint's estimate, which then widens its variances
/// to the initial ones again: for filters whose headings were not aligned, heading_std0 as far apart as they
/// may be, and a hinge finds 30 degrees within a degree in a minute of motion; align
/// larger offsets first, orient_rig_align_heading). A blob saved with
/// another value no longer loads (orient_joints_load: INVALID_STATE). INVALID_HANDLE for
/// joints that are not live, UNKNOWN_PARAM for a name no joint parameter has,
/// PARAM_OUT_OF_RANGE for a value outside its range (NaN, infinite and subnormal values
/// included); either changes nothing.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_set_param(
    joints: *mut OrientJoints,
    name: *const c_char,
    value: f64,
) -> OrientStatus {
    guard(|| {
        need(name.is_null())?;
        let j = &mut joints_mut(joints)?.joints;
        let name = joint_param(name)?;
        j.set_param(name, value).map_err(joint_error)
    })
}

/// Restores a blob from orient_joints_save into joints made for the same rig (the same
/// joints, axes as given, mountings and joint parameters). ORIENT_STATUS_INVALID_STATE, with the joints
/// unchanged, for a blob that is truncated, corrupted, of another format version, a
/// filter's, another rig's, or holding a state no joint could hold; COUNT_TOO_LARGE for a
/// `size` no buffer can have.
#[no_mangle]
pub unsafe extern "C" fn orient_joints_load(
    joints: *mut OrientJoints,
    buffer: *const u8,
    size: usize,
) -> OrientStatus {
    guard(|| {
        need(buffer.is_null())?;
        let j = joints_mut(joints)?;
        j.joints.load(blob_in(buffer, size)?).map_err(from_state)
    })
}

/// A hinge's axes from `n` gyroscope readings of its parent and child sensors taken at
/// the same instants (rad/s; a few seconds of the joint turning while the segments move),
/// started from the host's guesses `guess_parent`, `guess_child` (sensor frames; the
/// result is on their side): the pair that best makes the angular rate perpendicular to
/// the axis the same on both sides (Seel, Schauer, Raisch 2012), with its quality.
/// Allocates nothing. INVALID_ARGUMENT for n = 0, COUNT_TOO_LARGE for an `n` no array can
/// hold, NON_FINITE for a NaN or infinite reading or guess, ZERO_VECTOR for a guess too
/// short to normalise (its squared norm below DBL_MIN), TOO_LARGE for one whose squared
/// norm overflows.
#[no_mangle]
pub unsafe extern "C" fn orient_estimate_hinge_axes(
    gyro_parent: *const OrientVec3,
    gyro_child: *const OrientVec3,
    n: usize,
    guess_parent: OrientVec3,
    guess_child: OrientVec3,
    out: *mut OrientJointAxes,
) -> OrientStatus {
    guard(|| {
        need(out.is_null())?;
        let (p, c) = pair_of_arrays(gyro_parent, gyro_child, n, "readings")?;
        if let Some(i) = (0..n).position(|i| !(vec_from(p[i]).is_finite() && vec_from(c[i]).is_finite())) {
            return Err(fail(OrientStatus::NonFinite, format_args!("reading {i} is NaN or infinite")));
        }
        let (gp, gc) = (vec_from(guess_parent), vec_from(guess_child));
        check_guess(gp)?;
        check_guess(gc)?;
        // Every case the estimate refuses was refused above.
        let h =
            estimate_hinge_axes_by(n, |i| (vec_from(p[i]), vec_from(c[i])), (gp, gc)).ok_or_else(|| {
                fail(OrientStatus::InvalidArgument, format_args!("readings the estimate refuses"))
            })?;
        out.write(OrientJointAxes {
            axis_parent: vec_to(h.axis_parent),
            axis_child: vec_to(h.axis_child),
            quality: h.quality,
        });
        Ok(())
    })
}

/// A joint's two arrays of `n` items (parent's, child's): NULL_POINTER for a NULL one,
/// INVALID_ARGUMENT for n = 0, COUNT_TOO_LARGE for an `n` no array can hold.
unsafe fn pair_of_arrays<'a, T>(
    parent: *const T,
    child: *const T,
    n: usize,
    what: &str,
) -> Result<(&'a [T], &'a [T]), OrientStatus> {
    need(parent.is_null() || child.is_null())?;
    if n == 0 {
        return Err(fail(OrientStatus::InvalidArgument, format_args!("no {what} (n = 0)")));
    }
    Ok((items(parent, n, what)?, items(child, n, what)?))
}

/// Checks an axis guess: NON_FINITE, TOO_LARGE (its squared norm overflows) or
/// ZERO_VECTOR (too short to normalise).
fn check_guess(g: Vec3) -> Result<(), OrientStatus> {
    if !g.is_finite() {
        return Err(fail(OrientStatus::NonFinite, format_args!("a guess is NaN or infinite")));
    }
    if !g.norm_squared().is_finite() {
        return Err(fail(OrientStatus::TooLarge, format_args!("a guess's squared norm overflows")));
    }
    if g.norm_squared() < f64::MIN_POSITIVE {
        return Err(fail(OrientStatus::ZeroVector, format_args!("a guess is too short to normalise")));
    }
    Ok(())
}

/// A 2-DoF joint's axes, and its quality, from `n` orientations of its parent and child
/// sensors taken at the same instants (sensor to earth, as orient_filter_sensor_quaternion
/// gives them: 6D estimates will do, whatever their headings, as long as these hold still
/// relative to each other over the window; a few seconds of the joint turning about both
/// axes while the segments move), started from the host's guesses `guess_parent` (the
/// first axis, parent sensor frame) and `guess_child` (the second, child sensor frame;
/// the result is on the guesses' side): the pair that best keeps the two axes
/// perpendicular (Laidig, Weygers, Seel 2022), the child's heading offset estimated with
/// them. Allocates nothing. INVALID_ARGUMENT for n = 0, COUNT_TOO_LARGE for an `n` no
/// array can hold; a quaternion is checked as orient_filter_set_quaternion checks its
/// quaternion and a guess as an axis: NON_FINITE for a NaN or infinite value, ZERO_VECTOR
/// for one too short to normalise (its squared norm below DBL_MIN), TOO_LARGE for one
/// whose squared norm overflows.
#[no_mangle]
pub unsafe extern "C" fn orient_estimate_two_dof_axes(
    q_parent: *const OrientQuaternion,
    q_child: *const OrientQuaternion,
    n: usize,
    guess_parent: OrientVec3,
    guess_child: OrientVec3,
    out: *mut OrientJointAxes,
) -> OrientStatus {
    guard(|| {
        need(out.is_null())?;
        let (p, c) = pair_of_arrays(q_parent, q_child, n, "orientations")?;
        for (i, q) in p.iter().chain(c).enumerate() {
            check_quaternion(quat_from(*q)).map_err(|e| {
                let status = from_core(e);
                let side = if i < n { "parent" } else { "child" };
                fail(status, format_args!("{side} orientation {}: {e}", i % n))
            })?;
        }
        let (gp, gc) = (vec_from(guess_parent), vec_from(guess_child));
        check_guess(gp)?;
        check_guess(gc)?;
        // Every case the estimate refuses was refused above.
        let h = estimate_two_dof_axes_by(n, |i| (quat_from(p[i]), quat_from(c[i])), (gp, gc)).ok_or_else(
            || fail(OrientStatus::InvalidArgument, format_args!("orientations the estimate refuses")),
        )?;
        out.write(OrientJointAxes {
            axis_parent: vec_to(h.axis_parent),
            axis_child: vec_to(h.axis_child),
            quality: h.quality,
        });
        Ok(())
    })
}
