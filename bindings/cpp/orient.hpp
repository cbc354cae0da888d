// orient.hpp: header-only C++17 wrapper over the orient C ABI (include/orient.h).
//
// - orient::Filter is a move-only RAII handle: the destructor frees it, on every path.
// - Works with and without exceptions. Filter::create() and Config::defaults() never
//   throw and return an orient::Result (value or orient::Error). When exceptions are
//   enabled, the Filter(const Config&) and Filter(Kind) constructors throw
//   orient::Exception instead.
// - Batch updates take any contiguous container (std::array, std::vector, std::span,
//   C arrays) of OrientSample, and optionally one of OrientQuaternion for the output.
// - Numbers are the C library's: the same bits as the Rust API.
//
//   orient::Filter f(orient::Kind::Madgwick);                 // throws on error
//   f.update(orient::sample(0.01, {0, 0, 0.1}, {0, 0, 9.81}, {0, 20, -40}));
//   OrientQuaternion q = f.quaternion();
//
//   auto r = orient::Filter::create(orient::Config::defaults(orient::Kind::Ekf).value());
//   if (!r) std::puts(r.error().message.c_str());             // no exceptions needed
#ifndef ORIENT_HPP
#define ORIENT_HPP

#include "orient.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#if defined(__cpp_exceptions) || defined(__EXCEPTIONS) || defined(_CPPUNWIND)
#define ORIENT_HPP_EXCEPTIONS 1
#include <stdexcept>
#else
#define ORIENT_HPP_EXCEPTIONS 0
#endif

namespace orient {

enum class Kind : int32_t {
    Madgwick = ORIENT_KIND_MADGWICK,
    Mahony = ORIENT_KIND_MAHONY,
    Complementary = ORIENT_KIND_COMPLEMENTARY,
    Ekf = ORIENT_KIND_EKF,
    Gmvdk = ORIENT_KIND_GMVDK,
    Robust = ORIENT_KIND_ROBUST,
};

enum class Frame : int32_t { Enu = ORIENT_FRAME_ENU, Ned = ORIENT_FRAME_NED, Nwu = ORIENT_FRAME_NWU };

/// A failed call: its status and the library's message for it.
struct Error {
    OrientStatus status = ORIENT_STATUS_OK;
    std::string message;
};

/// The error of the call that just failed on this thread.
inline Error last_error(OrientStatus status) {
    std::string detail = orient_last_error();
    if (detail.empty()) detail = orient_status_message(status);
    return Error{status, std::move(detail)};
}

#if ORIENT_HPP_EXCEPTIONS
/// Thrown by the throwing constructors when exceptions are enabled.
class Exception : public std::runtime_error {
public:
    explicit Exception(Error e) : std::runtime_error(e.message), status_(e.status) {}
    OrientStatus status() const noexcept { return status_; }

private:
    OrientStatus status_;
};
#endif

/// A value or an Error, for code built without exceptions.
template <class T>
class Result {
public:
    Result(T value) : v_(std::move(value)) {}                  // NOLINT: implicit by design
    Result(Error error) : v_(std::move(error)) {}              // NOLINT
    explicit operator bool() const noexcept { return v_.index() == 0; }
    bool ok() const noexcept { return v_.index() == 0; }
    T& value() & { return std::get<0>(v_); }
    T&& value() && { return std::get<0>(std::move(v_)); }
    const Error& error() const { return std::get<1>(v_); }

private:
    std::variant<T, Error> v_;
};

inline OrientVec3 vec3(double x, double y, double z) noexcept { return OrientVec3{x, y, z}; }

/// A sample with gyroscope and accelerometer (IMU).
inline OrientSample sample(double dt, OrientVec3 gyro, OrientVec3 accel) noexcept {
    OrientSample s{};
    s.dt = dt;
    s.gyro = gyro;
    s.accel = accel;
    s.flags = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL;
    return s;
}

/// A sample with gyroscope, accelerometer and magnetometer (MARG).
inline OrientSample sample(double dt, OrientVec3 gyro, OrientVec3 accel, OrientVec3 mag) noexcept {
    OrientSample s = sample(dt, gyro, accel);
    s.mag = mag;
    s.flags |= ORIENT_SAMPLE_MAG;
    return s;
}

/// A filter configuration: OrientConfig with checked setters.
class Config {
public:
    /// The documented defaults of `kind`.
    static Result<Config> defaults(Kind kind) noexcept {
        Config c;
        OrientStatus s = orient_config_default(static_cast<int32_t>(kind), &c.raw_);
        if (s != ORIENT_STATUS_OK) return last_error(s);
        return c;
    }

    /// The offline defaults for orient::smooth (orient_smooth_config_default).
    static Result<Config> offline_defaults() noexcept {
        Config c;
        OrientStatus s = orient_smooth_config_default(&c.raw_);
        if (s != ORIENT_STATUS_OK) return last_error(s);
        return c;
    }

    /// Sets parameter slot `id` (ORIENT_PARAM_*), range-checked.
    OrientStatus set(uint32_t id, double value) noexcept { return orient_config_set_param(&raw_, id, value); }

    /// Sets the parameter called `name` (see orient_param_info), range-checked.
    OrientStatus set(const char* name, double value) noexcept {
        uint32_t id = 0;
        OrientStatus s = orient_param_find(raw_.kind, name, &id);
        return s == ORIENT_STATUS_OK ? set(id, value) : s;
    }

    /// Sets what a sensor's filter runs with under joints (orient_config_for_joints, whose
    /// doc in orient.h gives each value): for the recommended kind a faster bias random
    /// walk and a wider motion bias bound and rest threshold; other kinds are left as they
    /// were.
    OrientStatus for_joints() noexcept { return orient_config_for_joints(&raw_); }

    double get(uint32_t id) const noexcept { return id < ORIENT_MAX_PARAMS ? raw_.params[id] : 0.0; }
    Config& frame(Frame f) noexcept {
        raw_.frame = static_cast<int32_t>(f);
        return *this;
    }
    Config& init_identity() noexcept {
        raw_.init = ORIENT_INIT_IDENTITY;
        return *this;
    }
    Config& init_given(OrientQuaternion q) noexcept {
        raw_.init = ORIENT_INIT_GIVEN;
        raw_.initial = q;
        return *this;
    }
    Kind kind() const noexcept { return static_cast<Kind>(raw_.kind); }
    const OrientConfig& raw() const noexcept { return raw_; }
    OrientConfig& raw() noexcept { return raw_; }

private:
    OrientConfig raw_{};
};

/// An orientation filter of any kind. Move-only; freed by its destructor.
class Filter {
public:
    Filter() noexcept = default;

    /// Creates a filter without throwing.
    static Result<Filter> create(const Config& config) noexcept {
        Filter f;
        OrientStatus s = orient_filter_new(&config.raw(), &f.h_);
        if (s != ORIENT_STATUS_OK) return last_error(s);
        return f;
    }

#if ORIENT_HPP_EXCEPTIONS
    /// Creates a filter; throws orient::Exception on failure.
    explicit Filter(const Config& config) {
        OrientStatus s = orient_filter_new(&config.raw(), &h_);
        if (s != ORIENT_STATUS_OK) throw Exception(last_error(s));
    }

    /// A filter of `kind` with its defaults; throws orient::Exception on failure.
    explicit Filter(Kind kind) {
        Result<Config> c = Config::defaults(kind);
        if (!c) throw Exception(c.error());
        OrientStatus s = orient_filter_new(&c.value().raw(), &h_);
        if (s != ORIENT_STATUS_OK) throw Exception(last_error(s));
    }
#endif

    ~Filter() { reset_handle(); }
    Filter(const Filter&) = delete;
    Filter& operator=(const Filter&) = delete;
    Filter(Filter&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
    Filter& operator=(Filter&& o) noexcept {
        if (this != &o) {
            reset_handle();
            h_ = std::exchange(o.h_, nullptr);
        }
        return *this;
    }

    /// True while the object owns a handle (false after a move or default construction).
    explicit operator bool() const noexcept { return h_ != nullptr; }
    OrientFilter* native() const noexcept { return h_; }

    /// One sample. On any status but OK the filter's state is unchanged.
    OrientStatus update(const OrientSample& s) noexcept { return orient_filter_update(h_, &s); }

    /// Samples in order; stops at the first bad one (its index in *processed).
    OrientStatus update_batch(const OrientSample* samples, std::size_t n, OrientQuaternion* out = nullptr,
                              std::size_t* processed = nullptr) noexcept {
        return orient_filter_update_batch(h_, samples, n, out, processed);
    }

    /// Any contiguous container of OrientSample (std::array, std::vector, std::span, C array).
    template <class Samples>
    OrientStatus update_batch(const Samples& samples, std::size_t* processed = nullptr) noexcept {
        return update_batch(std::data(samples), std::size(samples), nullptr, processed);
    }

    /// As above, with the quaternion after each sample written to `out`. Fails with
    /// ORIENT_STATUS_COUNT_TOO_LARGE when `out` is smaller than `samples`.
    template <class Samples, class Quaternions>
    OrientStatus update_batch(const Samples& samples, Quaternions& out, std::size_t* processed = nullptr) noexcept {
        static_assert(std::is_same_v<std::remove_cv_t<std::remove_pointer_t<decltype(std::data(out))>>, OrientQuaternion>,
                      "output elements must be OrientQuaternion");
        if (std::size(out) < std::size(samples)) {
            if (processed) *processed = 0;
            return ORIENT_STATUS_COUNT_TOO_LARGE;
        }
        return update_batch(std::data(samples), std::size(samples), std::data(out), processed);
    }

    OrientStatus quaternion(OrientQuaternion& q) const noexcept { return orient_filter_quaternion(h_, &q); }
    /// The orientation; identity when the call fails (e.g. a moved-from filter).
    OrientQuaternion quaternion() const noexcept {
        OrientQuaternion q{1.0, 0.0, 0.0, 0.0};
        orient_filter_quaternion(h_, &q);
        return q;
    }
    OrientStatus euler(OrientEuler& e) const noexcept { return orient_filter_euler(h_, &e); }
    OrientStatus rotation_matrix(double (&m)[9]) const noexcept { return orient_filter_rotation_matrix(h_, m); }
    OrientStatus gravity(OrientVec3& v) const noexcept { return orient_filter_gravity(h_, &v); }
    OrientStatus linear_accel(OrientVec3& v) const noexcept { return orient_filter_linear_accel(h_, &v); }
    OrientStatus linear_accel_earth(OrientVec3& v) const noexcept {
        return orient_filter_linear_accel_earth(h_, &v);
    }
    OrientStatus diagnostics(OrientDiagnostics& d) const noexcept { return orient_filter_diagnostics(h_, &d); }
    /// One standard deviation (rad) of the heading and inclination errors where the kind
    /// models them (EKF: both; robust: heading); fields absent from `present` hold NaN.
    OrientStatus uncertainty(OrientUncertainty& u) const noexcept { return orient_filter_uncertainty(h_, &u); }
    /// The heading's standard deviation (rad); NaN where the kind has none.
    double heading_sigma() const noexcept {
        constexpr double nan = std::numeric_limits<double>::quiet_NaN();
        OrientUncertainty u{0, 0, nan, nan};
        orient_filter_uncertainty(h_, &u);
        return u.heading;
    }
    uint32_t flags() const noexcept {
        uint32_t f = 0;
        orient_filter_flags(h_, &f);
        return f;
    }
    bool initialized() const noexcept { return (flags() & ORIENT_FLAG_INITIALIZED) != 0; }
    OrientStatus set_param(uint32_t id, double value) noexcept { return orient_filter_set_param(h_, id, value); }
    OrientStatus get_param(uint32_t id, double& value) const noexcept {
        return orient_filter_get_param(h_, id, &value);
    }
    OrientStatus reset() noexcept { return orient_filter_reset(h_); }

    /// Size of save()'s snapshot (constant per kind).
    std::size_t state_size() const noexcept {
        std::size_t n = 0;
        orient_filter_state_size(h_, &n);
        return n;
    }
    /// Writes a versioned, checksummed snapshot of configuration and state.
    OrientStatus save(uint8_t* buffer, std::size_t capacity, std::size_t* written) const noexcept {
        return orient_filter_save(h_, buffer, capacity, written);
    }
    /// Restores save()'s snapshot; ORIENT_STATUS_INVALID_STATE (nothing changed) when it is
    /// truncated, corrupted, of another version or of another kind.
    OrientStatus load(const uint8_t* buffer, std::size_t size) noexcept { return orient_filter_load(h_, buffer, size); }
    OrientStatus set_quaternion(const OrientQuaternion& q) noexcept { return orient_filter_set_quaternion(h_, &q); }

    // Sensor calibration (issue 20): models applied to the readings before every update.
    /// ORIENT_SENSOR_GYRO / _ACCEL / _MAG; calibrated = matrix (raw - offset).
    OrientStatus set_sensor_model(uint32_t sensor, const OrientSensorModel& m) noexcept {
        return orient_filter_set_sensor_model(h_, sensor, &m);
    }
    /// Clears the sensor's model: its readings are used as they come.
    OrientStatus clear_sensor_model(uint32_t sensor) noexcept {
        return orient_filter_set_sensor_model(h_, sensor, nullptr);
    }
    /// The sensor's model; std::nullopt when none is set (or the call fails).
    std::optional<OrientSensorModel> sensor_model(uint32_t sensor) const noexcept {
        OrientSensorModel m{};
        if (orient_filter_sensor_model(h_, sensor, &m) != ORIENT_STATUS_OK) return std::nullopt;
        return m;
    }

    // Mounting and heading (issue 20): outputs are the segment's orientation.
    /// Sensor-to-segment rotation (v_segment = m v_sensor); kept by reset(), saved in snapshots.
    OrientStatus set_mounting(const OrientQuaternion& m) noexcept { return orient_filter_set_mounting(h_, &m); }
    /// The mounting; identity unless set (or when the call fails). Its conjugate maps segment to sensor.
    OrientQuaternion mounting() const noexcept {
        OrientQuaternion m{1.0, 0.0, 0.0, 0.0};
        orient_filter_mounting(h_, &m);
        return m;
    }
    /// The sensor's own orientation: heading offset and declination applied, mounting not.
    OrientQuaternion sensor_quaternion() const noexcept {
        OrientQuaternion q{1.0, 0.0, 0.0, 0.0};
        orient_filter_sensor_quaternion(h_, &q);
        return q;
    }
    /// Turns the outputs about the vertical so that the Euler yaw becomes `yaw` (rad).
    OrientStatus set_heading(double yaw) noexcept { return orient_filter_set_heading(h_, yaw); }
    /// set_heading(0): yaw 0, inclination kept.
    OrientStatus reset_heading() noexcept { return orient_filter_reset_heading(h_); }
    /// The heading offset (rad) set by set_heading() and the rig calls; 0 when the call fails.
    double heading_offset() const noexcept {
        double v = 0.0;
        orient_filter_heading_offset(h_, &v);
        return v;
    }
    /// Magnetic declination (rad, east positive, within [-pi, pi]).
    OrientStatus set_declination(double declination) noexcept { return orient_filter_set_declination(h_, declination); }
    /// The declination (rad); 0 when the call fails.
    double declination() const noexcept {
        double v = 0.0;
        orient_filter_declination(h_, &v);
        return v;
    }

private:
    void reset_handle() noexcept {
        if (h_) orient_filter_free(h_);
        h_ = nullptr;
    }
    OrientFilter* h_ = nullptr;
};

/// One frame of a rig in one call: `handles[i]` (from Filter::native()) takes
/// `samples[i]`, and `out[i]` (when given) receives its orientation. On x86-64 and
/// aarch64 two consecutive distinct Madgwick filters may run side by side; the results
/// equal separate updates bit for bit. Stops at the first bad sample, its index in *processed. Keep the handles in
/// an array you reuse across frames: the call allocates nothing.
inline OrientStatus update_rig(OrientFilter* const* handles, const OrientSample* samples, std::size_t n,
                               OrientQuaternion* out = nullptr, std::size_t* processed = nullptr) noexcept {
    return orient_filters_update(handles, samples, n, out, processed);
}

/// Offline mode (orient_smooth_arrays): the whole recording smoothed forward and backward
/// through the kind and parameters of `config`. Arrays as Filter's update_arrays: `gyro`
/// 3n doubles, `accel` and `mag` 3n or nullptr, `dt` 1 or n doubles; `out` has room for n.
/// On a bad sample its status is returned, its index in *processed, and `out` is unwritten.
inline OrientStatus smooth(const Config& config, std::size_t n, const double* dt, std::size_t dt_count,
                           const double* gyro, const double* accel, const double* mag, OrientQuaternion* out,
                           std::size_t* processed = nullptr) noexcept {
    return orient_smooth_arrays(&config.raw(), n, dt, dt_count, gyro, accel, mag, out, processed);
}

/// The most bytes orient::smooth allocates for n samples (orient_smooth_memory): 8 per
/// sample plus 32768, whatever the kind. ORIENT_STATUS_COUNT_TOO_LARGE above
/// PTRDIFF_MAX / 32; a buffer that cannot be allocated makes orient::smooth return
/// ORIENT_STATUS_OUT_OF_MEMORY with `out` unwritten.
inline OrientStatus smooth_memory(std::size_t n, std::size_t* bytes) noexcept {
    return orient_smooth_memory(n, bytes);
}

/// A magnetometer calibrator (ellipsoid fit over the readings; no allocation per reading).
class MagCalibrator {
public:
    MagCalibrator() noexcept { orient_mag_calibrator_init(&state_); }
    OrientStatus add(const OrientVec3& mag) noexcept { return orient_mag_calibrator_add(&state_, &mag); }
    /// The fit; std::nullopt while the readings do not determine an ellipsoid.
    std::optional<OrientMagFit> solve() const noexcept {
        OrientMagFit fit{};
        if (orient_mag_calibrator_solve(&state_, &fit) != ORIENT_STATUS_OK) return std::nullopt;
        return fit;
    }

private:
    OrientMagCalibrator state_{};
};

/// The gyroscope offset model from readings taken while still (any contiguous container
/// of OrientVec3); `spread` (when given) receives their RMS deviation (rad/s).
template <class Readings>
OrientStatus gyro_offset(const Readings& still, OrientSensorModel& model, double* spread = nullptr) noexcept {
    return orient_gyro_offset(std::data(still), std::size(still), &model, spread);
}

/// Rig calibration from a reference posture (orient_rig_calibrate): `handles[i]` (from
/// Filter::native()) reads `references[i]` afterwards and its segment's orientation from
/// then on. `heading` is the posture frame's yaw in the filters' earth frame (rad); leave
/// it out (NaN) to estimate it from the rig. The filters share one earth frame (a
/// magnetometer); 6D rigs take calibrate_rig_each.
inline OrientStatus calibrate_rig(OrientFilter* const* handles, const OrientQuaternion* references, std::size_t n,
                                  double heading = std::numeric_limits<double>::quiet_NaN()) noexcept {
    return orient_rig_calibrate(handles, references, n, heading);
}

/// Containers of handles and of references (std::array, std::vector, C arrays); INVALID_ARGUMENT
/// when their sizes differ.
template <class Handles, class References>
OrientStatus calibrate_rig(const Handles& handles, const References& references,
                           double heading = std::numeric_limits<double>::quiet_NaN()) noexcept {
    if (std::size(handles) != std::size(references)) return ORIENT_STATUS_INVALID_ARGUMENT;
    return orient_rig_calibrate(std::data(handles), std::data(references), std::size(handles), heading);
}

/// Rig calibration of 6D filters, each heading its own (orient_rig_calibrate_each): each
/// sensor taken as strapped along its segment, each mounting is its tilt there.
template <class Handles, class References>
OrientStatus calibrate_rig_each(const Handles& handles, const References& references) noexcept {
    if (std::size(handles) != std::size(references)) return ORIENT_STATUS_INVALID_ARGUMENT;
    return orient_rig_calibrate_each(std::data(handles), std::data(references), std::size(handles));
}

/// Heading-only rig alignment (orient_rig_align_heading): mountings kept.
template <class Handles, class References>
OrientStatus align_rig_heading(const Handles& handles, const References& references) noexcept {
    if (std::size(handles) != std::size(references)) return ORIENT_STATUS_INVALID_ARGUMENT;
    return orient_rig_align_heading(std::data(handles), std::data(references), std::size(handles));
}

/// A joint of a rig (orient_joints_new): `parent` and `child` index the rig's filters;
/// axes in the sensors' frames, or with ORIENT_JOINT_AXES_SEGMENT in the segments'.
inline OrientJoint hinge(uint32_t parent, uint32_t child, OrientVec3 axis_parent, OrientVec3 axis_child,
                         uint32_t axes_frame = ORIENT_JOINT_AXES_SENSOR) noexcept {
    return OrientJoint{ORIENT_JOINT_HINGE, parent, child, axes_frame, axis_parent, axis_child};
}
inline OrientJoint two_dof(uint32_t parent, uint32_t child, OrientVec3 axis_parent, OrientVec3 axis_child,
                           uint32_t axes_frame = ORIENT_JOINT_AXES_SENSOR) noexcept {
    return OrientJoint{ORIENT_JOINT_TWO_DOF, parent, child, axes_frame, axis_parent, axis_child};
}

/// A rig's joints (orient_joints_*): each child segment held to its parent without a
/// magnetometer. Move-only; freed by its destructor (the filters stay the host's).
class Joints {
public:
    Joints() noexcept = default;

    /// Joints over `segments` segments; `mountings` (sensor to segment, one per segment)
    /// give the angles' zero and the segments' outputs, nullptr for the identity (the
    /// filters' own mountings are not read: pass each filter's `mounting()`).
    static Result<Joints> create(const OrientJoint* joints, std::size_t n_joints, std::size_t segments,
                                 const OrientQuaternion* mountings = nullptr) noexcept {
        Joints j;
        OrientStatus s = orient_joints_new(joints, n_joints, segments, mountings, &j.h_);
        if (s != ORIENT_STATUS_OK) return last_error(s);
        j.segments_ = segments;
        return j;
    }

    /// Any contiguous container of OrientJoint.
    template <class Container>
    static Result<Joints> create(const Container& joints, std::size_t segments,
                                 const OrientQuaternion* mountings = nullptr) noexcept {
        return create(std::data(joints), std::size(joints), segments, mountings);
    }

#if ORIENT_HPP_EXCEPTIONS
    /// Throws orient::Exception on failure.
    template <class Container>
    Joints(const Container& joints, std::size_t segments, const OrientQuaternion* mountings = nullptr) {
        OrientStatus s = orient_joints_new(std::data(joints), std::size(joints), segments, mountings, &h_);
        if (s != ORIENT_STATUS_OK) throw Exception(last_error(s));
        segments_ = segments;
    }
#endif

    ~Joints() { reset_handle(); }
    Joints(const Joints&) = delete;
    Joints& operator=(const Joints&) = delete;
    Joints(Joints&& o) noexcept : h_(std::exchange(o.h_, nullptr)), segments_(std::exchange(o.segments_, 0)) {}
    Joints& operator=(Joints&& o) noexcept {
        if (this != &o) {
            reset_handle();
            h_ = std::exchange(o.h_, nullptr);
            segments_ = std::exchange(o.segments_, 0);
        }
        return *this;
    }

    explicit operator bool() const noexcept { return h_ != nullptr; }
    OrientJoints* native() const noexcept { return h_; }
    std::size_t segments() const noexcept { return segments_; }

    /// One row, after `handles[s]` took `samples[s]` (orient::update_rig): every joint
    /// updated; nothing changes on any status but OK. Allocates nothing.
    OrientStatus update(OrientFilter* const* handles, const OrientSample* samples, std::size_t n) noexcept {
        return orient_joints_update(h_, handles, samples, n);
    }

    /// Segment `s`'s orientation, the bone rotation; identity when the call fails.
    OrientQuaternion segment(std::size_t s) const noexcept {
        OrientQuaternion q{1.0, 0.0, 0.0, 0.0};
        orient_joints_segment_quaternion(h_, s, &q);
        return q;
    }
    OrientStatus segment(std::size_t s, OrientQuaternion& q) const noexcept {
        return orient_joints_segment_quaternion(h_, s, &q);
    }
    /// Joint `k`'s angles (rad): a hinge's in [0] ([1] NaN), a 2-DoF joint's in [0], [1].
    OrientStatus angles(std::size_t k, double (&out)[2]) const noexcept { return orient_joints_angles(h_, k, out); }
    /// Joint `k`'s rating in [0, 1]; NaN when the call fails.
    double rating(std::size_t k) const noexcept {
        double r = std::numeric_limits<double>::quiet_NaN();
        orient_joints_rating(h_, k, &r);
        return r;
    }
    OrientStatus relative_heading(std::size_t k, double& heading, double* sigma = nullptr) const noexcept {
        return orient_joints_relative_heading(h_, k, &heading, sigma);
    }
    OrientStatus axes(std::size_t k, OrientVec3& parent, OrientVec3& child) const noexcept {
        return orient_joints_axes(h_, k, &parent, &child);
    }
    OrientStatus reset() noexcept { return orient_joints_reset(h_); }

    /// Sets the joint parameter called `name` (orient_joint_param_info lists them with
    /// their ranges) for every joint: UNKNOWN_PARAM or PARAM_OUT_OF_RANGE change nothing.
    OrientStatus set_param(const char* name, double value) noexcept {
        return orient_joints_set_param(h_, name, value);
    }
    /// The joint parameter called `name`; NaN when the call fails.
    double param(const char* name) const noexcept {
        double v = std::numeric_limits<double>::quiet_NaN();
        orient_joints_get_param(h_, name, &v);
        return v;
    }

    /// Size of save()'s snapshot (constant for a rig).
    std::size_t state_size() const noexcept {
        std::size_t n = 0;
        orient_joints_state_size(h_, &n);
        return n;
    }
    /// The joints' estimates with the rig's description; save each filter too.
    OrientStatus save(uint8_t* buffer, std::size_t capacity, std::size_t* written) const noexcept {
        return orient_joints_save(h_, buffer, capacity, written);
    }
    /// Restores save()'s snapshot into joints of the same rig; ORIENT_STATUS_INVALID_STATE
    /// (nothing changed) for another rig's, a filter's or a damaged blob.
    OrientStatus load(const uint8_t* buffer, std::size_t size) noexcept { return orient_joints_load(h_, buffer, size); }

private:
    void reset_handle() noexcept {
        if (h_) orient_joints_free(h_);
        h_ = nullptr;
    }
    OrientJoints* h_ = nullptr;
    std::size_t segments_ = 0;
};

/// A hinge's axes from gyroscope readings of its two sensors at the same instants
/// (orient_estimate_hinge_axes), started from the host's guesses.
template <class Readings>
OrientStatus estimate_hinge_axes(const Readings& parent, const Readings& child, OrientVec3 guess_parent,
                                 OrientVec3 guess_child, OrientJointAxes& out) noexcept {
    if (std::size(parent) != std::size(child)) return ORIENT_STATUS_INVALID_ARGUMENT;
    return orient_estimate_hinge_axes(std::data(parent), std::data(child), std::size(parent), guess_parent,
                                      guess_child, &out);
}

/// A 2-DoF joint's axes from its two sensors' orientations (sensor to earth, 6D estimates
/// will do) at the same instants (orient_estimate_two_dof_axes), started from the host's
/// guesses: the first axis in the parent's frame, the second in the child's.
template <class Orientations>
OrientStatus estimate_two_dof_axes(const Orientations& parent, const Orientations& child,
                                   OrientVec3 guess_parent, OrientVec3 guess_child, OrientJointAxes& out) noexcept {
    if (std::size(parent) != std::size(child)) return ORIENT_STATUS_INVALID_ARGUMENT;
    return orient_estimate_two_dof_axes(std::data(parent), std::data(child), std::size(parent), guess_parent,
                                        guess_child, &out);
}

}  // namespace orient

#endif  // ORIENT_HPP
