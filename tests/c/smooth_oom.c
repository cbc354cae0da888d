/* orient_smooth_arrays with too little memory left: the address space is limited
   (setrlimit RLIMIT_AS) to what the process maps plus 8 MiB, below the 16 MB that
   2,000,000 samples need (orient_smooth_memory). The call must return
   ORIENT_STATUS_OUT_OF_MEMORY with the output unwritten, not abort the host; a
   recording that fits still smooths under the same limit. Linux only (/proc). */
#define _GNU_SOURCE
#include "orient.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

enum { N = 2000000, SMALL = 1000 };

static int failed = 0;
#define CHECK(cond)                                                                    \
    do {                                                                               \
        if (!(cond)) {                                                                 \
            printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);                     \
            failed++;                                                                  \
        }                                                                              \
    } while (0)

/* Bytes the process maps now: the first field of /proc/self/statm, in pages. */
static size_t mapped(void) {
    unsigned long pages = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f == NULL || fscanf(f, "%lu", &pages) != 1) {
        printf("FAIL cannot read /proc/self/statm\n");
        exit(2);
    }
    fclose(f);
    return (size_t)pages * (size_t)sysconf(_SC_PAGESIZE);
}

int main(void) {
    double *gyro = malloc(sizeof(double) * 3 * N), *accel = malloc(sizeof(double) * 3 * N);
    double *mag = malloc(sizeof(double) * 3 * N), dt = 0.01;
    OrientQuaternion *q = malloc(sizeof(OrientQuaternion) * N);
    OrientConfig c;
    size_t i, processed = 99, need = 0;
    struct rlimit limit;
    if (gyro == NULL || accel == NULL || mag == NULL || q == NULL) {
        printf("FAIL arrays\n");
        return 2;
    }
    for (i = 0; i < N; i++) {
        gyro[3 * i] = 0.001, gyro[3 * i + 1] = 0.0, gyro[3 * i + 2] = 0.0;
        accel[3 * i] = 0.0, accel[3 * i + 1] = 0.0, accel[3 * i + 2] = 9.81;
        mag[3 * i] = 0.0, mag[3 * i + 1] = 20.0, mag[3 * i + 2] = -40.0;
        q[i].w = 7.0, q[i].x = q[i].y = q[i].z = 0.0;
    }
    CHECK(orient_smooth_config_default(&c) == ORIENT_STATUS_OK);
    CHECK(orient_smooth_memory(N, &need) == ORIENT_STATUS_OK);
    CHECK(need == 8 * (size_t)N + 32768);
    /* Touch the library's error and message paths before the limit. */
    CHECK(strlen(orient_status_message(ORIENT_STATUS_OUT_OF_MEMORY)) > 0);
    limit.rlim_cur = limit.rlim_max = mapped() + 8u * 1024 * 1024;
    if (setrlimit(RLIMIT_AS, &limit) != 0) {
        printf("FAIL setrlimit\n");
        return 2;
    }
    CHECK(orient_smooth_arrays(&c, N, &dt, 1, gyro, accel, mag, q, &processed) == ORIENT_STATUS_OUT_OF_MEMORY);
    CHECK(processed == 0);
    CHECK(strstr(orient_last_error(), "could not be allocated") != NULL);
    for (i = 0; i < N; i++) {
        if (q[i].w != 7.0) {
            CHECK(!"the output is left unwritten");
            break;
        }
    }
    /* What fits the limit still runs. */
    CHECK(orient_smooth_arrays(&c, SMALL, &dt, 1, gyro, accel, mag, q, &processed) == ORIENT_STATUS_OK);
    CHECK(processed == SMALL);
    CHECK(fabs(q[0].w * q[0].w + q[0].x * q[0].x + q[0].y * q[0].y + q[0].z * q[0].z - 1.0) < 1e-12);
    CHECK(q[SMALL].w == 7.0);
    printf("smooth_oom: %d failed\n", failed);
    free(gyro), free(accel), free(mag), free(q);
    return failed != 0;
}
