/*
 * Reads a recording (CSV with a header naming t, gyr_x..z, acc_x..z and optionally
 * mag_x..z) and prints the Madgwick orientation once per second and at the end.
 *
 *   cc -std=c99 examples/c/print_orientation.c -Iinclude target/release/liborient.a -lm
 *   (from the repository after `cargo build --release`; README.md, *C*, for the shared library)
 *   ./a.out examples/data/broad_01_excerpt.csv
 */
#include "orient.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_COLUMNS 64

static int column(char names[][32], int n, const char *name) {
    int i;
    for (i = 0; i < n; i++)
        if (strcmp(names[i], name) == 0) return i;
    return -1;
}

int main(int argc, char **argv) {
    char line[4096], names[MAX_COLUMNS][32];
    double v[MAX_COLUMNS], previous_t = 0.0;
    int n = 0, t, gx, ax, mx, rows = 0;
    char *tok;
    OrientConfig config;
    OrientFilter *filter = NULL;
    OrientStatus status;
    OrientQuaternion q;
    OrientEuler e;
    FILE *fp;

    if (argc != 2) {
        fprintf(stderr, "usage: %s RECORDING.csv\n", argv[0]);
        return 2;
    }
    fp = fopen(argv[1], "r");
    if (!fp || !fgets(line, sizeof line, fp)) {
        fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    for (tok = strtok(line, ",\r\n"); tok && n < MAX_COLUMNS; tok = strtok(NULL, ",\r\n")) {
        strncpy(names[n], tok, sizeof names[n] - 1);
        names[n++][sizeof names[0] - 1] = '\0';
    }
    t = column(names, n, "t");
    gx = column(names, n, "gyr_x");
    ax = column(names, n, "acc_x");
    mx = column(names, n, "mag_x");
    if (t < 0 || gx < 0 || ax < 0) {
        fprintf(stderr, "missing columns t, gyr_x.. or acc_x..\n");
        return 2;
    }

    orient_config_default(ORIENT_KIND_MADGWICK, &config); /* ENU, init from first sample */
    status = orient_filter_new(&config, &filter);
    if (status != ORIENT_STATUS_OK) {
        fprintf(stderr, "orient_filter_new: %s\n", orient_last_error());
        return 1;
    }
    while (fgets(line, sizeof line, fp)) {
        OrientSample s;
        int i = 0;
        for (tok = strtok(line, ",\r\n"); tok && i < MAX_COLUMNS; tok = strtok(NULL, ",\r\n")) v[i++] = strtod(tok, NULL);
        if (i < n) continue;
        memset(&s, 0, sizeof s);
        s.dt = rows == 0 ? 0.01 : v[t] - previous_t;
        previous_t = v[t];
        s.gyro.x = v[gx], s.gyro.y = v[gx + 1], s.gyro.z = v[gx + 2];
        s.accel.x = v[ax], s.accel.y = v[ax + 1], s.accel.z = v[ax + 2];
        s.flags = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL;
        if (mx >= 0) {
            s.mag.x = v[mx], s.mag.y = v[mx + 1], s.mag.z = v[mx + 2];
            s.flags |= ORIENT_SAMPLE_MAG;
        }
        status = orient_filter_update(filter, &s);
        if (status != ORIENT_STATUS_OK) fprintf(stderr, "row %d: %s\n", rows, orient_last_error());
        if (rows % 286 == 0) { /* about once per second at BROAD's 285.7 Hz */
            orient_filter_euler(filter, &e);
            printf("t %8.3f s  yaw %7.2f  pitch %6.2f  roll %7.2f deg\n", v[t], e.yaw * 57.29578, e.pitch * 57.29578,
                   e.roll * 57.29578);
        }
        rows++;
    }
    fclose(fp);
    orient_filter_quaternion(filter, &q);
    printf("%d samples; final q = (%.6f, %.6f, %.6f, %.6f)\n", rows, q.w, q.x, q.y, q.z);
    orient_filter_free(filter);
    return 0;
}
