// Rig calibration, the motion-capture set-up step: sensors strapped on their segments at
// unknown angles are calibrated from a reference posture, after which every filter reads
// its segment's orientation. Here one recording plays one segment seen by four sensors,
// each mounted at another (made-up) angle: the readings are the recording's turned into
// each sensor's axes. At 2 s the segment's orientation is taken as the reference posture
// (the optical truth there; a T-pose or a flat hand in a real rig), orient::calibrate_rig
// computes the mountings, and afterwards the four filters agree on the segment.
//
//   c++ -std=c++17 examples/cpp/rig_calibration.cpp -Iinclude -Ibindings/cpp target/release/liborient.a -lm
//   (from the repository after `cargo build --release`; README.md, *C*, for the shared library)
//   ./a.out examples/data/broad_01_excerpt.csv
#include "orient.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

static OrientQuaternion mul(const OrientQuaternion& a, const OrientQuaternion& b) {
    return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

// v in the axes of a sensor whose mounting (sensor to segment) is m: conj(m) v m.
static OrientVec3 into_sensor(const OrientQuaternion& m, const OrientVec3& v) {
    OrientQuaternion c{m.w, -m.x, -m.y, -m.z};
    OrientQuaternion r = mul(mul(c, OrientQuaternion{0.0, v.x, v.y, v.z}), m);
    return {r.x, r.y, r.z};
}

static double angle_deg(const OrientQuaternion& a, const OrientQuaternion& b) {
    OrientQuaternion d = mul(OrientQuaternion{a.w, -a.x, -a.y, -a.z}, b);
    return 2.0 * std::atan2(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z), std::fabs(d.w)) * 57.29578;
}

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s RECORDING.csv\n", argv[0]);
        return 2;
    }
    std::ifstream in(argv[1]);
    std::string line;
    std::getline(in, line);
    std::vector<std::string> names;
    for (std::stringstream h(line); std::getline(h, line, ',');) names.push_back(line);
    auto col = [&](const char* n) {
        for (std::size_t i = 0; i < names.size(); ++i)
            if (names[i] == n) return static_cast<int>(i);
        return -1;
    };
    const int t = col("t"), gx = col("gyr_x"), ax = col("acc_x"), mx = col("mag_x"), qw = col("quat_w");
    if (t < 0 || gx < 0 || ax < 0 || mx < 0 || qw < 0) {
        std::fprintf(stderr, "need t, gyr_*, acc_*, mag_*, quat_* columns\n");
        return 2;
    }
    // Four mountings: unit quaternions at various angles.
    std::array<OrientQuaternion, 4> mountings{{{1, 0, 0, 0}, {0.9, 0.3, -0.2, 0.25}, {0.5, 0.5, 0.5, 0.5},
                                               {0.2, -0.7, 0.6, 0.3}}};
    for (auto& m : mountings) {
        double n = std::sqrt(m.w * m.w + m.x * m.x + m.y * m.y + m.z * m.z);
        m = {m.w / n, m.x / n, m.y / n, m.z / n};
    }
    std::vector<orient::Filter> filters;
    std::array<OrientFilter*, 4> handles{};
    for (std::size_t k = 0; k < 4; ++k) {
        filters.push_back(orient::Filter::create(orient::Config::defaults(orient::Kind::Robust).value()).value());
        handles[k] = filters[k].native();
    }
    double previous = 0.0, start = NAN, worst = 0.0;
    bool calibrated = false;
    std::size_t rows = 0;
    while (std::getline(in, line)) {
        std::vector<double> v;
        std::stringstream row(line);
        for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::strtod(cell.c_str(), nullptr));
        if (v.size() < names.size()) continue;
        double dt = rows == 0 ? 0.01 : v[t] - previous;
        previous = v[t];
        if (std::isnan(start)) start = v[t];
        ++rows;
        OrientVec3 g{v[gx], v[gx + 1], v[gx + 2]}, a{v[ax], v[ax + 1], v[ax + 2]}, m{v[mx], v[mx + 1], v[mx + 2]};
        for (std::size_t k = 0; k < 4; ++k) {
            const OrientQuaternion& mk = mountings[k];
            OrientStatus s = filters[k].update(
                orient::sample(dt, into_sensor(mk, g), into_sensor(mk, a), into_sensor(mk, m)));
            if (s != ORIENT_STATUS_OK) std::fprintf(stderr, "sensor %zu: %s\n", k, orient_last_error());
        }
        OrientQuaternion truth{v[qw], v[qw + 1], v[qw + 2], v[qw + 3]};
        if (!calibrated && v[t] - start >= 2.0) {
            // The reference posture: every sensor's segment is the recorded one.
            std::array<OrientQuaternion, 4> references{truth, truth, truth, truth};
            if (orient::calibrate_rig(handles, references) != ORIENT_STATUS_OK) {
                std::fprintf(stderr, "calibration: %s\n", orient_last_error());
                return 1;
            }
            calibrated = true;
            std::printf("calibrated at t = %.2f s\n", v[t] - start);
        } else if (calibrated) {
            OrientQuaternion q0 = filters[0].quaternion();
            for (std::size_t k = 1; k < 4; ++k) worst = std::fmax(worst, angle_deg(q0, filters[k].quaternion()));
        }
    }
    // The optical truth's body axes are not the IMU's (BROAD's markers sit elsewhere), so
    // every found mounting carries that one offset too; relative to sensor 0 (mounted
    // straight) it cancels: conj(m0) mk is the made-up mounting of sensor k.
    OrientQuaternion m0 = filters[0].mounting();
    for (std::size_t k = 0; k < 4; ++k) {
        OrientQuaternion rel = mul(OrientQuaternion{m0.w, -m0.x, -m0.y, -m0.z}, filters[k].mounting());
        std::printf("sensor %zu: mounting relative to sensor 0 (%+.4f, %+.4f, %+.4f, %+.4f), error %.3f deg\n", k,
                    rel.w, rel.x, rel.y, rel.z, angle_deg(rel, mountings[k]));
    }
    std::printf("%zu samples; after calibration the sensors disagree on the segment by at most %.3f deg\n", rows,
                worst);
    return 0;
}
