// Tests bindings/cpp/orient.hpp: golden vectors bit for bit through single and batch
// updates, move semantics, the non-throwing factory, and (with exceptions) the throwing
// constructors. Built by tests/cpp_wrapper.rs with -std=c++17 -Wall -Wextra -Werror
// -pedantic, once with and once without exceptions. Ends with "N passed, N failed".
#include "orient.hpp"

#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

static int passed = 0, failed = 0;

#define CHECK(cond)                                                                   \
    do {                                                                              \
        if (cond) {                                                                   \
            ++passed;                                                                 \
        } else {                                                                      \
            ++failed;                                                                 \
            std::printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);               \
        }                                                                             \
    } while (0)

static double unhex(const std::string& s) {
    uint64_t u = std::strtoull(s.c_str(), nullptr, 16);
    double d;
    std::memcpy(&d, &u, sizeof d);
    return d;
}

static bool same(const OrientQuaternion& a, const OrientQuaternion& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

struct Case {
    std::string name;
    orient::Config config;
    std::vector<OrientSample> samples;
    std::vector<OrientQuaternion> expected;
};

static std::vector<Case> read_golden(const char* path) {
    std::vector<Case> cases;
    std::ifstream in(path);
    std::string line;
    Case current;
    while (std::getline(in, line)) {
        std::istringstream t(line);
        std::string tag;
        t >> tag;
        if (tag == "case") {
            int kind, frame, init, nparams;
            std::string qw, qx, qy, qz;
            t >> current.name >> kind >> frame >> init >> qw >> qx >> qy >> qz >> nparams;
            auto c = orient::Config::defaults(static_cast<orient::Kind>(kind));
            CHECK(c.ok());
            if (!c) continue;
            current.config = c.value();
            current.config.raw().frame = frame;
            current.config.raw().init = init;
            current.config.raw().initial = OrientQuaternion{unhex(qw), unhex(qx), unhex(qy), unhex(qz)};
            for (int i = 0; i < nparams; ++i) {
                uint32_t id;
                std::string v;
                t >> id >> v;
                CHECK(current.config.set(id, unhex(v)) == ORIENT_STATUS_OK);
            }
            current.samples.clear();
            current.expected.clear();
        } else if (tag == "s") {
            std::string h[15];
            unsigned flags;
            t >> h[0] >> h[1] >> h[2] >> h[3] >> h[4] >> h[5] >> h[6] >> h[7] >> h[8] >> h[9] >> flags >> h[10] >>
                h[11] >> h[12] >> h[13];
            OrientSample s{};
            s.dt = unhex(h[0]);
            s.gyro = orient::vec3(unhex(h[1]), unhex(h[2]), unhex(h[3]));
            s.accel = orient::vec3(unhex(h[4]), unhex(h[5]), unhex(h[6]));
            s.mag = orient::vec3(unhex(h[7]), unhex(h[8]), unhex(h[9]));
            s.flags = flags;
            current.samples.push_back(s);
            current.expected.push_back(OrientQuaternion{unhex(h[10]), unhex(h[11]), unhex(h[12]), unhex(h[13])});
        } else if (tag == "end") {
            cases.push_back(current);
        }
    }
    return cases;
}

static void golden(const char* path) {
    std::vector<Case> cases = read_golden(path);
    CHECK(cases.size() >= 9);
    for (const Case& c : cases) {
        auto single = orient::Filter::create(c.config);
        CHECK(single.ok());
        if (!single) continue;
        orient::Filter f = std::move(single).value();
        std::size_t mismatches = 0;
        for (std::size_t i = 0; i < c.samples.size(); ++i) {
            if (f.update(c.samples[i]) != ORIENT_STATUS_OK || !same(f.quaternion(), c.expected[i])) ++mismatches;
        }
        if (mismatches) std::printf("FAIL golden %s: %zu mismatches\n", c.name.c_str(), mismatches);
        CHECK(mismatches == 0);

        // Batch from a std::vector into a std::vector.
        auto batch = orient::Filter::create(c.config);
        CHECK(batch.ok());
        std::vector<OrientQuaternion> out(c.samples.size());
        std::size_t processed = 0;
        CHECK(batch.value().update_batch(c.samples, out, &processed) == ORIENT_STATUS_OK);
        CHECK(processed == c.samples.size());
        CHECK(std::memcmp(out.data(), c.expected.data(), out.size() * sizeof(OrientQuaternion)) == 0);
    }
    std::printf("golden: %zu cases\n", cases.size());
}

static void wrapper() {
    // Non-throwing factory, error path with the library's message.
    auto bad = orient::Config::defaults(static_cast<orient::Kind>(42));
    CHECK(!bad.ok());
    CHECK(bad.error().status == ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK(!bad.error().message.empty());

    auto cfg = orient::Config::defaults(orient::Kind::Madgwick);
    CHECK(cfg.ok());
    orient::Config config = cfg.value();
    CHECK(config.set("beta_marg", 0.05) == ORIENT_STATUS_OK);
    CHECK(config.get(ORIENT_PARAM_MADGWICK_BETA_MARG) == 0.05);
    CHECK(config.set("no_such", 1.0) == ORIENT_STATUS_UNKNOWN_PARAM);
    CHECK(config.set(ORIENT_PARAM_MADGWICK_BETA_IMU, -3.0) == ORIENT_STATUS_PARAM_OUT_OF_RANGE);
    config.frame(orient::Frame::Ned);

    orient::Config broken = config;
    broken.raw().struct_size = 3;
    auto r = orient::Filter::create(broken);
    CHECK(!r.ok());
    CHECK(r.error().status == ORIENT_STATUS_VERSION_MISMATCH);

    // Move-only RAII.
    static_assert(!std::is_copy_constructible_v<orient::Filter>);
    static_assert(std::is_nothrow_move_constructible_v<orient::Filter>);
    auto made = orient::Filter::create(config);
    CHECK(made.ok());
    orient::Filter a = std::move(made).value();
    CHECK(static_cast<bool>(a));
    orient::Filter b = std::move(a);
    CHECK(!a && b);
    CHECK(a.update(orient::sample(0.01, {0, 0, 0}, {0, 0, 9.81})) == ORIENT_STATUS_NULL_POINTER);
    CHECK(b.update(orient::sample(0.01, {0, 0, 0.1}, {0, 0, 9.81}, {0, 20, -40})) == ORIENT_STATUS_OK);
    CHECK(b.initialized());
    orient::Filter c;
    c = std::move(b);
    CHECK(!b && c);
    OrientQuaternion q = c.quaternion();
    CHECK(std::fabs(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z - 1.0) < 1e-12);

    // Batch with std::array, output too small, and a bad sample.
    std::array<OrientSample, 3> samples = {orient::sample(0.01, {0, 0, 0.1}, {0, 0, 9.81}),
                                           orient::sample(0.01, {0, 0, 0.1}, {0, 0, 9.81}),
                                           orient::sample(-1.0, {0, 0, 0.1}, {0, 0, 9.81})};
    std::array<OrientQuaternion, 2> small{};
    CHECK(c.update_batch(samples, small) == ORIENT_STATUS_COUNT_TOO_LARGE);
    std::array<OrientQuaternion, 3> out{};
    std::size_t processed = 99;
    CHECK(c.update_batch(samples, out, &processed) == ORIENT_STATUS_INVALID_DT);
    CHECK(processed == 2);

    // Snapshot and restore into a second filter.
    std::vector<uint8_t> blob(c.state_size());
    std::size_t written = 0;
    CHECK(c.save(blob.data(), blob.size(), &written) == ORIENT_STATUS_OK && written == blob.size());
    auto copy = orient::Filter::create(config);
    CHECK(copy.ok());
    CHECK(copy.value().load(blob.data(), blob.size()) == ORIENT_STATUS_OK);
    CHECK(same(copy.value().quaternion(), c.quaternion()));
    blob[blob.size() / 2] ^= 1;
    CHECK(copy.value().load(blob.data(), blob.size()) == ORIENT_STATUS_INVALID_STATE);

    OrientDiagnostics d{};
    CHECK(c.diagnostics(d) == ORIENT_STATUS_OK);
    CHECK(d.present == 0 && std::isnan(d.alpha));
    OrientUncertainty u{};
    CHECK(c.uncertainty(u) == ORIENT_STATUS_OK && u.present == 0 && std::isnan(u.heading));
    CHECK(std::isnan(c.heading_sigma()));
    CHECK(c.reset() == ORIENT_STATUS_OK && !c.initialized());
}

#if ORIENT_HPP_EXCEPTIONS
static void exceptions() {
    bool threw = false;
    try {
        orient::Filter f(static_cast<orient::Kind>(0));
    } catch (const orient::Exception& e) {
        threw = e.status() == ORIENT_STATUS_INVALID_ARGUMENT && std::strlen(e.what()) > 0;
    }
    CHECK(threw);
    orient::Filter g(orient::Kind::Gmvdk);
    CHECK(static_cast<bool>(g));
}
#endif

/* A rig of Madgwick filters through update_rig: the same bits as separate updates. */
static void rig() {
    constexpr std::size_t n = 8;
    auto config = orient::Config::defaults(orient::Kind::Madgwick).value();
    std::vector<orient::Filter> rig, twins;
    for (std::size_t k = 0; k < n; k++) {
        rig.push_back(orient::Filter::create(config).value());
        twins.push_back(orient::Filter::create(config).value());
    }
    std::array<OrientFilter*, n> handles{};
    for (std::size_t k = 0; k < n; k++) handles[k] = rig[k].native();
    std::array<OrientSample, n> frame{};
    std::array<OrientQuaternion, n> out{};
    bool same = true;
    for (int i = 0; i < 200; i++) {
        for (std::size_t k = 0; k < n; k++) {
            frame[k] = orient::sample(0.01, orient::vec3(0.3 * std::sin(0.01 * i + k), 0.2, -0.1 * k),
                                      orient::vec3(0.2, 0.1 * k, 9.8), orient::vec3(20.0, 1.0 * k, -40.0));
        }
        std::size_t processed = 0;
        CHECK(orient::update_rig(handles.data(), frame.data(), n, out.data(), &processed) == ORIENT_STATUS_OK);
        CHECK(processed == n);
        for (std::size_t k = 0; k < n; k++) {
            CHECK(twins[k].update(frame[k]) == ORIENT_STATUS_OK);
            OrientQuaternion q = twins[k].quaternion();
            same = same && std::memcmp(&q, &out[k], sizeof q) == 0;
        }
    }
    CHECK(same);
}

// orient::smooth: the offline mode finds the tilt of a still, rolled recording, with the
// C call's bits, and names a bad sample.
static void offline() {
    const std::size_t n = 400;
    const double roll = 0.4, c = std::cos(roll), s = std::sin(roll), dt = 0.01;
    std::vector<double> gyro(3 * n, 0.0), accel(3 * n), mag(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        accel[3 * i] = 0.0, accel[3 * i + 1] = 9.81 * s, accel[3 * i + 2] = 9.81 * c;
        mag[3 * i] = 0.0, mag[3 * i + 1] = 20.0 * c - 40.0 * s, mag[3 * i + 2] = -20.0 * s - 40.0 * c;
    }
    auto config = orient::Config::defaults(orient::Kind::Robust);
    CHECK(config.ok());
    std::vector<OrientQuaternion> out(n), direct(n);
    std::size_t processed = 0;
    CHECK(orient::smooth(config.value(), n, &dt, 1, gyro.data(), accel.data(), mag.data(), out.data(), &processed) ==
          ORIENT_STATUS_OK);
    CHECK(processed == n);
    CHECK(orient_smooth_arrays(&config.value().raw(), n, &dt, 1, gyro.data(), accel.data(), mag.data(), direct.data(),
                               nullptr) == ORIENT_STATUS_OK);
    CHECK(std::memcmp(out.data(), direct.data(), n * sizeof(OrientQuaternion)) == 0);
    for (const OrientQuaternion& q : out) {
        CHECK(std::fabs(q.w * std::cos(roll / 2) + q.x * std::sin(roll / 2)) > std::cos(0.005));
    }
    auto off = orient::Config::offline_defaults();
    CHECK(off.ok() && off.value().get(ORIENT_PARAM_ROBUST_TAU_MAG) == 27.0);
    accel[3 * 5 + 2] = NAN;
    CHECK(orient::smooth(config.value(), n, &dt, 1, gyro.data(), accel.data(), mag.data(), out.data(), &processed) ==
          ORIENT_STATUS_NON_FINITE);
    CHECK(processed == 5);
    std::size_t bytes = 0;
    CHECK(orient::smooth_memory(n, &bytes) == ORIENT_STATUS_OK && bytes == 8 * n + 32768);
    CHECK(orient::smooth_memory(SIZE_MAX, &bytes) == ORIENT_STATUS_COUNT_TOO_LARGE);
}

/* Issue 20: mounting, heading, declination and rig calibration through the wrapper. */
static double angle(const OrientQuaternion& a, const OrientQuaternion& b) {
    double w = a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
    double x = a.w * b.x - a.x * b.w - a.y * b.z + a.z * b.y;
    double y = a.w * b.y + a.x * b.z - a.y * b.w - a.z * b.x;
    double z = a.w * b.z - a.x * b.y + a.y * b.x - a.z * b.w;
    return 2.0 * std::atan2(std::sqrt(x * x + y * y + z * z), std::fabs(w));
}

static void mounting_and_heading() {
    auto config = orient::Config::defaults(orient::Kind::Mahony).value();
    std::vector<orient::Filter> fs;
    for (int k = 0; k < 3; k++) {
        fs.push_back(orient::Filter::create(config).value());
        for (int i = 0; i < 50; i++) {
            CHECK(fs[k].update(orient::sample(0.01, orient::vec3(0.1 * k, 0.2, 0.0), orient::vec3(0.3 * k, 0.5, 9.7),
                                              orient::vec3(20.0, 3.0 * k, -40.0))) == ORIENT_STATUS_OK);
        }
    }
    orient::Filter& f = fs[0];
    OrientQuaternion sensor = f.sensor_quaternion();
    CHECK(same(sensor, f.quaternion()));
    OrientQuaternion m{0.8, 0.2, 0.5, -0.1};
    CHECK(f.set_mounting(m) == ORIENT_STATUS_OK);
    CHECK(angle(f.sensor_quaternion(), sensor) < 1e-9);
    CHECK(!same(f.quaternion(), sensor));
    CHECK(f.mounting().w != 1.0);
    OrientEuler e{};
    CHECK(f.set_heading(1.25) == ORIENT_STATUS_OK);
    CHECK(f.euler(e) == ORIENT_STATUS_OK && std::fabs(e.yaw - 1.25) < 1e-12);
    CHECK(f.heading_offset() != 0.0);
    CHECK(f.reset_heading() == ORIENT_STATUS_OK);
    CHECK(f.euler(e) == ORIENT_STATUS_OK && std::fabs(e.yaw) < 1e-12);
    CHECK(f.set_declination(0.1) == ORIENT_STATUS_OK && f.declination() == 0.1);
    CHECK(f.set_declination(std::nan("")) == ORIENT_STATUS_NON_FINITE);

    std::array<OrientFilter*, 3> handles{fs[0].native(), fs[1].native(), fs[2].native()};
    std::array<OrientQuaternion, 3> refs{{{1, 0, 0, 0}, {std::cos(0.3), 0, std::sin(0.3), 0}, {0, 0, 0, 1}}};
    CHECK(orient::calibrate_rig(handles, refs, 0.4) == ORIENT_STATUS_OK);
    for (int k = 0; k < 3; k++) CHECK(angle(fs[k].quaternion(), refs[k]) < 1e-9);
    CHECK(orient::calibrate_rig(handles, refs) == ORIENT_STATUS_OK);
    for (int k = 0; k < 3; k++) CHECK(angle(fs[k].quaternion(), refs[k]) < 1e-9);
    CHECK(fs[1].set_heading(-2.0) == ORIENT_STATUS_OK);
    CHECK(angle(fs[1].quaternion(), refs[1]) > 0.1);
    CHECK(orient::align_rig_heading(handles, refs) == ORIENT_STATUS_OK);
    CHECK(angle(fs[1].quaternion(), refs[1]) < 1e-9);
    std::array<OrientQuaternion, 2> short_refs{};
    CHECK(orient::align_rig_heading(handles, short_refs) == ORIENT_STATUS_INVALID_ARGUMENT);
    // 6D filters, each heading its own: each reads its reference, an offset set before
    // changes nothing.
    CHECK(fs[1].set_heading(2.0) == ORIENT_STATUS_OK);
    CHECK(orient::calibrate_rig_each(handles, refs) == ORIENT_STATUS_OK);
    for (int k = 0; k < 3; k++) CHECK(angle(fs[k].quaternion(), refs[k]) < 1e-9);
    CHECK(orient::calibrate_rig_each(handles, short_refs) == ORIENT_STATUS_INVALID_ARGUMENT);
}

static void calibration() {
    std::array<OrientVec3, 2> still{{{0.011, -0.02, 0.03}, {0.009, -0.02, 0.03}}};
    OrientSensorModel gm{};
    double spread = 0.0;
    CHECK(orient::gyro_offset(still, gm, &spread) == ORIENT_STATUS_OK);
    CHECK(std::fabs(gm.offset.x - 0.01) < 1e-12 && gm.matrix[0] == 1.0 && spread > 0.0);
    orient::Filter f = orient::Filter::create(orient::Config::defaults(orient::Kind::Mahony).value()).value();
    orient::Filter g = orient::Filter::create(orient::Config::defaults(orient::Kind::Mahony).value()).value();
    CHECK(!f.sensor_model(ORIENT_SENSOR_GYRO));
    CHECK(f.set_sensor_model(ORIENT_SENSOR_GYRO, gm) == ORIENT_STATUS_OK);
    CHECK(f.sensor_model(ORIENT_SENSOR_GYRO).has_value());
    for (int i = 0; i < 50; i++) {
        CHECK(f.update(orient::sample(0.01, orient::vec3(0.21, -0.02, 0.03), orient::vec3(0.3, 0.2, 9.7))) ==
              ORIENT_STATUS_OK);
        CHECK(g.update(orient::sample(0.01, orient::vec3(0.21 - gm.offset.x, -0.02 - gm.offset.y, 0.03 - gm.offset.z),
                                      orient::vec3(0.3, 0.2, 9.7))) == ORIENT_STATUS_OK);
    }
    CHECK(same(f.quaternion(), g.quaternion()));
    CHECK(f.clear_sensor_model(ORIENT_SENSOR_GYRO) == ORIENT_STATUS_OK && !f.sensor_model(ORIENT_SENSOR_GYRO));
    orient::MagCalibrator cal;
    CHECK(!cal.solve());
    for (int k = 0; k < 288; k++) {
        int idx = (k * 97) % 288;
        double th = 3.141592653589793 * (idx / 24 + 0.5) / 12, ph = 6.283185307179586 * (idx % 24) / 24;
        CHECK(cal.add(orient::vec3(60 * std::sin(th) * std::cos(ph) + 10, 45 * std::sin(th) * std::sin(ph) - 20,
                                   50 * std::cos(th) + 5)) == ORIENT_STATUS_OK);
    }
    auto fit = cal.solve();
    CHECK(fit && std::fabs(fit->model.offset.x - 10) < 1e-6 && fit->trustworthy == 1);
}

/* Issue 20: the robust kind's heading uncertainty through the wrapper: it settles while
 * the magnetometer is used and grows at every sample without it. */
static void uncertainty() {
    orient::Filter f = orient::Filter::create(orient::Config::defaults(orient::Kind::Robust).value()).value();
    OrientSample s{};
    s.dt = 0.01;
    s.accel = OrientVec3{0.0, 0.0, 9.81};
    s.mag = OrientVec3{0.0, 20.0, -40.0};
    s.flags = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG;
    CHECK(std::isnan(f.heading_sigma()));
    /* 30 s: rest is seen, and the bias uncertainty settles to its value after a rest. */
    for (int i = 0; i < 3000; ++i) CHECK(f.update(s) == ORIENT_STATUS_OK);
    double settled = f.heading_sigma(), sigma_m = 0.0, sigma_b = 0.0, tau = 0.0;
    CHECK(f.get_param(ORIENT_PARAM_ROBUST_MAG_HEADING_SIGMA, sigma_m) == ORIENT_STATUS_OK);
    CHECK(f.get_param(ORIENT_PARAM_ROBUST_BIAS_SIGMA_REST, sigma_b) == ORIENT_STATUS_OK);
    CHECK(f.get_param(ORIENT_PARAM_ROBUST_TAU_MAG, tau) == ORIENT_STATUS_OK);
    /* The header's settle value at rest in a clean field: sqrt(sigma_m^2 + (sigma_b tau)^2). */
    double expected = std::sqrt(sigma_m * sigma_m + sigma_b * tau * sigma_b * tau);
    CHECK(std::fabs(settled - expected) < 0.05 * expected); /* "about": 2.6 % below at 30 s */
    s.flags &= ~static_cast<uint32_t>(ORIENT_SAMPLE_MAG);
    bool grows = true;
    for (int i = 0; i < 100; ++i) {
        double before = f.heading_sigma();
        CHECK(f.update(s) == ORIENT_STATUS_OK);
        grows = grows && f.heading_sigma() > before;
    }
    CHECK(grows);
    OrientUncertainty u{};
    CHECK(f.uncertainty(u) == ORIENT_STATUS_OK && u.present == ORIENT_UNCERTAINTY_HEADING && std::isnan(u.inclination));
}

// The wrapper's Kind names every kind the library makes: each kind the library accepts
// must be one of the enumerators (a kind the library gains without one fails here), and
// -Wswitch makes an enumerator added to the wrapper without a case here fail to compile.
static bool wrapper_names(orient::Kind k) {
    switch (k) {
    case orient::Kind::Madgwick:
    case orient::Kind::Mahony:
    case orient::Kind::Complementary:
    case orient::Kind::Ekf:
    case orient::Kind::Gmvdk:
    case orient::Kind::Robust:
        return true;
    }
    return false;
}

static void kinds() {
    int accepted = 0;
    for (int32_t k = 0; k < 64; k++) {
        OrientConfig c;
        if (orient_config_default(static_cast<OrientKind>(k), &c) != ORIENT_STATUS_OK) continue;
        accepted++;
        CHECK(wrapper_names(static_cast<orient::Kind>(k)));
        CHECK(orient::Config::defaults(static_cast<orient::Kind>(k)).ok());
    }
    CHECK(accepted > 0); // the loop checked something
}

// orient::Joints: a hand and a finger on a hinge about both sensors' x axis, each sensor's
// filter robust; RAII, moves, the statuses of the C calls, the axes' estimate.
static void joints() {
    const double dt = 0.01;
    auto rot = [](double x, double y, double z, double a) {
        double n = std::sqrt(x * x + y * y + z * z), s = std::sin(0.5 * a);
        return OrientQuaternion{std::cos(0.5 * a), x / n * s, y / n * s, z / n * s};
    };
    auto mul = [](OrientQuaternion a, OrientQuaternion b) {
        return OrientQuaternion{a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
                                a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                                a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                                a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
    };
    auto conj = [](OrientQuaternion a) { return OrientQuaternion{a.w, -a.x, -a.y, -a.z}; };
    auto parent = [&](double t) {
        return mul(mul(rot(0, 0, 1, 0.5 * std::sin(0.3 * t)), rot(0, 1, 0, 0.6 * std::sin(0.7 * t))),
                   rot(1, 0, 0, 0.4 * std::sin(1.1 * t)));
    };
    auto flexion = [](double t) { return 0.5 + 0.8 * std::sin(1.9 * t); };
    auto child = [&](double t) { return mul(parent(t), rot(1, 0, 0, flexion(t))); };
    auto sample = [&](OrientQuaternion a, OrientQuaternion b) {
        OrientQuaternion d = mul(conj(a), b);
        if (d.w < 0) d = OrientQuaternion{-d.w, -d.x, -d.y, -d.z};
        double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        double k = n > 1e-15 ? 2.0 * std::atan2(n, d.w) / n / dt : 0.0;
        OrientQuaternion g = mul(mul(conj(b), OrientQuaternion{0, 0, 0, 9.81}), b);
        return orient::sample(dt, orient::vec3(d.x * k, d.y * k, d.z * k), orient::vec3(g.x, g.y, g.z));
    };

    std::array<OrientJoint, 1> spec{orient::hinge(0, 1, orient::vec3(1, 0, 0), orient::vec3(1, 0, 0))};
    auto made = orient::Joints::create(spec, 2);
    CHECK(made.ok());
    orient::Joints joints = std::move(made).value();
    CHECK(static_cast<bool>(joints) && joints.segments() == 2);
    std::vector<orient::Filter> filters;
    for (int k = 0; k < 2; k++) filters.push_back(orient::Filter::create(orient::Config::defaults(orient::Kind::Robust).value()).value());
    std::array<OrientFilter*, 2> handles{filters[0].native(), filters[1].native()};
    std::array<OrientSample, 2> row{};
    std::vector<OrientVec3> wp, wc;
    for (int i = 1; i <= 1000; i++) {
        double t0 = (i - 1) * dt, t1 = i * dt;
        row[0] = sample(parent(t0), parent(t1));
        row[1] = sample(child(t0), child(t1));
        CHECK(orient::update_rig(handles.data(), row.data(), 2) == ORIENT_STATUS_OK);
        CHECK(joints.update(handles.data(), row.data(), 2) == ORIENT_STATUS_OK);
        wp.push_back(row[0].gyro);
        wc.push_back(row[1].gyro);
    }
    double angles[2];
    CHECK(joints.angles(0, angles) == ORIENT_STATUS_OK);
    CHECK(std::fabs(angles[0] - flexion(10.0)) < 0.035 && std::isnan(angles[1]));
    CHECK(joints.rating(0) > 0.1 && joints.rating(0) <= 1.0);
    CHECK(std::isnan(joints.rating(1)));
    OrientQuaternion p = joints.segment(0), c = joints.segment(1), rel = mul(conj(p), c), truth = rot(1, 0, 0, flexion(10.0));
    CHECK(std::fabs(std::fabs(rel.w * truth.w + rel.x * truth.x + rel.y * truth.y + rel.z * truth.z) - 1.0) < 2e-4);
    double heading = 0.0, sigma = 0.0;
    CHECK(joints.relative_heading(0, heading, &sigma) == ORIENT_STATUS_OK && sigma >= 0.0);
    OrientVec3 a{}, b{};
    CHECK(joints.axes(0, a, b) == ORIENT_STATUS_OK && a.x > 0.99 && b.x > 0.99);
    CHECK(joints.update(handles.data(), row.data(), 1) == ORIENT_STATUS_INVALID_ARGUMENT);
    std::vector<uint8_t> blob(joints.state_size());
    std::size_t written = 0;
    CHECK(joints.save(blob.data(), blob.size(), &written) == ORIENT_STATUS_OK && written == blob.size());
    orient::Joints twin = orient::Joints::create(spec, 2).value();
    CHECK(twin.load(blob.data(), blob.size()) == ORIENT_STATUS_OK);
    OrientQuaternion s1 = joints.segment(1), s2 = twin.segment(1);
    CHECK(std::memcmp(&s1, &s2, sizeof s1) == 0);
    CHECK(twin.load(blob.data(), blob.size() - 1) == ORIENT_STATUS_INVALID_STATE);
    CHECK(joints.reset() == ORIENT_STATUS_OK);
    CHECK(joints.relative_heading(0, heading) == ORIENT_STATUS_OK && heading == 0.0);
    // The tuning by name: read back when taken, unchanged when refused.
    CHECK(joints.param("gate") == 3.0);
    CHECK(joints.set_param("gate", 2.5) == ORIENT_STATUS_OK && joints.param("gate") == 2.5);
    CHECK(joints.set_param("gate", -1.0) == ORIENT_STATUS_PARAM_OUT_OF_RANGE && joints.param("gate") == 2.5);
    CHECK(joints.set_param("beta", 1.0) == ORIENT_STATUS_UNKNOWN_PARAM);
    CHECK(std::isnan(joints.param("beta")));

    // Moves leave one owner; a bad rig is an Error naming the joint.
    orient::Joints moved = std::move(joints);
    CHECK(!joints && static_cast<bool>(moved));
    CHECK(joints.update(handles.data(), row.data(), 2) == ORIENT_STATUS_NULL_POINTER);
    std::array<OrientJoint, 2> cycle{orient::hinge(0, 1, orient::vec3(1, 0, 0), orient::vec3(1, 0, 0)),
                                     orient::hinge(1, 0, orient::vec3(1, 0, 0), orient::vec3(1, 0, 0))};
    auto bad = orient::Joints::create(cycle, 2);
    CHECK(!bad.ok() && bad.error().status == ORIENT_STATUS_INVALID_JOINT);
    CHECK(bad.error().message.find("joint 1") != std::string::npos);

    OrientJointAxes h{};
    CHECK(orient::estimate_hinge_axes(wp, wc, orient::vec3(1, 0.08, 0), orient::vec3(1, 0, -0.08), h) == ORIENT_STATUS_OK);
    CHECK(h.axis_parent.x > 0.9999 && h.axis_child.x > 0.9999 && h.quality < 0.01);
    // A 2-DoF joint (the parent's z, then the child's y) from orientations, the child's
    // 40 degrees off in heading.
    std::vector<OrientQuaternion> qp, qc;
    for (int i = 0; i < 1000; i++) {
        double t = i * dt;
        qp.push_back(parent(t));
        qc.push_back(mul(rot(0, 0, 1, 0.7), mul(parent(t), mul(rot(0, 0, 1, 0.25 * std::sin(2.1 * t)), rot(0, 1, 0, flexion(t))))));
    }
    CHECK(orient::estimate_two_dof_axes(qp, qc, orient::vec3(0, 0.08, 1), orient::vec3(0.08, 1, 0), h) == ORIENT_STATUS_OK);
    CHECK(h.axis_parent.z > 0.9999 && h.axis_child.y > 0.9999 && h.quality < 0.05);
    qc.pop_back();
    CHECK(orient::estimate_two_dof_axes(qp, qc, orient::vec3(0, 0, 1), orient::vec3(0, 1, 0), h) == ORIENT_STATUS_INVALID_ARGUMENT);
    // A sensor's configuration under joints: the three settings, other kinds unchanged.
    orient::Config under = orient::Config::defaults(orient::Kind::Robust).value();
    CHECK(under.for_joints() == ORIENT_STATUS_OK);
    CHECK(std::fabs(under.get(ORIENT_PARAM_ROBUST_BIAS_WALK) - 0.05 * 0.017453292519943295) < 1e-15);
    CHECK(std::fabs(under.get(ORIENT_PARAM_ROBUST_BIAS_LIMIT) - 4.0 * 0.017453292519943295) < 1e-15);
    CHECK(std::fabs(under.get(ORIENT_PARAM_ROBUST_REST_GYRO) - 4.0 * 0.017453292519943295) < 1e-15);
    orient::Config other = orient::Config::defaults(orient::Kind::Madgwick).value();
    CHECK(other.for_joints() == ORIENT_STATUS_OK);
    CHECK(std::memcmp(&other.raw(), &orient::Config::defaults(orient::Kind::Madgwick).value().raw(), sizeof(OrientConfig)) == 0);
#if ORIENT_HPP_EXCEPTIONS
    bool thrown = false;
    try {
        orient::Joints j(cycle, 2);
    } catch (const orient::Exception& e) {
        thrown = e.status() == ORIENT_STATUS_INVALID_JOINT;
    }
    CHECK(thrown);
#endif
}

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s GOLDEN_FILE\n", argv[0]);
        return 2;
    }
    kinds();
    wrapper();
    rig();
    offline();
    mounting_and_heading();
    calibration();
    uncertainty();
    joints();
#if ORIENT_HPP_EXCEPTIONS
    exceptions();
#endif
    golden(argv[1]);
    std::printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
