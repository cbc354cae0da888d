/*
 * Loads and unloads liborient N times, using it in between (every kind's parameter
 * table, a filter's lifecycle, a refused call), so that valgrind can show whether a
 * load/unload cycle leaves memory behind.
 *
 * Usage: dlopen_test LIBRARY N
 * Built by tests/c_abi.rs with -std=c99 -Wall -Wextra -Werror -pedantic and run under
 * valgrind for two values of N: the leaked bytes must not grow with N.
 */
#define _POSIX_C_SOURCE 200809L
#include "orient.h"

#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef OrientStatus (*ConfigDefault)(int32_t, OrientConfig *);
typedef OrientStatus (*ParamCount)(int32_t, uint32_t *);
typedef OrientStatus (*ParamInfo)(int32_t, uint32_t, OrientParamInfo *);
typedef OrientStatus (*FilterNew)(const OrientConfig *, OrientFilter **);
typedef OrientStatus (*FilterUpdate)(OrientFilter *, const OrientSample *);
typedef OrientStatus (*FilterFree)(OrientFilter *);

/* dlsym returns a data pointer; POSIX guarantees it converts to a function pointer. */
#define LOOKUP(lib, name, type, out)                                                   \
    do {                                                                               \
        void *sym = dlsym(lib, name);                                                  \
        if (!sym) {                                                                    \
            fprintf(stderr, "missing %s\n", name);                                     \
            return 1;                                                                  \
        }                                                                              \
        memcpy(&out, &sym, sizeof out);                                                \
    } while (0)

static int cycle(const char *path) {
    void *lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    ConfigDefault config_default;
    ParamCount param_count;
    ParamInfo param_info;
    FilterNew filter_new;
    FilterUpdate filter_update;
    FilterFree filter_free;
    int32_t kind;
    if (!lib) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        return 1;
    }
    LOOKUP(lib, "orient_config_default", ConfigDefault, config_default);
    LOOKUP(lib, "orient_param_count", ParamCount, param_count);
    LOOKUP(lib, "orient_param_info", ParamInfo, param_info);
    LOOKUP(lib, "orient_filter_new", FilterNew, filter_new);
    LOOKUP(lib, "orient_filter_update", FilterUpdate, filter_update);
    LOOKUP(lib, "orient_filter_free", FilterFree, filter_free);
    /* Every kind the library knows: the first kind it refuses ends the loop. */
    for (kind = ORIENT_KIND_MADGWICK;; kind++) {
        OrientConfig c;
        OrientFilter *f = NULL;
        OrientSample s;
        uint32_t count = 0, i;
        if (config_default(kind, &c) != ORIENT_STATUS_OK) break;
        if (param_count(kind, &count) != ORIENT_STATUS_OK) return 1;
        for (i = 0; i < count; i++) {
            OrientParamInfo info;
            if (param_info(kind, i, &info) != ORIENT_STATUS_OK || strlen(info.name) == 0) return 1;
        }
        if (filter_new(&c, &f) != ORIENT_STATUS_OK) return 1;
        memset(&s, 0, sizeof s);
        s.dt = 0.01;
        s.accel.z = 9.81;
        s.flags = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL;
        if (filter_update(f, &s) != ORIENT_STATUS_OK) return 1;
        s.dt = -1.0; /* refused: records an error detail */
        if (filter_update(f, &s) != ORIENT_STATUS_INVALID_DT) return 1;
        if (filter_free(f) != ORIENT_STATUS_OK) return 1;
    }
    if (kind <= ORIENT_KIND_ROBUST) {
        fprintf(stderr, "kind %d refused\n", (int)kind);
        return 1;
    }
    if (dlclose(lib) != 0) {
        fprintf(stderr, "dlclose: %s\n", dlerror());
        return 1;
    }
    return 0;
}

int main(int argc, char **argv) {
    int n, i;
    if (argc != 3) {
        fprintf(stderr, "usage: %s LIBRARY N\n", argv[0]);
        return 2;
    }
    n = atoi(argv[2]);
    for (i = 0; i < n; i++) {
        if (cycle(argv[1]) != 0) return 1;
    }
    printf("%d cycles\n", n);
    return 0;
}
