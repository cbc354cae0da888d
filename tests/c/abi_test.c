/*
 * ABI behaviour and exact numeric parity of liborient, from C.
 *
 * Usage: abi_test GOLDEN_FILE
 * Built by tests/c_abi.rs with -std=c99 -Wall -Wextra -Werror -pedantic, once against
 * liborient.so and once against liborient.a, and run by `cargo test`. Prints one line
 * per failed check and ends with "N passed, N failed".
 */
#include "orient.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int passed = 0;
static int failed = 0;

#define CHECK(cond)                                                                    \
    do {                                                                               \
        if (cond) {                                                                    \
            passed++;                                                                  \
        } else {                                                                       \
            failed++;                                                                  \
            printf("FAIL %s:%d: %s (last error: %s)\n", __FILE__, __LINE__, #cond,     \
                   orient_last_error());                                               \
        }                                                                              \
    } while (0)

#define CHECK_STATUS(call, expected) CHECK((call) == (expected))

static uint64_t bits(double v) {
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    return u;
}

#include "rig_test.h" /* issue 20 */

static double unhex(const char *s) {
    uint64_t u = (uint64_t)strtoull(s, NULL, 16);
    double v;
    memcpy(&v, &u, sizeof v);
    return v;
}

static int same_quaternion(OrientQuaternion a, OrientQuaternion b) {
    return bits(a.w) == bits(b.w) && bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) &&
           bits(a.z) == bits(b.z);
}

static OrientFilter *new_filter(int32_t kind) {
    OrientConfig c;
    OrientFilter *f = NULL;
    if (orient_config_default(kind, &c) != ORIENT_STATUS_OK) return NULL;
    if (orient_filter_new(&c, &f) != ORIENT_STATUS_OK) return NULL;
    return f;
}

static OrientFilter *new_madgwick(void) { return new_filter(ORIENT_KIND_MADGWICK); }

#include "joints_test.h" /* issue 42 */

static OrientSample good_sample(void) {
    OrientSample s;
    memset(&s, 0, sizeof s);
    s.dt = 0.01;
    s.gyro.x = 0.1;
    s.gyro.y = -0.2;
    s.gyro.z = 0.3;
    s.accel.x = 0.5;
    s.accel.y = 0.2;
    s.accel.z = 9.7;
    s.mag.x = 10.0;
    s.mag.y = 20.0;
    s.mag.z = -40.0;
    s.flags = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG;
    return s;
}

/* ---- golden vectors ------------------------------------------------------------ */

#define MAX_ROWS 4096
#define MAX_TOKENS 64

typedef struct {
    OrientSample sample;
    OrientQuaternion expected;
} Row;

static Row rows[MAX_ROWS];
static OrientQuaternion batch_out[MAX_ROWS];

static int split(char *line, char **tok) {
    int n = 0;
    char *p = strtok(line, " \t\r\n");
    while (p && n < MAX_TOKENS) {
        tok[n++] = p;
        p = strtok(NULL, " \t\r\n");
    }
    return n;
}

/* Runs a case through orient_filter_update_arrays when every row has the same sensors
 * (the arrays carry a sensor for all samples or for none). */
static void arrays_case(const OrientConfig *config, int n) {
    static double dt[MAX_ROWS], gyro[3 * MAX_ROWS], accel[3 * MAX_ROWS], mag[3 * MAX_ROWS];
    static uint32_t flags[MAX_ROWS];
    OrientFilter *f = NULL;
    uint32_t sensors = rows[0].sample.flags;
    size_t processed = 0;
    int i, mismatches = 0;
    for (i = 0; i < n; i++) {
        const OrientSample *s = &rows[i].sample;
        if (s->flags != sensors) return;
        dt[i] = s->dt;
        gyro[3 * i] = s->gyro.x, gyro[3 * i + 1] = s->gyro.y, gyro[3 * i + 2] = s->gyro.z;
        accel[3 * i] = s->accel.x, accel[3 * i + 1] = s->accel.y, accel[3 * i + 2] = s->accel.z;
        mag[3 * i] = s->mag.x, mag[3 * i + 1] = s->mag.y, mag[3 * i + 2] = s->mag.z;
    }
    CHECK_STATUS(orient_filter_new(config, &f), ORIENT_STATUS_OK);
    if (!f) return;
    CHECK_STATUS(orient_filter_update_arrays(f, (size_t)n, dt, (size_t)n, gyro,
                                             (sensors & ORIENT_SAMPLE_ACCEL) ? accel : NULL,
                                             (sensors & ORIENT_SAMPLE_MAG) ? mag : NULL, batch_out,
                                             flags, NULL, &processed),
                 ORIENT_STATUS_OK);
    CHECK(processed == (size_t)n);
    for (i = 0; i < n; i++) {
        if (!same_quaternion(batch_out[i], rows[i].expected)) mismatches++;
    }
    CHECK(mismatches == 0);
    CHECK(n == 0 || (flags[n - 1] & ORIENT_FLAG_INITIALIZED));
    CHECK_STATUS(orient_filter_free(f), ORIENT_STATUS_OK);
}

/* Runs one case through single updates and through one batch call. */
static void run_case(const char *name, const OrientConfig *config, int n) {
    OrientFilter *single = NULL;
    OrientFilter *batch = NULL;
    int i, mismatches = 0;
    size_t processed = 12345;
    CHECK_STATUS(orient_filter_new(config, &single), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_new(config, &batch), ORIENT_STATUS_OK);
    if (!single || !batch) return;
    for (i = 0; i < n; i++) {
        OrientQuaternion q;
        if (orient_filter_update(single, &rows[i].sample) != ORIENT_STATUS_OK ||
            orient_filter_quaternion(single, &q) != ORIENT_STATUS_OK ||
            !same_quaternion(q, rows[i].expected)) {
            if (mismatches++ == 0) printf("FAIL golden %s: first mismatch at sample %d\n", name, i);
        }
    }
    CHECK(mismatches == 0);
    {
        /* The batch call takes the samples as one array. */
        static OrientSample samples[MAX_ROWS];
        for (i = 0; i < n; i++) samples[i] = rows[i].sample;
        CHECK_STATUS(orient_filter_update_batch(batch, samples, (size_t)n, batch_out, &processed),
                     ORIENT_STATUS_OK);
        CHECK(processed == (size_t)n);
        mismatches = 0;
        for (i = 0; i < n; i++) {
            if (!same_quaternion(batch_out[i], rows[i].expected)) mismatches++;
        }
        CHECK(mismatches == 0);
    }
    arrays_case(config, n);
    CHECK_STATUS(orient_filter_free(single), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_free(batch), ORIENT_STATUS_OK);
}

static void golden(const char *path) {
    FILE *fp = fopen(path, "r");
    char line[2048];
    char *tok[MAX_TOKENS];
    char name[128] = "";
    OrientConfig config;
    int n = 0, cases = 0, ntok;
    CHECK(fp != NULL);
    if (!fp) return;
    while (fgets(line, sizeof line, fp)) {
        ntok = split(line, tok);
        if (ntok == 0 || tok[0][0] == '#') continue;
        if (strcmp(tok[0], "case") == 0) {
            int p, nparams;
            CHECK(ntok >= 10);
            strncpy(name, tok[1], sizeof name - 1);
            CHECK_STATUS(orient_config_default(atoi(tok[2]), &config), ORIENT_STATUS_OK);
            config.frame = atoi(tok[3]);
            config.init = atoi(tok[4]);
            config.initial.w = unhex(tok[5]);
            config.initial.x = unhex(tok[6]);
            config.initial.y = unhex(tok[7]);
            config.initial.z = unhex(tok[8]);
            nparams = atoi(tok[9]);
            for (p = 0; p < nparams && 11 + 2 * p < ntok; p++) {
                CHECK_STATUS(orient_config_set_param(&config, (uint32_t)atoi(tok[10 + 2 * p]),
                                                     unhex(tok[11 + 2 * p])),
                             ORIENT_STATUS_OK);
            }
            n = 0;
        } else if (strcmp(tok[0], "s") == 0) {
            Row *r = &rows[n];
            CHECK(ntok == 16 && n < MAX_ROWS);
            if (ntok != 16 || n >= MAX_ROWS) break;
            memset(&r->sample, 0, sizeof r->sample);
            r->sample.dt = unhex(tok[1]);
            r->sample.gyro.x = unhex(tok[2]);
            r->sample.gyro.y = unhex(tok[3]);
            r->sample.gyro.z = unhex(tok[4]);
            r->sample.accel.x = unhex(tok[5]);
            r->sample.accel.y = unhex(tok[6]);
            r->sample.accel.z = unhex(tok[7]);
            r->sample.mag.x = unhex(tok[8]);
            r->sample.mag.y = unhex(tok[9]);
            r->sample.mag.z = unhex(tok[10]);
            r->sample.flags = (uint32_t)atoi(tok[11]);
            r->expected.w = unhex(tok[12]);
            r->expected.x = unhex(tok[13]);
            r->expected.y = unhex(tok[14]);
            r->expected.z = unhex(tok[15]);
            n++;
        } else if (strcmp(tok[0], "end") == 0) {
            run_case(name, &config, n);
            cases++;
        }
    }
    fclose(fp);
    CHECK(cases >= 4);
    printf("golden: %d cases\n", cases);
}

/* ---- ABI behaviour -------------------------------------------------------------- */

static void layout(void) {
    CHECK(sizeof(OrientStatus) == 4);
    CHECK(sizeof(OrientVec3) == 24);
    CHECK(sizeof(OrientQuaternion) == 32);
    CHECK(sizeof(OrientSample) == 88);
    CHECK(sizeof(OrientConfig) == 1072);
    CHECK(sizeof(OrientDiagnostics) == 176);
    CHECK(offsetof(OrientSample, flags) == 80);
    CHECK(offsetof(OrientConfig, params) == 48);
    CHECK(offsetof(OrientDiagnostics, covariance) == 96);
    CHECK(sizeof(OrientUncertainty) == 24);
    CHECK(offsetof(OrientUncertainty, heading) == 8);
    CHECK(orient_abi_version() == ORIENT_ABI_VERSION);
    CHECK(orient_version() != NULL && strlen(orient_version()) > 0);
}

static void status_messages(void) {
    int s;
    for (s = ORIENT_STATUS_OK; s <= ORIENT_STATUS_OUT_OF_MEMORY; s++) {
        const char *m = orient_status_message(s);
        CHECK(m != NULL && strlen(m) > 0 && strcmp(m, "unknown status code") != 0);
    }
    CHECK(strcmp(orient_status_message(-7), "unknown status code") == 0);
    CHECK(strcmp(orient_status_message(ORIENT_STATUS_INVALID_JOINT + 1), "unknown status code") == 0);
    CHECK(orient_last_error() != NULL);
}

static void config_paths(void) {
    OrientConfig c;
    OrientFilter *f = (OrientFilter *)&c; /* must be overwritten with NULL on failure */
    OrientParamInfo info;
    uint32_t count = 0, id = 0, i;
    double v = 0;
    int k;

    CHECK_STATUS(orient_config_default(ORIENT_KIND_MADGWICK, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_config_default(0, &c), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_config_default(99, &c), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_config_default(ORIENT_KIND_ROBUST + 1, &c), ORIENT_STATUS_INVALID_ARGUMENT);
    for (k = ORIENT_KIND_MADGWICK; k <= ORIENT_KIND_ROBUST; k++) {
        CHECK_STATUS(orient_config_default(k, &c), ORIENT_STATUS_OK);
        CHECK(c.kind == k);
        CHECK_STATUS(orient_param_count(k, &count), ORIENT_STATUS_OK);
        CHECK(count > 3);
        for (i = 0; i < count; i++) {
            CHECK_STATUS(orient_param_info(k, i, &info), ORIENT_STATUS_OK);
            CHECK(info.id < ORIENT_MAX_PARAMS && c.params[info.id] == info.default_value);
            CHECK(strstr(info.description, "default") != NULL);
        }
    }
    CHECK_STATUS(orient_config_default(ORIENT_KIND_MADGWICK, &c), ORIENT_STATUS_OK);
    CHECK(c.struct_size == sizeof(OrientConfig));
    CHECK(c.kind == ORIENT_KIND_MADGWICK && c.frame == ORIENT_FRAME_ENU && c.init == ORIENT_INIT_ACC_MAG);
    CHECK(c.params[ORIENT_PARAM_MADGWICK_BETA_IMU] == 0.041);
    CHECK(c.params[ORIENT_PARAM_MADGWICK_BETA_MARG] == 0.041);
    CHECK(c.params[ORIENT_PARAM_GRAVITY] == 9.80665);

    /* Parameters: discoverable by index and by name, range-checked. */
    CHECK_STATUS(orient_param_count(ORIENT_KIND_MADGWICK, &count), ORIENT_STATUS_OK);
    CHECK(count == 9);
    for (i = 0; i < count; i++) {
        CHECK_STATUS(orient_param_info(ORIENT_KIND_MADGWICK, i, &info), ORIENT_STATUS_OK);
        CHECK(info.name && info.unit && info.description && strlen(info.description) > 10);
        CHECK((info.flags & ~(uint32_t)ORIENT_PARAM_FLAG_ZERO_OFF) == 0);
        if (info.default_value == 0.0 && (info.flags & ORIENT_PARAM_FLAG_ZERO_OFF)) {
            /* Off by default: 0 is accepted, and so is min, while a value below min is not. */
            CHECK_STATUS(orient_config_set_param(&c, info.id, info.min), ORIENT_STATUS_OK);
            CHECK_STATUS(orient_config_set_param(&c, info.id, 0.5 * info.min), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
            CHECK_STATUS(orient_config_set_param(&c, info.id, 0.0), ORIENT_STATUS_OK);
        } else {
            CHECK(info.min <= info.default_value && info.default_value <= info.max);
        }
        CHECK_STATUS(orient_config_set_param(&c, info.id, 5e-324), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
        CHECK_STATUS(orient_param_find(ORIENT_KIND_MADGWICK, info.name, &id), ORIENT_STATUS_OK);
        CHECK(id == info.id);
        CHECK(c.params[info.id] == info.default_value);
    }
    CHECK_STATUS(orient_param_info(ORIENT_KIND_MADGWICK, count, &info), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_param_info(ORIENT_KIND_MADGWICK, 0, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_param_count(42, &count), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_param_find(ORIENT_KIND_MADGWICK, "no_such", &id), ORIENT_STATUS_UNKNOWN_PARAM);
    CHECK_STATUS(orient_param_find(ORIENT_KIND_MADGWICK, NULL, &id), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_param_find(ORIENT_KIND_MADGWICK, "beta_imu", &id), ORIENT_STATUS_OK);
    CHECK(id == ORIENT_PARAM_MADGWICK_BETA_IMU);

    CHECK_STATUS(orient_config_set_param(&c, ORIENT_PARAM_MADGWICK_BETA_IMU, -1.0), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
    CHECK_STATUS(orient_config_set_param(&c, ORIENT_PARAM_MADGWICK_BETA_IMU, NAN), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
    CHECK(c.params[ORIENT_PARAM_MADGWICK_BETA_IMU] == 0.041);
    CHECK_STATUS(orient_config_set_param(&c, 40, 1.0), ORIENT_STATUS_UNKNOWN_PARAM);
    CHECK_STATUS(orient_config_set_param(&c, ORIENT_PARAM_MADGWICK_BETA_IMU, 0.2), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_config_get_param(&c, ORIENT_PARAM_MADGWICK_BETA_IMU, &v), ORIENT_STATUS_OK);
    CHECK(v == 0.2);
    CHECK_STATUS(orient_config_set_param(NULL, 8, 0.2), ORIENT_STATUS_NULL_POINTER);
    CHECK(fabs(orient_madgwick_beta(0.1) - sqrt(0.75) * 0.1) < 1e-15);
    CHECK(isnan(orient_madgwick_beta(-1.0)));

    /* Creation refuses bad configurations and sets *out to NULL. */
    c.params[ORIENT_PARAM_MADGWICK_BETA_MARG] = INFINITY;
    CHECK_STATUS(orient_filter_new(&c, &f), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
    CHECK(f == NULL);
    CHECK_STATUS(orient_config_default(ORIENT_KIND_MADGWICK, &c), ORIENT_STATUS_OK);
    c.struct_size = 100;
    CHECK_STATUS(orient_filter_new(&c, &f), ORIENT_STATUS_VERSION_MISMATCH);
    c.struct_size = sizeof c;
    c.frame = 3;
    CHECK_STATUS(orient_filter_new(&c, &f), ORIENT_STATUS_INVALID_ARGUMENT);
    c.frame = ORIENT_FRAME_NED;
    c.init = 7;
    CHECK_STATUS(orient_filter_new(&c, &f), ORIENT_STATUS_INVALID_ARGUMENT);
    c.init = ORIENT_INIT_GIVEN;
    c.initial.w = c.initial.x = c.initial.y = c.initial.z = 0.0;
    CHECK_STATUS(orient_filter_new(&c, &f), ORIENT_STATUS_ZERO_VECTOR);
    c.initial.w = NAN;
    CHECK_STATUS(orient_filter_new(&c, &f), ORIENT_STATUS_NON_FINITE);
    c.kind = 0;
    CHECK_STATUS(orient_filter_new(&c, &f), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_filter_new(NULL, &f), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_new(&c, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK(f == NULL);
}

static void handle_paths(void) {
    OrientFilter *f = new_madgwick();
    OrientQuaternion q;
    OrientEuler e;
    OrientVec3 v;
    double m[9];
    uint32_t flags = 99;
    int32_t kind = 0;
    uint64_t fake[32];
    OrientFilter *not_a_handle = (OrientFilter *)(void *)fake;
    OrientFilter *misaligned = (OrientFilter *)(void *)((char *)fake + 1);
    OrientSample s = good_sample();

    CHECK(f != NULL);
    memset(fake, 0x5a, sizeof fake);
    /* NULL handles and NULL out-pointers */
    CHECK_STATUS(orient_filter_update(NULL, &s), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_update(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_quaternion(NULL, &q), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_quaternion(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_euler(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_rotation_matrix(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_gravity(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_linear_accel(NULL, &v), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_flags(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_kind(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_reset(NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_set_quaternion(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_get_param(f, 8, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_set_param(NULL, 8, 0.1), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_free(NULL), ORIENT_STATUS_OK);
    /* Pointers that are not handles */
    CHECK_STATUS(orient_filter_update(not_a_handle, &s), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_quaternion(misaligned, &q), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_free(not_a_handle), ORIENT_STATUS_INVALID_HANDLE);
    CHECK(strstr(orient_last_error(), "not a live") != NULL);
    /* A block that starts with the tag older versions checked, and a byte copy of the
     * start of a live handle: neither is a handle, and freeing them frees nothing. */
    memset(fake, 0, sizeof fake);
    memcpy(fake, "ORIENT.1", 8);
    CHECK_STATUS(orient_filter_update(not_a_handle, &s), ORIENT_STATUS_INVALID_HANDLE);
    memcpy(fake, (const void *)f, 16); /* a handle block is 16 bytes: kind tag, pointer */
    CHECK_STATUS(orient_filter_update(not_a_handle, &s), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_kind(not_a_handle, &kind), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_free(not_a_handle), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_kind(f, &kind), ORIENT_STATUS_OK);
    CHECK(kind == ORIENT_KIND_MADGWICK);

    /* Before initialisation: identity, flag clear, no linear acceleration yet. */
    CHECK_STATUS(orient_filter_flags(f, &flags), ORIENT_STATUS_OK);
    CHECK(flags == 0);
    CHECK_STATUS(orient_filter_quaternion(f, &q), ORIENT_STATUS_OK);
    CHECK(q.w == 1.0 && q.x == 0.0 && q.y == 0.0 && q.z == 0.0);
    CHECK_STATUS(orient_filter_linear_accel(f, &v), ORIENT_STATUS_NO_DATA);
    CHECK_STATUS(orient_filter_linear_accel_earth(f, &v), ORIENT_STATUS_NO_DATA);
    s.flags = ORIENT_SAMPLE_GYRO;
    CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_NOT_INITIALIZED);
    s = good_sample();
    CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_flags(f, &flags), ORIENT_STATUS_OK);
    CHECK(flags == (ORIENT_FLAG_INITIALIZED | ORIENT_FLAG_ACCEL_USED | ORIENT_FLAG_MAG_USED));
    CHECK_STATUS(orient_filter_kind(f, &kind), ORIENT_STATUS_OK);
    CHECK(kind == ORIENT_KIND_MADGWICK);

    /* Outputs agree with each other. */
    CHECK_STATUS(orient_filter_quaternion(f, &q), ORIENT_STATUS_OK);
    CHECK(fabs(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z - 1.0) < 1e-12);
    CHECK_STATUS(orient_filter_euler(f, &e), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_rotation_matrix(f, m), ORIENT_STATUS_OK);
    CHECK(fabs(m[8] - (1.0 - 2.0 * (q.x * q.x + q.y * q.y))) < 1e-12);
    CHECK(fabs(atan2(m[3], m[0]) - e.yaw) < 1e-12);
    CHECK_STATUS(orient_filter_gravity(f, &v), ORIENT_STATUS_OK);
    CHECK(fabs(sqrt(v.x * v.x + v.y * v.y + v.z * v.z) - 9.80665) < 1e-9);
    /* gravity in the sensor frame is the third row of R (earth up in sensor coords). */
    CHECK(fabs(v.z / 9.80665 - m[8]) < 1e-12);
    CHECK_STATUS(orient_filter_linear_accel(f, &v), ORIENT_STATUS_OK);
    CHECK(sqrt(v.x * v.x + v.y * v.y + v.z * v.z) < 1.0);
    CHECK_STATUS(orient_filter_linear_accel_earth(f, &v), ORIENT_STATUS_OK);

    /* Runtime parameters */
    {
        double b = 0;
        CHECK_STATUS(orient_filter_set_param(f, ORIENT_PARAM_MADGWICK_BETA_MARG, 0.5), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_get_param(f, ORIENT_PARAM_MADGWICK_BETA_MARG, &b), ORIENT_STATUS_OK);
        CHECK(b == 0.5);
        CHECK_STATUS(orient_filter_set_param(f, ORIENT_PARAM_MADGWICK_BETA_MARG, 1e9), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
        CHECK_STATUS(orient_filter_get_param(f, 63, &b), ORIENT_STATUS_UNKNOWN_PARAM);
    }

    /* set_quaternion normalises; reset returns to the uninitialised state. */
    q.w = 2.0;
    q.x = q.y = q.z = 0.0;
    CHECK_STATUS(orient_filter_set_quaternion(f, &q), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(f, &q), ORIENT_STATUS_OK);
    CHECK(fabs(q.w - 1.0) < 1e-15);
    q.w = NAN;
    CHECK_STATUS(orient_filter_set_quaternion(f, &q), ORIENT_STATUS_NON_FINITE);
    CHECK_STATUS(orient_filter_reset(f), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_flags(f, &flags), ORIENT_STATUS_OK);
    CHECK(flags == 0);

    /* A freed handle is refused by every call and its memory is not read (the valgrind
     * and sanitizer runs of this program would report the read). */
    CHECK_STATUS(orient_filter_free(f), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_free(f), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_quaternion(f, &q), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_set_param(f, ORIENT_PARAM_GRAVITY, 9.8), ORIENT_STATUS_INVALID_HANDLE);
    {
        /* The documented limit: an address handed out again names the new filter. */
        OrientFilter *g = new_filter(ORIENT_KIND_MAHONY);
        CHECK(g != NULL);
        if (g == f) {
            CHECK_STATUS(orient_filter_kind(f, &kind), ORIENT_STATUS_OK);
            CHECK(kind == ORIENT_KIND_MAHONY);
        }
        CHECK_STATUS(orient_filter_free(g), ORIENT_STATUS_OK);
    }
}

/* A NULL required pointer is NULL_POINTER before any other check: with a pointer that
 * is not a handle, an unknown kind, or a filter that has no data for the output yet. */
static void null_pointers_come_first(void) {
    OrientFilter *f = new_madgwick();
    uint64_t fake[32];
    OrientFilter *bad = (OrientFilter *)(void *)fake;
    OrientConfig c;
    const uint8_t blob[4] = {0, 0, 0, 0};
    uint32_t id = 0;
    size_t n = 0;
    memset(fake, 0, sizeof fake);
    CHECK(f != NULL);
    if (!f) return;
    /* No accelerometer reading yet: NO_DATA with an out-pointer, NULL_POINTER without. */
    {
        OrientVec3 v;
        CHECK_STATUS(orient_filter_linear_accel(f, &v), ORIENT_STATUS_NO_DATA);
        CHECK_STATUS(orient_filter_linear_accel_earth(f, &v), ORIENT_STATUS_NO_DATA);
    }
    CHECK_STATUS(orient_filter_linear_accel(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_linear_accel_earth(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_linear_accel(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_linear_accel_earth(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_quaternion(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_euler(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_rotation_matrix(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_gravity(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_diagnostics(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_uncertainty(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_flags(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_kind(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_get_param(bad, 9999, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_state_size(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_save(bad, NULL, 0, &n), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_save(bad, (uint8_t *)fake, 8, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_load(bad, NULL, 4), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_set_quaternion(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_update(bad, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_config_default(99, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_param_count(99, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_param_info(99, 9999, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_param_find(99, NULL, &id), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_param_find(99, "beta_imu", NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_config_get_param(NULL, 9999, NULL), ORIENT_STATUS_NULL_POINTER);
    memset(&c, 0, sizeof c); /* struct_size 0: VERSION_MISMATCH once the pointers pass */
    CHECK_STATUS(orient_config_get_param(&c, 9999, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_new(&c, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_load(bad, blob, sizeof blob), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_update_batch(bad, NULL, 3, NULL, &n), ORIENT_STATUS_NULL_POINTER);
    {
        OrientFilter *rig[3];
        OrientSample frame[3];
        rig[0] = f;
        rig[1] = bad;
        rig[2] = NULL;
        frame[0] = frame[1] = frame[2] = good_sample();
        CHECK_STATUS(orient_filters_update(rig, NULL, 3, NULL, &n), ORIENT_STATUS_NULL_POINTER);
        CHECK_STATUS(orient_filters_update(rig, frame, 3, NULL, &n), ORIENT_STATUS_NULL_POINTER);
        CHECK(strstr(orient_last_error(), "filter 2") != NULL);
        rig[2] = f;
        CHECK_STATUS(orient_filters_update(rig, frame, 3, NULL, &n), ORIENT_STATUS_INVALID_HANDLE);
        CHECK(strstr(orient_last_error(), "filter 1") != NULL);
        /* Every handle is checked before any filter changes: f took no sample. */
        {
            uint32_t flags = 99;
            CHECK_STATUS(orient_filter_flags(f, &flags), ORIENT_STATUS_OK);
            CHECK(flags == 0);
        }
    }
    CHECK_STATUS(orient_filter_free(f), ORIENT_STATUS_OK);
}

/* Every rejected sample leaves the state bit-identical: a twin that never saw the bad
 * samples must produce the same bits afterwards. */
/* Feeds still samples until the filter has an orientation (start-up periods). */
static int warm_up(OrientFilter *f) {
    OrientSample s = good_sample();
    uint32_t flags = 0;
    int i;
    s.gyro.x = s.gyro.y = s.gyro.z = 0.0;
    for (i = 0; i < 1000; i++) {
        if (orient_filter_update(f, &s) != ORIENT_STATUS_OK) return -1;
        if (orient_filter_flags(f, &flags) != ORIENT_STATUS_OK) return -1;
        if (flags & ORIENT_FLAG_INITIALIZED) return i + 1;
    }
    return -1;
}

/* Sentences of the header about the C layer that no other check covers. */
static void header_promises(void) {
    int32_t k;
    /* orient_madgwick_beta: NaN for a negative or non-finite input. */
    CHECK(isnan(orient_madgwick_beta(NAN)) && isnan(orient_madgwick_beta(INFINITY)));
    CHECK(orient_madgwick_beta(0.0) == 0.0);
    for (k = ORIENT_KIND_MADGWICK; k <= ORIENT_KIND_ROBUST; k++) {
        OrientConfig c;
        OrientFilter *f = NULL, *g = NULL;
        OrientQuaternion q;
        OrientParamInfo info;
        OrientDiagnostics d;
        uint32_t flags = 0, i, count = 0;
        size_t size_f = 0, size_g = 0;
        double v = 0.0;
        OrientSample s = good_sample(), hidden = good_sample(), shown;
        CHECK_STATUS(orient_config_default(k, &c), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_new(&c, &f), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_config_set_param(&c, ORIENT_PARAM_GRAVITY, 9.7), ORIENT_STATUS_OK);
        c.frame = ORIENT_FRAME_NED;
        CHECK_STATUS(orient_filter_new(&c, &g), ORIENT_STATUS_OK);
        if (!f || !g) return;
        /* Parameter flags and ranges, reserved fields. */
        CHECK_STATUS(orient_param_count(k, &count), ORIENT_STATUS_OK);
        for (i = 0; i < count; i++) {
            int off_by_default;
            CHECK_STATUS(orient_param_info(k, i, &info), ORIENT_STATUS_OK);
            CHECK((info.flags & ~(uint32_t)ORIENT_PARAM_FLAG_ZERO_OFF) == 0);
            off_by_default = info.default_value == 0.0 && (info.flags & ORIENT_PARAM_FLAG_ZERO_OFF);
            CHECK(off_by_default || info.min <= info.default_value);
            CHECK(info.default_value <= info.max);
            /* Subnormal values are never accepted; 0 exactly where the flag says. */
            CHECK_STATUS(orient_config_set_param(&c, info.id, 5e-324), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
            if (info.min > 0.0) {
                CHECK_STATUS(orient_config_set_param(&c, info.id, 0.0),
                             (info.flags & ORIENT_PARAM_FLAG_ZERO_OFF) ? ORIENT_STATUS_OK
                                                                       : ORIENT_STATUS_PARAM_OUT_OF_RANGE);
            }
            CHECK_STATUS(orient_config_set_param(&c, info.id, info.default_value), ORIENT_STATUS_OK);
        }
        CHECK_STATUS(orient_filter_diagnostics(f, &d), ORIENT_STATUS_OK);
        CHECK(d.reserved == 0);
        /* set_quaternion: unusable quaternions are refused; afterwards initialised. */
        q.w = q.x = q.y = q.z = 0.0;
        CHECK_STATUS(orient_filter_set_quaternion(f, &q), ORIENT_STATUS_ZERO_VECTOR);
        q.w = q.x = 1e300;
        CHECK_STATUS(orient_filter_set_quaternion(f, &q), ORIENT_STATUS_TOO_LARGE);
        CHECK_STATUS(orient_filter_flags(f, &flags), ORIENT_STATUS_OK);
        CHECK((flags & ORIENT_FLAG_INITIALIZED) == 0);
        q.w = 0.5;
        q.x = 0.5;
        CHECK_STATUS(orient_filter_set_quaternion(f, &q), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_flags(f, &flags), ORIENT_STATUS_OK);
        CHECK((flags & ORIENT_FLAG_INITIALIZED) != 0);
        /* The state size is one per kind, whatever the configuration or the state. */
        CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_state_size(f, &size_f), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_state_size(g, &size_g), ORIENT_STATUS_OK);
        CHECK(size_f == size_g && size_f > 0);
        /* reset keeps the parameters set since creation. */
        CHECK_STATUS(orient_filter_set_param(f, ORIENT_PARAM_GRAVITY, 9.6), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_reset(f), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_get_param(f, ORIENT_PARAM_GRAVITY, &v), ORIENT_STATUS_OK);
        CHECK(v == 9.6);
        /* Fields whose bit is clear are not read: NaN there changes nothing. */
        CHECK_STATUS(orient_filter_reset(f), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_free(g), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_config_default(k, &c), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_new(&c, &g), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_set_param(g, ORIENT_PARAM_GRAVITY, 9.6), ORIENT_STATUS_OK);
        CHECK(warm_up(f) > 0 && warm_up(g) > 0);
        hidden.flags = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL;
        hidden.mag.x = NAN;
        hidden.mag.z = INFINITY;
        shown = hidden;
        shown.mag.x = shown.mag.y = shown.mag.z = 0.0;
        CHECK_STATUS(orient_filter_update(f, &hidden), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_update(g, &shown), ORIENT_STATUS_OK);
        hidden.flags = ORIENT_SAMPLE_GYRO;
        hidden.accel.y = NAN;
        shown = hidden;
        shown.accel.x = shown.accel.y = shown.accel.z = 0.0;
        CHECK_STATUS(orient_filter_update(f, &hidden), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_update(g, &shown), ORIENT_STATUS_OK);
        {
            OrientQuaternion a, b;
            CHECK_STATUS(orient_filter_quaternion(f, &a), ORIENT_STATUS_OK);
            CHECK_STATUS(orient_filter_quaternion(g, &b), ORIENT_STATUS_OK);
            CHECK(same_quaternion(a, b));
        }
        CHECK_STATUS(orient_filter_free(f), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_free(g), ORIENT_STATUS_OK);
    }
}

/* Header sentences the other cases do not reach: set_param keeps the estimate and refuses
 * an unknown slot; orient_last_error() holds its detail through successful calls; a save
 * into too small a buffer writes nothing; and the order of the update's checks around
 * NOT_INITIALIZED. */
static void more_promises(int32_t kind) {
    OrientConfig c;
    OrientFilter *f = NULL, *fresh = NULL;
    OrientQuaternion before, after;
    OrientSample s = good_sample();
    uint8_t blob[64];
    size_t written = 12345, size = 0, i;
    uint32_t flags = 0;
    int n = 0, untouched = 1;
    char kept[256];
    CHECK_STATUS(orient_config_default(kind, &c), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_new(&c, &f), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_new(&c, &fresh), ORIENT_STATUS_OK);
    if (!f || !fresh) return;
    s.gyro.x = s.gyro.y = s.gyro.z = 0.0; /* still: past any start-up period */
    while (!(flags & ORIENT_FLAG_INITIALIZED) && n++ < 2000) {
        CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_flags(f, &flags), ORIENT_STATUS_OK);
    }
    CHECK(flags & ORIENT_FLAG_INITIALIZED);
    /* "Changes parameter slot id of a running filter; the estimate is kept." */
    CHECK_STATUS(orient_filter_quaternion(f, &before), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_param(f, ORIENT_PARAM_GRAVITY, 9.7), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(f, &after), ORIENT_STATUS_OK);
    CHECK(same_quaternion(before, after));
    CHECK_STATUS(orient_filter_set_param(f, 9999, 1.0), ORIENT_STATUS_UNKNOWN_PARAM);
    CHECK_STATUS(orient_filter_quaternion(f, &after), ORIENT_STATUS_OK);
    CHECK(same_quaternion(before, after));
    /* The detail stays until the next failing call: a successful call leaves it. */
    strncpy(kept, orient_last_error(), sizeof kept - 1);
    kept[sizeof kept - 1] = 0;
    CHECK(kept[0] != 0);
    CHECK_STATUS(orient_filter_quaternion(f, &after), ORIENT_STATUS_OK);
    CHECK(strcmp(kept, orient_last_error()) == 0);
    /* BUFFER_TOO_SMALL: the call changed nothing, the buffer and *written included. */
    CHECK_STATUS(orient_filter_state_size(f, &size), ORIENT_STATUS_OK);
    CHECK(size > sizeof blob);
    memset(blob, 0xA5, sizeof blob);
    CHECK_STATUS(orient_filter_save(f, blob, sizeof blob, &written), ORIENT_STATUS_BUFFER_TOO_SMALL);
    CHECK(written == 12345);
    for (i = 0; i < sizeof blob; i++) untouched = untouched && blob[i] == 0xA5;
    CHECK(untouched);
    /* Order: dt and the gyroscope are checked before NOT_INITIALIZED (the last check). */
    s = good_sample();
    s.flags = ORIENT_SAMPLE_GYRO;
    s.gyro.y = NAN;
    CHECK_STATUS(orient_filter_update(fresh, &s), ORIENT_STATUS_NON_FINITE);
    s.gyro.y = 0.0;
    s.dt = -1.0;
    CHECK_STATUS(orient_filter_update(fresh, &s), ORIENT_STATUS_INVALID_DT);
    s.dt = 0.01;
    CHECK_STATUS(orient_filter_update(fresh, &s), ORIENT_STATUS_NOT_INITIALIZED);
    CHECK_STATUS(orient_filter_free(f), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_free(fresh), ORIENT_STATUS_OK);
}

static void bad_input(int32_t kind) {
    OrientFilter *f = new_filter(kind);
    OrientFilter *twin = new_filter(kind);
    OrientSample s = good_sample(), bad;
    OrientQuaternion a, b;
    size_t processed = 0;
    OrientSample batch[4];
    struct {
        OrientSample s;
        OrientStatus expected;
    } cases[32];
    int n = 0, i;

    CHECK(f && twin);
    if (!f || !twin) return;
    CHECK_STATUS(orient_filter_set_param(f, ORIENT_PARAM_GYRO_RANGE, 34.9), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_param(f, ORIENT_PARAM_ACCEL_RANGE, 156.9), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_param(twin, ORIENT_PARAM_GYRO_RANGE, 34.9), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_param(twin, ORIENT_PARAM_ACCEL_RANGE, 156.9), ORIENT_STATUS_OK);
    CHECK(warm_up(f) > 0);
    CHECK(warm_up(twin) > 0);
    /* No gap policy here: a dt beyond 1e6 s is still refused. */
    CHECK_STATUS(orient_filter_set_param(f, ORIENT_PARAM_GAP_DT, 0.0), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_param(twin, ORIENT_PARAM_GAP_DT, 0.0), ORIENT_STATUS_OK);

#define BAD(field_assign, status)                                                      \
    do {                                                                               \
        bad = good_sample();                                                           \
        field_assign;                                                                  \
        cases[n].s = bad;                                                              \
        cases[n].expected = status;                                                    \
        n++;                                                                           \
    } while (0)
    BAD(bad.dt = 0.0, ORIENT_STATUS_INVALID_DT);
    BAD(bad.dt = -0.01, ORIENT_STATUS_INVALID_DT);
    BAD(bad.dt = NAN, ORIENT_STATUS_INVALID_DT);
    BAD(bad.dt = INFINITY, ORIENT_STATUS_INVALID_DT);
    BAD(bad.gyro.y = NAN, ORIENT_STATUS_NON_FINITE);
    BAD(bad.gyro.z = -INFINITY, ORIENT_STATUS_NON_FINITE);
    BAD(bad.accel.x = NAN, ORIENT_STATUS_NON_FINITE);
    BAD(bad.mag.z = INFINITY, ORIENT_STATUS_NON_FINITE);
    BAD(bad.accel.x = bad.accel.y = bad.accel.z = 0.0, ORIENT_STATUS_ZERO_VECTOR);
    BAD(bad.mag.x = bad.mag.y = bad.mag.z = 0.0, ORIENT_STATUS_ZERO_VECTOR);
    BAD((bad.mag.x = 1e-170, bad.mag.y = 0.0, bad.mag.z = 0.0), ORIENT_STATUS_ZERO_VECTOR);
    BAD((bad.accel.x = 1e300, bad.accel.y = 1e300), ORIENT_STATUS_TOO_LARGE);
    BAD((bad.mag.x = 1e300, bad.mag.y = 1e300), ORIENT_STATUS_TOO_LARGE);
    BAD(bad.gyro.x = 35.0, ORIENT_STATUS_SATURATED);
    BAD(bad.accel.z = -157.0, ORIENT_STATUS_SATURATED);
    BAD(bad.flags = ORIENT_SAMPLE_ACCEL, ORIENT_STATUS_MISSING_SENSOR);
    BAD(bad.flags |= 8u, ORIENT_STATUS_INVALID_ARGUMENT);
    BAD(bad.reserved = 1, ORIENT_STATUS_INVALID_ARGUMENT);
    /* Flags are checked before dt. */
    BAD((bad.flags |= 8u, bad.dt = -1.0), ORIENT_STATUS_INVALID_ARGUMENT);
    BAD(bad.dt = 1e300, ORIENT_STATUS_INVALID_DT);
    BAD(bad.dt = 2e6, ORIENT_STATUS_INVALID_DT);
    BAD(bad.gyro.y = 1e4, ORIENT_STATUS_SATURATED);
    BAD(bad.mag.y = -1e12, ORIENT_STATUS_TOO_LARGE);
#undef BAD

    for (i = 0; i < n; i++) {
        OrientStatus st = orient_filter_update(f, &cases[i].s);
        if (st != cases[i].expected) {
            printf("FAIL bad-input kind %d case %d: status %d, expected %d (%s)\n", (int)kind, i, (int)st,
                   (int)cases[i].expected, orient_last_error());
            failed++;
        } else {
            passed++;
        }
        CHECK_STATUS(orient_filter_quaternion(f, &a), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_quaternion(twin, &b), ORIENT_STATUS_OK);
        CHECK(same_quaternion(a, b));
    }
    /* The same good sample afterwards gives the same bits in both. */
    CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_update(twin, &s), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(f, &a), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(twin, &b), ORIENT_STATUS_OK);
    CHECK(same_quaternion(a, b));

    /* A batch stops at the first bad sample and reports its index. */
    batch[0] = s;
    batch[1] = s;
    batch[2] = s;
    batch[2].accel.x = NAN;
    batch[3] = s;
    CHECK_STATUS(orient_filter_update_batch(f, batch, 4, NULL, &processed), ORIENT_STATUS_NON_FINITE);
    CHECK(processed == 2);
    CHECK(strstr(orient_last_error(), "sample 2") != NULL);
    CHECK_STATUS(orient_filter_update_batch(twin, batch, 2, NULL, NULL), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(f, &a), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(twin, &b), ORIENT_STATUS_OK);
    CHECK(same_quaternion(a, b));
    /* n = 0 is a no-op even with NULL samples; NULL samples with n > 0 and huge n fail. */
    CHECK_STATUS(orient_filter_update_batch(f, NULL, 0, NULL, &processed), ORIENT_STATUS_OK);
    CHECK(processed == 0);
    CHECK_STATUS(orient_filter_update_batch(f, NULL, 3, NULL, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_update_batch(f, batch, SIZE_MAX, NULL, NULL), ORIENT_STATUS_COUNT_TOO_LARGE);
    CHECK_STATUS(orient_filter_update_batch(NULL, batch, 1, NULL, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_quaternion(f, &a), ORIENT_STATUS_OK);
    CHECK(same_quaternion(a, b));
    /* The arrays call: the same stop at a bad sample, its own argument checks. */
    {
        double dt = s.dt, gyro[9], accel[9];
        OrientDiagnostics d[3];
        uint32_t fl[3];
        for (i = 0; i < 3; i++) {
            gyro[3 * i] = s.gyro.x, gyro[3 * i + 1] = s.gyro.y, gyro[3 * i + 2] = s.gyro.z;
            accel[3 * i] = s.accel.x, accel[3 * i + 1] = s.accel.y, accel[3 * i + 2] = s.accel.z;
        }
        accel[5] = NAN;
        CHECK_STATUS(orient_filter_update_arrays(f, 3, &dt, 1, gyro, accel, NULL, NULL, fl, d, &processed),
                     ORIENT_STATUS_NON_FINITE);
        CHECK(processed == 1);
        CHECK(strstr(orient_last_error(), "sample 1") != NULL);
        {
            /* Sample 0's flags and diagnostics are the filter's after it (no mag given). */
            OrientDiagnostics now;
            uint32_t flags_now = 0;
            CHECK_STATUS(orient_filter_flags(f, &flags_now), ORIENT_STATUS_OK);
            CHECK_STATUS(orient_filter_diagnostics(f, &now), ORIENT_STATUS_OK);
            CHECK(fl[0] == flags_now && !(fl[0] & ORIENT_FLAG_MAG_USED));
            CHECK(d[0].present == now.present && bits(d[0].gyro_bias.x) == bits(now.gyro_bias.x));
        }
        CHECK_STATUS(orient_filter_update_arrays(twin, 1, &dt, 1, gyro, accel, NULL, NULL, NULL, NULL, NULL),
                     ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_quaternion(f, &a), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_quaternion(twin, &b), ORIENT_STATUS_OK);
        CHECK(same_quaternion(a, b));
        CHECK_STATUS(orient_filter_update_arrays(f, 3, &dt, 2, gyro, NULL, NULL, NULL, NULL, NULL, NULL),
                     ORIENT_STATUS_INVALID_ARGUMENT);
        CHECK_STATUS(orient_filter_update_arrays(f, 3, &dt, 1, NULL, NULL, NULL, NULL, NULL, NULL, NULL),
                     ORIENT_STATUS_NULL_POINTER);
        CHECK_STATUS(orient_filter_update_arrays(f, 3, NULL, 1, gyro, NULL, NULL, NULL, NULL, NULL, NULL),
                     ORIENT_STATUS_NULL_POINTER);
        CHECK_STATUS(orient_filter_update_arrays(f, SIZE_MAX, &dt, 1, gyro, NULL, NULL, NULL, NULL, NULL, NULL),
                     ORIENT_STATUS_COUNT_TOO_LARGE);
        CHECK_STATUS(orient_filter_update_arrays(NULL, 1, &dt, 1, gyro, NULL, NULL, NULL, NULL, NULL, NULL),
                     ORIENT_STATUS_NULL_POINTER);
        CHECK_STATUS(orient_filter_update_arrays(f, 0, NULL, 0, NULL, NULL, NULL, NULL, NULL, NULL, &processed),
                     ORIENT_STATUS_OK);
        CHECK(processed == 0);
        /* dt_count is 1 or n, n = 0 included. */
        CHECK_STATUS(orient_filter_update_arrays(f, 0, &dt, 7, gyro, NULL, NULL, NULL, NULL, NULL, NULL),
                     ORIENT_STATUS_INVALID_ARGUMENT);
        /* A NULL required pointer before the handle and the counts. */
        CHECK_STATUS(orient_filter_update_arrays((OrientFilter *)&dt, 3, &dt, 1, NULL, NULL, NULL, NULL, NULL, NULL,
                                                 NULL),
                     ORIENT_STATUS_NULL_POINTER);
        CHECK_STATUS(orient_filter_update_arrays(f, SIZE_MAX, NULL, 1, gyro, NULL, NULL, NULL, NULL, NULL, NULL),
                     ORIENT_STATUS_NULL_POINTER);
        CHECK_STATUS(orient_filter_quaternion(f, &a), ORIENT_STATUS_OK);
        CHECK(same_quaternion(a, b));
    }

    /* A gap: after a dt above ORIENT_PARAM_GAP_DT the orientation is re-acquired from
       the sensors, and flagged. */
    {
        uint32_t flags = 0;
        OrientSample g = good_sample();
        CHECK_STATUS(orient_filter_set_param(f, ORIENT_PARAM_GAP_DT, 1.0), ORIENT_STATUS_OK);
        g.dt = 3.0;
        CHECK_STATUS(orient_filter_update(f, &g), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_flags(f, &flags), ORIENT_STATUS_OK);
        CHECK((flags & ORIENT_FLAG_GAP) != 0);
        CHECK((flags & ORIENT_FLAG_REACQUIRED) != 0);
        CHECK_STATUS(orient_filter_quaternion(f, &a), ORIENT_STATUS_OK);
        CHECK(fabs(a.w * a.w + a.x * a.x + a.y * a.y + a.z * a.z - 1.0) < 1e-12);
        g.dt = 0.01;
        CHECK_STATUS(orient_filter_update(f, &g), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_flags(f, &flags), ORIENT_STATUS_OK);
        CHECK((flags & ORIENT_FLAG_GAP) == 0);
    }

    orient_filter_free(f);
    orient_filter_free(twin);
}

/* Every kind: same lifecycle, and the diagnostics it documents (absent fields NaN). */
static void diagnostics(int32_t kind) {
    OrientFilter *f = new_filter(kind);
    OrientDiagnostics d;
    uint32_t expected;
    int n;
    CHECK(f != NULL);
    if (!f) return;
    n = warm_up(f);
    CHECK(n > 0 && n <= 300); /* start-up periods are at most 2 s; samples are 10 ms */
    {
        OrientSample s = good_sample();
        CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_OK);
    }
    {
        /* The sample had both readings: each is used or rejected, never both or neither. */
        uint32_t fl = 0;
        CHECK_STATUS(orient_filter_flags(f, &fl), ORIENT_STATUS_OK);
        CHECK(!(fl & ORIENT_FLAG_ACCEL_USED) != !(fl & ORIENT_FLAG_ACCEL_REJECTED));
        CHECK(!(fl & ORIENT_FLAG_MAG_USED) != !(fl & ORIENT_FLAG_MAG_REJECTED));
        /* McGinnis' filter has no heading correction after its start-up. */
        if (kind == ORIENT_KIND_COMPLEMENTARY) CHECK(fl & ORIENT_FLAG_MAG_REJECTED);
        /* Only the robust kind tells a disturbed field. */
        if (kind != ORIENT_KIND_ROBUST) CHECK(!(fl & ORIENT_FLAG_MAG_DISTURBED));
    }
    CHECK_STATUS(orient_filter_diagnostics(f, &d), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_diagnostics(f, NULL), ORIENT_STATUS_NULL_POINTER);
    switch (kind) {
    case ORIENT_KIND_MAHONY: expected = ORIENT_DIAG_GYRO_BIAS; break;
    case ORIENT_KIND_COMPLEMENTARY:
    case ORIENT_KIND_ROBUST: expected = ORIENT_DIAG_GYRO_BIAS | ORIENT_DIAG_REST; break;
    case ORIENT_KIND_EKF: expected = ORIENT_DIAG_GYRO_BIAS | ORIENT_DIAG_RATE | ORIENT_DIAG_COVARIANCE; break;
    case ORIENT_KIND_GMVDK:
        expected = ORIENT_DIAG_GYRO_BIAS | ORIENT_DIAG_ALPHA | ORIENT_DIAG_MU_KA | ORIENT_DIAG_MU_KM | ORIENT_DIAG_MU_K;
        break;
    default: expected = 0; break;
    }
    CHECK(d.present == expected);
    CHECK((d.present & ORIENT_DIAG_GYRO_BIAS) ? isfinite(d.gyro_bias.x) : isnan(d.gyro_bias.x));
    CHECK((d.present & ORIENT_DIAG_REST) ? (d.rest == 0.0 || d.rest == 1.0) : isnan(d.rest));
    CHECK((d.present & ORIENT_DIAG_ALPHA) ? (d.alpha >= 0.0 && d.alpha <= 1.0) : isnan(d.alpha));
    CHECK((d.present & ORIENT_DIAG_MU_K) ? (d.mu_k >= 0.0 && d.mu_k <= 1.0) : isnan(d.mu_k));
    CHECK((d.present & ORIENT_DIAG_RATE) ? isfinite(d.rate.z) : isnan(d.rate.z));
    CHECK((d.present & ORIENT_DIAG_COVARIANCE) ? d.covariance[9] > 0.0 : isnan(d.covariance[9]));
    CHECK_STATUS(orient_filter_reset(f), ORIENT_STATUS_OK);
    CHECK(warm_up(f) == n);
    CHECK_STATUS(orient_filter_free(f), ORIENT_STATUS_OK);
}

/* orient_filter_uncertainty (issue 20): which kinds fill which field, NaN elsewhere and
 * before initialisation; the robust kind's heading settles to its
 * ORIENT_PARAM_ROBUST_MAG_HEADING_SIGMA while the magnetometer is used and grows at every
 * sample without it; offsets the host sets change nothing. */
static void uncertainty(int32_t kind) {
    OrientFilter *f = new_filter(kind);
    OrientUncertainty u, v;
    OrientSample s = good_sample();
    uint32_t expected;
    double sigma_m = 0.0, sigma_b = 0.0, tau = 0.0, settle = 0.0;
    int i, grows = 1;
    CHECK(f != NULL);
    if (!f) return;
    CHECK_STATUS(orient_filter_uncertainty(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_uncertainty(f, &u), ORIENT_STATUS_OK);
    CHECK(u.present == 0 && isnan(u.heading) && isnan(u.inclination));
    CHECK(warm_up(f) > 0);
    s.gyro.x = s.gyro.y = s.gyro.z = 0.0;
    for (i = 0; i < 100; i++) CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_uncertainty(f, &u), ORIENT_STATUS_OK);
    switch (kind) {
    case ORIENT_KIND_ROBUST: expected = ORIENT_UNCERTAINTY_HEADING; break;
    case ORIENT_KIND_EKF: expected = ORIENT_UNCERTAINTY_HEADING | ORIENT_UNCERTAINTY_INCLINATION; break;
    default: expected = 0; break;
    }
    CHECK(u.present == expected && u.reserved == 0);
    CHECK((u.present & ORIENT_UNCERTAINTY_HEADING) ? (u.heading > 0.0 && u.heading < 2.0) : isnan(u.heading));
    CHECK((u.present & ORIENT_UNCERTAINTY_INCLINATION) ? (u.inclination > 0.0 && u.inclination < 2.0)
                                                       : isnan(u.inclination));
    CHECK_STATUS(orient_filter_set_heading(f, 1.0), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_declination(f, 0.2), ORIENT_STATUS_OK);
    {
        OrientQuaternion m = {0.8, 0.2, 0.5, -0.1};
        CHECK_STATUS(orient_filter_set_mounting(f, &m), ORIENT_STATUS_OK);
    }
    CHECK_STATUS(orient_filter_uncertainty(f, &v), ORIENT_STATUS_OK);
    CHECK(v.present == u.present && (v.present == 0 || (v.heading == u.heading)));
    if (kind == ORIENT_KIND_ROBUST) {
        CHECK_STATUS(orient_filter_get_param(f, ORIENT_PARAM_ROBUST_MAG_HEADING_SIGMA, &sigma_m), ORIENT_STATUS_OK);
        /* The header's settle value at rest in a clean field: sqrt(sigma_m^2 + (sigma_b tau)^2),
         * sigma_b the bias uncertainty after a rest. */
        CHECK_STATUS(orient_filter_get_param(f, ORIENT_PARAM_ROBUST_BIAS_SIGMA_REST, &sigma_b), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_get_param(f, ORIENT_PARAM_ROBUST_TAU_MAG, &tau), ORIENT_STATUS_OK);
        settle = sqrt(sigma_m * sigma_m + sigma_b * tau * sigma_b * tau);
        CHECK(fabs(u.heading - settle) < 0.02 * settle);
        s.flags &= ~(uint32_t)ORIENT_SAMPLE_MAG;
        for (i = 0; i < 200; i++) {
            CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_OK);
            CHECK_STATUS(orient_filter_uncertainty(f, &v), ORIENT_STATUS_OK);
            grows = grows && v.heading > u.heading;
            u = v;
        }
        CHECK(grows);
        s.flags |= ORIENT_SAMPLE_MAG;
        for (i = 0; i < 10000; i++) CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_uncertainty(f, &u), ORIENT_STATUS_OK);
        CHECK(fabs(u.heading - sigma_m) < 0.01 * sigma_m);
    }
    CHECK_STATUS(orient_filter_free(f), ORIENT_STATUS_OK);
}

/* A hand of 20 Madgwick filters: pairs run side by side in lanes; the bits must still
 * equal separate updates, and a bad sample inside a pair must stop the frame at its
 * index with the filters before it updated. */
static void madgwick_rig(void) {
    enum { N = 20 };
    OrientFilter *rig[N], *twins[N];
    OrientSample frame[N];
    OrientQuaternion out[N], q, unwritten;
    size_t processed = 0;
    int i, k, mismatches = 0;
    unwritten.w = unwritten.x = unwritten.y = unwritten.z = 7.0;
    for (k = 0; k < N; k++) {
        rig[k] = new_madgwick();
        twins[k] = new_madgwick();
    }
    for (i = 0; i < 400; i++) {
        for (k = 0; k < N; k++) {
            frame[k] = good_sample();
            frame[k].gyro.x = 0.5 * sin(0.01 * i + k);
            frame[k].gyro.y = 0.3 * cos(0.013 * i + 2 * k);
            frame[k].accel.x = 0.4 * cos(0.02 * i + k);
            frame[k].mag.y = 20.0 + k;
            if (i % 50 == 7) frame[k].flags &= ~(uint32_t)ORIENT_SAMPLE_MAG; /* IMU frames too */
        }
        CHECK_STATUS(orient_filters_update(rig, frame, N, out, &processed), ORIENT_STATUS_OK);
        for (k = 0; k < N; k++) {
            CHECK_STATUS(orient_filter_update(twins[k], &frame[k]), ORIENT_STATUS_OK);
            CHECK_STATUS(orient_filter_quaternion(twins[k], &q), ORIENT_STATUS_OK);
            if (!same_quaternion(out[k], q)) mismatches++;
        }
    }
    if (mismatches) {
        fprintf(stderr, "FAIL madgwick rig: %d quaternions differ from separate updates\n", mismatches);
        failed++;
    } else {
        passed++;
    }
    /* The bad sample is the first of the pair 6-7: filters 0-5 are updated and their
     * outputs written; from 6 on nothing is written. The flag case below puts it second
     * in that pair (7), so that its pair's first filter is updated. */
    frame[6].accel.y = INFINITY;
    for (k = 0; k < N; k++) out[k] = unwritten;
    CHECK_STATUS(orient_filters_update(rig, frame, N, out, &processed), ORIENT_STATUS_NON_FINITE);
    CHECK(processed == 6);
    /* The twins by separate calls, so that the rig call is compared with them. */
    for (k = 0; k < 6; k++) CHECK_STATUS(orient_filter_update(twins[k], &frame[k]), ORIENT_STATUS_OK);
    for (k = 0; k < N; k++) {
        OrientQuaternion a;
        CHECK_STATUS(orient_filter_quaternion(rig[k], &a), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_quaternion(twins[k], &q), ORIENT_STATUS_OK);
        CHECK(same_quaternion(a, q));
        CHECK(same_quaternion(out[k], k < 6 ? q : unwritten));
    }
    /* The same when the flag check refuses the sample (before any reading is looked at). */
    frame[6] = good_sample();
    frame[7].reserved = 1;
    for (k = 0; k < N; k++) out[k] = unwritten;
    CHECK_STATUS(orient_filters_update(rig, frame, N, out, &processed), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK(processed == 7);
    for (k = 0; k < 7; k++) CHECK_STATUS(orient_filter_update(twins[k], &frame[k]), ORIENT_STATUS_OK);
    for (k = 0; k < N; k++) {
        CHECK_STATUS(orient_filter_quaternion(twins[k], &q), ORIENT_STATUS_OK);
        CHECK(same_quaternion(out[k], k < 7 ? q : unwritten));
    }
    for (k = 0; k < N; k++) {
        CHECK_STATUS(orient_filter_free(rig[k]), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_free(twins[k]), ORIENT_STATUS_OK);
    }
}

/* One call for a rig: every kind in one frame, bit-identical to separate updates. */
static void multi_sensor(void) {
    OrientFilter *rig[6], *twins[6];
    OrientFilter *kept;
    OrientSample frame[6];
    OrientQuaternion out[6], q;
    size_t processed = 99;
    int i, k;
    for (k = 0; k < 6; k++) {
        rig[k] = new_filter(ORIENT_KIND_MADGWICK + k);
        twins[k] = new_filter(ORIENT_KIND_MADGWICK + k);
        frame[k] = good_sample();
        frame[k].gyro.z = 0.1 * k;
    }
    for (i = 0; i < 300; i++) {
        CHECK_STATUS(orient_filters_update(rig, frame, 6, out, &processed), ORIENT_STATUS_OK);
        CHECK(processed == 6);
        for (k = 0; k < 6; k++) {
            CHECK_STATUS(orient_filter_update(twins[k], &frame[k]), ORIENT_STATUS_OK);
            CHECK_STATUS(orient_filter_quaternion(twins[k], &q), ORIENT_STATUS_OK);
            if (!same_quaternion(out[k], q)) {
                fprintf(stderr, "FAIL multi-sensor kind %d sample %d\n", ORIENT_KIND_MADGWICK + k, i);
                failed++;
                break;
            }
        }
    }
    passed++;
    /* A bad sample stops the frame at its index; the filters after it are untouched. */
    frame[3].mag.x = NAN;
    frame[3].flags |= ORIENT_SAMPLE_MAG;
    CHECK_STATUS(orient_filters_update(rig, frame, 6, NULL, &processed), ORIENT_STATUS_NON_FINITE);
    CHECK(processed == 3);
    CHECK(strstr(orient_last_error(), "filter 3") != NULL);
    CHECK_STATUS(orient_filters_update(twins, frame, 3, NULL, NULL), ORIENT_STATUS_OK);
    for (k = 0; k < 6; k++) {
        OrientQuaternion a;
        CHECK_STATUS(orient_filter_quaternion(rig[k], &a), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_quaternion(twins[k], &q), ORIENT_STATUS_OK);
        CHECK(same_quaternion(a, q));
    }
    /* A NULL handle anywhere changes nothing, not even the filters before it. */
    frame[3] = good_sample();
    kept = twins[4];
    twins[4] = NULL;
    CHECK_STATUS(orient_filters_update(twins, frame, 6, NULL, &processed), ORIENT_STATUS_NULL_POINTER);
    CHECK(processed == 0);
    CHECK_STATUS(orient_filter_quaternion(twins[0], &q), ORIENT_STATUS_OK);
    {
        OrientQuaternion a;
        CHECK_STATUS(orient_filter_quaternion(rig[0], &a), ORIENT_STATUS_OK);
        CHECK(same_quaternion(a, q));
    }
    CHECK_STATUS(orient_filters_update(NULL, NULL, 0, NULL, &processed), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filters_update(rig, NULL, 2, NULL, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filters_update(rig, frame, SIZE_MAX, NULL, NULL), ORIENT_STATUS_COUNT_TOO_LARGE);
    /* A NULL array before any count. */
    CHECK_STATUS(orient_filters_update(NULL, frame, SIZE_MAX, NULL, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filters_update(rig, NULL, SIZE_MAX, NULL, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_update_batch(NULL, frame, SIZE_MAX, NULL, NULL), ORIENT_STATUS_NULL_POINTER);
    for (k = 0; k < 6; k++) {
        CHECK_STATUS(orient_filter_free(rig[k]), ORIENT_STATUS_OK);
        if (k != 4) CHECK_STATUS(orient_filter_free(twins[k]), ORIENT_STATUS_OK);
    }
    CHECK_STATUS(orient_filter_free(kept), ORIENT_STATUS_OK);
    madgwick_rig();
}

/* The offline mode: a tilted still recording smooths to the tilt at every sample, the
   same bits on every call; a bad sample is named and leaves the output unwritten; the
   argument checks of the arrays call. */
static void offline_smoothing(void) {
    enum { N = 600 };
    static double gyro[3 * N], accel[3 * N], mag[3 * N];
    static OrientQuaternion q[N], again[N];
    OrientConfig c;
    double dt = 0.01, s = sin(0.2), co = cos(0.2);
    size_t processed = 99, i;
    int k;
    for (i = 0; i < N; i++) {
        /* Rolled 0.4 rad about x: gravity and the field seen in the sensor frame. */
        gyro[3 * i] = 0.001, gyro[3 * i + 1] = 0.0, gyro[3 * i + 2] = 0.0;
        accel[3 * i] = 0.0, accel[3 * i + 1] = 9.81 * 2 * s * co, accel[3 * i + 2] = 9.81 * (co * co - s * s);
        mag[3 * i] = 0.0, mag[3 * i + 1] = 20.0 * (co * co - s * s) - 40.0 * 2 * s * co;
        mag[3 * i + 2] = -20.0 * 2 * s * co - 40.0 * (co * co - s * s);
    }
    for (k = ORIENT_KIND_MADGWICK; k <= ORIENT_KIND_ROBUST; k++) {
        CHECK_STATUS(orient_config_default(k, &c), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_smooth_arrays(&c, N, &dt, 1, gyro, accel, mag, q, &processed), ORIENT_STATUS_OK);
        CHECK(processed == N);
        CHECK_STATUS(orient_smooth_arrays(&c, N, &dt, 1, gyro, accel, mag, again, NULL), ORIENT_STATUS_OK);
        for (i = 0; i < N; i++) {
            /* The up axis in the sensor frame is the third row of R(q): compare with the
               accelerometer's direction. */
            double w = q[i].w, x = q[i].x, y = q[i].y, z = q[i].z;
            double ux = 2 * (x * z - w * y), uy = 2 * (y * z + w * x), uz = 1 - 2 * (x * x + y * y);
            double cosang = (uy * 2 * s * co + uz * (co * co - s * s)) / sqrt(ux * ux + uy * uy + uz * uz);
            CHECK(cosang > cos(0.01));
            CHECK(fabs(w * w + x * x + y * y + z * z - 1.0) < 1e-12);
            CHECK(same_quaternion(q[i], again[i]));
        }
    }
    /* The offline defaults: the recommended kind, heading time constant 27 s. */
    {
        double tau = 0.0, tau_causal = 0.0;
        OrientConfig causal;
        CHECK_STATUS(orient_smooth_config_default(NULL), ORIENT_STATUS_NULL_POINTER);
        CHECK_STATUS(orient_smooth_config_default(&c), ORIENT_STATUS_OK);
        CHECK(c.kind == ORIENT_KIND_ROBUST);
        CHECK_STATUS(orient_config_get_param(&c, ORIENT_PARAM_ROBUST_TAU_MAG, &tau), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_config_default(ORIENT_KIND_ROBUST, &causal), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_config_get_param(&causal, ORIENT_PARAM_ROBUST_TAU_MAG, &tau_causal), ORIENT_STATUS_OK);
        CHECK(tau == 27.0 && tau_causal * 3.0 == tau);
    }
    again[0].w = 7.0;
    accel[3 * 5 + 1] = NAN;
    CHECK_STATUS(orient_smooth_arrays(&c, N, &dt, 1, gyro, accel, mag, again, &processed), ORIENT_STATUS_NON_FINITE);
    CHECK(processed == 5);
    CHECK(strstr(orient_last_error(), "sample 5") != NULL);
    CHECK(again[0].w == 7.0);
    accel[3 * 5 + 1] = accel[1];
    CHECK_STATUS(orient_smooth_arrays(NULL, N, &dt, 1, gyro, accel, mag, q, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_smooth_arrays(&c, N, &dt, 1, NULL, accel, mag, q, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_smooth_arrays(&c, N, &dt, 1, gyro, accel, mag, NULL, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_smooth_arrays(&c, N, &dt, 2, gyro, accel, mag, q, NULL), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_smooth_arrays(&c, SIZE_MAX, &dt, 1, gyro, accel, mag, q, NULL),
                 ORIENT_STATUS_COUNT_TOO_LARGE);
    CHECK_STATUS(orient_smooth_arrays(&c, 0, NULL, 0, NULL, NULL, NULL, NULL, &processed), ORIENT_STATUS_OK);
    CHECK(processed == 0);
    /* What the call may allocate: 8 bytes per sample and 32768, up to PTRDIFF_MAX / 32
       samples. */
    {
        size_t bytes = 5, most = (size_t)PTRDIFF_MAX / 32;
        CHECK_STATUS(orient_smooth_memory(0, &bytes), ORIENT_STATUS_OK);
        CHECK(bytes == 32768);
        CHECK_STATUS(orient_smooth_memory(N, &bytes), ORIENT_STATUS_OK);
        CHECK(bytes == 8 * N + 32768);
        CHECK_STATUS(orient_smooth_memory(most, &bytes), ORIENT_STATUS_OK);
        CHECK(bytes == 8 * most + 32768);
        bytes = 5;
        CHECK_STATUS(orient_smooth_memory(most + 1, &bytes), ORIENT_STATUS_COUNT_TOO_LARGE);
        CHECK_STATUS(orient_smooth_memory(SIZE_MAX, &bytes), ORIENT_STATUS_COUNT_TOO_LARGE);
        CHECK(bytes == 5);
        CHECK_STATUS(orient_smooth_memory(N, NULL), ORIENT_STATUS_NULL_POINTER);
        CHECK_STATUS(orient_smooth_arrays(&c, most + 1, &dt, 1, gyro, accel, mag, q, &processed),
                     ORIENT_STATUS_COUNT_TOO_LARGE);
        /* On 64-bit targets the largest count needs 2^61 bytes, which no address space
           holds: OUT_OF_MEMORY before any sample is read (the arrays hold only N), the
           output unwritten. (tests/c/smooth_oom.c runs out of memory for real.) */
        if (sizeof(size_t) == 8) {
            again[0].w = 7.0;
            processed = 99;
            CHECK_STATUS(orient_smooth_arrays(&c, most, &dt, 1, gyro, accel, mag, again, &processed),
                         ORIENT_STATUS_OUT_OF_MEMORY);
            CHECK(processed == 0 && again[0].w == 7.0);
            CHECK(strstr(orient_last_error(), "could not be allocated") != NULL);
        }
    }
}

int main(int argc, char **argv) {
    int k;
    if (argc != 2) {
        fprintf(stderr, "usage: %s GOLDEN_FILE\n", argv[0]);
        return 2;
    }
    layout();
    status_messages();
    config_paths();
    handle_paths();
    null_pointers_come_first();
    header_promises();
    for (k = ORIENT_KIND_MADGWICK; k <= ORIENT_KIND_ROBUST; k++) {
        bad_input(k);
        more_promises(k);
        diagnostics(k);
        uncertainty(k);
    }
    multi_sensor();
    offline_smoothing();
    rig_calls(); /* issue 20 */
    calibration_calls();
    joint_calls(); /* issue 42 */
    golden(argv[1]);
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
