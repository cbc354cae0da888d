// Several filters side by side on one recording, the motion-capture use: every kind
// gets the same samples in one batch call per block; prints each filter's orientation
// once per second and, when the recording has optical ground truth, its error.
//
//   c++ -std=c++17 examples/cpp/side_by_side.cpp -Iinclude -Ibindings/cpp target/release/liborient.a -lm
//   (from the repository after `cargo build --release`; README.md, *C*, for the shared library)
//   ./a.out examples/data/broad_01_excerpt.csv
#include "orient.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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
    if (t < 0 || gx < 0 || ax < 0 || mx < 0) {
        std::fprintf(stderr, "need t, gyr_*, acc_*, mag_* columns\n");
        return 2;
    }
    std::vector<OrientSample> samples;
    std::vector<OrientQuaternion> truth;
    double previous = 0.0;
    while (std::getline(in, line)) {
        std::vector<double> v;
        std::stringstream row(line);
        for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::strtod(cell.c_str(), nullptr));
        if (v.size() < names.size()) continue;
        double dt = samples.empty() ? 0.01 : v[t] - previous;
        previous = v[t];
        samples.push_back(orient::sample(dt, orient::vec3(v[gx], v[gx + 1], v[gx + 2]),
                                         orient::vec3(v[ax], v[ax + 1], v[ax + 2]),
                                         orient::vec3(v[mx], v[mx + 1], v[mx + 2])));
        truth.push_back(qw >= 0 ? OrientQuaternion{v[qw], v[qw + 1], v[qw + 2], v[qw + 3]}
                                : OrientQuaternion{NAN, NAN, NAN, NAN});
    }

    const orient::Kind kinds[] = {orient::Kind::Madgwick, orient::Kind::Mahony, orient::Kind::Complementary,
                                  orient::Kind::Ekf,      orient::Kind::Gmvdk,  orient::Kind::Robust};
    const char* labels[] = {"madgwick", "mahony", "complementary", "ekf", "gmvdk", "robust"};
    std::vector<orient::Filter> filters;
    for (orient::Kind k : kinds) {
        auto f = orient::Filter::create(orient::Config::defaults(k).value());
        if (!f) {
            std::fprintf(stderr, "%s\n", f.error().message.c_str());
            return 1;
        }
        filters.push_back(std::move(f).value());
    }

    const std::size_t block = 286;  // about one second at 285.7 Hz
    std::vector<OrientQuaternion> out(block);
    std::vector<double> sum_sq(filters.size(), 0.0);
    std::size_t scored = 0;
    for (std::size_t start = 0; start < samples.size(); start += block) {
        std::size_t n = std::min(block, samples.size() - start);
        for (std::size_t i = 0; i < filters.size(); ++i) {
            OrientStatus s = filters[i].update_batch(samples.data() + start, n, out.data());
            if (s != ORIENT_STATUS_OK) std::fprintf(stderr, "%s: %s\n", labels[i], orient_last_error());
            const OrientQuaternion& q = out[n - 1];
            const OrientQuaternion& g = truth[start + n - 1];
            if (!std::isnan(g.w)) {
                double dot = std::fabs(q.w * g.w + q.x * g.x + q.y * g.y + q.z * g.z);
                double angle = 2.0 * std::acos(std::fmin(1.0, dot)) * 57.29578;
                sum_sq[i] += angle * angle;
                if (i == 0) ++scored;
            }
        }
    }
    std::printf("%zu samples, %zu filters\n", samples.size(), filters.size());
    for (std::size_t i = 0; i < filters.size(); ++i) {
        OrientQuaternion q = filters[i].quaternion();
        std::printf("%-14s q = (%+.5f, %+.5f, %+.5f, %+.5f)", labels[i], q.w, q.x, q.y, q.z);
        if (scored) std::printf("  RMS error vs optical truth, once per second: %6.2f deg", std::sqrt(sum_sq[i] / scored));
        std::printf("\n");
    }
    return 0;
}
