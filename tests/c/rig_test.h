/*
 * Issue 20 from C: mounting, heading, declination and rig calibration.
 * Included by abi_test.c (uses its CHECK macros).
 */

/* The angle of the rotation from a to b (radians), well conditioned near 0. */
static double quat_angle(OrientQuaternion a, OrientQuaternion b) {
    double w = a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
    double x = a.w * b.x - a.x * b.w - a.y * b.z + a.z * b.y;
    double y = a.w * b.y + a.x * b.z - a.y * b.w - a.z * b.x;
    double z = a.w * b.z - a.x * b.y + a.y * b.x - a.z * b.w;
    return 2.0 * atan2(sqrt(x * x + y * y + z * z), fabs(w));
}

static OrientFilter *rig_filter(void) {
    OrientConfig c;
    OrientFilter *f = NULL;
    OrientQuaternion q0 = {0.9, 0.1, -0.3, 0.2};
    CHECK_STATUS(orient_config_default(ORIENT_KIND_MADGWICK, &c), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_new(&c, &f), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_quaternion(f, &q0), ORIENT_STATUS_OK);
    return f;
}

static void rig_calls(void) {
    OrientFilter *f = rig_filter();
    OrientFilter *g = rig_filter();
    OrientFilter *fresh = NULL;
    OrientFilter *both[2];
    OrientFilter *twice[2];
    OrientConfig c;
    OrientQuaternion m = {0.8, 0.2, 0.5, -0.1}, got, sensor, seg, refs[2];
    OrientEuler e, before;
    double v = 1.0;
    uint32_t flags;

    /* Mounting: the segment's orientation is the sensor's times the mounting's inverse. */
    CHECK_STATUS(orient_filter_mounting(f, &got), ORIENT_STATUS_OK);
    CHECK(got.w == 1.0 && got.x == 0.0 && got.y == 0.0 && got.z == 0.0);
    CHECK_STATUS(orient_filter_set_mounting(f, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_set_mounting(NULL, &m), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_filter_sensor_quaternion(f, &sensor), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_mounting(f, &m), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_mounting(f, &got), ORIENT_STATUS_OK);
    CHECK(fabs(got.w * got.w + got.x * got.x + got.y * got.y + got.z * got.z - 1.0) < 1e-12);
    CHECK_STATUS(orient_filter_quaternion(f, &seg), ORIENT_STATUS_OK);
    {
        /* sensor * conj(mounting) */
        OrientQuaternion a = sensor, b = {got.w, -got.x, -got.y, -got.z}, p;
        p.w = a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z;
        p.x = a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y;
        p.y = a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x;
        p.z = a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w;
        CHECK(quat_angle(p, seg) < 1e-12);
    }
    CHECK_STATUS(orient_filter_sensor_quaternion(f, &got), ORIENT_STATUS_OK);
    CHECK(quat_angle(got, sensor) < 1e-12);
    m.w = NAN;
    CHECK_STATUS(orient_filter_set_mounting(f, &m), ORIENT_STATUS_NON_FINITE);
    /* Kept by reset. */
    CHECK_STATUS(orient_filter_reset(f), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_mounting(f, &got), ORIENT_STATUS_OK);
    CHECK(got.w != 1.0);
    m.w = 0.9;
    m.x = 0.1;
    m.y = -0.3;
    m.z = 0.2;
    CHECK_STATUS(orient_filter_set_quaternion(f, &m), ORIENT_STATUS_OK);

    /* Heading. */
    CHECK_STATUS(orient_config_default(ORIENT_KIND_MAHONY, &c), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_new(&c, &fresh), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_heading(fresh, 1.0), ORIENT_STATUS_NOT_INITIALIZED);
    CHECK_STATUS(orient_filter_euler(g, &before), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_heading(g, 2.0), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_euler(g, &e), ORIENT_STATUS_OK);
    CHECK(fabs(e.yaw - 2.0) < 1e-12 && fabs(e.pitch - before.pitch) < 1e-12 && fabs(e.roll - before.roll) < 1e-12);
    CHECK_STATUS(orient_filter_heading_offset(g, &v), ORIENT_STATUS_OK);
    CHECK(fabs(v - (2.0 - before.yaw)) < 1e-12);
    CHECK_STATUS(orient_filter_set_heading(g, INFINITY), ORIENT_STATUS_NON_FINITE);
    CHECK_STATUS(orient_filter_reset_heading(g), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_euler(g, &e), ORIENT_STATUS_OK);
    CHECK(fabs(e.yaw) < 1e-12 && fabs(e.pitch - before.pitch) < 1e-12);

    /* Declination: the ENU yaw shrinks by an east declination. */
    CHECK_STATUS(orient_filter_declination(g, &v), ORIENT_STATUS_OK);
    CHECK(v == 0.0);
    CHECK_STATUS(orient_filter_set_declination(g, 0.25), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_euler(g, &e), ORIENT_STATUS_OK);
    CHECK(fabs(e.yaw + 0.25) < 1e-12);
    CHECK_STATUS(orient_filter_set_declination(g, 4.0), ORIENT_STATUS_TOO_LARGE);
    CHECK_STATUS(orient_filter_set_declination(g, NAN), ORIENT_STATUS_NON_FINITE);
    CHECK_STATUS(orient_filter_declination(g, &v), ORIENT_STATUS_OK);
    CHECK(v == 0.25);
    CHECK_STATUS(orient_filter_declination(g, NULL), ORIENT_STATUS_NULL_POINTER);

    /* Rig calibration: each filter reads its reference afterwards. */
    refs[0].w = 1.0; refs[0].x = 0.0; refs[0].y = 0.0; refs[0].z = 0.0;
    refs[1].w = cos(0.4); refs[1].x = sin(0.4); refs[1].y = 0.0; refs[1].z = 0.0;
    both[0] = f;
    both[1] = g;
    twice[0] = f;
    twice[1] = f;
    CHECK_STATUS(orient_rig_calibrate(both, refs, 0, NAN), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_rig_calibrate(twice, refs, 2, NAN), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_rig_calibrate(both, NULL, 2, NAN), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_rig_calibrate(both, refs, 2, INFINITY), ORIENT_STATUS_NON_FINITE);
    both[1] = fresh;
    CHECK_STATUS(orient_rig_calibrate(both, refs, 2, NAN), ORIENT_STATUS_NOT_INITIALIZED);
    CHECK(strncmp(orient_last_error(), "filter 1: ", 10) == 0);
    both[1] = g;
    CHECK_STATUS(orient_rig_calibrate(both, refs, 2, 0.5), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(f, &got), ORIENT_STATUS_OK);
    CHECK(quat_angle(got, refs[0]) < 1e-9);
    CHECK_STATUS(orient_filter_quaternion(g, &got), ORIENT_STATUS_OK);
    CHECK(quat_angle(got, refs[1]) < 1e-9);
    CHECK_STATUS(orient_filter_heading_offset(g, &v), ORIENT_STATUS_OK);
    CHECK(fabs(v + 0.5) < 1e-12);
    CHECK_STATUS(orient_rig_calibrate(both, refs, 2, NAN), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(g, &got), ORIENT_STATUS_OK);
    CHECK(quat_angle(got, refs[1]) < 1e-9);

    /* Rig calibration of 6D filters, each on its own: each reads its reference, and the
     * checks of orient_rig_calibrate. Two calls from different offsets end alike. */
    CHECK_STATUS(orient_rig_calibrate_each(both, refs, 0), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_rig_calibrate_each(twice, refs, 2), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_rig_calibrate_each(both, NULL, 2), ORIENT_STATUS_NULL_POINTER);
    both[1] = fresh;
    CHECK_STATUS(orient_rig_calibrate_each(both, refs, 2), ORIENT_STATUS_NOT_INITIALIZED);
    CHECK(strncmp(orient_last_error(), "filter 1: ", 10) == 0);
    both[1] = g;
    {
        double first = 0.0, second = 0.0;
        CHECK_STATUS(orient_rig_calibrate_each(both, refs, 2), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_quaternion(f, &got), ORIENT_STATUS_OK);
        CHECK(quat_angle(got, refs[0]) < 1e-9);
        CHECK_STATUS(orient_filter_quaternion(g, &got), ORIENT_STATUS_OK);
        CHECK(quat_angle(got, refs[1]) < 1e-9);
        CHECK_STATUS(orient_filter_heading_offset(g, &first), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_set_heading(g, 1.5), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_rig_calibrate_each(both, refs, 2), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_heading_offset(g, &second), ORIENT_STATUS_OK);
        CHECK(fabs(first - second) < 1e-12);
    }

    /* Heading alignment: turn one filter away, align it back. */
    CHECK_STATUS(orient_filter_set_heading(g, 1.5), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_rig_align_heading(both, refs, 2), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(g, &got), ORIENT_STATUS_OK);
    CHECK(quat_angle(got, refs[1]) < 1e-9);

    /* A snapshot carries mounting, heading offset and declination. */
    {
        uint8_t blob[4096];
        size_t size = 0, written = 0;
        OrientFilter *h = rig_filter();
        CHECK_STATUS(orient_filter_state_size(g, &size), ORIENT_STATUS_OK);
        CHECK(size <= sizeof blob);
        CHECK_STATUS(orient_filter_save(g, blob, sizeof blob, &written), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_load(h, blob, written), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_quaternion(h, &sensor), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_quaternion(g, &got), ORIENT_STATUS_OK);
        CHECK(bits(sensor.w) == bits(got.w) && bits(sensor.z) == bits(got.z));
        CHECK_STATUS(orient_filter_declination(h, &v), ORIENT_STATUS_OK);
        CHECK(v == 0.25);
        CHECK_STATUS(orient_filter_free(h), ORIENT_STATUS_OK);
    }
    CHECK_STATUS(orient_filter_flags(g, &flags), ORIENT_STATUS_OK);
    CHECK((flags & ORIENT_FLAG_INITIALIZED) != 0);
    CHECK_STATUS(orient_filter_free(f), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_free(g), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_free(fresh), ORIENT_STATUS_OK);
}

/* Issue 20: sensor models, the magnetometer calibrator, the gyroscope offset. */
static void calibration_calls(void) {
    OrientFilter *f = rig_filter(), *g = rig_filter();
    OrientSensorModel gm, accel_model, got, mag_model;
    OrientMagCalibrator cal;
    OrientMagFit fit;
    OrientSample s, pre;
    OrientQuaternion a, b;
    OrientVec3 still[4] = {{0.011, -0.02, 0.03}, {0.009, -0.02, 0.03}, {0.01, -0.021, 0.03}, {0.01, -0.019, 0.03}};
    double spread = -1.0;
    int i;

    memset(&gm, 0, sizeof gm);
    CHECK_STATUS(orient_gyro_offset(still, 4, &gm, &spread), ORIENT_STATUS_OK);
    CHECK(fabs(gm.offset.x - 0.01) < 1e-12 && fabs(gm.offset.y + 0.02) < 1e-12 && fabs(gm.offset.z - 0.03) < 1e-12);
    CHECK(gm.matrix[0] == 1.0 && gm.matrix[4] == 1.0 && gm.matrix[8] == 1.0 && gm.matrix[1] == 0.0);
    CHECK(spread > 0.0 && spread < 0.001);
    CHECK_STATUS(orient_gyro_offset(still, 0, &gm, NULL), ORIENT_STATUS_INVALID_ARGUMENT);

    /* A model gives the same bits as feeding the calibrated readings. */
    memset(&accel_model, 0, sizeof accel_model);
    accel_model.matrix[0] = 1.01; accel_model.matrix[1] = 0.02; accel_model.matrix[4] = 0.99; accel_model.matrix[8] = 1.0;
    accel_model.offset.z = 0.1;
    CHECK_STATUS(orient_filter_sensor_model(f, ORIENT_SENSOR_GYRO, &got), ORIENT_STATUS_NO_DATA);
    CHECK_STATUS(orient_filter_set_sensor_model(f, ORIENT_SENSOR_GYRO, &gm), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_sensor_model(f, ORIENT_SENSOR_ACCEL, &accel_model), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_set_sensor_model(f, 7, &gm), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_filter_sensor_model(f, ORIENT_SENSOR_ACCEL, &got), ORIENT_STATUS_OK);
    CHECK(memcmp(&got, &accel_model, sizeof got) == 0);
    got.matrix[4] = 0.0;
    got.matrix[3] = 0.0;
    got.matrix[5] = 0.0;
    CHECK_STATUS(orient_filter_set_sensor_model(f, ORIENT_SENSOR_MAG, &got), ORIENT_STATUS_ZERO_VECTOR);
    for (i = 0; i < 100; i++) {
        s.dt = 0.01;
        s.gyro.x = 0.2 + 0.01; s.gyro.y = -0.1 - 0.02; s.gyro.z = 0.05 + 0.03;
        s.accel.x = 0.3; s.accel.y = 0.2; s.accel.z = 9.7;
        s.mag.x = 20.0; s.mag.y = 5.0; s.mag.z = -40.0;
        s.flags = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL;
        s.reserved = 0;
        pre = s;
        pre.gyro.x = s.gyro.x - gm.offset.x;
        pre.gyro.y = s.gyro.y - gm.offset.y;
        pre.gyro.z = s.gyro.z - gm.offset.z;
        pre.accel.x = 1.01 * s.accel.x + 0.02 * s.accel.y;
        pre.accel.y = 0.99 * s.accel.y;
        pre.accel.z = s.accel.z - 0.1;
        CHECK_STATUS(orient_filter_update(f, &s), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_update(g, &pre), ORIENT_STATUS_OK);
    }
    CHECK_STATUS(orient_filter_quaternion(f, &a), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(g, &b), ORIENT_STATUS_OK);
    CHECK(bits(a.w) == bits(b.w) && bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) && bits(a.z) == bits(b.z));
    CHECK_STATUS(orient_filter_set_sensor_model(f, ORIENT_SENSOR_GYRO, NULL), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_sensor_model(f, ORIENT_SENSOR_GYRO, &got), ORIENT_STATUS_NO_DATA);

    /* The calibrator: a field of 50 over a sphere of directions, scaled per axis and offset. */
    CHECK_STATUS(orient_mag_calibrator_init(&cal), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_mag_calibrator_solve(&cal, &fit), ORIENT_STATUS_NO_DATA);
    /* In a scrambled order, as a tumbling sensor gives them. */
    for (i = 0; i < 288; i++) {
        {
            int idx = (i * 97) % 288;
            double th = 3.14159265 * (idx / 24 + 0.5) / 12.0, ph = 6.2831853 * (idx % 24) / 24.0;
            OrientVec3 m;
            m.x = 1.2 * 50.0 * sin(th) * cos(ph) + 10.0;
            m.y = 0.9 * 50.0 * sin(th) * sin(ph) - 20.0;
            m.z = 1.0 * 50.0 * cos(th) + 5.0;
            CHECK_STATUS(orient_mag_calibrator_add(&cal, &m), ORIENT_STATUS_OK);
        }
    }
    CHECK_STATUS(orient_mag_calibrator_add(&cal, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_mag_calibrator_solve(&cal, &fit), ORIENT_STATUS_OK);
    CHECK(fabs(fit.model.offset.x - 10.0) < 1e-6 && fabs(fit.model.offset.y + 20.0) < 1e-6 &&
          fabs(fit.model.offset.z - 5.0) < 1e-6);
    CHECK(fit.samples == 288 && fit.trustworthy == 1 && fit.residual < 1e-6 && fit.coverage > 0.9);
    /* The calibrated field's norm: the semi-axes' geometric mean. */
    CHECK(fabs(fit.field - 50.0 * cbrt(1.2 * 0.9)) < 1e-6);
    mag_model = fit.model;
    CHECK_STATUS(orient_filter_set_sensor_model(f, ORIENT_SENSOR_MAG, &mag_model), ORIENT_STATUS_OK);
    cal.scale = -1.0;
    CHECK_STATUS(orient_mag_calibrator_solve(&cal, &fit), ORIENT_STATUS_INVALID_ARGUMENT);
    /* Saturation: rejected by default, clipped and flagged with the recovery policy. */
    {
        uint32_t fl = 0;
        s.dt = 0.01;
        s.gyro.x = 6.0; s.gyro.y = 0.0; s.gyro.z = 0.0;
        s.accel.x = 0.0; s.accel.y = 0.0; s.accel.z = 9.8;
        s.flags = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL;
        CHECK_STATUS(orient_filter_set_param(g, ORIENT_PARAM_GYRO_RANGE, 5.0), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_update(g, &s), ORIENT_STATUS_SATURATED);
        CHECK_STATUS(orient_filter_set_param(g, ORIENT_PARAM_SATURATION_RECOVERY, 1.0), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_update(g, &s), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_flags(g, &fl), ORIENT_STATUS_OK);
        CHECK((fl & ORIENT_FLAG_SATURATED) != 0 && (fl & ORIENT_FLAG_REACQUIRE_PENDING) != 0);
        s.gyro.x = 0.1;
        CHECK_STATUS(orient_filter_update(g, &s), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_flags(g, &fl), ORIENT_STATUS_OK);
        CHECK((fl & ORIENT_FLAG_REACQUIRED) != 0 && (fl & ORIENT_FLAG_SATURATED) == 0);
        /* Bursts: dt = 0 refused by default, the same instant with the policy. */
        s.dt = 0.0;
        CHECK_STATUS(orient_filter_update(g, &s), ORIENT_STATUS_INVALID_DT);
        CHECK_STATUS(orient_filter_set_param(g, ORIENT_PARAM_SAME_INSTANT, 1.0), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_update(g, &s), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_flags(g, &fl), ORIENT_STATUS_OK);
        CHECK((fl & ORIENT_FLAG_SAME_INSTANT) != 0);
        s.dt = 0.01;
        CHECK_STATUS(orient_filter_update(g, &s), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_flags(g, &fl), ORIENT_STATUS_OK);
        CHECK((fl & ORIENT_FLAG_SAME_INSTANT) == 0);
    }
    CHECK_STATUS(orient_filter_free(f), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_free(g), ORIENT_STATUS_OK);
}
