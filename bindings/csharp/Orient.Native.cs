// Orient.Native.cs: the low-level P/Invoke layer, matching include/orient.h one to one.
// Hand-written; tests/csharp_binding.rs fails when it drifts from the header (every
// exported function declared with the same parameter count, every ORIENT_* constant
// with the same value), and the Mono test checks every struct's size and offsets.
//
// IL2CPP-safe: blittable structs only (fixed buffers, no bool, no managed arrays or
// strings in structs), no callbacks, `__Internal` as the library where the player links
// the static library (iOS, Android with IL2CPP, WebGL).
using System;
using System.Runtime.InteropServices;

namespace Orient.Native
{
    /// <summary>OrientStatus: result of every fallible call (fixed numbers).</summary>
    public enum Status : int
    {
        Ok = 0,
        NullPointer = 1,
        InvalidHandle = 2,
        UnsupportedKind = 3,
        InvalidArgument = 4,
        UnknownParam = 5,
        ParamOutOfRange = 6,
        NonFinite = 7,
        InvalidDt = 8,
        ZeroVector = 9,
        TooLarge = 10,
        Saturated = 11,
        MissingSensor = 12,
        NotInitialized = 13,
        NoData = 14,
        Numeric = 15,
        CountTooLarge = 16,
        VersionMismatch = 17,
        Panic = 18,
        BufferTooSmall = 19,
        InvalidState = 20,
    }

    /// <summary>OrientKind.</summary>
    public enum Kind : int
    {
        Madgwick = 1,
        Mahony = 2,
        Complementary = 3,
        Ekf = 4,
        Gmvdk = 5,
        Robust = 6,
    }

    /// <summary>OrientFrame: the earth frame outputs are expressed in.</summary>
    public enum Frame : int
    {
        Enu = 0,
        Ned = 1,
        Nwu = 2,
    }

    /// <summary>OrientInit: how the filter gets its first orientation.</summary>
    public enum Init : int
    {
        AccMag = 0,
        Identity = 1,
        Given = 2,
    }

    /// <summary>The header's #define constants.</summary>
    public static class Consts
    {
        public const uint AbiVersion = 1; // ORIENT_ABI_VERSION
        public const uint MaxParams = 128; // ORIENT_MAX_PARAMS
        public const uint SampleGyro = 1; // ORIENT_SAMPLE_GYRO
        public const uint SampleAccel = 2; // ORIENT_SAMPLE_ACCEL
        public const uint SampleMag = 4; // ORIENT_SAMPLE_MAG
        public const uint FlagInitialized = 1; // ORIENT_FLAG_INITIALIZED
        public const uint FlagAccelUsed = 2; // ORIENT_FLAG_ACCEL_USED
        public const uint FlagMagUsed = 4; // ORIENT_FLAG_MAG_USED
        public const uint FlagGap = 8; // ORIENT_FLAG_GAP
        public const uint FlagReacquired = 16; // ORIENT_FLAG_REACQUIRED
        public const uint FlagReacquirePending = 32; // ORIENT_FLAG_REACQUIRE_PENDING
        public const uint FlagSaturated = 64; // ORIENT_FLAG_SATURATED (issue 20)
        public const uint FlagSameInstant = 128; // ORIENT_FLAG_SAME_INSTANT (issue 20)
        public const uint ParamFlagZeroOff = 1; // ORIENT_PARAM_FLAG_ZERO_OFF
        public const uint ParamGravity = 0; // ORIENT_PARAM_GRAVITY
        public const uint ParamGyroRange = 1; // ORIENT_PARAM_GYRO_RANGE
        public const uint ParamAccelRange = 2; // ORIENT_PARAM_ACCEL_RANGE
        public const uint ParamGapDt = 3; // ORIENT_PARAM_GAP_DT
        public const uint ParamSaturationRecovery = 4; // ORIENT_PARAM_SATURATION_RECOVERY (issue 20)
        public const uint ParamSameInstant = 5; // ORIENT_PARAM_SAME_INSTANT (issue 20)
        public const uint SensorGyro = 0; // ORIENT_SENSOR_GYRO (issue 20)
        public const uint SensorAccel = 1; // ORIENT_SENSOR_ACCEL
        public const uint SensorMag = 2; // ORIENT_SENSOR_MAG
        public const uint ParamMadgwickBetaImu = 8; // ORIENT_PARAM_MADGWICK_BETA_IMU
        public const uint ParamMadgwickBetaMarg = 9; // ORIENT_PARAM_MADGWICK_BETA_MARG
        public const uint ParamMadgwickRestBiasTau = 10; // ORIENT_PARAM_MADGWICK_REST_BIAS_TAU
        public const uint ParamMahonyKp = 16; // ORIENT_PARAM_MAHONY_KP
        public const uint ParamMahonyKi = 17; // ORIENT_PARAM_MAHONY_KI
        public const uint ParamMahonyRestBiasTau = 18; // ORIENT_PARAM_MAHONY_REST_BIAS_TAU
        public const uint ParamComplementaryKp = 24; // ORIENT_PARAM_COMPLEMENTARY_KP
        public const uint ParamComplementaryKi = 25; // ORIENT_PARAM_COMPLEMENTARY_KI
        public const uint ParamComplementaryGyroRest = 26; // ORIENT_PARAM_COMPLEMENTARY_GYRO_REST
        public const uint ParamComplementaryAccelRest = 27; // ORIENT_PARAM_COMPLEMENTARY_ACCEL_REST
        public const uint ParamComplementaryInitDuration = 28; // ORIENT_PARAM_COMPLEMENTARY_INIT_DURATION
        public const uint ParamComplementaryAlignHeading = 29; // ORIENT_PARAM_COMPLEMENTARY_ALIGN_HEADING
        public const uint ParamEkfTauOmega = 40; // ORIENT_PARAM_EKF_TAU_OMEGA
        public const uint ParamEkfOmegaStd = 41; // ORIENT_PARAM_EKF_OMEGA_STD
        public const uint ParamEkfTauDrift = 42; // ORIENT_PARAM_EKF_TAU_DRIFT
        public const uint ParamEkfDriftStd = 43; // ORIENT_PARAM_EKF_DRIFT_STD
        public const uint ParamEkfGyroNoise = 44; // ORIENT_PARAM_EKF_GYRO_NOISE
        public const uint ParamEkfAccelNoise = 45; // ORIENT_PARAM_EKF_ACCEL_NOISE
        public const uint ParamEkfAccelMotion = 46; // ORIENT_PARAM_EKF_ACCEL_MOTION
        public const uint ParamEkfHeadingStd = 47; // ORIENT_PARAM_EKF_HEADING_STD
        public const uint ParamEkfMotionTau = 48; // ORIENT_PARAM_EKF_MOTION_TAU
        public const uint ParamEkfHeadingTau = 49; // ORIENT_PARAM_EKF_HEADING_TAU
        public const uint ParamEkfRestRateStd = 50; // ORIENT_PARAM_EKF_REST_RATE_STD
        public const uint ParamEkfAccelAdaptTau = 51; // ORIENT_PARAM_EKF_ACCEL_ADAPT_TAU
        public const uint ParamEkfHeadingAdaptTau = 52; // ORIENT_PARAM_EKF_HEADING_ADAPT_TAU
        public const uint ParamGmvdkSlopeAlpha = 56; // ORIENT_PARAM_GMVDK_SLOPE_ALPHA
        public const uint ParamGmvdkSlopeMuk = 57; // ORIENT_PARAM_GMVDK_SLOPE_MUK
        public const uint ParamGmvdkMuWindow = 58; // ORIENT_PARAM_GMVDK_MU_WINDOW
        public const uint ParamGmvdkInitDuration = 59; // ORIENT_PARAM_GMVDK_INIT_DURATION
        public const uint ParamGmvdkActivityTau = 60; // ORIENT_PARAM_GMVDK_ACTIVITY_TAU
        public const uint ParamGmvdkGyroActivity = 61; // ORIENT_PARAM_GMVDK_GYRO_ACTIVITY
        public const uint ParamGmvdkAccelActivity = 62; // ORIENT_PARAM_GMVDK_ACCEL_ACTIVITY
        public const uint ParamGmvdkBiasWindow = 63; // ORIENT_PARAM_GMVDK_BIAS_WINDOW
        public const uint ParamGmvdkStaticAlpha = 64; // ORIENT_PARAM_GMVDK_STATIC_ALPHA
        public const uint ParamGmvdkRelativeOutput = 65; // ORIENT_PARAM_GMVDK_RELATIVE_OUTPUT
        public const uint ParamRobustTauAcc = 80; // ORIENT_PARAM_ROBUST_TAU_ACC
        public const uint ParamRobustTauMag = 81; // ORIENT_PARAM_ROBUST_TAU_MAG
        public const uint ParamRobustRestGyro = 82; // ORIENT_PARAM_ROBUST_REST_GYRO
        public const uint ParamRobustRestAccel = 83; // ORIENT_PARAM_ROBUST_REST_ACCEL
        public const uint ParamRobustRestTime = 84; // ORIENT_PARAM_ROBUST_REST_TIME
        public const uint ParamRobustRestTau = 85; // ORIENT_PARAM_ROBUST_REST_TAU
        public const uint ParamRobustBiasTauRest = 86; // ORIENT_PARAM_ROBUST_BIAS_TAU_REST
        public const uint ParamRobustBiasTauMotion = 87; // ORIENT_PARAM_ROBUST_BIAS_TAU_MOTION
        public const uint ParamRobustBiasLimit = 88; // ORIENT_PARAM_ROBUST_BIAS_LIMIT
        public const uint ParamRobustMagNormTh = 89; // ORIENT_PARAM_ROBUST_MAG_NORM_TH
        public const uint ParamRobustMagDipTh = 90; // ORIENT_PARAM_ROBUST_MAG_DIP_TH
        public const uint ParamRobustHardIronTime = 91; // ORIENT_PARAM_ROBUST_HARD_IRON_TIME
        public const uint ParamRobustRestTilt = 92; // ORIENT_PARAM_ROBUST_REST_TILT
        public const uint DiagGyroBias = 1; // ORIENT_DIAG_GYRO_BIAS
        public const uint DiagRest = 2; // ORIENT_DIAG_REST
        public const uint DiagAlpha = 4; // ORIENT_DIAG_ALPHA
        public const uint DiagMuKa = 8; // ORIENT_DIAG_MU_KA
        public const uint DiagMuKm = 16; // ORIENT_DIAG_MU_KM
        public const uint DiagMuK = 32; // ORIENT_DIAG_MU_K
        public const uint DiagRate = 64; // ORIENT_DIAG_RATE
        public const uint DiagCovariance = 128; // ORIENT_DIAG_COVARIANCE
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct Vec3
    {
        public double X, Y, Z;
        public Vec3(double x, double y, double z) { X = x; Y = y; Z = z; }
    }

    /// <summary>Hamilton quaternion, scalar first; sensor to earth.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Quaternion
    {
        public double W, X, Y, Z;
        public Quaternion(double w, double x, double y, double z) { W = w; X = x; Y = y; Z = z; }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct Euler
    {
        public double Yaw, Pitch, Roll;
    }

    /// <summary>OrientSample (88 bytes).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Sample
    {
        public double Dt;
        public Vec3 Gyro;
        public Vec3 Accel;
        public Vec3 Mag;
        public uint Flags;
        public uint Reserved;
    }

    /// <summary>OrientConfig (1072 bytes).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct Config
    {
        public uint StructSize;
        public int Kind;
        public int Frame;
        public int Init;
        public Quaternion Initial;
        public fixed double Params[128];
    }

    /// <summary>OrientSensorModel: calibrated = Matrix (raw - Offset), Matrix row-major.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct SensorModel
    {
        public fixed double Matrix[9];
        public Vec3 Offset;
    }

    /// <summary>OrientMagCalibrator: a magnetometer calibrator's sums, owned by the host.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct MagCalibrator
    {
        public fixed double Sums[55];
        public double Scale;
        public Vec3 Mean;
        public ulong Count;
        public ulong Bins;
    }

    /// <summary>OrientMagFit: what orient_mag_calibrator_solve found.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct MagFit
    {
        public SensorModel Model;
        public double Field;
        public double Residual;
        public double Coverage;
        public ulong Samples;
        public int Trustworthy;
        public int Reserved;
    }

    /// <summary>OrientParamInfo; the strings are static UTF-8 owned by the library.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ParamInfo
    {
        public uint Id;
        public uint Flags; // ORIENT_PARAM_FLAG_*
        public IntPtr Name;
        public IntPtr Unit;
        public IntPtr Description;
        public double DefaultValue;
        public double Min;
        public double Max;
    }

    /// <summary>OrientDiagnostics (176 bytes); absent fields hold NaN.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct Diagnostics
    {
        public uint Present;
        public uint Reserved;
        public Vec3 GyroBias;
        public double Rest;
        public double Alpha;
        public double MuKa;
        public double MuKm;
        public double MuK;
        public Vec3 Rate;
        public fixed double Covariance[10];
    }

    /// <summary>The C functions. Handles are IntPtr (the wrapper keeps them in a SafeHandle).</summary>
    public static class NativeMethods
    {
        // iOS and Android players link the static liborient.a into the app (IL2CPP on
        // Android: the Mono backend cannot use a static library), and Unity names code
        // linked into its own binary "__Internal". Everywhere else (the Editor, Windows,
        // macOS, Linux) the shared library is loaded by name: orient.dll, liborient.dylib,
        // liborient.so.
#if (UNITY_IOS || UNITY_ANDROID || UNITY_WEBGL) && !UNITY_EDITOR
        public const string Library = "__Internal";
#else
        public const string Library = "orient";
#endif

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern IntPtr orient_version();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern uint orient_abi_version();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern IntPtr orient_status_message(int status);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern IntPtr orient_last_error();

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern double orient_madgwick_beta(double gyroError);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_config_default(int kind, out Config config);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_config_set_param(ref Config config, uint id, double value);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_config_get_param(ref Config config, uint id, out double value);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_param_count(int kind, out uint count);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_param_info(int kind, uint index, out ParamInfo info);

        /// <param name="name">NUL-terminated UTF-8 bytes.</param>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_param_find(int kind, byte[] name, out uint id);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_new(ref Config config, out IntPtr filter);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_free(IntPtr filter);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_kind(IntPtr filter, out int kind);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_set_param(IntPtr filter, uint id, double value);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_get_param(IntPtr filter, uint id, out double value);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_update(IntPtr filter, ref Sample sample);

        /// <param name="quaternions">null, or room for n quaternions.</param>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern unsafe Status orient_filter_update_batch(
            IntPtr filter, Sample* samples, UIntPtr n, Quaternion* quaternions, UIntPtr* processed);

        /// <summary>One frame of a multi-sensor rig: filters[i] takes samples[i].</summary>
        /// <param name="quaternions">null, or room for n quaternions.</param>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern unsafe Status orient_filters_update(
            IntPtr* filters, Sample* samples, UIntPtr n, Quaternion* quaternions, UIntPtr* processed);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_quaternion(IntPtr filter, out Quaternion q);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_euler(IntPtr filter, out Euler euler);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern unsafe Status orient_filter_rotation_matrix(IntPtr filter, double* matrix);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_gravity(IntPtr filter, out Vec3 gravity);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_linear_accel(IntPtr filter, out Vec3 accel);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_linear_accel_earth(IntPtr filter, out Vec3 accel);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_diagnostics(IntPtr filter, out Diagnostics diagnostics);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_state_size(IntPtr filter, out UIntPtr size);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_save(IntPtr filter, byte[] buffer, UIntPtr capacity, out UIntPtr written);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_load(IntPtr filter, byte[] buffer, UIntPtr size);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_flags(IntPtr filter, out uint flags);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_reset(IntPtr filter);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_set_quaternion(IntPtr filter, ref Quaternion q);

        // ---- mounting, heading, declination, rig calibration (issue 20) ----

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_set_mounting(IntPtr filter, ref Quaternion mounting);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_mounting(IntPtr filter, out Quaternion mounting);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_sensor_quaternion(IntPtr filter, out Quaternion q);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_set_heading(IntPtr filter, double yaw);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_reset_heading(IntPtr filter);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_heading_offset(IntPtr filter, out double offset);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_set_declination(IntPtr filter, double declination);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_declination(IntPtr filter, out double declination);

        /// <summary>Rig calibration: n filters and n reference orientations; heading NaN = estimate.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern unsafe Status orient_rig_calibrate(
            IntPtr* filters, Quaternion* references, UIntPtr n, double heading);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern unsafe Status orient_rig_align_heading(
            IntPtr* filters, Quaternion* references, UIntPtr n);

        // ---- sensor calibration (issue 20) ----

        /// <summary>model null clears the sensor's model.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern unsafe Status orient_filter_set_sensor_model(IntPtr filter, uint sensor, SensorModel* model);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_filter_sensor_model(IntPtr filter, uint sensor, out SensorModel model);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_mag_calibrator_init(out MagCalibrator calibrator);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_mag_calibrator_add(ref MagCalibrator calibrator, ref Vec3 mag);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern Status orient_mag_calibrator_solve(ref MagCalibrator calibrator, out MagFit fit);

        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern unsafe Status orient_gyro_offset(Vec3* readings, UIntPtr n, out SensorModel model, double* spread);

        /// <summary>Batch update from arrays: gyro, accel and mag hold 3n doubles each
        /// (accel and mag may be null), dt holds dtCount (1 or n) doubles.</summary>
        /// <param name="quaternions">null, or room for n quaternions; flags and diagnostics likewise.</param>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl)]
        public static extern unsafe Status orient_filter_update_arrays(
            IntPtr filter, UIntPtr n, double* dt, UIntPtr dtCount, double* gyro, double* accel, double* mag,
            Quaternion* quaternions, uint* flags, Diagnostics* diagnostics, UIntPtr* processed);
    }
}
