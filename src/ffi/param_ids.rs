//! Parameter slots for C. Generated from the parameter tables (each kind's `settings!`,
//! `params::COMMON` and the slot map `params::BLOCKS`) by the test
//! `param_ids_are_generated_from_the_tables` in `src/ffi/render.rs`; do not edit.
//! Regenerate: ORIENT_BLESS=1 cargo test -p orient --lib generated_from_the_tables

/// Number of parameter slots in `OrientConfig.params`. Slots 0-7 are common to every
/// kind; each kind has its own block (Madgwick 8-15, Mahony 16-23, complementary 24-39,
/// EKF 40-55, GMVDK 56-79, robust 80-103); 104-127 are free for later versions.
pub const ORIENT_MAX_PARAMS: usize = 128;

/// Parameter slot (every kind): Gravity magnitude for the gravity and linear-acceleration
/// outputs; default 9.80665 (orient: standard gravity, CGPM 1901).
///
/// Unit m/s^2; range 0.001 to 1000; default 9.80665.
pub const ORIENT_PARAM_GRAVITY: u32 = 0;

/// Parameter slot (every kind): Gyroscope full scale: a sample with any axis at or beyond
/// it is rejected as saturated; 0 turns the check off (default; orient: the range is the
/// sensor's, which a configuration has to give).
///
/// Unit rad/s; range 0 (off) or 0.1 to 10000; default 0.
pub const ORIENT_PARAM_GYRO_RANGE: u32 = 1;

/// Parameter slot (every kind): Accelerometer full scale: a sample with any axis at or
/// beyond it is rejected as saturated; 0 turns the check off (default; orient: as
/// gyro_range).
///
/// Unit m/s^2; range 0 (off) or 1 to 100000; default 0.
pub const ORIENT_PARAM_ACCEL_RANGE: u32 = 2;

/// Parameter slot (every kind): Longest dt taken as given: a larger dt is a gap in the
/// data (dropped packets), and the update re-acquires the orientation from the sensors
/// instead of integrating over it (GAP and REACQUIRED flags); default 0.25 (orient: over
/// a quarter second a hand's rate changes enough that integrating the next sample's rate
/// errs more than one accelerometer reading; 10 periods of a 40 Hz sensor); 0 turns it
/// off.
///
/// Unit s; range 0 (off) or 0.001 to 1000000; default 0.25.
pub const ORIENT_PARAM_GAP_DT: u32 = 3;

/// Parameter slot (every kind): What a reading at or beyond gyro_range or accel_range
/// does: 0 (default; orient: a clipped reading is wrong, so by default it is refused)
/// rejects the sample as saturated; 1 uses it clipped (a gyroscope reading clipped just
/// under the range, a saturated accelerometer reading left out), sets the SATURATED flag,
/// and after gyroscope saturation re-acquires the orientation from the next unsaturated
/// sample with an accelerometer reading (x-io Fusion's angular-rate recovery). The
/// physical bounds stay errors.
///
/// Unit 1; range 0 (off) or 1 to 1; default 0.
pub const ORIENT_PARAM_SATURATION_RECOVERY: u32 = 4;

/// Parameter slot (every kind): What a sample with dt = 0 does (bursts of packets with
/// one timestamp): 0 (default; orient: dt = 0 is an error unless the host says its sensor
/// sends bursts) rejects it as an invalid dt; 1 takes it as the same instant as the next
/// sample with dt > 0: nothing is integrated then, its gyroscope reading is averaged with
/// the following ones up to and including that sample, which integrates the average over
/// its dt, so no rotation is lost (the SAME_INSTANT flag is set). Its accelerometer and
/// magnetometer readings are not used.
///
/// Unit 1; range 0 (off) or 1 to 1; default 0.
pub const ORIENT_PARAM_SAME_INSTANT: u32 = 5;

/// Parameter slot (madgwick): Gradient step beta for steps without magnetometer, eq.
/// (30); default 0.041 (paper: Madgwick 2010, section V, optimum of the IMU
/// implementation). beta = sqrt(3/4) * max gyro error, eq. (33). The step follows the
/// normalised gradient, so the estimate wanders by about beta * dt rad RMS at rest (0.6
/// deg at beta 1 and 100 Hz).
///
/// Unit rad/s; range 0 to 100; default 0.041.
pub const ORIENT_PARAM_MADGWICK_BETA_IMU: u32 = 8;

/// Parameter slot (madgwick): Gradient step beta for steps with magnetometer, eq. (30);
/// default 0.041, the paper's IMU optimum (section V). The paper's MARG optimum, 0.033,
/// was found for its own sensor (beta scales with gyro error, eq. (33)); on BROAD it
/// scores 7.79 deg against 7.22 for 0.041, which is also the Python ahrs reference's
/// value. At rest the estimate wanders by about beta * dt rad RMS, as with beta_imu.
///
/// Unit rad/s; range 0 to 100; default 0.041.
pub const ORIENT_PARAM_MADGWICK_BETA_MARG: u32 = 9;

/// Parameter slot (madgwick): orient option: learn the gyro bias at detected rest (2
/// deg/s, 0.5 m/s^2, 0.5 deg tilt for 1.5 s) with this time constant and subtract it;
/// default 0 = off (the paper has no bias estimate in this form).
///
/// Unit s; range 0 (off) or 0.001 to 3600; default 0.
pub const ORIENT_PARAM_MADGWICK_REST_BIAS_TAU: u32 = 10;

/// Parameter slot (mahony): Proportional gain on the direction error (Mahony 2008);
/// default 0.5 as in the GMVDK paper's comparison and BROAD's baseline.
///
/// Unit 1/s; range 0 to 1000; default 0.5.
pub const ORIENT_PARAM_MAHONY_KP: u32 = 16;

/// Parameter slot (mahony): Integral gain for the gyroscope bias (Mahony 2008); default 0
/// (no bias estimation) as in the GMVDK paper's comparison. Set to 0 with rest_bias_tau
/// also 0, the bias estimate is dropped.
///
/// Unit 1/s^2; range 0 to 1000; default 0.
pub const ORIENT_PARAM_MAHONY_KI: u32 = 17;

/// Parameter slot (mahony): orient option: at detected rest (2 deg/s, 0.5 m/s^2, 0.5 deg
/// tilt for 1.5 s) the bias b follows the low-passed gyro with this time constant;
/// default 0 = off (Mahony's filter).
///
/// Unit s; range 0 (off) or 0.001 to 3600; default 0.
pub const ORIENT_PARAM_MAHONY_REST_BIAS_TAU: u32 = 18;

/// Parameter slot (complementary): Proportional gain K_P, eq. (4), applied only at rest;
/// default 1.0 (the paper gives no value: 1 s attitude time constant at rest).
///
/// Unit 1/s; range 0 to 1000; default 1.
pub const ORIENT_PARAM_COMPLEMENTARY_KP: u32 = 24;

/// Parameter slot (complementary): Integral gain K_I for the gyro bias, eqs. (5) and
/// (10), applied only at rest; default 0.01 (the paper gives no value): stable for rests
/// up to 100 s apart, since the loop gain per rest is about K_I * motion time / K_P and
/// must stay below 2.
///
/// Unit 1/s^2; range 0 to 1000; default 0.01.
pub const ORIENT_PARAM_COMPLEMENTARY_KI: u32 = 25;

/// Parameter slot (complementary): Rest when |gyro - start-up mean gyro| is below this;
/// default 0.02 (about 3x the per-sample noise floor of the paper's 0.03 deg/s/sqrt(Hz)
/// gyro at 100 Hz).
///
/// Unit rad/s; range 0 to 100; default 0.02.
pub const ORIENT_PARAM_COMPLEMENTARY_GYRO_REST: u32 = 26;

/// Parameter slot (complementary): Rest when | |accel| - g0 | is below this (g0: start-up
/// mean); default 0.2 (about 3x the per-sample noise floor of the paper's 650 ug/sqrt(Hz)
/// accelerometer).
///
/// Unit m/s^2; range 0 to 100; default 0.2.
pub const ORIENT_PARAM_COMPLEMENTARY_ACCEL_REST: u32 = 27;

/// Parameter slot (complementary): Stationary start-up period giving the initial bias and
/// attitude (paper: 'a time period at the start of a trial'); default 2.
///
/// Unit s; range 0 to 3600; default 2.
pub const ORIENT_PARAM_COMPLEMENTARY_INIT_DURATION: u32 = 28;

/// Parameter slot (complementary): 1: take north from the start-up mean magnetometer
/// reading, aligning heading with the earth frame; 0 (default, the paper): heading
/// relative to the sensor y axis.
///
/// Unit 1; range 0 to 1; default 0.
pub const ORIENT_PARAM_COMPLEMENTARY_ALIGN_HEADING: u32 = 29;

/// Parameter slot (ekf): Correlation time of the angular-rate Markov process, eq. (9)
/// (stable -1/tau form); default 0.2 (orient: the paper sets it from the motion's
/// bandwidth without a value; a few Hz for hand and body motion).
///
/// Unit s; range 0.0001 to 1000000; default 0.2.
pub const ORIENT_PARAM_EKF_TAU_OMEGA: u32 = 40;

/// Parameter slot (ekf): Stationary standard deviation of the angular rate ('limit of the
/// magnitude of the motion', section III.A); default 3 (orient: the paper gives no value;
/// about 170 deg/s, the scale of hand and body rotation).
///
/// Unit rad/s; range 0.001 to 1000; default 3.
pub const ORIENT_PARAM_EKF_OMEGA_STD: u32 = 41;

/// Parameter slot (ekf): Correlation time of the gyro drift Markov process, eq. (10)
/// (stable -1/tau form); default 100 (orient: the paper gives no value; MEMS drift
/// changes over minutes).
///
/// Unit s; range 0.001 to 1000000000; default 100.
pub const ORIENT_PARAM_EKF_TAU_DRIFT: u32 = 42;

/// Parameter slot (ekf): Stationary standard deviation of the gyro drift; default 0.02
/// (orient: the paper gives no value; about 1 deg/s covers consumer MEMS gyroscopes'
/// typical zero-rate offset, 0.5 deg/s in the BMI270 and LSM6DSO datasheets).
///
/// Unit rad/s; range 0.000001 to 10; default 0.02.
pub const ORIENT_PARAM_EKF_DRIFT_STD: u32 = 43;

/// Parameter slot (ekf): Gyroscope noise density; default 0.05 deg/s/sqrt(Hz) (paper,
/// section IV).
///
/// Unit rad/s/sqrt(Hz); range 0.00001 to 10; default 0.0008726646259971648.
pub const ORIENT_PARAM_EKF_GYRO_NOISE: u32 = 44;

/// Parameter slot (ekf): Accelerometer noise density; default 32 ug/sqrt(Hz) (paper,
/// section IV).
///
/// Unit m/s^2/sqrt(Hz); range 0.00001 to 100; default 0.00031381279999999996.
pub const ORIENT_PARAM_EKF_ACCEL_NOISE: u32 = 45;

/// Parameter slot (ekf): Standing allowance for linear acceleration added to the
/// accelerometer noise (plus (|f|-g)^2 per sample); default 0.5 (orient: the paper's
/// model has none and tolerates 'a modicum'; real recordings need it, BROAD trial 15).
///
/// Unit m/s^2; range 0 to 1000; default 0.5.
pub const ORIENT_PARAM_EKF_ACCEL_MOTION: u32 = 46;

/// Parameter slot (ekf): Standard deviation of the magnetometer heading measurement (the
/// paper's proposed extension); default 0.1 (orient: about 6 deg for a clean field;
/// heading_tau and heading_adapt_tau raise it when it is not).
///
/// Unit rad; range 0.0001 to 10; default 0.1.
pub const ORIENT_PARAM_EKF_HEADING_STD: u32 = 47;

/// Parameter slot (ekf): Correlation time of linear acceleration: its variance is counted
/// once per 2*motion_tau/dt samples (coloured, not white, noise); default 0.5 (orient:
/// the length of a hand movement); 0 treats it as white, as the paper does.
///
/// Unit s; range 0 to 100; default 0.5.
pub const ORIENT_PARAM_EKF_MOTION_TAU: u32 = 48;

/// Parameter slot (ekf): Correlation time of magnetic heading errors: the heading
/// variance is counted once per 2*heading_tau/dt samples; default 1 (orient: disturbances
/// change as the sensor moves through a room's field); 0 treats them as white.
///
/// Unit s; range 0 to 1000; default 1.
pub const ORIENT_PARAM_EKF_HEADING_TAU: u32 = 49;

/// Parameter slot (ekf): orient option: at detected rest (2 deg/s, 0.5 m/s^2, 0.5 deg
/// tilt for 1.5 s) add the pseudo-measurement omega = 0 with this standard deviation
/// (zero-rate update), which pins the drift delta to the resting gyro; default 0 = off
/// (the paper).
///
/// Unit rad/s; range 0 (off) or 0.000001 to 10; default 0.
pub const ORIENT_PARAM_EKF_REST_RATE_STD: u32 = 50;

/// Parameter slot (ekf): Time constant of the accelerometer innovation's running power;
/// the measurement variance is at least that power (colour-scaled), so sustained linear
/// acceleration is trusted less (innovation-based adaptive noise, where the paper only
/// allows 'a modicum'); default 2 (BROAD mean 9D within 0.15 deg over 1-5 s); 0 = off.
///
/// Unit s; range 0 (off) or 0.001 to 1000; default 2.
pub const ORIENT_PARAM_EKF_ACCEL_ADAPT_TAU: u32 = 51;

/// Parameter slot (ekf): Time constant of the heading innovation's running power, which
/// likewise bounds the heading variance from below, so a disturbed field is trusted less;
/// default 2 (orient: as accel_adapt_tau; BROAD trial 32 goes from 25.3 to 2.8 deg); 0 =
/// off.
///
/// Unit s; range 0 (off) or 0.001 to 1000; default 2.
pub const ORIENT_PARAM_EKF_HEADING_ADAPT_TAU: u32 = 52;

/// Parameter slot (gmvdk): SlopeAlpha of Appendix B.1: alpha = max(0, stillness*slope + 1
/// - slope); default 1.0 (paper).
///
/// Unit 1; range 0 to 100; default 1.
pub const ORIENT_PARAM_GMVDK_SLOPE_ALPHA: u32 = 56;

/// Parameter slot (gmvdk): SlopeMuk of Appendix B.2 / eq. (20): muKA = 1 - slope*lambda;
/// default 1.5 (paper).
///
/// Unit 1/rad; range 0 to 100; default 1.5.
pub const ORIENT_PARAM_GMVDK_SLOPE_MUK: u32 = 57;

/// Parameter slot (gmvdk): Window of the running minimum mu2 of mu1 (section 2.2.2);
/// default 0.4 (paper).
///
/// Unit s; range 0 to 60; default 0.4.
pub const ORIENT_PARAM_GMVDK_MU_WINDOW: u32 = 58;

/// Parameter slot (gmvdk): Static start-up period averaging A_init, M_init and the first
/// gyro bias; default 1 (orient: the paper averages a static start-up period without
/// giving its length).
///
/// Unit s; range 0 to 3600; default 1.
pub const ORIENT_PARAM_GMVDK_INIT_DURATION: u32 = 59;

/// Parameter slot (gmvdk): Time constant of the mean-square activity averages behind
/// stillness; default 0.1 (orient: the paper reads Stillness from its sensor module; with
/// 0.1 s, alpha falls within a tenth of a second of the start of motion).
///
/// Unit s; range 0.0001 to 100; default 0.1.
pub const ORIENT_PARAM_GMVDK_ACTIVITY_TAU: u32 = 60;

/// Parameter slot (gmvdk): Gyro activity scale: RMS de-biased rate at which stillness
/// reaches 0 (with no accelerometer activity, at sqrt(2) times it); default 0.5 (orient:
/// about 30 deg/s, slow deliberate motion).
///
/// Unit rad/s; range 0.000001 to 100; default 0.5.
pub const ORIENT_PARAM_GMVDK_GYRO_ACTIVITY: u32 = 61;

/// Parameter slot (gmvdk): Accelerometer activity scale: RMS deviation of |a| from its
/// start-up value at which stillness reaches 0 (alone: sqrt(2) times it); default 1.0
/// (orient: about 0.1 g of linear acceleration).
///
/// Unit m/s^2; range 0.000001 to 1000; default 1.
pub const ORIENT_PARAM_GMVDK_ACCEL_ACTIVITY: u32 = 62;

/// Parameter slot (gmvdk): Static run length for the linear-regression gyro de-biasing of
/// the paper's step 1; default 1.0 (orient: the paper's 'window of consecutive samples'
/// has no length).
///
/// Unit s; range 0.001 to 3600; default 1.
pub const ORIENT_PARAM_GMVDK_BIAS_WINDOW: u32 = 63;

/// Parameter slot (gmvdk): alpha at or above which the sensor counts as static for
/// de-biasing; default 0.95 (orient: the paper says 'estimated to be static' without a
/// threshold).
///
/// Unit 1; range 0 to 1; default 0.95.
pub const ORIENT_PARAM_GMVDK_STATIC_ALPHA: u32 = 64;

/// Parameter slot (gmvdk): 1: report orientation relative to the start-up pose (the
/// paper's output); 0 (default): in the configured earth frame.
///
/// Unit 1; range 0 to 1; default 0.
pub const ORIENT_PARAM_GMVDK_RELATIVE_OUTPUT: u32 = 65;

/// Parameter slot (robust): Time constant of the accelerometer low-pass (2nd-order
/// Butterworth, cutoff sqrt(2)/(2 pi tau)) in the quasi-inertial frame; default 2.5
/// (orient: long enough to average out hand and body accelerations; BROAD scores vary by
/// under 0.03 deg over 2.5-3 s).
///
/// Unit s; range 0.001 to 1000; default 2.5.
pub const ORIENT_PARAM_ROBUST_TAU_ACC: u32 = 80;

/// Parameter slot (robust): Time constant of the magnetometer heading correction; default
/// 9 (VQF's default: slow enough that a short undetected disturbance moves heading
/// little).
///
/// Unit s; range 0.001 to 1000; default 9.
pub const ORIENT_PARAM_ROBUST_TAU_MAG: u32 = 81;

/// Parameter slot (robust): Rest when the gyroscope's spread around its low-pass and the
/// low-pass itself stay below this; default 0.0349 (2 deg/s, VQF's default; MEMS biases
/// are below it); another under joints (orient_config_for_joints()), with bias_limit.
///
/// Unit rad/s; range 0 to 10; default 0.03490658503988659.
pub const ORIENT_PARAM_ROBUST_REST_GYRO: u32 = 82;

/// Parameter slot (robust): Rest when the accelerometer's spread around its low-pass
/// stays below this; default 0.5 (VQF's default).
///
/// Unit m/s^2; range 0 to 100; default 0.5.
pub const ORIENT_PARAM_ROBUST_REST_ACCEL: u32 = 83;

/// Parameter slot (robust): How long the rest conditions must hold before the sensor
/// counts as resting (0: rest_tau/2, the tilt test's window, rest_tilt); default 1.5
/// (VQF's default).
///
/// Unit s; range 0 to 3600; default 1.5.
pub const ORIENT_PARAM_ROBUST_REST_TIME: u32 = 84;

/// Parameter slot (robust): Rest also needs the accelerometer's direction to stay within
/// this angle of where the still period began (the mean of its first window of
/// rest_tau/2, or rest_time/6 when shorter, against a low-pass of that window started
/// with the period), so a slow turn under rest_gyro is not learned as bias; default
/// 0.0087 (0.5 deg, orient: 10x the direction noise after the rest low-pass of a consumer
/// MEMS accelerometer).
///
/// Unit rad; range 0 to 3.2; default 0.008726646259971648.
pub const ORIENT_PARAM_ROBUST_REST_TILT: u32 = 92;

/// Parameter slot (robust): Time constant of the low-pass that rest detection compares
/// against (the tilt test, rest_tilt, takes half of it, or rest_time/6 when shorter);
/// default 0.5 (VQF's default).
///
/// Unit s; range 0.001 to 100; default 0.5.
pub const ORIENT_PARAM_ROBUST_REST_TAU: u32 = 85;

/// Parameter slot (robust): Time constant with which the bias follows the low-passed
/// gyroscope at rest; default 1 (orient: a hand's pauses last a few seconds, of which
/// rest detection takes rest_time; shorter learns more of each pause but also more of a
/// slow turn that starts from rest below rest_gyro, docs/ACCURACY.md).
///
/// Unit s; range 0.001 to 3600; default 1.
pub const ORIENT_PARAM_ROBUST_BIAS_TAU_REST: u32 = 86;

/// Parameter slot (robust): Standard deviation the bias estimate in motion settles to
/// while the inclination correction measures the bias (sigma_m of the motion bias Kalman
/// filter, VQF's biasSigmaMotion; smaller learns faster and trusts the correction more);
/// default 5.24e-4 (0.03 deg/s, orient: with the filter's rate and acceleration terms,
/// chosen on BROAD and simulated gloves, docs/ACCURACY.md); 0 turns the estimate in
/// motion off.
///
/// Unit rad/s; range 0 (off) or 0 to 1; default 0.0005235987755982988.
pub const ORIENT_PARAM_ROBUST_BIAS_SIGMA_MOTION: u32 = 100;

/// Parameter slot (robust): Largest component the motion estimate may give the bias, and
/// its measurement error (a larger component learned at rest raises the bound for every
/// component to it); default 0.0349 (orient: 2 deg/s, VQF's biasClip and the rest
/// threshold: a larger bias would also hide rest); another under joints, with rest_gyro
/// (orient_config_for_joints()).
///
/// Unit rad/s; range 0 to 10; default 0.03490658503988659.
pub const ORIENT_PARAM_ROBUST_BIAS_LIMIT: u32 = 88;

/// Parameter slot (robust): Magnetic disturbance when the field norm deviates from the
/// reference by more than this fraction; default 0.1 (VQF's default).
///
/// Unit 1; range 0 to 10; default 0.1.
pub const ORIENT_PARAM_ROBUST_MAG_NORM_TH: u32 = 89;

/// Parameter slot (robust): Magnetic disturbance when the dip angle deviates from the
/// reference by more than this; default 0.1745 (10 deg, VQF's default).
///
/// Unit rad; range 0 to 3.2; default 0.17453292519943295.
pub const ORIENT_PARAM_ROBUST_MAG_DIP_TH: u32 = 90;

/// Parameter slot (robust): A sensor-fixed disturbance (attached magnet) is compensated
/// once its estimate has been consistent this long; default 3 (orient); 0 turns
/// compensation off.
///
/// Unit s; range 0 (off) or 0.001 to 3600; default 3.
pub const ORIENT_PARAM_ROBUST_HARD_IRON_TIME: u32 = 91;

/// Parameter slot (robust): Gyroscope rate noise density, for the heading uncertainty
/// only (eq. H1); default 1.745e-4 (orient: 0.01 deg/s/sqrt(Hz), the MPU-9250
/// datasheet's, the largest of common MEMS gyroscopes: BMI270 0.007, LSM6DSO 0.0038).
///
/// Unit rad/s/sqrt(Hz); range 0 to 1; default 0.00017453292519943296.
pub const ORIENT_PARAM_ROBUST_GYRO_NOISE: u32 = 93;

/// Parameter slot (robust): Standard deviation of the gyroscope bias before any rest, and
/// the most its uncertainty grows back to: the heading uncertainty's (eq. H1) and the
/// motion bias filter's starting and largest covariance (0 leaves that filter nothing to
/// learn); default 0.0087 (0.5 deg/s: VQF's biasSigmaInit, and the typical zero-rate
/// offset after soldering in the BMI270 and LSM6DSO datasheets).
///
/// Unit rad/s; range 0 to 10; default 0.008726646259971648.
pub const ORIENT_PARAM_ROBUST_BIAS_SIGMA: u32 = 94;

/// Parameter slot (robust): Standard deviation of the bias learned at rest: what the bias
/// uncertainty settles to during a rest, the heading uncertainty's (eq. H2) and the
/// motion bias filter's covariance; default 5.24e-4 (0.03 deg/s, VQF's biasSigmaRest).
///
/// Unit rad/s; range 0 to 10; default 0.0005235987755982989.
pub const ORIENT_PARAM_ROBUST_BIAS_SIGMA_REST: u32 = 95;

/// Parameter slot (robust): Random walk of the gyroscope bias: how fast the motion bias
/// filter lets a learned bias go (its process noise) and the heading uncertainty grows
/// with it (eq. H1); larger follows a drifting bias sooner and takes more of a fast
/// motion's scale errors for bias; 0 learns the bias at rest only; default 1.745e-4 (0.01
/// deg/s/sqrt(s): VQF's 0.1 deg/s over its biasForgettingTime of 100 s); another under
/// joints (orient_config_for_joints()).
///
/// Unit rad/s/sqrt(s); range 0 to 10; default 0.00017453292519943296.
pub const ORIENT_PARAM_ROBUST_BIAS_WALK: u32 = 96;

/// Parameter slot (robust): Standard deviation of the heading a clean accepted
/// magnetometer field gives, for the heading uncertainty only (eq. H3): the floor the
/// uncertainty settles to while an undisturbed field is used; at most 1.8, the sigma of a
/// heading uniform on the circle (eq. H4); default 0.01745 (1 deg, orient: the heading of
/// a clean field at rest against BROAD's optically aligned north, -1.5 to +1.3 deg over
/// its trials).
///
/// Unit rad; range 0 to 1.8; default 0.017453292519943295.
pub const ORIENT_PARAM_ROBUST_MAG_HEADING_SIGMA: u32 = 97;

/// Parameter slot (robust): Heading error per unit of an accepted field's deviation from
/// the reference (its dip's in rad and its norm's as a fraction), for the heading
/// uncertainty only (eq. H3): a field the norm and dip tests let through still turns the
/// heading; default 0.2 (orient: chosen by leave-one-group-out cross-validation over
/// BROAD's 14 shared trials, tools/src/bin/robust_sigma.rs: 0.1 or 0.2 in every fold).
///
/// Unit 1; range 0 to 100; default 0.2.
pub const ORIENT_PARAM_ROBUST_MAG_DEVIATION_GAIN: u32 = 98;

/// Parameter slot (robust): Heading error the gyroscope's scale and axis errors add per
/// square root of the angle turned, for the heading uncertainty only (eq. H1); default
/// 0.0075 (orient: chosen by leave-one-group-out cross-validation over BROAD's 14 shared
/// trials, tools/src/bin/robust_sigma.rs: 0.0075 in every fold).
///
/// Unit sqrt(rad); range 0 to 1; default 0.0075.
pub const ORIENT_PARAM_ROBUST_GYRO_SCALE_SIGMA: u32 = 99;
