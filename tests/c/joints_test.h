/*
 * Issue 42 from C: a rig's joints (orient_joints_*) and the hinge axes' estimate, each
 * sentence of their header comments. Included by abi_test.c (uses its CHECK macros and
 * rig_test.h's quat_angle).
 */

typedef struct {
    double w, x, y, z;
} Q;

#define DEGREE 0.017453292519943295

static Q q_of(OrientQuaternion a) {
    Q r;
    r.w = a.w, r.x = a.x, r.y = a.y, r.z = a.z;
    return r;
}

static OrientQuaternion oq_of(Q a) {
    OrientQuaternion r;
    r.w = a.w, r.x = a.x, r.y = a.y, r.z = a.z;
    return r;
}

static Q q_mul(Q a, Q b) {
    Q r;
    r.w = a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z;
    r.x = a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y;
    r.y = a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x;
    r.z = a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w;
    return r;
}

static Q q_conj(Q a) {
    Q r;
    r.w = a.w;
    r.x = -a.x;
    r.y = -a.y;
    r.z = -a.z;
    return r;
}

static Q q_axis(double x, double y, double z, double angle) {
    double n = sqrt(x * x + y * y + z * z), s = sin(0.5 * angle);
    Q r;
    r.w = cos(0.5 * angle);
    r.x = x / n * s;
    r.y = y / n * s;
    r.z = z / n * s;
    return r;
}

/* The parent's motion: turns about every axis, its x axis mostly horizontal. */
static Q parent_at(double t) {
    return q_mul(q_mul(q_axis(0, 0, 1, 0.5 * sin(0.3 * t)), q_axis(0, 1, 0, 0.6 * sin(0.7 * t))),
                 q_axis(1, 0, 0, 0.4 * sin(1.1 * t)));
}

static double flexion_at(double t) { return 0.5 + 0.8 * sin(1.9 * t); }

/* The child hangs from the parent by a hinge about both sensors' x axis. */
static Q child_at(double t) { return q_mul(parent_at(t), q_axis(1, 0, 0, flexion_at(t))); }

/* A sensor at the joint centre turning from a to b in dt: body rates and gravity. */
static OrientSample moving(Q a, Q b, double dt) {
    OrientSample s;
    Q d = q_mul(q_conj(a), b), g, up = {0.0, 0.0, 0.0, 9.81};
    double n = sqrt(d.x * d.x + d.y * d.y + d.z * d.z), k;
    if (d.w < 0) {
        d.w = -d.w, d.x = -d.x, d.y = -d.y, d.z = -d.z;
    }
    k = n > 1e-15 ? 2.0 * atan2(n, d.w) / n / dt : 0.0;
    memset(&s, 0, sizeof s);
    s.dt = dt;
    s.gyro.x = d.x * k;
    s.gyro.y = d.y * k;
    s.gyro.z = d.z * k;
    g = q_mul(q_mul(q_conj(b), up), b);
    s.accel.x = g.x;
    s.accel.y = g.y;
    s.accel.z = g.z;
    s.flags = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL;
    return s;
}

static OrientJoint hinge_joint(uint32_t parent, uint32_t child) {
    OrientJoint j;
    memset(&j, 0, sizeof j);
    j.kind = ORIENT_JOINT_HINGE;
    j.parent = parent;
    j.child = child;
    j.axis_parent.x = 1.0;
    j.axis_child.x = 1.0;
    return j;
}

static OrientJoints *sentinel_joints(void) { return (OrientJoints *)(uintptr_t)0x1000; }

static void joints_new_refusals(void) {
    OrientJoint j[ORIENT_MAX_JOINTS + 1];
    OrientJoints *out = sentinel_joints();
    OrientQuaternion m[2] = {{1, 0, 0, 0}, {1, 0, 0, 0}};
    int i;
    for (i = 0; i <= ORIENT_MAX_JOINTS; i++) j[i] = hinge_joint(0, 1);
    CHECK_STATUS(orient_joints_new(j, 1, 2, NULL, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_joints_new(NULL, 1, 2, NULL, &out), ORIENT_STATUS_NULL_POINTER);
    CHECK(out == NULL); /* "on failure it is set to NULL" */
    /* INVALID_JOINT: a missing segment, its own parent, a second parent, a cycle, an axis. */
    j[0] = hinge_joint(0, 2);
    out = sentinel_joints();
    CHECK_STATUS(orient_joints_new(j, 1, 2, NULL, &out), ORIENT_STATUS_INVALID_JOINT);
    CHECK(out == NULL && strstr(orient_last_error(), "joint 0") != NULL);
    j[0] = hinge_joint(1, 1);
    CHECK_STATUS(orient_joints_new(j, 1, 2, NULL, &out), ORIENT_STATUS_INVALID_JOINT);
    j[0] = hinge_joint(0, 1);
    j[1] = hinge_joint(2, 1);
    CHECK_STATUS(orient_joints_new(j, 2, 3, NULL, &out), ORIENT_STATUS_INVALID_JOINT);
    CHECK(strstr(orient_last_error(), "joint 1") != NULL);
    j[1] = hinge_joint(1, 0);
    CHECK_STATUS(orient_joints_new(j, 2, 2, NULL, &out), ORIENT_STATUS_INVALID_JOINT);
    CHECK(strstr(orient_last_error(), "cycle") != NULL);
    j[1] = hinge_joint(0, 1);
    j[0].axis_child.x = 0.0;
    CHECK_STATUS(orient_joints_new(j, 1, 2, NULL, &out), ORIENT_STATUS_INVALID_JOINT);
    j[0].axis_child.x = NAN;
    CHECK_STATUS(orient_joints_new(j, 1, 2, NULL, &out), ORIENT_STATUS_INVALID_JOINT);
    j[0].axis_child.x = INFINITY;
    CHECK_STATUS(orient_joints_new(j, 1, 2, NULL, &out), ORIENT_STATUS_INVALID_JOINT);
    j[0] = hinge_joint(0, 1);
    /* INVALID_ARGUMENT: an unknown kind, a reserved field, no segment. */
    j[0].kind = 7;
    CHECK_STATUS(orient_joints_new(j, 1, 2, NULL, &out), ORIENT_STATUS_INVALID_ARGUMENT);
    j[0] = hinge_joint(0, 1);
    j[0].axes_frame = 2;
    CHECK_STATUS(orient_joints_new(j, 1, 2, NULL, &out), ORIENT_STATUS_INVALID_ARGUMENT);
    j[0] = hinge_joint(0, 1);
    CHECK_STATUS(orient_joints_new(j, 0, 0, NULL, &out), ORIENT_STATUS_INVALID_ARGUMENT);
    /* COUNT_TOO_LARGE: joints and segments beyond the maxima. */
    CHECK_STATUS(orient_joints_new(j, ORIENT_MAX_JOINTS + 1, 2, NULL, &out), ORIENT_STATUS_COUNT_TOO_LARGE);
    CHECK_STATUS(orient_joints_new(j, 1, ORIENT_MAX_SEGMENTS + 1, NULL, &out), ORIENT_STATUS_COUNT_TOO_LARGE);
    /* A mounting as orient_filter_set_quaternion checks it. */
    m[1].x = NAN;
    CHECK_STATUS(orient_joints_new(j, 1, 2, m, &out), ORIENT_STATUS_NON_FINITE);
    m[1].w = 0.0, m[1].x = 0.0;
    CHECK_STATUS(orient_joints_new(j, 1, 2, m, &out), ORIENT_STATUS_ZERO_VECTOR);
    m[1].w = 1e200, m[1].x = 1e200;
    CHECK_STATUS(orient_joints_new(j, 1, 2, m, &out), ORIENT_STATUS_TOO_LARGE);
    CHECK(out == NULL);
    /* Axes in the segments' frames go through the mountings: the child's sensor sits
       turned a quarter turn about z on its segment, so the segment's x axis is the
       sensor's -y. */
    {
        OrientQuaternion mounts[2] = {{1, 0, 0, 0}, {0.7071067811865476, 0, 0, 0.7071067811865476}};
        OrientVec3 pa, ca;
        j[0] = hinge_joint(0, 1);
        j[0].axes_frame = ORIENT_JOINT_AXES_SEGMENT;
        CHECK_STATUS(orient_joints_new(j, 1, 2, mounts, &out), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_axes(out, 0, &pa, &ca), ORIENT_STATUS_OK);
        CHECK(fabs(pa.x - 1.0) < 1e-12 && fabs(ca.y + 1.0) < 1e-12 && fabs(ca.x) < 1e-12);
        CHECK_STATUS(orient_joints_free(out), ORIENT_STATUS_OK);
        j[0].axes_frame = ORIENT_JOINT_AXES_SENSOR;
        CHECK_STATUS(orient_joints_new(j, 1, 2, mounts, &out), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_axes(out, 0, &pa, &ca), ORIENT_STATUS_OK);
        CHECK(fabs(ca.x - 1.0) < 1e-12);
        CHECK_STATUS(orient_joints_free(out), ORIENT_STATUS_OK);
        j[0].axes_frame = ORIENT_JOINT_AXES_SEGMENT;
        j[0].child = 9; /* a missing segment is still named, not read */
        CHECK_STATUS(orient_joints_new(j, 1, 2, mounts, &out), ORIENT_STATUS_INVALID_JOINT);
        j[0] = hinge_joint(0, 1);
    }
    /* A forest is a rig: two roots, a segment in no joint, no joint at all. */
    j[1] = hinge_joint(2, 3);
    CHECK_STATUS(orient_joints_new(j, 2, 5, NULL, &out), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_free(out), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_new(NULL, 0, 1, NULL, &out), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_free(out), ORIENT_STATUS_OK);
}

/* A 2-DoF joint's axes (the parent's z, then the child's y) from ten seconds of the two
 * sensors' orientations, the child's 40 degrees off in heading, started 5 degrees off. */
static void two_dof_axes(void) {
    const int n = 1000;
    OrientQuaternion *qp = (OrientQuaternion *)malloc(sizeof *qp * (size_t)n);
    OrientQuaternion *qc = (OrientQuaternion *)malloc(sizeof *qc * (size_t)n);
    OrientVec3 a, b;
    OrientJointAxes h;
    double t;
    int i;
    if (qp == NULL || qc == NULL) {
        CHECK(0);
        free(qp);
        free(qc);
        return;
    }
    for (i = 0; i < n; i++) {
        t = i * 0.01;
        qp[i] = oq_of(parent_at(t));
        qc[i] = oq_of(q_mul(q_axis(0, 0, 1, 40 * DEGREE),
                            q_mul(parent_at(t), q_mul(q_axis(0, 0, 1, 0.25 * sin(2.1 * t)),
                                                      q_axis(0, 1, 0, flexion_at(t))))));
    }
    a.x = 0.0, a.y = 0.087, a.z = 1.0;
    b.x = 0.087, b.y = 1.0, b.z = 0.0;
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, (size_t)n, a, b, &h), ORIENT_STATUS_OK);
    CHECK(h.axis_parent.z > cos(0.1 * DEGREE) && h.axis_child.y > cos(0.1 * DEGREE));
    CHECK(h.quality >= 0.0 && h.quality < 0.05);
    /* Every refusal the header lists. */
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, 0, a, b, &h), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_estimate_two_dof_axes(NULL, qc, (size_t)n, a, b, &h), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, NULL, (size_t)n, a, b, &h), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, (size_t)n, a, b, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, SIZE_MAX, a, b, &h), ORIENT_STATUS_COUNT_TOO_LARGE);
    qc[7].y = NAN;
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, (size_t)n, a, b, &h), ORIENT_STATUS_NON_FINITE);
    qc[7].w = 0.0, qc[7].x = 0.0, qc[7].y = 0.0, qc[7].z = 0.0;
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, (size_t)n, a, b, &h), ORIENT_STATUS_ZERO_VECTOR);
    qc[7].w = 1e200;
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, (size_t)n, a, b, &h), ORIENT_STATUS_TOO_LARGE);
    qc[7].w = 1.0;
    b.x = 0.0, b.y = 0.0, b.z = 0.0;
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, (size_t)n, a, b, &h), ORIENT_STATUS_ZERO_VECTOR);
    b.x = INFINITY;
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, (size_t)n, a, b, &h), ORIENT_STATUS_NON_FINITE);
    b.x = 1e200;
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, (size_t)n, a, b, &h), ORIENT_STATUS_TOO_LARGE);
    /* A refused call leaves *out as it was. */
    h.quality = -1.0;
    CHECK_STATUS(orient_estimate_two_dof_axes(qp, qc, (size_t)n, a, b, &h), ORIENT_STATUS_TOO_LARGE);
    CHECK(h.quality == -1.0);
    free(qp);
    free(qc);
}

/* orient_config_for_joints: the robust kind's three settings, other kinds and refused
 * configs left byte for byte. */
static void config_for_joints(void) {
    OrientConfig c, before;
    double walk, limit, rest;
    CHECK_STATUS(orient_config_default(ORIENT_KIND_ROBUST, &c), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_config_for_joints(&c), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_config_get_param(&c, ORIENT_PARAM_ROBUST_BIAS_WALK, &walk), ORIENT_STATUS_OK);
    CHECK(fabs(walk - 0.05 * DEGREE) < 1e-15);
    CHECK_STATUS(orient_config_get_param(&c, ORIENT_PARAM_ROBUST_BIAS_LIMIT, &limit), ORIENT_STATUS_OK);
    CHECK(fabs(limit - 4.0 * DEGREE) < 1e-15);
    CHECK_STATUS(orient_config_get_param(&c, ORIENT_PARAM_ROBUST_REST_GYRO, &rest), ORIENT_STATUS_OK);
    CHECK(fabs(rest - 4.0 * DEGREE) < 1e-15);
    /* Nothing else: the default with those three set is the same struct. */
    CHECK_STATUS(orient_config_default(ORIENT_KIND_ROBUST, &before), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_config_set_param(&before, ORIENT_PARAM_ROBUST_BIAS_WALK, walk), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_config_set_param(&before, ORIENT_PARAM_ROBUST_BIAS_LIMIT, limit), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_config_set_param(&before, ORIENT_PARAM_ROBUST_REST_GYRO, rest), ORIENT_STATUS_OK);
    CHECK(memcmp(&c, &before, sizeof c) == 0);
    CHECK_STATUS(orient_config_default(ORIENT_KIND_MADGWICK, &c), ORIENT_STATUS_OK);
    before = c;
    CHECK_STATUS(orient_config_for_joints(&c), ORIENT_STATUS_OK);
    CHECK(memcmp(&c, &before, sizeof c) == 0);
    /* The statuses of orient_config_set_param for a NULL or invalid config. */
    CHECK_STATUS(orient_config_for_joints(NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_config_default(ORIENT_KIND_ROBUST, &c), ORIENT_STATUS_OK);
    c.struct_size -= 8;
    before = c;
    CHECK_STATUS(orient_config_for_joints(&c), ORIENT_STATUS_VERSION_MISMATCH);
    CHECK_STATUS(orient_config_set_param(&c, ORIENT_PARAM_ROBUST_BIAS_WALK, 0.0), ORIENT_STATUS_VERSION_MISMATCH);
    CHECK(memcmp(&c, &before, sizeof c) == 0);
    c.struct_size += 8;
    c.kind = 99;
    before = c;
    CHECK_STATUS(orient_config_for_joints(&c), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_config_set_param(&c, ORIENT_PARAM_ROBUST_BIAS_WALK, 0.0), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK(memcmp(&c, &before, sizeof c) == 0);
    CHECK_STATUS(orient_config_default(ORIENT_KIND_ROBUST, &c), ORIENT_STATUS_OK);
    c.frame = 7;
    before = c;
    CHECK_STATUS(orient_config_for_joints(&c), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK(memcmp(&c, &before, sizeof c) == 0);
    CHECK_STATUS(orient_config_default(ORIENT_KIND_ROBUST, &c), ORIENT_STATUS_OK);
    c.init = 7;
    before = c;
    CHECK_STATUS(orient_config_for_joints(&c), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK(memcmp(&c, &before, sizeof c) == 0);
    CHECK_STATUS(orient_config_default(ORIENT_KIND_ROBUST, &c), ORIENT_STATUS_OK);
    c.params[ORIENT_PARAM_ROBUST_BIAS_SIGMA] = -1.0;
    before = c;
    CHECK_STATUS(orient_config_for_joints(&c), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
    CHECK(memcmp(&c, &before, sizeof c) == 0);
}

/* The joints' tuning: listed with its ranges, read and set by name; refusals change
   nothing; an initial standard deviation set before the first update applies at once; a
   blob saved with another tuning does not load. */
static void joint_params(void) {
    OrientJoint j = hinge_joint(0, 1);
    OrientJoints *joints = NULL, *twin = NULL;
    OrientParamInfo info;
    uint32_t count = 0, i;
    double v = 0.0, heading = 0.0, sigma = 0.0;
    size_t size = 0, written = 0;
    unsigned char *blob;
    CHECK_STATUS(orient_joint_param_count(&count), ORIENT_STATUS_OK);
    CHECK(count == 22);
    CHECK_STATUS(orient_joint_param_count(NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_joints_new(&j, 1, 2, NULL, &joints), ORIENT_STATUS_OK);
    for (i = 0; i < count; i++) {
        CHECK_STATUS(orient_joint_param_info(i, &info), ORIENT_STATUS_OK);
        CHECK(info.id == i && info.flags == 0 && info.name != NULL && info.unit != NULL);
        CHECK(info.description != NULL && strlen(info.description) > 10);
        CHECK(info.min <= info.default_value && info.default_value <= info.max);
        CHECK_STATUS(orient_joints_get_param(joints, info.name, &v), ORIENT_STATUS_OK);
        CHECK(bits(v) == bits(info.default_value));
        /* Out of range (NaN included): refused, nothing changed. */
        CHECK_STATUS(orient_joints_set_param(joints, info.name, info.max * 2.0), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
        CHECK_STATUS(orient_joints_set_param(joints, info.name, NAN), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
        CHECK_STATUS(orient_joints_set_param(joints, info.name, 4.9e-324), ORIENT_STATUS_PARAM_OUT_OF_RANGE);
        CHECK_STATUS(orient_joints_get_param(joints, info.name, &v), ORIENT_STATUS_OK);
        CHECK(bits(v) == bits(info.default_value));
        /* Its range's ends are taken. */
        CHECK_STATUS(orient_joints_set_param(joints, info.name, info.max), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_get_param(joints, info.name, &v), ORIENT_STATUS_OK);
        CHECK(v == info.max);
        CHECK_STATUS(orient_joints_set_param(joints, info.name, info.default_value), ORIENT_STATUS_OK);
    }
    CHECK_STATUS(orient_joint_param_info(count, &info), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_joint_param_info(0, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_joints_get_param(joints, "beta", &v), ORIENT_STATUS_UNKNOWN_PARAM);
    CHECK_STATUS(orient_joints_set_param(joints, "beta", 1.0), ORIENT_STATUS_UNKNOWN_PARAM);
    CHECK_STATUS(orient_joints_get_param(joints, NULL, &v), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_joints_get_param(joints, "gate", NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_joints_set_param(joints, NULL, 1.0), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_joints_get_param(sentinel_joints(), "gate", &v), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_joints_set_param(sentinel_joints(), "gate", 1.0), ORIENT_STATUS_INVALID_HANDLE);

    /* Before the first update, an initial standard deviation applies at once. */
    CHECK_STATUS(orient_joints_set_param(joints, "heading_std0", 0.5), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading, &sigma), ORIENT_STATUS_OK);
    CHECK(heading == 0.0 && fabs(sigma - 0.5) < 1e-15);

    /* Another tuning's blob is refused; the same tuning's loads. */
    CHECK_STATUS(orient_joints_new(&j, 1, 2, NULL, &twin), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_state_size(joints, &size), ORIENT_STATUS_OK);
    blob = (unsigned char *)malloc(size);
    if (blob != NULL) {
        CHECK_STATUS(orient_joints_save(joints, blob, size, &written), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_load(twin, blob, written), ORIENT_STATUS_INVALID_STATE);
        CHECK_STATUS(orient_joints_set_param(twin, "heading_std0", 0.5), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_load(twin, blob, written), ORIENT_STATUS_OK);
        free(blob);
    } else {
        CHECK(0);
    }
    orient_joints_free(twin);
    orient_joints_free(joints);
}

/* Whether the filters learn their bias in motion: the joints apply bias_learn_rate only to
 * those that do. Two joint handles on the same filters, one with bias_learn_rate 0:
 * bit for bit the same where the filters learn none in motion, apart where they do.
 * Returns 1 when the two handles' relative headings are the same bits. */
static int same_as_without_learning(int32_t kind, uint32_t param, double value) {
    OrientJoint j = hinge_joint(0, 1);
    OrientJoints *with = NULL, *without = NULL;
    OrientFilter *filters[2];
    OrientSample s[2];
    double a = 0.0, b = 1.0, dt = 0.01;
    int i, k;
    for (k = 0; k < 2; k++) {
        filters[k] = new_filter(kind);
        if (param != UINT32_MAX) CHECK_STATUS(orient_filter_set_param(filters[k], param, value), ORIENT_STATUS_OK);
    }
    CHECK_STATUS(orient_joints_new(&j, 1, 2, NULL, &with), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_new(&j, 1, 2, NULL, &without), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_set_param(without, "bias_learn_rate", 0.0), ORIENT_STATUS_OK);
    /* 3 s still (the complementary filter and GMVDK start from a still period), then the
     * hinge turning. */
    for (i = 1; i <= 800; i++) {
        double t0 = i <= 300 ? 0.0 : (i - 301) * dt, t1 = i < 300 ? 0.0 : (i - 300) * dt;
        s[0] = moving(parent_at(t0), parent_at(t1), dt);
        s[1] = moving(child_at(t0), child_at(t1), dt);
        CHECK_STATUS(orient_filters_update(filters, s, 2, NULL, NULL), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_update(with, filters, s, 2), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_update(without, filters, s, 2), ORIENT_STATUS_OK);
    }
    CHECK_STATUS(orient_joints_relative_heading(with, 0, &a, NULL), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_relative_heading(without, 0, &b, NULL), ORIENT_STATUS_OK);
    orient_joints_free(with);
    orient_joints_free(without);
    orient_filter_free(filters[0]);
    orient_filter_free(filters[1]);
    return bits(a) == bits(b);
}

static void learning_by_kind(void) {
    CHECK(same_as_without_learning(ORIENT_KIND_MADGWICK, UINT32_MAX, 0.0));
    CHECK(same_as_without_learning(ORIENT_KIND_COMPLEMENTARY, UINT32_MAX, 0.0));
    CHECK(same_as_without_learning(ORIENT_KIND_GMVDK, UINT32_MAX, 0.0));
    CHECK(same_as_without_learning(ORIENT_KIND_MAHONY, UINT32_MAX, 0.0));
    CHECK(!same_as_without_learning(ORIENT_KIND_MAHONY, ORIENT_PARAM_MAHONY_KI, 0.3));
    CHECK(!same_as_without_learning(ORIENT_KIND_EKF, UINT32_MAX, 0.0));
    CHECK(!same_as_without_learning(ORIENT_KIND_ROBUST, UINT32_MAX, 0.0));
    CHECK(same_as_without_learning(ORIENT_KIND_ROBUST, ORIENT_PARAM_ROBUST_BIAS_SIGMA_MOTION, 0.0));
    CHECK(same_as_without_learning(ORIENT_KIND_ROBUST, ORIENT_PARAM_ROBUST_BIAS_WALK, 0.0));
}

/* The segments' outputs apply the mountings given to orient_joints_new, never the
 * filters' own (orient_joints_segment_quaternion's doc): the root segment of joints made
 * without mountings is its filter's sensor orientation, of joints made with the
 * filter's mounting its filter's orientation. */
static void joints_read_their_own_mountings(void) {
    OrientJoint j = hinge_joint(0, 1);
    OrientJoints *plain = NULL, *mounted = NULL;
    OrientFilter *filters[2];
    OrientSample s[2];
    OrientQuaternion m = oq_of(q_axis(0, 0, 1, 90 * DEGREE)), mountings[2], seg, sensor, own;
    filters[0] = new_filter(ORIENT_KIND_ROBUST);
    filters[1] = new_filter(ORIENT_KIND_ROBUST);
    CHECK_STATUS(orient_filter_set_mounting(filters[0], &m), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_mounting(filters[0], &mountings[0]), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_mounting(filters[1], &mountings[1]), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_new(&j, 1, 2, NULL, &plain), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_new(&j, 1, 2, mountings, &mounted), ORIENT_STATUS_OK);
    s[0] = moving(parent_at(0.0), parent_at(0.01), 0.01);
    s[1] = moving(child_at(0.0), child_at(0.01), 0.01);
    CHECK_STATUS(orient_filters_update(filters, s, 2, NULL, NULL), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_update(plain, filters, s, 2), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_update(mounted, filters, s, 2), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_sensor_quaternion(filters[0], &sensor), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_quaternion(filters[0], &own), ORIENT_STATUS_OK);
    CHECK(quat_angle(sensor, own) > 89.0 * DEGREE);
    CHECK_STATUS(orient_joints_segment_quaternion(plain, 0, &seg), ORIENT_STATUS_OK);
    CHECK(quat_angle(seg, sensor) < 1e-9);
    CHECK_STATUS(orient_joints_segment_quaternion(mounted, 0, &seg), ORIENT_STATUS_OK);
    CHECK(quat_angle(seg, own) < 1e-9);
    CHECK_STATUS(orient_joints_free(plain), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_free(mounted), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_free(filters[0]), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_free(filters[1]), ORIENT_STATUS_OK);
}

static void joint_calls(void) {
    OrientJoint j = hinge_joint(0, 1);
    OrientJoints *joints = NULL, *gone = NULL;
    OrientFilter *filters[2], *other;
    OrientSample s[2], bad[2];
    OrientQuaternion q, before;
    OrientVec3 a, b, *gp, *gc;
    OrientJointAxes h;
    double angles[2], r, heading, sigma, heading_before, dt = 0.01;
    int i, n;
    const int rows = 1500;

    joints_new_refusals();
    joint_params();
    joints_read_their_own_mountings();
    CHECK(strcmp(orient_status_message(ORIENT_STATUS_INVALID_JOINT), "unknown status code") != 0);

    filters[0] = new_filter(ORIENT_KIND_ROBUST);
    filters[1] = new_filter(ORIENT_KIND_ROBUST);
    CHECK_STATUS(orient_joints_new(&j, 1, 2, NULL, &joints), ORIENT_STATUS_OK);
    /* Before the first update: the identity (no mounting), angles 0. */
    CHECK_STATUS(orient_joints_segment_quaternion(joints, 1, &q), ORIENT_STATUS_OK);
    CHECK(q.w == 1.0 && q.x == 0.0 && q.y == 0.0 && q.z == 0.0);
    CHECK_STATUS(orient_joints_angles(joints, 0, angles), ORIENT_STATUS_OK);
    CHECK(angles[0] == 0.0 && angles[1] == 0.0);

    /* Ten seconds of the hinge turning: each filter takes its sample, then the joints. */
    for (i = 1; i <= rows; i++) {
        double t0 = (i - 1) * dt, t1 = i * dt;
        s[0] = moving(parent_at(t0), parent_at(t1), dt);
        s[1] = moving(child_at(t0), child_at(t1), dt);
        CHECK_STATUS(orient_filters_update(filters, s, 2, NULL, NULL), ORIENT_STATUS_OK);
        if (orient_joints_update(joints, filters, s, 2) != ORIENT_STATUS_OK) {
            CHECK(0);
            break;
        }
    }
    /* The hinge's angle is the flexion; a hinge's second angle is NaN. */
    CHECK_STATUS(orient_joints_angles(joints, 0, angles), ORIENT_STATUS_OK);
    CHECK(fabs(angles[0] - flexion_at(rows * dt)) < 2.0 * DEGREE);
    CHECK(isnan(angles[1]));
    /* The child relative to its parent is the truth's. */
    {
        OrientQuaternion p, c;
        Q rel, truth = q_axis(1, 0, 0, flexion_at(rows * dt));
        CHECK_STATUS(orient_joints_segment_quaternion(joints, 0, &p), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_segment_quaternion(joints, 1, &c), ORIENT_STATUS_OK);
        rel = q_mul(q_conj(q_of(p)), q_of(c));
        CHECK(quat_angle(oq_of(rel), oq_of(truth)) < 2.0 * DEGREE);
    }
    CHECK_STATUS(orient_joints_rating(joints, 0, &r), ORIENT_STATUS_OK);
    CHECK(r >= 0.0 && r <= 1.0 && r > 0.1);
    CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading, &sigma), ORIENT_STATUS_OK);
    CHECK(isfinite(heading) && sigma >= 0.0 && sigma < 0.1);
    CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading, NULL), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_axes(joints, 0, &a, &b), ORIENT_STATUS_OK);
    CHECK(fabs(a.x * a.x + a.y * a.y + a.z * a.z - 1.0) < 1e-12 && a.x > 0.99 && b.x > 0.99);

    /* Indices beyond the rig, NULL outputs. */
    CHECK_STATUS(orient_joints_segment_quaternion(joints, 2, &q), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_joints_angles(joints, 1, angles), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_joints_rating(joints, 1, &r), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_joints_relative_heading(joints, 1, &heading, &sigma), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_joints_axes(joints, 1, &a, &b), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_joints_rating(joints, 0, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_joints_axes(joints, 0, &a, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_joints_relative_heading(joints, 0, NULL, &sigma), ORIENT_STATUS_NULL_POINTER);

    /* A refused row changes nothing. */
    CHECK_STATUS(orient_joints_segment_quaternion(joints, 1, &before), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading_before, NULL), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_update(joints, filters, s, 1), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_joints_update(joints, NULL, s, 2), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_joints_update(joints, filters, NULL, 2), ORIENT_STATUS_NULL_POINTER);
    bad[0] = s[0], bad[1] = s[1];
    bad[1].gyro.y = NAN;
    CHECK_STATUS(orient_joints_update(joints, filters, bad, 2), ORIENT_STATUS_NON_FINITE);
    CHECK(strstr(orient_last_error(), "segment 1") != NULL);
    bad[1] = s[1];
    bad[1].dt = INFINITY;
    CHECK_STATUS(orient_joints_update(joints, filters, bad, 2), ORIENT_STATUS_NON_FINITE);
    bad[1] = s[1];
    bad[1].flags |= 64;
    CHECK_STATUS(orient_joints_update(joints, filters, bad, 2), ORIENT_STATUS_INVALID_ARGUMENT);
    bad[1] = s[1];
    bad[1].reserved = 3;
    CHECK_STATUS(orient_joints_update(joints, filters, bad, 2), ORIENT_STATUS_INVALID_ARGUMENT);
    other = filters[1];
    filters[1] = NULL;
    CHECK_STATUS(orient_joints_update(joints, filters, s, 2), ORIENT_STATUS_NULL_POINTER);
    filters[1] = new_filter(ORIENT_KIND_MADGWICK);
    CHECK_STATUS(orient_filter_free(filters[1]), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_update(joints, filters, s, 2), ORIENT_STATUS_INVALID_HANDLE);
    filters[1] = other;
    CHECK_STATUS(orient_joints_segment_quaternion(joints, 1, &q), ORIENT_STATUS_OK);
    CHECK(same_quaternion(q, before));
    /* A child's dt outside [1e-9, 1) s holds the joint (the row is taken, nothing moves). */
    {
        double s0 = 0.0, s1 = 0.0;
        CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading, &s0), ORIENT_STATUS_OK);
        bad[0] = s[0], bad[1] = s[1];
        bad[1].dt = 5e-10;
        CHECK_STATUS(orient_joints_update(joints, filters, bad, 2), ORIENT_STATUS_OK);
        bad[1].dt = 1.0;
        CHECK_STATUS(orient_joints_update(joints, filters, bad, 2), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading_before, &s1), ORIENT_STATUS_OK);
        CHECK(bits(heading) == bits(heading_before) && bits(s0) == bits(s1));
    }
    CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading, NULL), ORIENT_STATUS_OK);
    CHECK(bits(heading) == bits(heading_before));
    /* A row without accelerometer readings is accepted and holds the joint. */
    bad[0] = s[0], bad[1] = s[1];
    bad[0].flags = ORIENT_SAMPLE_GYRO;
    CHECK_STATUS(orient_joints_update(joints, filters, bad, 2), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading, NULL), ORIENT_STATUS_OK);
    CHECK(bits(heading) == bits(heading_before));

    /* Snapshots: the joints and the filters saved together continue bit for bit. */
    {
        size_t size = 0, written = 0, fsize = 0;
        unsigned char *blob, *fblob[2];
        OrientJoints *twin = NULL;
        OrientFilter *twins[2];
        OrientQuaternion a1, a2;
        int k, ok = 1;
        CHECK_STATUS(orient_joints_state_size(joints, &size), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_filter_state_size(filters[0], &fsize), ORIENT_STATUS_OK);
        blob = (unsigned char *)malloc(size);
        fblob[0] = (unsigned char *)malloc(fsize);
        fblob[1] = (unsigned char *)malloc(fsize);
        if (blob != NULL && fblob[0] != NULL && fblob[1] != NULL) {
            CHECK_STATUS(orient_joints_save(joints, blob, size - 1, &written), ORIENT_STATUS_BUFFER_TOO_SMALL);
            CHECK_STATUS(orient_joints_save(joints, blob, size, &written), ORIENT_STATUS_OK);
            CHECK(written == size);
            CHECK_STATUS(orient_joints_save(joints, NULL, size, &written), ORIENT_STATUS_NULL_POINTER);
            CHECK_STATUS(orient_joints_new(&j, 1, 2, NULL, &twin), ORIENT_STATUS_OK);
            for (k = 0; k < 2; k++) {
                twins[k] = new_filter(ORIENT_KIND_ROBUST);
                CHECK_STATUS(orient_filter_save(filters[k], fblob[k], fsize, &written), ORIENT_STATUS_OK);
                CHECK_STATUS(orient_filter_load(twins[k], fblob[k], written), ORIENT_STATUS_OK);
            }
            /* Refused blobs change nothing: truncated, flipped, a filter's. */
            CHECK_STATUS(orient_joints_load(twin, blob, size - 1), ORIENT_STATUS_INVALID_STATE);
            blob[size / 2] ^= 4;
            CHECK_STATUS(orient_joints_load(twin, blob, size), ORIENT_STATUS_INVALID_STATE);
            blob[size / 2] ^= 4;
            CHECK_STATUS(orient_joints_load(twin, fblob[0], fsize), ORIENT_STATUS_INVALID_STATE);
            CHECK_STATUS(orient_joints_relative_heading(twin, 0, &heading, NULL), ORIENT_STATUS_OK);
            CHECK(heading == 0.0);
            CHECK_STATUS(orient_joints_load(twin, blob, size), ORIENT_STATUS_OK);
            for (i = 1; i <= 200; i++) {
                double t0 = 20.0 + (i - 1) * dt, t1 = 20.0 + i * dt;
                s[0] = moving(parent_at(t0), parent_at(t1), dt);
                s[1] = moving(child_at(t0), child_at(t1), dt);
                CHECK_STATUS(orient_filters_update(filters, s, 2, NULL, NULL), ORIENT_STATUS_OK);
                CHECK_STATUS(orient_filters_update(twins, s, 2, NULL, NULL), ORIENT_STATUS_OK);
                CHECK_STATUS(orient_joints_update(joints, filters, s, 2), ORIENT_STATUS_OK);
                CHECK_STATUS(orient_joints_update(twin, twins, s, 2), ORIENT_STATUS_OK);
                orient_joints_segment_quaternion(joints, 1, &a1);
                orient_joints_segment_quaternion(twin, 1, &a2);
                ok = ok && same_quaternion(a1, a2);
            }
            CHECK(ok);
            CHECK_STATUS(orient_joints_load(NULL, blob, size), ORIENT_STATUS_NULL_POINTER);
            CHECK_STATUS(orient_joints_load(twin, NULL, size), ORIENT_STATUS_NULL_POINTER);
            orient_joints_free(twin);
            orient_filter_free(twins[0]);
            orient_filter_free(twins[1]);
        } else {
            CHECK(0);
        }
        free(blob);
        free(fblob[0]);
        free(fblob[1]);
    }

    /* After updates an initial standard deviation waits for the reset. */
    {
        double before_sigma = 0.0;
        CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading, &before_sigma), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_set_param(joints, "heading_std0", 0.25), ORIENT_STATUS_OK);
        CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading, &sigma), ORIENT_STATUS_OK);
        CHECK(bits(sigma) == bits(before_sigma));
    }

    /* Reset: no correction, the initial standard deviation set. */
    CHECK_STATUS(orient_joints_reset(joints), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_relative_heading(joints, 0, &heading, &sigma), ORIENT_STATUS_OK);
    CHECK(heading == 0.0 && sigma == 0.25);

    /* Handles: a filter is no joints handle, a joints handle no filter, a freed one nothing,
       nor a pointer two bytes on from a live one (a joints handle's registry key). */
    CHECK_STATUS(orient_joints_reset((OrientJoints *)((char *)joints + 2)), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_joints_free((OrientJoints *)((char *)joints + 2)), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_reset((OrientFilter *)((char *)joints + 2)), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_free((OrientFilter *)((char *)joints + 2)), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_reset((OrientFilter *)((char *)filters[0] + 2)), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_joints_reset((OrientJoints *)filters[0]), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_filter_reset((OrientFilter *)joints), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_joints_free((OrientJoints *)filters[0]), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_joints_new(&j, 1, 2, NULL, &gone), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_free(gone), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_free(gone), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_joints_update(gone, filters, s, 2), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_joints_angles(gone, 0, angles), ORIENT_STATUS_INVALID_HANDLE);
    CHECK_STATUS(orient_joints_free(NULL), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_joints_free(joints), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_free(filters[0]), ORIENT_STATUS_OK);
    CHECK_STATUS(orient_filter_free(filters[1]), ORIENT_STATUS_OK);

    /* The hinge's axes from five seconds of motion, started 5 degrees off. */
    n = 500;
    gp = (OrientVec3 *)malloc(sizeof *gp * (size_t)n);
    gc = (OrientVec3 *)malloc(sizeof *gc * (size_t)n);
    if (gp == NULL || gc == NULL) {
        CHECK(0);
        free(gp);
        free(gc);
        return;
    }
    for (i = 0; i < n; i++) {
        s[0] = moving(parent_at(i * dt), parent_at((i + 1) * dt), dt);
        s[1] = moving(child_at(i * dt), child_at((i + 1) * dt), dt);
        gp[i] = s[0].gyro;
        gc[i] = s[1].gyro;
    }
    a.x = 1.0, a.y = 0.087, a.z = 0.0;
    b.x = 1.0, b.y = 0.0, b.z = -0.087;
    CHECK_STATUS(orient_estimate_hinge_axes(gp, gc, (size_t)n, a, b, &h), ORIENT_STATUS_OK);
    CHECK(h.axis_parent.x > cos(0.2 * DEGREE) && h.axis_child.x > cos(0.2 * DEGREE));
    CHECK(h.quality >= 0.0 && h.quality < 0.01);
    CHECK_STATUS(orient_estimate_hinge_axes(gp, gc, 0, a, b, &h), ORIENT_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(orient_estimate_hinge_axes(NULL, gc, (size_t)n, a, b, &h), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_estimate_hinge_axes(gp, gc, (size_t)n, a, b, NULL), ORIENT_STATUS_NULL_POINTER);
    CHECK_STATUS(orient_estimate_hinge_axes(gp, gc, SIZE_MAX, a, b, &h), ORIENT_STATUS_COUNT_TOO_LARGE);
    gc[7].z = NAN;
    CHECK_STATUS(orient_estimate_hinge_axes(gp, gc, (size_t)n, a, b, &h), ORIENT_STATUS_NON_FINITE);
    gc[7].z = 0.0;
    b.x = 0.0, b.y = 0.0, b.z = 0.0;
    CHECK_STATUS(orient_estimate_hinge_axes(gp, gc, (size_t)n, a, b, &h), ORIENT_STATUS_ZERO_VECTOR);
    b.x = NAN;
    CHECK_STATUS(orient_estimate_hinge_axes(gp, gc, (size_t)n, a, b, &h), ORIENT_STATUS_NON_FINITE);
    b.x = 1e200;
    CHECK_STATUS(orient_estimate_hinge_axes(gp, gc, (size_t)n, a, b, &h), ORIENT_STATUS_TOO_LARGE);
    free(gp);
    free(gc);
    two_dof_axes();
    config_for_joints();
    learning_by_kind();
}
