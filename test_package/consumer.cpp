// Links against the orient Conan package through the C++ wrapper.
#include <orient.hpp>

#include <cstdio>

int main() {
    orient::Filter f(orient::Kind::Madgwick);
    if (f.update(orient::sample(0.01, {0, 0, 0.1}, {0, 0, 9.81}, {0, 20, -40})) != ORIENT_STATUS_OK) return 1;
    OrientQuaternion q = f.quaternion();
    std::printf("orient C++: q = (%.4f, %.4f, %.4f, %.4f)\n", q.w, q.x, q.y, q.z);
    return 0;
}
