/* Links against the orient Conan package and runs one filter step. */
#include <orient.h>
#include <stdio.h>

int main(void) {
    OrientConfig c;
    OrientFilter *f = NULL;
    OrientSample s = {0.01, {0.0, 0.0, 0.1}, {0.0, 0.0, 9.81}, {0.0, 20.0, -40.0},
                      ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG, 0};
    OrientQuaternion q;
    if (orient_config_default(ORIENT_KIND_EKF, &c) != ORIENT_STATUS_OK) return 1;
    if (orient_filter_new(&c, &f) != ORIENT_STATUS_OK) return 1;
    if (orient_filter_update(f, &s) != ORIENT_STATUS_OK) return 1;
    orient_filter_quaternion(f, &q);
    orient_filter_free(f);
    printf("orient %s abi %u: q = (%.4f, %.4f, %.4f, %.4f)\n", orient_version(), orient_abi_version(), q.w, q.x, q.y, q.z);
    return orient_abi_version() == ORIENT_ABI_VERSION ? 0 : 1;
}
