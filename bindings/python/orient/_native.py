# Generated from include/orient.h by scripts/gen-python.py; do not edit. Regenerate with
# scripts/gen-python.py; scripts/check-python-native.sh (run by scripts/test-all.sh)
# fails when this file differs from what the header gives.
"""ctypes declarations of the C API in include/orient.h, and the loaded library.

One to one with the header: the #define constants (without ORIENT_), the enums
(IntEnum), the structs (ctypes Structures of the same names and fields) and the
functions (PROTOTYPES, set on the library when it is loaded). Parameter names, units,
defaults and ranges are read from the library at run time (orient_param_info). The
idiomatic layer is _filter.py.
"""

import ctypes
import enum
import os
import sys
from ctypes import POINTER, Structure, c_char_p, c_double, c_int32, c_size_t, c_uint32, c_uint64, c_uint8, c_void_p
from pathlib import Path

#: orient_filter_set_sensor_model's `sensor`: the gyroscope.
SENSOR_GYRO = 0

#: The accelerometer.
SENSOR_ACCEL = 1

#: The magnetometer.
SENSOR_MAG = 2

#: OrientJoint.kind: one degree of freedom. The child turns about one axis,
#: `axis_parent` in the parent sensor's frame and `axis_child` in the child's, the same
#: line at every instant (an elbow, a knee, a finger's PIP and DIP joints).
JOINT_HINGE = 0

#: OrientJoint.kind: two degrees of freedom. The child turns about `axis_parent` (fixed
#: in the parent), then about `axis_child` (fixed in the child), the two perpendicular (a
#: wrist, a finger's MCP joint, an ankle).
JOINT_TWO_DOF = 1

#: OrientJoint.axes_frame: the axes are given in the sensors' frames.
JOINT_AXES_SENSOR = 0

#: OrientJoint.axes_frame: the axes are given in the segments' frames (a segment's
#: anatomical axes: a finger's flexion axis in its bone's frame), and turned into the
#: sensors' through the mountings (v_sensor = conj(m) v_segment m).
JOINT_AXES_SEGMENT = 1

#: The most joints one OrientJoints holds (two hands have 30, a suit 19).
MAX_JOINTS = 64

#: The most segments one OrientJoints holds.
MAX_SEGMENTS = 256

#: Number of parameter slots in `OrientConfig.params`. Slots 0-7 are common to every
#: kind; each kind has its own block (Madgwick 8-15, Mahony 16-23, complementary 24-39,
#: EKF 40-55, GMVDK 56-79, robust 80-103); 104-127 are free for later versions.
MAX_PARAMS = 128

#: Parameter slot (every kind): Gravity magnitude for the gravity and linear-acceleration
#: outputs; default 9.80665 (orient: standard gravity, CGPM 1901).
#:
#: Unit m/s^2; range 0.001 to 1000; default 9.80665.
PARAM_GRAVITY = 0

#: Parameter slot (every kind): Gyroscope full scale: a sample with any axis at or beyond
#: it is rejected as saturated; 0 turns the check off (default; orient: the range is the
#: sensor's, which a configuration has to give).
#:
#: Unit rad/s; range 0 (off) or 0.1 to 10000; default 0.
PARAM_GYRO_RANGE = 1

#: Parameter slot (every kind): Accelerometer full scale: a sample with any axis at or
#: beyond it is rejected as saturated; 0 turns the check off (default; orient: as
#: gyro_range).
#:
#: Unit m/s^2; range 0 (off) or 1 to 100000; default 0.
PARAM_ACCEL_RANGE = 2

#: Parameter slot (every kind): Longest dt taken as given: a larger dt is a gap in the
#: data (dropped packets), and the update re-acquires the orientation from the sensors
#: instead of integrating over it (GAP and REACQUIRED flags); default 0.25 (orient: over
#: a quarter second a hand's rate changes enough that integrating the next sample's rate
#: errs more than one accelerometer reading; 10 periods of a 40 Hz sensor); 0 turns it
#: off.
#:
#: Unit s; range 0 (off) or 0.001 to 1000000; default 0.25.
PARAM_GAP_DT = 3

#: Parameter slot (every kind): What a reading at or beyond gyro_range or accel_range
#: does: 0 (default; orient: a clipped reading is wrong, so by default it is refused)
#: rejects the sample as saturated; 1 uses it clipped (a gyroscope reading clipped just
#: under the range, a saturated accelerometer reading left out), sets the SATURATED flag,
#: and after gyroscope saturation re-acquires the orientation from the next unsaturated
#: sample with an accelerometer reading (x-io Fusion's angular-rate recovery). The
#: physical bounds stay errors.
#:
#: Unit 1; range 0 (off) or 1 to 1; default 0.
PARAM_SATURATION_RECOVERY = 4

#: Parameter slot (every kind): What a sample with dt = 0 does (bursts of packets with
#: one timestamp): 0 (default; orient: dt = 0 is an error unless the host says its sensor
#: sends bursts) rejects it as an invalid dt; 1 takes it as the same instant as the next
#: sample with dt > 0: nothing is integrated then, its gyroscope reading is averaged with
#: the following ones up to and including that sample, which integrates the average over
#: its dt, so no rotation is lost (the SAME_INSTANT flag is set). Its accelerometer and
#: magnetometer readings are not used.
#:
#: Unit 1; range 0 (off) or 1 to 1; default 0.
PARAM_SAME_INSTANT = 5

#: Parameter slot (madgwick): Gradient step beta for steps without magnetometer, eq.
#: (30); default 0.041 (paper: Madgwick 2010, section V, optimum of the IMU
#: implementation). beta = sqrt(3/4) * max gyro error, eq. (33). The step follows the
#: normalised gradient, so the estimate wanders by about beta * dt rad RMS at rest (0.6
#: deg at beta 1 and 100 Hz).
#:
#: Unit rad/s; range 0 to 100; default 0.041.
PARAM_MADGWICK_BETA_IMU = 8

#: Parameter slot (madgwick): Gradient step beta for steps with magnetometer, eq. (30);
#: default 0.041, the paper's IMU optimum (section V). The paper's MARG optimum, 0.033,
#: was found for its own sensor (beta scales with gyro error, eq. (33)); on BROAD it
#: scores 7.79 deg against 7.22 for 0.041, which is also the Python ahrs reference's
#: value. At rest the estimate wanders by about beta * dt rad RMS, as with beta_imu.
#:
#: Unit rad/s; range 0 to 100; default 0.041.
PARAM_MADGWICK_BETA_MARG = 9

#: Parameter slot (madgwick): orient option: learn the gyro bias at detected rest (2
#: deg/s, 0.5 m/s^2, 0.5 deg tilt for 1.5 s) with this time constant and subtract it;
#: default 0 = off (the paper has no bias estimate in this form).
#:
#: Unit s; range 0 (off) or 0.001 to 3600; default 0.
PARAM_MADGWICK_REST_BIAS_TAU = 10

#: Parameter slot (mahony): Proportional gain on the direction error (Mahony 2008);
#: default 0.5 as in the GMVDK paper's comparison and BROAD's baseline.
#:
#: Unit 1/s; range 0 to 1000; default 0.5.
PARAM_MAHONY_KP = 16

#: Parameter slot (mahony): Integral gain for the gyroscope bias (Mahony 2008); default 0
#: (no bias estimation) as in the GMVDK paper's comparison. Set to 0 with rest_bias_tau
#: also 0, the bias estimate is dropped.
#:
#: Unit 1/s^2; range 0 to 1000; default 0.
PARAM_MAHONY_KI = 17

#: Parameter slot (mahony): orient option: at detected rest (2 deg/s, 0.5 m/s^2, 0.5 deg
#: tilt for 1.5 s) the bias b follows the low-passed gyro with this time constant;
#: default 0 = off (Mahony's filter).
#:
#: Unit s; range 0 (off) or 0.001 to 3600; default 0.
PARAM_MAHONY_REST_BIAS_TAU = 18

#: Parameter slot (complementary): Proportional gain K_P, eq. (4), applied only at rest;
#: default 1.0 (the paper gives no value: 1 s attitude time constant at rest).
#:
#: Unit 1/s; range 0 to 1000; default 1.
PARAM_COMPLEMENTARY_KP = 24

#: Parameter slot (complementary): Integral gain K_I for the gyro bias, eqs. (5) and
#: (10), applied only at rest; default 0.01 (the paper gives no value): stable for rests
#: up to 100 s apart, since the loop gain per rest is about K_I * motion time / K_P and
#: must stay below 2.
#:
#: Unit 1/s^2; range 0 to 1000; default 0.01.
PARAM_COMPLEMENTARY_KI = 25

#: Parameter slot (complementary): Rest when |gyro - start-up mean gyro| is below this;
#: default 0.02 (about 3x the per-sample noise floor of the paper's 0.03 deg/s/sqrt(Hz)
#: gyro at 100 Hz).
#:
#: Unit rad/s; range 0 to 100; default 0.02.
PARAM_COMPLEMENTARY_GYRO_REST = 26

#: Parameter slot (complementary): Rest when | |accel| - g0 | is below this (g0: start-up
#: mean); default 0.2 (about 3x the per-sample noise floor of the paper's 650 ug/sqrt(Hz)
#: accelerometer).
#:
#: Unit m/s^2; range 0 to 100; default 0.2.
PARAM_COMPLEMENTARY_ACCEL_REST = 27

#: Parameter slot (complementary): Stationary start-up period giving the initial bias and
#: attitude (paper: 'a time period at the start of a trial'); default 2.
#:
#: Unit s; range 0 to 3600; default 2.
PARAM_COMPLEMENTARY_INIT_DURATION = 28

#: Parameter slot (complementary): 1: take north from the start-up mean magnetometer
#: reading, aligning heading with the earth frame; 0 (default, the paper): heading
#: relative to the sensor y axis.
#:
#: Unit 1; range 0 to 1; default 0.
PARAM_COMPLEMENTARY_ALIGN_HEADING = 29

#: Parameter slot (ekf): Correlation time of the angular-rate Markov process, eq. (9)
#: (stable -1/tau form); default 0.2 (orient: the paper sets it from the motion's
#: bandwidth without a value; a few Hz for hand and body motion).
#:
#: Unit s; range 0.0001 to 1000000; default 0.2.
PARAM_EKF_TAU_OMEGA = 40

#: Parameter slot (ekf): Stationary standard deviation of the angular rate ('limit of the
#: magnitude of the motion', section III.A); default 3 (orient: the paper gives no value;
#: about 170 deg/s, the scale of hand and body rotation).
#:
#: Unit rad/s; range 0.001 to 1000; default 3.
PARAM_EKF_OMEGA_STD = 41

#: Parameter slot (ekf): Correlation time of the gyro drift Markov process, eq. (10)
#: (stable -1/tau form); default 100 (orient: the paper gives no value; MEMS drift
#: changes over minutes).
#:
#: Unit s; range 0.001 to 1000000000; default 100.
PARAM_EKF_TAU_DRIFT = 42

#: Parameter slot (ekf): Stationary standard deviation of the gyro drift; default 0.02
#: (orient: the paper gives no value; about 1 deg/s covers consumer MEMS gyroscopes'
#: typical zero-rate offset, 0.5 deg/s in the BMI270 and LSM6DSO datasheets).
#:
#: Unit rad/s; range 0.000001 to 10; default 0.02.
PARAM_EKF_DRIFT_STD = 43

#: Parameter slot (ekf): Gyroscope noise density; default 0.05 deg/s/sqrt(Hz) (paper,
#: section IV).
#:
#: Unit rad/s/sqrt(Hz); range 0.00001 to 10; default 0.0008726646259971648.
PARAM_EKF_GYRO_NOISE = 44

#: Parameter slot (ekf): Accelerometer noise density; default 32 ug/sqrt(Hz) (paper,
#: section IV).
#:
#: Unit m/s^2/sqrt(Hz); range 0.00001 to 100; default 0.00031381279999999996.
PARAM_EKF_ACCEL_NOISE = 45

#: Parameter slot (ekf): Standing allowance for linear acceleration added to the
#: accelerometer noise (plus (|f|-g)^2 per sample); default 0.5 (orient: the paper's
#: model has none and tolerates 'a modicum'; real recordings need it, BROAD trial 15).
#:
#: Unit m/s^2; range 0 to 1000; default 0.5.
PARAM_EKF_ACCEL_MOTION = 46

#: Parameter slot (ekf): Standard deviation of the magnetometer heading measurement (the
#: paper's proposed extension); default 0.1 (orient: about 6 deg for a clean field;
#: heading_tau and heading_adapt_tau raise it when it is not).
#:
#: Unit rad; range 0.0001 to 10; default 0.1.
PARAM_EKF_HEADING_STD = 47

#: Parameter slot (ekf): Correlation time of linear acceleration: its variance is counted
#: once per 2*motion_tau/dt samples (coloured, not white, noise); default 0.5 (orient:
#: the length of a hand movement); 0 treats it as white, as the paper does.
#:
#: Unit s; range 0 to 100; default 0.5.
PARAM_EKF_MOTION_TAU = 48

#: Parameter slot (ekf): Correlation time of magnetic heading errors: the heading
#: variance is counted once per 2*heading_tau/dt samples; default 1 (orient: disturbances
#: change as the sensor moves through a room's field); 0 treats them as white.
#:
#: Unit s; range 0 to 1000; default 1.
PARAM_EKF_HEADING_TAU = 49

#: Parameter slot (ekf): orient option: at detected rest (2 deg/s, 0.5 m/s^2, 0.5 deg
#: tilt for 1.5 s) add the pseudo-measurement omega = 0 with this standard deviation
#: (zero-rate update), which pins the drift delta to the resting gyro; default 0 = off
#: (the paper).
#:
#: Unit rad/s; range 0 (off) or 0.000001 to 10; default 0.
PARAM_EKF_REST_RATE_STD = 50

#: Parameter slot (ekf): Time constant of the accelerometer innovation's running power;
#: the measurement variance is at least that power (colour-scaled), so sustained linear
#: acceleration is trusted less (innovation-based adaptive noise, where the paper only
#: allows 'a modicum'); default 2 (BROAD mean 9D within 0.15 deg over 1-5 s); 0 = off.
#:
#: Unit s; range 0 (off) or 0.001 to 1000; default 2.
PARAM_EKF_ACCEL_ADAPT_TAU = 51

#: Parameter slot (ekf): Time constant of the heading innovation's running power, which
#: likewise bounds the heading variance from below, so a disturbed field is trusted less;
#: default 2 (orient: as accel_adapt_tau; BROAD trial 32 goes from 25.3 to 2.8 deg); 0 =
#: off.
#:
#: Unit s; range 0 (off) or 0.001 to 1000; default 2.
PARAM_EKF_HEADING_ADAPT_TAU = 52

#: Parameter slot (gmvdk): SlopeAlpha of Appendix B.1: alpha = max(0, stillness*slope + 1
#: - slope); default 1.0 (paper).
#:
#: Unit 1; range 0 to 100; default 1.
PARAM_GMVDK_SLOPE_ALPHA = 56

#: Parameter slot (gmvdk): SlopeMuk of Appendix B.2 / eq. (20): muKA = 1 - slope*lambda;
#: default 1.5 (paper).
#:
#: Unit 1/rad; range 0 to 100; default 1.5.
PARAM_GMVDK_SLOPE_MUK = 57

#: Parameter slot (gmvdk): Window of the running minimum mu2 of mu1 (section 2.2.2);
#: default 0.4 (paper).
#:
#: Unit s; range 0 to 60; default 0.4.
PARAM_GMVDK_MU_WINDOW = 58

#: Parameter slot (gmvdk): Static start-up period averaging A_init, M_init and the first
#: gyro bias; default 1 (orient: the paper averages a static start-up period without
#: giving its length).
#:
#: Unit s; range 0 to 3600; default 1.
PARAM_GMVDK_INIT_DURATION = 59

#: Parameter slot (gmvdk): Time constant of the mean-square activity averages behind
#: stillness; default 0.1 (orient: the paper reads Stillness from its sensor module; with
#: 0.1 s, alpha falls within a tenth of a second of the start of motion).
#:
#: Unit s; range 0.0001 to 100; default 0.1.
PARAM_GMVDK_ACTIVITY_TAU = 60

#: Parameter slot (gmvdk): Gyro activity scale: RMS de-biased rate at which stillness
#: reaches 0 (with no accelerometer activity, at sqrt(2) times it); default 0.5 (orient:
#: about 30 deg/s, slow deliberate motion).
#:
#: Unit rad/s; range 0.000001 to 100; default 0.5.
PARAM_GMVDK_GYRO_ACTIVITY = 61

#: Parameter slot (gmvdk): Accelerometer activity scale: RMS deviation of |a| from its
#: start-up value at which stillness reaches 0 (alone: sqrt(2) times it); default 1.0
#: (orient: about 0.1 g of linear acceleration).
#:
#: Unit m/s^2; range 0.000001 to 1000; default 1.
PARAM_GMVDK_ACCEL_ACTIVITY = 62

#: Parameter slot (gmvdk): Static run length for the linear-regression gyro de-biasing of
#: the paper's step 1; default 1.0 (orient: the paper's 'window of consecutive samples'
#: has no length).
#:
#: Unit s; range 0.001 to 3600; default 1.
PARAM_GMVDK_BIAS_WINDOW = 63

#: Parameter slot (gmvdk): alpha at or above which the sensor counts as static for
#: de-biasing; default 0.95 (orient: the paper says 'estimated to be static' without a
#: threshold).
#:
#: Unit 1; range 0 to 1; default 0.95.
PARAM_GMVDK_STATIC_ALPHA = 64

#: Parameter slot (gmvdk): 1: report orientation relative to the start-up pose (the
#: paper's output); 0 (default): in the configured earth frame.
#:
#: Unit 1; range 0 to 1; default 0.
PARAM_GMVDK_RELATIVE_OUTPUT = 65

#: Parameter slot (robust): Time constant of the accelerometer low-pass (2nd-order
#: Butterworth, cutoff sqrt(2)/(2 pi tau)) in the quasi-inertial frame; default 2.5
#: (orient: long enough to average out hand and body accelerations; BROAD scores vary by
#: under 0.03 deg over 2.5-3 s).
#:
#: Unit s; range 0.001 to 1000; default 2.5.
PARAM_ROBUST_TAU_ACC = 80

#: Parameter slot (robust): Time constant of the magnetometer heading correction; default
#: 9 (VQF's default: slow enough that a short undetected disturbance moves heading
#: little).
#:
#: Unit s; range 0.001 to 1000; default 9.
PARAM_ROBUST_TAU_MAG = 81

#: Parameter slot (robust): Rest when the gyroscope's spread around its low-pass and the
#: low-pass itself stay below this; default 0.0349 (2 deg/s, VQF's default; MEMS biases
#: are below it); another under joints (orient_config_for_joints()), with bias_limit.
#:
#: Unit rad/s; range 0 to 10; default 0.03490658503988659.
PARAM_ROBUST_REST_GYRO = 82

#: Parameter slot (robust): Rest when the accelerometer's spread around its low-pass
#: stays below this; default 0.5 (VQF's default).
#:
#: Unit m/s^2; range 0 to 100; default 0.5.
PARAM_ROBUST_REST_ACCEL = 83

#: Parameter slot (robust): How long the rest conditions must hold before the sensor
#: counts as resting (0: rest_tau/2, the tilt test's window, rest_tilt); default 1.5
#: (VQF's default).
#:
#: Unit s; range 0 to 3600; default 1.5.
PARAM_ROBUST_REST_TIME = 84

#: Parameter slot (robust): Rest also needs the accelerometer's direction to stay within
#: this angle of where the still period began (the mean of its first window of
#: rest_tau/2, or rest_time/6 when shorter, against a low-pass of that window started
#: with the period), so a slow turn under rest_gyro is not learned as bias; default
#: 0.0087 (0.5 deg, orient: 10x the direction noise after the rest low-pass of a consumer
#: MEMS accelerometer).
#:
#: Unit rad; range 0 to 3.2; default 0.008726646259971648.
PARAM_ROBUST_REST_TILT = 92

#: Parameter slot (robust): Time constant of the low-pass that rest detection compares
#: against (the tilt test, rest_tilt, takes half of it, or rest_time/6 when shorter);
#: default 0.5 (VQF's default).
#:
#: Unit s; range 0.001 to 100; default 0.5.
PARAM_ROBUST_REST_TAU = 85

#: Parameter slot (robust): Time constant with which the bias follows the low-passed
#: gyroscope at rest; default 1 (orient: a hand's pauses last a few seconds, of which
#: rest detection takes rest_time; shorter learns more of each pause but also more of a
#: slow turn that starts from rest below rest_gyro, docs/ACCURACY.md).
#:
#: Unit s; range 0.001 to 3600; default 1.
PARAM_ROBUST_BIAS_TAU_REST = 86

#: Parameter slot (robust): Standard deviation the bias estimate in motion settles to
#: while the inclination correction measures the bias (sigma_m of the motion bias Kalman
#: filter, VQF's biasSigmaMotion; smaller learns faster and trusts the correction more);
#: default 5.24e-4 (0.03 deg/s, orient: with the filter's rate and acceleration terms,
#: chosen on BROAD and simulated gloves, docs/ACCURACY.md); 0 turns the estimate in
#: motion off.
#:
#: Unit rad/s; range 0 (off) or 0 to 1; default 0.0005235987755982988.
PARAM_ROBUST_BIAS_SIGMA_MOTION = 100

#: Parameter slot (robust): Largest component the motion estimate may give the bias, and
#: its measurement error (a larger component learned at rest raises the bound for every
#: component to it); default 0.0349 (orient: 2 deg/s, VQF's biasClip and the rest
#: threshold: a larger bias would also hide rest); another under joints, with rest_gyro
#: (orient_config_for_joints()).
#:
#: Unit rad/s; range 0 to 10; default 0.03490658503988659.
PARAM_ROBUST_BIAS_LIMIT = 88

#: Parameter slot (robust): Magnetic disturbance when the field norm deviates from the
#: reference by more than this fraction; default 0.1 (VQF's default).
#:
#: Unit 1; range 0 to 10; default 0.1.
PARAM_ROBUST_MAG_NORM_TH = 89

#: Parameter slot (robust): Magnetic disturbance when the dip angle deviates from the
#: reference by more than this; default 0.1745 (10 deg, VQF's default).
#:
#: Unit rad; range 0 to 3.2; default 0.17453292519943295.
PARAM_ROBUST_MAG_DIP_TH = 90

#: Parameter slot (robust): A sensor-fixed disturbance (attached magnet) is compensated
#: once its estimate has been consistent this long; default 3 (orient); 0 turns
#: compensation off.
#:
#: Unit s; range 0 (off) or 0.001 to 3600; default 3.
PARAM_ROBUST_HARD_IRON_TIME = 91

#: Parameter slot (robust): Gyroscope rate noise density, for the heading uncertainty
#: only (eq. H1); default 1.745e-4 (orient: 0.01 deg/s/sqrt(Hz), the MPU-9250
#: datasheet's, the largest of common MEMS gyroscopes: BMI270 0.007, LSM6DSO 0.0038).
#:
#: Unit rad/s/sqrt(Hz); range 0 to 1; default 0.00017453292519943296.
PARAM_ROBUST_GYRO_NOISE = 93

#: Parameter slot (robust): Standard deviation of the gyroscope bias before any rest, and
#: the most its uncertainty grows back to: the heading uncertainty's (eq. H1) and the
#: motion bias filter's starting and largest covariance (0 leaves that filter nothing to
#: learn); default 0.0087 (0.5 deg/s: VQF's biasSigmaInit, and the typical zero-rate
#: offset after soldering in the BMI270 and LSM6DSO datasheets).
#:
#: Unit rad/s; range 0 to 10; default 0.008726646259971648.
PARAM_ROBUST_BIAS_SIGMA = 94

#: Parameter slot (robust): Standard deviation of the bias learned at rest: what the bias
#: uncertainty settles to during a rest, the heading uncertainty's (eq. H2) and the
#: motion bias filter's covariance; default 5.24e-4 (0.03 deg/s, VQF's biasSigmaRest).
#:
#: Unit rad/s; range 0 to 10; default 0.0005235987755982989.
PARAM_ROBUST_BIAS_SIGMA_REST = 95

#: Parameter slot (robust): Random walk of the gyroscope bias: how fast the motion bias
#: filter lets a learned bias go (its process noise) and the heading uncertainty grows
#: with it (eq. H1); larger follows a drifting bias sooner and takes more of a fast
#: motion's scale errors for bias; 0 learns the bias at rest only; default 1.745e-4 (0.01
#: deg/s/sqrt(s): VQF's 0.1 deg/s over its biasForgettingTime of 100 s); another under
#: joints (orient_config_for_joints()).
#:
#: Unit rad/s/sqrt(s); range 0 to 10; default 0.00017453292519943296.
PARAM_ROBUST_BIAS_WALK = 96

#: Parameter slot (robust): Standard deviation of the heading a clean accepted
#: magnetometer field gives, for the heading uncertainty only (eq. H3): the floor the
#: uncertainty settles to while an undisturbed field is used; at most 1.8, the sigma of a
#: heading uniform on the circle (eq. H4); default 0.01745 (1 deg, orient: the heading of
#: a clean field at rest against BROAD's optically aligned north, -1.5 to +1.3 deg over
#: its trials).
#:
#: Unit rad; range 0 to 1.8; default 0.017453292519943295.
PARAM_ROBUST_MAG_HEADING_SIGMA = 97

#: Parameter slot (robust): Heading error per unit of an accepted field's deviation from
#: the reference (its dip's in rad and its norm's as a fraction), for the heading
#: uncertainty only (eq. H3): a field the norm and dip tests let through still turns the
#: heading; default 0.2 (orient: chosen by leave-one-group-out cross-validation over
#: BROAD's 14 shared trials, tools/src/bin/robust_sigma.rs: 0.1 or 0.2 in every fold).
#:
#: Unit 1; range 0 to 100; default 0.2.
PARAM_ROBUST_MAG_DEVIATION_GAIN = 98

#: Parameter slot (robust): Heading error the gyroscope's scale and axis errors add per
#: square root of the angle turned, for the heading uncertainty only (eq. H1); default
#: 0.0075 (orient: chosen by leave-one-group-out cross-validation over BROAD's 14 shared
#: trials, tools/src/bin/robust_sigma.rs: 0.0075 in every fold).
#:
#: Unit sqrt(rad); range 0 to 1; default 0.0075.
PARAM_ROBUST_GYRO_SCALE_SIGMA = 99

#: Version of the C ABI described by this header. It changes only when an existing
#: function, struct layout or constant changes meaning; additions keep it.
ABI_VERSION = 1

#: `OrientSample.flags`: the gyroscope field holds a reading (every filter needs one).
SAMPLE_GYRO = 1

#: `OrientSample.flags`: the accelerometer field holds a reading.
SAMPLE_ACCEL = 2

#: `OrientSample.flags`: the magnetometer field holds a reading.
SAMPLE_MAG = 4

#: `OrientParamInfo.flags`: 0 is also accepted and turns the feature off; `min` is the
#: smallest value that has it on.
PARAM_FLAG_ZERO_OFF = 1

#: OrientUncertainty.present: heading holds a value.
UNCERTAINTY_HEADING = 1

#: OrientUncertainty.present: inclination holds a value.
UNCERTAINTY_INCLINATION = 2

#: `orient_filter_flags`: the filter has an orientation. Clear while it waits for its
#: first accelerometer sample (the default initialisation, from the accelerometer and
#: magnetometer), and through the start-up period of the complementary and GMVDK kinds,
#: ORIENT_PARAM_*_INIT_DURATION seconds of samples with an accelerometer reading: their
#: readings are averaged into the initial orientation, and each such sample sets
#: ORIENT_FLAG_ACCEL_USED and, for the magnetometer, ORIENT_FLAG_MAG_USED or
#: ORIENT_FLAG_MAG_REJECTED as the period will use it; the dt = 0 samples of
#: ORIENT_PARAM_SAME_INSTANT are samples of the period too.
FLAG_INITIALIZED = 1

#: `orient_filter_flags`: the last accepted update used the accelerometer.
FLAG_ACCEL_USED = 2

#: `orient_filter_flags`: the last accepted update used the magnetometer.
FLAG_MAG_USED = 4

#: `orient_filter_flags`: the last accepted update followed a gap (dt above
#: ORIENT_PARAM_GAP_DT). Nothing was integrated over the gap, whose motion is unknown:
#: the update re-acquired the orientation (ORIENT_FLAG_REACQUIRED) or, on a sample
#: without an accelerometer reading, held it (ORIENT_FLAG_REACQUIRE_PENDING). During the
#: start-up period of the complementary and GMVDK kinds the period started over with the
#: sample instead (not at a gap right after a gap: where every sample is one, it goes on,
#: and its stillness test alone starts it over).
FLAG_GAP = 8

#: `orient_filter_flags`: the last accepted update re-acquired the orientation (after a
#: gap, a gyroscope saturation or the rest watch, see ORIENT_FLAG_REACQUIRE_PENDING):
#: inclination from its accelerometer reading, heading from its magnetometer reading when
#: it has one (every kind but the robust one, whose magnetic disturbance test may refuse
#: the reading, and the complementary one, which uses it only with
#: ORIENT_PARAM_COMPLEMENTARY_ALIGN_HEADING), else the heading held before. The kind's
#: low-passes and detectors start over; its bias estimate is kept, but after the rest
#: watch the still sample's gyroscope reading becomes the bias of every kind that learns
#: one or still subtracts one (the complementary filter's rest reference ω_b0 too).
FLAG_REACQUIRED = 16

#: `orient_filter_flags`: the next sample with an accelerometer reading re-acquires the
#: orientation (ORIENT_FLAG_REACQUIRED); until then it is integrated from the gyroscope.
#: Set when a gap ends on a sample without an accelerometer reading (the orientation is
#: held over the gap), after gyroscope saturation, and by the rest watch: when the sensor
#: lies still (gyroscope below 3 °/s, accelerometer norm within 5 % of the configured
#: gravity) and the estimate's vertical has been more than 10° from the accelerometer's,
#: or the kind's bias more than 6 °/s from the gyroscope's reading, for 5 s net of the
#: time it was not (looked at every 128th sample, at least four looks; a look at a moving
#: sensor starts the count over). An estimate can rest there at a stationary point of its
#: kind's correction (Madgwick's and Mahony's magnetometer terms near a 180° heading
#: error, the EKF's gravity update near an upside-down estimate), or spin on a wrong bias
#: that its kind then cannot learn (GMVDK distrusts the accelerometer while the de-biased
#: rate is large, the complementary filter's rest test compares with its start-up bias).
FLAG_REACQUIRE_PENDING = 32

#: `orient_filter_flags`: the last accepted sample had an accelerometer reading that the
#: update did not use (the kind's own test turned it down, e.g. the robust kind's and the
#: EKF's gating of linear acceleration, GMVDK's trust, McGinnis' rest gate).
FLAG_ACCEL_REJECTED = 64

#: `orient_filter_flags`: the last accepted sample had a magnetometer reading that the
#: update did not use (the kind has no heading correction, the field defines no north, or
#: the kind turned it down).
FLAG_MAG_REJECTED = 128

#: `orient_filter_flags`: the kind counts the magnetic field as disturbed now (the robust
#: kind: the last reading failed its norm and dip tests, hard iron compensated). Read
#: from the state, not stored.
FLAG_MAG_DISTURBED = 256

#: `orient_filter_flags`: the kind counts the sensor as resting now (McGinnis' and the
#: robust kind's rest detection; the EKF, Madgwick and Mahony with their rest options on,
#: ORIENT_PARAM_EKF_REST_RATE_STD and ORIENT_PARAM_*_REST_BIAS_TAU; GMVDK never sets it).
#: Read from the state, not stored.
FLAG_REST = 512

#: `orient_filter_flags`: the last update had a reading at or beyond its configured range
#: and used it clipped (ORIENT_PARAM_SATURATION_RECOVERY = 1): a gyroscope reading
#: clipped just under the range, an accelerometer reading left out. After gyroscope
#: saturation ORIENT_FLAG_REACQUIRE_PENDING is set too: the next unsaturated sample with
#: an accelerometer reading re-acquires the orientation (ORIENT_FLAG_REACQUIRED).
FLAG_SATURATED = 1024

#: `orient_filter_flags`: the last sample had dt = 0 and was taken as the same instant as
#: the next sample with dt > 0 (ORIENT_PARAM_SAME_INSTANT = 1): nothing was integrated;
#: its gyroscope reading is averaged into that sample's step.
FLAG_SAME_INSTANT = 2048

#: OrientDiagnostics.present: gyro_bias holds a value.
DIAG_GYRO_BIAS = 1

#: OrientDiagnostics.present: rest holds a value.
DIAG_REST = 2

#: OrientDiagnostics.present: alpha holds a value.
DIAG_ALPHA = 4

#: OrientDiagnostics.present: mu_ka holds a value.
DIAG_MU_KA = 8

#: OrientDiagnostics.present: mu_km holds a value.
DIAG_MU_KM = 16

#: OrientDiagnostics.present: mu_k holds a value.
DIAG_MU_K = 32

#: OrientDiagnostics.present: rate holds a value.
DIAG_RATE = 64

#: OrientDiagnostics.present: covariance holds values.
DIAG_COVARIANCE = 128


class Status(enum.IntEnum):
    """Result of every fallible call. Numbers are fixed and never reused. On any status but
    ORIENT_STATUS_OK the call changed nothing (a batch keeps the samples before the bad
    one), and orient_last_error() has the detail.
    """

    #: Success.
    OK = 0
    #: A required pointer argument is NULL (checked before anything else).
    NULL_POINTER = 1
    #: The handle is not a live OrientFilter (OrientJoints): freed, or never returned by
    #: orient_filter_new (orient_joints_new), a copy of a handle's bytes included.
    INVALID_HANDLE = 2
    #: The kind is known but not built in this version of the library (reserved: every
    #: kind is built in this version).
    UNSUPPORTED_KIND = 3
    #: An enum value, flag bit or index that the library does not know.
    INVALID_ARGUMENT = 4
    #: The filter kind has no parameter with that id or name.
    UNKNOWN_PARAM = 5
    #: A parameter value is not finite or outside its documented range.
    PARAM_OUT_OF_RANGE = 6
    #: A present sample field, or a given quaternion, holds NaN or +-Inf.
    NON_FINITE = 7
    #: dt is below 1e-9 s (zero, negative, subnormal), above 1e6 s, NaN or infinite
    #: (a zero dt is a burst sample instead when ORIENT_PARAM_SAME_INSTANT is 1).
    INVALID_DT = 8
    #: An accelerometer, magnetometer or quaternion whose norm is zero (or so small
    #: that its square is not a normal double).
    ZERO_VECTOR = 9
    #: A vector whose squared norm overflows a double, or a reading with a component at
    #: or beyond its physical bound: gyroscope 1e4 rad/s, accelerometer 1e5 m/s^2,
    #: magnetometer 1e12 (any unit).
    TOO_LARGE = 10
    #: A reading at or beyond the configured ORIENT_PARAM_*_RANGE (with
    #: ORIENT_PARAM_SATURATION_RECOVERY set to 1 the sample is used clipped instead and
    #: ORIENT_FLAG_SATURATED is set).
    SATURATED = 11
    #: The sample lacks a sensor the filter needs (every filter needs the gyroscope).
    MISSING_SENSOR = 12
    #: The filter waits for its first accelerometer sample (ORIENT_INIT_ACC_MAG); with
    #: ORIENT_PARAM_SAME_INSTANT set to 1, for its first sample with dt > 0 as well. During
    #: a kind's start-up period (ORIENT_KIND_COMPLEMENTARY, ORIENT_KIND_GMVDK) a sample
    #: without an accelerometer reading is refused so too; a same-instant sample (dt 0) is
    #: not.
    NOT_INITIALIZED = 13
    #: The output needs data the filter has not received yet (linear acceleration
    #: before the first accelerometer sample).
    NO_DATA = 14
    #: The update would have produced a non-finite state. A guard: the bounds on dt and
    #: the readings keep accepted samples from reaching it.
    NUMERIC = 15
    #: A count so large that the buffers it describes cannot exist; from
    #: orient_filter_new: 24576 filters are live already, the most the library holds.
    COUNT_TOO_LARGE = 16
    #: `struct_size` does not match a configuration layout this library knows.
    VERSION_MISMATCH = 17
    #: A bug: the library panicked. The panic was caught at the C boundary.
    PANIC = 18
    #: The output buffer is smaller than the data (orient_filter_save: see
    #: orient_filter_state_size).
    BUFFER_TOO_SMALL = 19
    #: A state blob that is truncated, corrupted (checksum), of another format version or
    #: of another filter kind; the filter is unchanged.
    INVALID_STATE = 20
    #: A buffer the call needs could not be allocated; nothing was changed
    #: (orient_smooth_arrays: see orient_smooth_memory).
    OUT_OF_MEMORY = 21
    #: A joint of orient_joints_new names a segment the rig does not have, is its own
    #: child's parent, gives its child a second parent, closes a cycle, or has an axis
    #: that is NaN, infinite, or too short or too long to normalise; orient_last_error
    #: names the joint.
    INVALID_JOINT = 22


class Kind(enum.IntEnum):
    """Filter kinds, as the `kind` argument and `OrientConfig.kind`."""

    #: Madgwick 2010 gradient descent, IMU and MARG.
    MADGWICK = 1
    #: Mahony nonlinear complementary filter, IMU and MARG, bias estimate optional.
    MAHONY = 2
    #: McGinnis 2014 PI complementary filter: gains at rest only, start-up period (IMU).
    COMPLEMENTARY = 3
    #: Kim & Golnaraghi 2004 quaternion EKF [q, omega, drift]; magnetometer heading optional.
    EKF = 4
    #: GMVDK 2024 double-SLERP filter with trust alpha and mu_K; start-up period.
    GMVDK = 5
    #: Recommended: strapdown with a quasi-inertial accelerometer low-pass, rest and motion
    #: gyro-bias estimation, magnetic disturbance rejection and hard-iron compensation.
    ROBUST = 6


class Frame(enum.IntEnum):
    """Earth frames, as `OrientConfig.frame`."""

    #: x East, y North, z Up (default).
    ENU = 0
    #: x North, y East, z Down.
    NED = 1
    #: x North, y West, z Up.
    NWU = 2


class Init(enum.IntEnum):
    """Initial orientation, as `OrientConfig.init`."""

    #: From the first sample with an accelerometer (and magnetometer, if that sample has
    #: one); that sample is also used for a normal update (default).
    ACC_MAG = 0
    #: The identity orientation in the configured frame.
    IDENTITY = 1
    #: `OrientConfig.initial`, in the configured frame (normalised).
    GIVEN = 2


class OrientQuaternion(Structure):
    """A Hamilton quaternion, scalar first. As an orientation it maps sensor to earth
    coordinates: v_earth = q * v_sensor * conj(q).
    """

    _fields_ = [
        ("w", c_double),
        ("x", c_double),
        ("y", c_double),
        ("z", c_double),
    ]


class OrientVec3(Structure):
    """A 3-vector."""

    _fields_ = [
        ("x", c_double),
        ("y", c_double),
        ("z", c_double),
    ]


class OrientDiagnostics(Structure):
    """Internal states for display, the same struct for every kind. A field whose
    ORIENT_DIAG_* bit is clear in `present` does not apply (to this kind, or yet) and
    holds NaN; it is never a made-up zero.
    """

    _fields_ = [
        # ORIENT_DIAG_* bits of the fields that hold values.
        ("present", c_uint32),
        # Always 0.
        ("reserved", c_uint32),
        # Gyroscope bias being subtracted, rad/s, sensor frame (Mahony b, complementary
        # omega_b, EKF drift delta, GMVDK regression bias, the robust kind's estimate,
        # Madgwick's with its rest-bias option on).
        ("gyro_bias", OrientVec3),
        # 1 when the last sample counted as rest, else 0 (complementary: gains on; robust:
        # its rest detector; EKF, Madgwick and Mahony: with their rest options on).
        ("rest", c_double),
        # GMVDK accelerometer trust alpha, [0, 1].
        ("alpha", c_double),
        # GMVDK magnetometer angle trust mu_KA, [0, 1].
        ("mu_ka", c_double),
        # GMVDK magnetometer magnitude trust mu_KM, [0, 1].
        ("mu_km", c_double),
        # GMVDK magnetometer trust mu_K = mu_2 * alpha, [0, 1].
        ("mu_k", c_double),
        # EKF angular-rate state, rad/s, sensor frame.
        ("rate", OrientVec3),
        # EKF covariance diagonal, state order [q0, q1, q2, q3, omega_xyz, drift_xyz]
        # (the quaternion in the filter's native North-East-Down frame).
        ("covariance", c_double * 10),
    ]


class OrientSensorModel(Structure):
    """A sensor model: calibrated = matrix (raw - offset), `matrix` row-major. For the
    gyroscope and accelerometer the matrix is the misalignment times the sensitivity;
    for the magnetometer it is the soft-iron matrix and `offset` the hard-iron offset.
    """

    _fields_ = [
        ("matrix", c_double * 9),
        ("offset", OrientVec3),
    ]


class OrientMagCalibrator(Structure):
    """A magnetometer calibrator's state, owned by the host (on its stack or in its own
    struct): initialise it with orient_mag_calibrator_init, feed it readings with
    orient_mag_calibrator_add (no allocation, no samples kept), solve it with
    orient_mag_calibrator_solve. Its fields are the fit's sums and its outlier gate's
    state; do not write them.
    """

    _fields_ = [
        ("sums", c_double * 55),
        ("scale", c_double),
        ("mean", OrientVec3),
        ("count", c_uint64),
        ("bins", c_uint64),
        ("rejected", c_uint64),
        ("streak", c_uint64),
        ("gate", c_double * 10),
    ]


class OrientMagFit(Structure):
    """What orient_mag_calibrator_solve found."""

    _fields_ = [
        # calibrated = soft_iron (raw - hard_iron): pass to orient_filter_set_sensor_model
        # with ORIENT_SENSOR_MAG.
        ("model", OrientSensorModel),
        # The field's magnitude after calibration (the readings' unit).
        ("field", c_double),
        # RMS of |calibrated| / field - 1 over the readings kept, to first order: the RMS
        # of (|calibrated|^2 / field^2 - 1) / 2, which the sums give exactly (within a few
        # per cent of the RMS of |calibrated| / field - 1 for residuals up to 0.02). 0.01 is
        # 1 %.
        ("residual", c_double),
        # Fraction of 54 direction bins on the sphere that readings fell in (1: all), the
        # directions taken from the readings' running mean: a sensor that sweeps the sphere
        # in order (one latitude after another) gets less than it covered.
        ("coverage", c_double),
        # Readings kept (in the fit); orient_mag_calibrator_rejected gives those set aside.
        ("samples", c_uint64),
        # 1 when coverage >= 0.5 and residual < 0.02 (the fit can be trusted), else 0.
        ("trustworthy", c_int32),
        ("reserved", c_int32),
    ]


class OrientConfig(Structure):
    """A filter configuration (1072 bytes). Fill it with orient_config_default(), then
    change fields or parameters.

    Compatibility rule: `struct_size` is set by orient_config_default() to the size
    this header describes. Later versions of the library only append fields and give
    new parameters new slots in `params`; they accept every `struct_size` an earlier
    header wrote. This version accepts exactly sizeof(OrientConfig) and returns
    ORIENT_STATUS_VERSION_MISMATCH otherwise.
    """

    _fields_ = [
        # sizeof(OrientConfig) as the caller compiled it.
        ("struct_size", c_uint32),
        # One of ORIENT_KIND_*.
        ("kind", c_int32),
        # One of ORIENT_FRAME_*; the frame every output is expressed in.
        ("frame", c_int32),
        # One of ORIENT_INIT_*.
        ("init", c_int32),
        # Initial orientation for ORIENT_INIT_GIVEN.
        ("initial", OrientQuaternion),
        # Parameter values by slot (ORIENT_PARAM_*). Slots the kind does not use are
        # ignored; list a kind's slots with orient_param_count() / orient_param_info().
        ("params", c_double * MAX_PARAMS),
    ]


class OrientParamInfo(Structure):
    """What one parameter means, for hosts that list settings (an inspector, a CLI).
    The strings are static, NUL-terminated UTF-8, and live as long as the library.
    """

    _fields_ = [
        # Slot in OrientConfig.params (a joint parameter's: its index,
        # orient_joint_param_info).
        ("id", c_uint32),
        # ORIENT_PARAM_FLAG_* bits.
        ("flags", c_uint32),
        # Identifier, e.g. "beta_imu".
        ("name", c_char_p),
        # Unit, e.g. "rad/s"; "1" for dimensionless.
        ("unit", c_char_p),
        # Meaning and the source of the default.
        ("description", c_char_p),
        ("default_value", c_double),
        # Smallest accepted value (inclusive), besides 0 where ORIENT_PARAM_FLAG_ZERO_OFF
        # is set. Subnormal values are never accepted.
        ("min", c_double),
        # Largest accepted value (inclusive).
        ("max", c_double),
    ]


class OrientJoint(Structure):
    """One joint of a rig: segment indices (a segment is one sensor with its filter, by its
    index in the filters array of orient_joints_update) and axes in the sensors' frames
    (normalised: any length whose square is a normal finite double).
    """

    _fields_ = [
        # ORIENT_JOINT_HINGE or ORIENT_JOINT_TWO_DOF.
        ("kind", c_int32),
        # The parent segment.
        ("parent", c_uint32),
        # The child segment.
        ("child", c_uint32),
        # ORIENT_JOINT_AXES_SENSOR (0): the axes below are in the sensors' frames;
        # ORIENT_JOINT_AXES_SEGMENT: in the segments' frames (anatomical axes), turned into
        # the sensors' through orient_joints_new's mountings.
        ("axes_frame", c_uint32),
        # The (first) axis in the parent's frame.
        ("axis_parent", OrientVec3),
        # The hinge's axis, or the second axis of a 2-DoF joint, in the child's frame.
        ("axis_child", OrientVec3),
    ]


class OrientSample(Structure):
    """One sensor sample (88 bytes)."""

    _fields_ = [
        # Seconds since the previous sample; finite, at least 1e-9 and at most 1e6.
        ("dt", c_double),
        # Angular rate, rad/s, sensor frame.
        ("gyro", OrientVec3),
        # Specific force, m/s^2, sensor frame (reads about +9.81 along "up" at rest).
        ("accel", OrientVec3),
        # Magnetic field, any unit consistent over the run (uT in the examples).
        ("mag", OrientVec3),
        # ORIENT_SAMPLE_* bits saying which fields hold readings; other bits must be 0.
        # Fields whose bit is clear are ignored, whatever they hold.
        ("flags", c_uint32),
        # Must be 0.
        ("reserved", c_uint32),
    ]


class OrientJointAxes(Structure):
    """A joint's axes estimated from motion (orient_estimate_hinge_axes,
    orient_estimate_two_dof_axes).
    """

    _fields_ = [
        # The (first) axis in the parent sensor's frame (unit, on the side of the guess).
        ("axis_parent", OrientVec3),
        # The hinge's axis, or the 2-DoF joint's second axis, in the child sensor's frame
        # (unit, on the side of the guess).
        ("axis_child", OrientVec3),
        # How far the motion bears the axes out, 0 to 1; below 0.1 they can be trusted. A
        # hinge: RMS residual over RMS angular rate perpendicular to the axis (0 for an
        # ideal hinge, a few hundredths with laxity and noise, near 1 when the motion did
        # not turn the joint or the joint is no hinge). A 2-DoF joint: the larger of the RMS
        # residual (rad, how far from perpendicular the axes were seen) and three times the
        # axes' standard error (rad, large when the motion did not turn the joint about both
        # axes far enough, as a hinge's does not).
        ("quality", c_double),
    ]


class OrientEuler(Structure):
    """Euler angles, radians, intrinsic Z-Y'-X'': R = Rz(yaw) * Ry(pitch) * Rx(roll)."""

    _fields_ = [
        # About the earth z axis, (-pi, pi].
        ("yaw", c_double),
        # [-pi/2, pi/2].
        ("pitch", c_double),
        # (-pi, pi].
        ("roll", c_double),
    ]


class OrientUncertainty(Structure):
    """One standard deviation of the orientation's error, radians, from the kinds that model
    it (orient_filter_uncertainty). A field whose ORIENT_UNCERTAINTY_* bit in `present` is
    clear holds NaN.
    """

    _fields_ = [
        # ORIENT_UNCERTAINTY_* bits of the fields that hold values.
        ("present", c_uint32),
        # 0.
        ("reserved", c_uint32),
        # Heading error about the earth's vertical: EKF from its covariance; robust from its
        # heading error model, growing while the magnetometer is distrusted or absent and
        # settling while it is used (orient_filter_uncertainty says to what).
        ("heading", c_double),
        # Inclination error (tilt of the estimated vertical): EKF, from its covariance.
        ("inclination", c_double),
    ]


#: Every function of the header: name -> (restype, argtypes).
PROTOTYPES = {
    "orient_filter_update_arrays": (
        c_int32,
        [
            c_void_p,
            c_size_t,
            POINTER(c_double),
            c_size_t,
            POINTER(c_double),
            POINTER(c_double),
            POINTER(c_double),
            POINTER(OrientQuaternion),
            POINTER(c_uint32),
            POINTER(OrientDiagnostics),
            POINTER(c_size_t),
        ],
    ),
    "orient_filter_set_sensor_model": (c_int32, [c_void_p, c_uint32, POINTER(OrientSensorModel)]),
    "orient_filter_sensor_model": (c_int32, [c_void_p, c_uint32, POINTER(OrientSensorModel)]),
    "orient_mag_calibrator_init": (c_int32, [POINTER(OrientMagCalibrator)]),
    "orient_mag_calibrator_add": (c_int32, [POINTER(OrientMagCalibrator), POINTER(OrientVec3)]),
    "orient_mag_calibrator_solve": (c_int32, [POINTER(OrientMagCalibrator), POINTER(OrientMagFit)]),
    "orient_mag_calibrator_rejected": (c_int32, [POINTER(OrientMagCalibrator), POINTER(c_uint64)]),
    "orient_gyro_offset": (
        c_int32,
        [
            POINTER(OrientVec3),
            c_size_t,
            POINTER(OrientSensorModel),
            POINTER(c_double),
        ],
    ),
    "orient_config_default": (c_int32, [c_int32, POINTER(OrientConfig)]),
    "orient_config_set_param": (c_int32, [POINTER(OrientConfig), c_uint32, c_double]),
    "orient_config_get_param": (c_int32, [POINTER(OrientConfig), c_uint32, POINTER(c_double)]),
    "orient_param_count": (c_int32, [c_int32, POINTER(c_uint32)]),
    "orient_param_info": (c_int32, [c_int32, c_uint32, POINTER(OrientParamInfo)]),
    "orient_param_find": (c_int32, [c_int32, c_char_p, POINTER(c_uint32)]),
    "orient_filter_set_param": (c_int32, [c_void_p, c_uint32, c_double]),
    "orient_filter_get_param": (c_int32, [c_void_p, c_uint32, POINTER(c_double)]),
    "orient_filter_new": (c_int32, [POINTER(OrientConfig), POINTER(c_void_p)]),
    "orient_filter_free": (c_int32, [c_void_p]),
    "orient_filter_kind": (c_int32, [c_void_p, POINTER(c_int32)]),
    "orient_version": (c_char_p, []),
    "orient_abi_version": (c_uint32, []),
    "orient_status_message": (c_char_p, [c_int32]),
    "orient_last_error": (c_char_p, []),
    "orient_madgwick_beta": (c_double, [c_double]),
    "orient_config_for_joints": (c_int32, [POINTER(OrientConfig)]),
    "orient_joints_new": (
        c_int32,
        [
            POINTER(OrientJoint),
            c_size_t,
            c_size_t,
            POINTER(OrientQuaternion),
            POINTER(c_void_p),
        ],
    ),
    "orient_joints_free": (c_int32, [c_void_p]),
    "orient_joints_update": (
        c_int32,
        [
            c_void_p,
            POINTER(c_void_p),
            POINTER(OrientSample),
            c_size_t,
        ],
    ),
    "orient_joints_segment_quaternion": (c_int32, [c_void_p, c_size_t, POINTER(OrientQuaternion)]),
    "orient_joints_angles": (c_int32, [c_void_p, c_size_t, POINTER(c_double)]),
    "orient_joints_rating": (c_int32, [c_void_p, c_size_t, POINTER(c_double)]),
    "orient_joints_relative_heading": (
        c_int32,
        [
            c_void_p,
            c_size_t,
            POINTER(c_double),
            POINTER(c_double),
        ],
    ),
    "orient_joints_axes": (c_int32, [c_void_p, c_size_t, POINTER(OrientVec3), POINTER(OrientVec3)]),
    "orient_joints_reset": (c_int32, [c_void_p]),
    "orient_joints_state_size": (c_int32, [c_void_p, POINTER(c_size_t)]),
    "orient_joints_save": (c_int32, [c_void_p, POINTER(c_uint8), c_size_t, POINTER(c_size_t)]),
    "orient_joint_param_count": (c_int32, [POINTER(c_uint32)]),
    "orient_joint_param_info": (c_int32, [c_uint32, POINTER(OrientParamInfo)]),
    "orient_joints_get_param": (c_int32, [c_void_p, c_char_p, POINTER(c_double)]),
    "orient_joints_set_param": (c_int32, [c_void_p, c_char_p, c_double]),
    "orient_joints_load": (c_int32, [c_void_p, POINTER(c_uint8), c_size_t]),
    "orient_estimate_hinge_axes": (
        c_int32,
        [
            POINTER(OrientVec3),
            POINTER(OrientVec3),
            c_size_t,
            OrientVec3,
            OrientVec3,
            POINTER(OrientJointAxes),
        ],
    ),
    "orient_estimate_two_dof_axes": (
        c_int32,
        [
            POINTER(OrientQuaternion),
            POINTER(OrientQuaternion),
            c_size_t,
            OrientVec3,
            OrientVec3,
            POINTER(OrientJointAxes),
        ],
    ),
    "orient_smooth_config_default": (c_int32, [POINTER(OrientConfig)]),
    "orient_smooth_memory": (c_int32, [c_size_t, POINTER(c_size_t)]),
    "orient_smooth_arrays": (
        c_int32,
        [
            POINTER(OrientConfig),
            c_size_t,
            POINTER(c_double),
            c_size_t,
            POINTER(c_double),
            POINTER(c_double),
            POINTER(c_double),
            POINTER(OrientQuaternion),
            POINTER(c_size_t),
        ],
    ),
    "orient_filter_quaternion": (c_int32, [c_void_p, POINTER(OrientQuaternion)]),
    "orient_filter_euler": (c_int32, [c_void_p, POINTER(OrientEuler)]),
    "orient_filter_rotation_matrix": (c_int32, [c_void_p, POINTER(c_double)]),
    "orient_filter_gravity": (c_int32, [c_void_p, POINTER(OrientVec3)]),
    "orient_filter_linear_accel": (c_int32, [c_void_p, POINTER(OrientVec3)]),
    "orient_filter_linear_accel_earth": (c_int32, [c_void_p, POINTER(OrientVec3)]),
    "orient_filter_diagnostics": (c_int32, [c_void_p, POINTER(OrientDiagnostics)]),
    "orient_filter_uncertainty": (c_int32, [c_void_p, POINTER(OrientUncertainty)]),
    "orient_filter_flags": (c_int32, [c_void_p, POINTER(c_uint32)]),
    "orient_filter_set_mounting": (c_int32, [c_void_p, POINTER(OrientQuaternion)]),
    "orient_filter_mounting": (c_int32, [c_void_p, POINTER(OrientQuaternion)]),
    "orient_filter_sensor_quaternion": (c_int32, [c_void_p, POINTER(OrientQuaternion)]),
    "orient_filter_set_heading": (c_int32, [c_void_p, c_double]),
    "orient_filter_reset_heading": (c_int32, [c_void_p]),
    "orient_filter_heading_offset": (c_int32, [c_void_p, POINTER(c_double)]),
    "orient_filter_set_declination": (c_int32, [c_void_p, c_double]),
    "orient_filter_declination": (c_int32, [c_void_p, POINTER(c_double)]),
    "orient_rig_calibrate": (
        c_int32,
        [
            POINTER(c_void_p),
            POINTER(OrientQuaternion),
            c_size_t,
            c_double,
        ],
    ),
    "orient_rig_calibrate_each": (
        c_int32,
        [
            POINTER(c_void_p),
            POINTER(OrientQuaternion),
            c_size_t,
        ],
    ),
    "orient_rig_align_heading": (c_int32, [POINTER(c_void_p), POINTER(OrientQuaternion), c_size_t]),
    "orient_filter_state_size": (c_int32, [c_void_p, POINTER(c_size_t)]),
    "orient_filter_save": (c_int32, [c_void_p, POINTER(c_uint8), c_size_t, POINTER(c_size_t)]),
    "orient_filter_load": (c_int32, [c_void_p, POINTER(c_uint8), c_size_t]),
    "orient_filter_reset": (c_int32, [c_void_p]),
    "orient_filter_set_quaternion": (c_int32, [c_void_p, POINTER(OrientQuaternion)]),
    "orient_filter_update": (c_int32, [c_void_p, POINTER(OrientSample)]),
    "orient_filter_update_batch": (
        c_int32,
        [
            c_void_p,
            POINTER(OrientSample),
            c_size_t,
            POINTER(OrientQuaternion),
            POINTER(c_size_t),
        ],
    ),
    "orient_filters_update": (
        c_int32,
        [
            POINTER(c_void_p),
            POINTER(OrientSample),
            c_size_t,
            POINTER(OrientQuaternion),
            POINTER(c_size_t),
        ],
    ),
}


def _library_path() -> Path:
    """ORIENT_LIBRARY if set, else the library bundled beside this file."""
    override = os.environ.get("ORIENT_LIBRARY")
    if override:
        return Path(override)
    names = {"win32": "orient.dll", "darwin": "liborient.dylib"}
    return Path(__file__).with_name(names.get(sys.platform, "liborient.so"))


def _load() -> ctypes.CDLL:
    path = _library_path()
    lib = ctypes.CDLL(str(path))
    for name, (restype, argtypes) in PROTOTYPES.items():
        fn = getattr(lib, name)
        fn.restype = restype
        fn.argtypes = argtypes
    if lib.orient_abi_version() != ABI_VERSION:
        raise ImportError(
            f"{path}: C ABI version {lib.orient_abi_version()}, this package needs {ABI_VERSION}"
        )
    return lib


lib = _load()
