// Orient.cs: the high-level C# API over Orient.Native (no UnityEngine dependency).
//
//   using (var f = new Orient.OrientFilter(Orient.Native.Kind.Madgwick))
//   {
//       f["beta_marg"] = 0.05;
//       f.Update(Orient.OrientFilter.Marg(0.01, gyro, accel, mag));   // throws OrientException on bad input
//       Orient.Native.Quaternion q = f.Quaternion;                     // ENU, scalar first
//   }
//
// Status codes become OrientException with the library's message. Handles live in a
// SafeHandle, so a forgotten Dispose is released by the finaliser and a double Dispose
// is harmless. Units and conventions are the library's: rad/s, m/s^2, any magnetometer
// unit, dt in seconds, Hamilton quaternions mapping sensor to earth (ENU by default).
// UnityConvert turns them into Unity's left-handed, Y-up values.
using System;
using System.Collections.Generic;
using System.Runtime.InteropServices;
using System.Text;
using Orient.Native;

namespace Orient.Native
{
    // The generated structs (Orient.Native.cs) are partial; these constructors are the
    // hand-written part.
    public partial struct Vec3
    {
        public Vec3(double x, double y, double z) { X = x; Y = y; Z = z; }
    }

    public partial struct Quaternion
    {
        public Quaternion(double w, double x, double y, double z) { W = w; X = x; Y = y; Z = z; }
    }
}

namespace Orient
{
    /// <summary>A call into the library failed; Status is its code.</summary>
    public sealed class OrientException : Exception
    {
        public Status Status { get; private set; }

        public OrientException(Status status, string message) : base(message)
        {
            Status = status;
        }

        /// <summary>Throws for any status but Ok, with the thread's last error detail.</summary>
        public static void Check(Status status)
        {
            if (status != Status.Ok)
            {
                throw new OrientException(status, LastError(status));
            }
        }

        internal static string LastError(Status status)
        {
            string detail = Marshal.PtrToStringAnsi(NativeMethods.orient_last_error());
            if (string.IsNullOrEmpty(detail))
            {
                detail = Marshal.PtrToStringAnsi(NativeMethods.orient_status_message((int)status));
            }
            return status + ": " + detail;
        }
    }

    /// <summary>Owns one OrientFilter handle; releases it exactly once.</summary>
    public sealed class FilterHandle : SafeHandle
    {
        public FilterHandle() : base(IntPtr.Zero, true) { }

        public override bool IsInvalid
        {
            get { return handle == IntPtr.Zero; }
        }

        internal void Set(IntPtr h)
        {
            SetHandle(h);
        }

        protected override bool ReleaseHandle()
        {
            return NativeMethods.orient_filter_free(handle) == Status.Ok;
        }
    }

    /// <summary>What one parameter means (for inspectors and settings screens).</summary>
    public struct ParameterInfo
    {
        public uint Id;
        public string Name;
        public string Unit;
        public string Description;
        public double Default;
        /// <summary>Smallest accepted value, besides 0 where ZeroTurnsOff.</summary>
        public double Min;
        public double Max;
        /// <summary>0 is also accepted and turns the feature off.</summary>
        public bool ZeroTurnsOff;
    }

    /// <summary>A filter configuration: kind, frame, initial orientation, parameters.</summary>
    public sealed unsafe class OrientSettings
    {
        internal Config raw;

        public OrientSettings(Kind kind)
        {
            fixed (Config* c = &raw)
            {
                OrientException.Check(NativeMethods.orient_config_default((int)kind, c));
            }
        }

        private OrientSettings()
        {
        }

        /// <summary>The offline defaults for OrientFilter.Smooth (orient_smooth_config_default):
        /// the recommended kind with a heading time constant of 27 s.</summary>
        public static unsafe OrientSettings Offline()
        {
            var s = new OrientSettings();
            fixed (Config* c = &s.raw)
            {
                OrientException.Check(NativeMethods.orient_smooth_config_default(c));
            }
            return s;
        }

        public Kind Kind
        {
            get { return (Kind)raw.Kind; }
        }

        public Frame Frame
        {
            get { return (Frame)raw.Frame; }
            set { raw.Frame = (int)value; }
        }

        public Init Init
        {
            get { return (Init)raw.Init; }
            set { raw.Init = (int)value; }
        }

        /// <summary>Used with Init.Given, in the configured frame.</summary>
        public Native.Quaternion Initial
        {
            get { return raw.Initial; }
            set { raw.Initial = value; }
        }

        /// <summary>A parameter by slot id (ORIENT_PARAM_*), range-checked on set.</summary>
        public double this[uint id]
        {
            get
            {
                double v;
                fixed (Config* c = &raw)
                {
                    OrientException.Check(NativeMethods.orient_config_get_param(c, id, &v));
                }
                return v;
            }
            set
            {
                fixed (Config* c = &raw)
                {
                    OrientException.Check(NativeMethods.orient_config_set_param(c, id, value));
                }
            }
        }

        /// <summary>Sets what a sensor's filter runs with under joints
        /// (orient_config_for_joints, whose doc in orient.h gives each value): for the
        /// recommended kind a faster bias random walk and a wider motion bias bound and rest
        /// threshold; other kinds are left as they were. Returns this.</summary>
        public OrientSettings ForJoints()
        {
            fixed (Config* c = &raw)
            {
                OrientException.Check(NativeMethods.orient_config_for_joints(c));
            }
            return this;
        }

        /// <summary>A parameter by name (see Parameters), range-checked on set.</summary>
        public double this[string name]
        {
            get { return this[OrientFilter.FindParameter(Kind, name)]; }
            set { this[OrientFilter.FindParameter(Kind, name)] = value; }
        }

        /// <summary>Gravity magnitude for the gravity and linear-acceleration outputs, m/s^2.</summary>
        public double Gravity
        {
            get { return this[Consts.ParamGravity]; }
            set { this[Consts.ParamGravity] = value; }
        }

        /// <summary>Gyroscope full scale, rad/s (0 = no saturation check).</summary>
        public double GyroRange
        {
            get { return this[Consts.ParamGyroRange]; }
            set { this[Consts.ParamGyroRange] = value; }
        }

        /// <summary>Accelerometer full scale, m/s^2 (0 = no saturation check).</summary>
        public double AccelRange
        {
            get { return this[Consts.ParamAccelRange]; }
            set { this[Consts.ParamAccelRange] = value; }
        }

        /// <summary>Every parameter of this kind, with unit, default, range and source.</summary>
        public IList<ParameterInfo> Parameters
        {
            get { return OrientFilter.ParametersOf(Kind); }
        }
    }

    /// <summary>An orientation filter of any kind.</summary>
    public sealed unsafe class OrientFilter : IDisposable
    {
        private readonly FilterHandle handle = new FilterHandle();

        public OrientFilter(Kind kind) : this(new OrientSettings(kind)) { }

        public OrientFilter(OrientSettings settings)
        {
            IntPtr h;
            Status s;
            fixed (Config* c = &settings.raw)
            {
                s = NativeMethods.orient_filter_new(c, &h);
            }
            OrientException.Check(s);
            handle.Set(h);
            Kind = settings.Kind;
            Frame = settings.Frame;
        }

        public Kind Kind { get; private set; }
        public Frame Frame { get; private set; }

        /// <summary>The library version, e.g. "0.1.0".</summary>
        public static string Version
        {
            get { return Marshal.PtrToStringAnsi(NativeMethods.orient_version()); }
        }

        /// <summary>Madgwick's beta from the maximum gyroscope error, eq. (33).</summary>
        public static double MadgwickBeta(double gyroErrorRadPerSecond)
        {
            return NativeMethods.orient_madgwick_beta(gyroErrorRadPerSecond);
        }

        private IntPtr H
        {
            get
            {
                if (handle.IsClosed || handle.IsInvalid)
                {
                    throw new ObjectDisposedException("OrientFilter");
                }
                return handle.DangerousGetHandle();
            }
        }

        public void Dispose()
        {
            handle.Dispose();
        }

        /// <summary>The native handle (throws ObjectDisposedException once disposed).</summary>
        internal IntPtr NativeHandle
        {
            get { return H; }
        }

        public bool IsDisposed
        {
            get { return handle.IsClosed; }
        }

        // ---- samples ----

        public static Sample Imu(double dt, Vec3 gyro, Vec3 accel)
        {
            Sample s = new Sample();
            s.Dt = dt;
            s.Gyro = gyro;
            s.Accel = accel;
            s.Flags = Consts.SampleGyro | Consts.SampleAccel;
            return s;
        }

        public static Sample Marg(double dt, Vec3 gyro, Vec3 accel, Vec3 mag)
        {
            Sample s = Imu(dt, gyro, accel);
            s.Mag = mag;
            s.Flags |= Consts.SampleMag;
            return s;
        }

        /// <summary>One sample; throws OrientException (state unchanged) when rejected.</summary>
        public void Update(Sample sample)
        {
            Status s = NativeMethods.orient_filter_update(H, &sample);
            GC.KeepAlive(this);
            OrientException.Check(s);
        }

        /// <summary>Like Update, returning the status instead of throwing.</summary>
        public Status TryUpdate(ref Sample sample)
        {
            Status s;
            fixed (Sample* p = &sample)
            {
                s = NativeMethods.orient_filter_update(H, p);
            }
            GC.KeepAlive(this);
            return s;
        }

        /// <summary>
        /// Updates with samples[offset .. offset+count]; when quaternions is not null it
        /// receives the orientation after each sample (from index 0). Returns the number of
        /// samples processed; throws OrientException at the first bad sample (the ones before
        /// it stay applied; its index is in the message).
        /// </summary>
        public int UpdateBatch(Sample[] samples, int offset, int count, Native.Quaternion[] quaternions)
        {
            if (samples == null) throw new ArgumentNullException("samples");
            if (offset < 0 || count < 0 || offset + count > samples.Length)
                throw new ArgumentOutOfRangeException("count");
            if (quaternions != null && quaternions.Length < count)
                throw new ArgumentException("quaternions is shorter than count", "quaternions");
            if (count == 0) return 0;
            UIntPtr processed = UIntPtr.Zero;
            Status s;
            fixed (Sample* ps = &samples[offset])
            {
                if (quaternions != null)
                {
                    fixed (Native.Quaternion* pq = quaternions)
                    {
                        s = NativeMethods.orient_filter_update_batch(H, ps, (UIntPtr)count, pq, &processed);
                    }
                }
                else
                {
                    s = NativeMethods.orient_filter_update_batch(H, ps, (UIntPtr)count, null, &processed);
                }
            }
            GC.KeepAlive(this);
            OrientException.Check(s);
            return (int)processed;
        }

        /// <summary>
        /// Offline mode (orient_smooth_arrays): the whole recording smoothed forward and
        /// backward through the kind and parameters of settings; every output uses the
        /// samples before and after it. gyro holds 3n doubles (x, y, z per sample), accel and
        /// mag likewise or null, dt 1 or n doubles. Returns the n orientations; throws
        /// OrientException at the first bad sample (its index is in the message), and with
        /// Status.OutOfMemory when the library's buffer (SmoothMemory) cannot be allocated.
        /// </summary>
        public static unsafe Native.Quaternion[] Smooth(OrientSettings settings, double[] dt, double[] gyro, double[] accel, double[] mag)
        {
            if (settings == null) throw new ArgumentNullException("settings");
            if (gyro == null) throw new ArgumentNullException("gyro");
            if (dt == null) throw new ArgumentNullException("dt");
            int n = gyro.Length / 3;
            if (gyro.Length != 3 * n || (accel != null && accel.Length != 3 * n) || (mag != null && mag.Length != 3 * n))
                throw new ArgumentException("gyro, accel and mag must hold 3 doubles per sample");
            var q = new Native.Quaternion[n];
            if (n == 0) return q;
            UIntPtr processed = UIntPtr.Zero;
            Status s;
            fixed (double* pd = dt, pg = gyro, pa = accel, pm = mag)
            fixed (Native.Quaternion* pq = q)
            fixed (Config* pc = &settings.raw)
            {
                s = NativeMethods.orient_smooth_arrays(pc, (UIntPtr)n, pd, (UIntPtr)dt.Length, pg, pa, pm, pq, &processed);
            }
            OrientException.Check(s);
            return q;
        }

        /// <summary>
        /// Bytes Smooth may allocate inside the library for n samples (orient_smooth_memory):
        /// 8 per sample plus 32768, whatever the kind, besides the returned array. Throws
        /// OrientException (CountTooLarge) above PTRDIFF_MAX / 32.
        /// </summary>
        public static unsafe ulong SmoothMemory(ulong n)
        {
            UIntPtr bytes = UIntPtr.Zero;
            OrientException.Check(NativeMethods.orient_smooth_memory((UIntPtr)n, &bytes));
            return (ulong)bytes;
        }

        public int UpdateBatch(Sample[] samples, Native.Quaternion[] quaternions)
        {
            return UpdateBatch(samples, 0, samples == null ? 0 : samples.Length, quaternions);
        }

        // ---- outputs ----

        /// <summary>Orientation, sensor to earth, in the configured frame.</summary>
        public Native.Quaternion Quaternion
        {
            get
            {
                Native.Quaternion q;
                OrientException.Check(NativeMethods.orient_filter_quaternion(H, &q));
                GC.KeepAlive(this);
                return q;
            }
            set
            {
                OrientException.Check(NativeMethods.orient_filter_set_quaternion(H, &value));
                GC.KeepAlive(this);
            }
        }

        // ---- sensor calibration (issue 20) ----

        /// <summary>Sets the model applied to one sensor's readings (Consts.SensorGyro,
        /// SensorAccel, SensorMag) before every update; null clears it.</summary>
        public unsafe void SetSensorModel(uint sensor, SensorModel? model)
        {
            Status s;
            if (model.HasValue)
            {
                SensorModel m = model.Value;
                s = NativeMethods.orient_filter_set_sensor_model(H, sensor, &m);
            }
            else
            {
                s = NativeMethods.orient_filter_set_sensor_model(H, sensor, null);
            }
            GC.KeepAlive(this);
            OrientException.Check(s);
        }

        /// <summary>The model set for the sensor, or null when none is set.</summary>
        public SensorModel? GetSensorModel(uint sensor)
        {
            SensorModel m;
            Status s = NativeMethods.orient_filter_sensor_model(H, sensor, &m);
            GC.KeepAlive(this);
            if (s == Status.NoData) return null;
            OrientException.Check(s);
            return m;
        }

        // ---- mounting and heading (issue 20) ----

        /// <summary>Sensor-to-segment rotation (v_segment = m v_sensor): Quaternion, Euler
        /// and the rotation matrix become the segment's. Identity unless set; kept by Reset
        /// and saved in snapshots. Its conjugate maps the segment's frame to the sensor's.</summary>
        public Native.Quaternion Mounting
        {
            get
            {
                Native.Quaternion q;
                OrientException.Check(NativeMethods.orient_filter_mounting(H, &q));
                GC.KeepAlive(this);
                return q;
            }
            set
            {
                OrientException.Check(NativeMethods.orient_filter_set_mounting(H, &value));
                GC.KeepAlive(this);
            }
        }

        /// <summary>The sensor's own orientation: heading offset and declination applied,
        /// the mounting not.</summary>
        public Native.Quaternion SensorQuaternion
        {
            get
            {
                Native.Quaternion q;
                OrientException.Check(NativeMethods.orient_filter_sensor_quaternion(H, &q));
                GC.KeepAlive(this);
                return q;
            }
        }

        /// <summary>Turns the outputs about the vertical so that Euler.Yaw becomes yaw
        /// (radians); inclination and mounting kept. Throws before initialisation.</summary>
        public void SetHeading(double yaw)
        {
            OrientException.Check(NativeMethods.orient_filter_set_heading(H, yaw));
            GC.KeepAlive(this);
        }

        /// <summary>SetHeading(0): yaw 0, inclination kept.</summary>
        public void ResetHeading()
        {
            OrientException.Check(NativeMethods.orient_filter_reset_heading(H));
            GC.KeepAlive(this);
        }

        /// <summary>The heading offset (radians) kept by SetHeading and the rig calls.</summary>
        public double HeadingOffset
        {
            get
            {
                double v;
                OrientException.Check(NativeMethods.orient_filter_heading_offset(H, &v));
                GC.KeepAlive(this);
                return v;
            }
        }

        /// <summary>Magnetic declination (radians, east positive, within [-pi, pi]).</summary>
        public double Declination
        {
            get
            {
                double v;
                OrientException.Check(NativeMethods.orient_filter_declination(H, &v));
                GC.KeepAlive(this);
                return v;
            }
            set
            {
                OrientException.Check(NativeMethods.orient_filter_set_declination(H, value));
                GC.KeepAlive(this);
            }
        }

        public Euler Euler
        {
            get
            {
                Euler e;
                OrientException.Check(NativeMethods.orient_filter_euler(H, &e));
                GC.KeepAlive(this);
                return e;
            }
        }

        /// <summary>Row-major rotation matrix, sensor to earth.</summary>
        public double[] RotationMatrix
        {
            get
            {
                double[] m = new double[9];
                fixed (double* p = m)
                {
                    OrientException.Check(NativeMethods.orient_filter_rotation_matrix(H, p));
                }
                GC.KeepAlive(this);
                return m;
            }
        }

        /// <summary>The accelerometer reading at rest (gravity's reaction), sensor frame, m/s^2.</summary>
        public Vec3 Gravity
        {
            get
            {
                Vec3 v;
                OrientException.Check(NativeMethods.orient_filter_gravity(H, &v));
                GC.KeepAlive(this);
                return v;
            }
        }

        /// <summary>Accelerometer minus gravity, sensor frame, m/s^2.</summary>
        public Vec3 LinearAcceleration
        {
            get
            {
                Vec3 v;
                OrientException.Check(NativeMethods.orient_filter_linear_accel(H, &v));
                GC.KeepAlive(this);
                return v;
            }
        }

        /// <summary>Linear acceleration in the earth frame, m/s^2.</summary>
        public Vec3 LinearAccelerationEarth
        {
            get
            {
                Vec3 v;
                OrientException.Check(NativeMethods.orient_filter_linear_accel_earth(H, &v));
                GC.KeepAlive(this);
                return v;
            }
        }

        public Diagnostics Diagnostics
        {
            get
            {
                Diagnostics d;
                OrientException.Check(NativeMethods.orient_filter_diagnostics(H, &d));
                GC.KeepAlive(this);
                return d;
            }
        }

        /// <summary>One standard deviation (rad) of the heading and inclination errors where
        /// the kind models them (EKF: both; robust: heading, growing while the magnetometer
        /// is distrusted or absent); a field whose bit in Present is clear is NaN.</summary>
        public Uncertainty Uncertainty
        {
            get
            {
                Uncertainty u;
                OrientException.Check(NativeMethods.orient_filter_uncertainty(H, &u));
                GC.KeepAlive(this);
                return u;
            }
        }

        public uint Flags
        {
            get
            {
                uint f;
                OrientException.Check(NativeMethods.orient_filter_flags(H, &f));
                GC.KeepAlive(this);
                return f;
            }
        }

        public bool Initialized
        {
            get { return (Flags & Consts.FlagInitialized) != 0; }
        }

        /// <summary>A versioned, checksummed snapshot of configuration and state. A filter
        /// of the same kind that loads it continues bit for bit as this one would.</summary>
        public byte[] SaveState()
        {
            UIntPtr size;
            OrientException.Check(NativeMethods.orient_filter_state_size(H, &size));
            byte[] blob = new byte[(int)size];
            UIntPtr written;
            fixed (byte* p = blob)
            {
                OrientException.Check(NativeMethods.orient_filter_save(H, p, size, &written));
            }
            GC.KeepAlive(this);
            return blob;
        }

        /// <summary>Restores SaveState's snapshot; throws OrientException (InvalidState) for
        /// a truncated, corrupted, foreign-kind or foreign-version blob, changing nothing.</summary>
        public void LoadState(byte[] blob)
        {
            if (blob == null) throw new ArgumentNullException("blob");
            byte empty = 0;
            fixed (byte* p = blob)
            {
                // An empty array pins as NULL; the library wants a pointer even for 0 bytes.
                byte* data = blob.Length == 0 ? &empty : p;
                OrientException.Check(NativeMethods.orient_filter_load(H, data, (UIntPtr)blob.Length));
            }
            GC.KeepAlive(this);
        }

        public void Reset()
        {
            OrientException.Check(NativeMethods.orient_filter_reset(H));
            GC.KeepAlive(this);
        }

        // ---- parameters ----

        /// <summary>A parameter by slot id; set changes a running filter (range-checked).</summary>
        public double this[uint id]
        {
            get
            {
                double v;
                OrientException.Check(NativeMethods.orient_filter_get_param(H, id, &v));
                GC.KeepAlive(this);
                return v;
            }
            set
            {
                OrientException.Check(NativeMethods.orient_filter_set_param(H, id, value));
                GC.KeepAlive(this);
            }
        }

        public double this[string name]
        {
            get { return this[FindParameter(Kind, name)]; }
            set { this[FindParameter(Kind, name)] = value; }
        }

        internal static uint FindParameter(Kind kind, string name)
        {
            byte[] bytes = NameBytes(name);
            uint id;
            fixed (byte* p = bytes)
            {
                OrientException.Check(NativeMethods.orient_param_find((int)kind, p, &id));
            }
            return id;
        }

        /// <summary>A parameter's name as the C calls take it: NUL-terminated UTF-8.</summary>
        internal static byte[] NameBytes(string name)
        {
            if (name == null) throw new ArgumentNullException("name");
            return Encoding.UTF8.GetBytes(name + "\0");
        }

        /// <summary>Every parameter of a kind, for inspectors.</summary>
        public static IList<ParameterInfo> ParametersOf(Kind kind)
        {
            uint n;
            OrientException.Check(NativeMethods.orient_param_count((int)kind, &n));
            List<ParameterInfo> list = new List<ParameterInfo>((int)n);
            for (uint i = 0; i < n; i++)
            {
                Native.ParamInfo info;
                OrientException.Check(NativeMethods.orient_param_info((int)kind, i, &info));
                list.Add(FromNative(info));
            }
            return list;
        }

        /// <summary>A parameter's description as the library gives it.</summary>
        internal static ParameterInfo FromNative(Native.ParamInfo info)
        {
            ParameterInfo p = new ParameterInfo();
            p.Id = info.Id;
            p.Name = Marshal.PtrToStringAnsi(info.Name);
            p.Unit = Marshal.PtrToStringAnsi(info.Unit);
            p.Description = Marshal.PtrToStringAnsi(info.Description);
            p.Default = info.DefaultValue;
            p.Min = info.Min;
            p.ZeroTurnsOff = (info.Flags & Native.Consts.ParamFlagZeroOff) != 0;
            p.Max = info.Max;
            return p;
        }
    }

    /// <summary>
    /// Conversions between orient's right-handed earth frames (ENU, NED, NWU; Z up for ENU)
    /// and Unity's left-handed, Y-up world. The map is the reflection that swaps the second
    /// and third axes: a vector (x, y, z) in ENU is (x, z, y) in Unity (east stays +X, up
    /// becomes +Y, north +Z); a rotation q = (w, x, y, z) becomes (x, y, z, w) =
    /// (-x, -z, -y, w) in Unity's component order.
    /// </summary>
    public static class UnityConvert
    {
        private const double H = 0.70710678118654752440;

        /// <summary>q_ENU = c * q_frame for a quaternion expressed in `frame`.</summary>
        public static Native.Quaternion ToEnu(Native.Quaternion q, Frame frame)
        {
            switch (frame)
            {
                case Frame.Ned:
                    return Mul(new Native.Quaternion(0, H, H, 0), q);
                case Frame.Nwu:
                    return Mul(new Native.Quaternion(H, 0, 0, H), q);
                default:
                    return q;
            }
        }

        /// <summary>An orientation (sensor to earth, `frame`) as Unity's (x, y, z, w).</summary>
        public static void ToUnity(Native.Quaternion q, Frame frame, out double x, out double y, out double z, out double w)
        {
            Native.Quaternion e = ToEnu(q, frame);
            x = -e.X;
            y = -e.Z;
            z = -e.Y;
            w = e.W;
        }

        /// <summary>Unity's (x, y, z, w) as an ENU orientation.</summary>
        public static Native.Quaternion FromUnity(double x, double y, double z, double w)
        {
            return new Native.Quaternion(w, -x, -z, -y);
        }

        /// <summary>An ENU vector as Unity's (x, y, z).</summary>
        public static void ToUnity(Vec3 v, out double x, out double y, out double z)
        {
            x = v.X;
            y = v.Z;
            z = v.Y;
        }

        /// <summary>Unity's (x, y, z) as an ENU vector.</summary>
        public static Vec3 FromUnity(double x, double y, double z)
        {
            return new Vec3(x, z, y);
        }

        /// <summary>Hamilton product a * b.</summary>
        public static Native.Quaternion Mul(Native.Quaternion a, Native.Quaternion b)
        {
            return new Native.Quaternion(
                a.W * b.W - a.X * b.X - a.Y * b.Y - a.Z * b.Z,
                a.W * b.X + a.X * b.W + a.Y * b.Z - a.Z * b.Y,
                a.W * b.Y - a.X * b.Z + a.Y * b.W + a.Z * b.X,
                a.W * b.Z + a.X * b.Y - a.Y * b.X + a.Z * b.W);
        }
    }

    /// <summary>
    /// A magnetometer calibrator (ellipsoid fit): Add readings while rotating the sensor
    /// over the sphere (no allocation per reading), then Solve; use the model when the
    /// fit is Trustworthy.
    /// </summary>
    public sealed class MagCalibration
    {
        private Native.MagCalibrator state;

        public unsafe MagCalibration()
        {
            fixed (Native.MagCalibrator* p = &state)
            {
                OrientException.Check(NativeMethods.orient_mag_calibrator_init(p));
            }
        }

        public unsafe void Add(Vec3 mag)
        {
            fixed (Native.MagCalibrator* p = &state)
            {
                OrientException.Check(NativeMethods.orient_mag_calibrator_add(p, &mag));
            }
        }

        /// <summary>The fit, or null while the readings do not determine an ellipsoid.</summary>
        public unsafe MagFit? Solve()
        {
            MagFit fit;
            Status s;
            fixed (Native.MagCalibrator* p = &state)
            {
                s = NativeMethods.orient_mag_calibrator_solve(p, &fit);
            }
            if (s == Status.NoData) return null;
            OrientException.Check(s);
            return fit;
        }

        /// <summary>The gyroscope offset model from readings taken while still, and their spread (rad/s).</summary>
        public static unsafe SensorModel GyroOffset(Vec3[] still, out double spread)
        {
            if (still == null) throw new ArgumentNullException("still");
            SensorModel m;
            double sp = 0;
            Status s;
            fixed (Vec3* p = still)
            {
                s = NativeMethods.orient_gyro_offset(p, (UIntPtr)still.Length, &m, &sp);
            }
            OrientException.Check(s);
            spread = sp;
            return m;
        }
    }

    /// <summary>
    /// Filters updated together, one sample each, in one native call per frame: the bones
    /// of a hand, the segments of a body. The filters may be of any kinds; the rig does not
    /// own them (dispose them yourself). Update allocates nothing.
    /// </summary>
    public sealed unsafe class OrientRig
    {
        private readonly OrientFilter[] filters;
        private readonly IntPtr[] handles;

        public OrientRig(params OrientFilter[] filters)
        {
            if (filters == null) throw new ArgumentNullException("filters");
            foreach (var f in filters)
            {
                if (f == null) throw new ArgumentNullException("filters", "a filter is null");
            }
            this.filters = (OrientFilter[])filters.Clone();
            handles = new IntPtr[filters.Length];
        }

        public int Count
        {
            get { return filters.Length; }
        }

        /// <summary>The filters' native handles into `into` (one per filter).</summary>
        internal void CopyHandles(IntPtr[] into)
        {
            for (int i = 0; i < filters.Length; i++)
            {
                into[i] = filters[i].NativeHandle;
            }
        }

        /// <summary>
        /// Updates filter i with samples[i]; when quaternions is not null it receives each
        /// filter's orientation afterwards. Throws OrientException at the first bad sample
        /// (the filters before it stay updated, it and those after are unchanged; its index
        /// is in the message).
        /// </summary>
        public void Update(Sample[] samples, Native.Quaternion[] quaternions)
        {
            if (samples == null) throw new ArgumentNullException("samples");
            if (samples.Length < filters.Length)
                throw new ArgumentException("fewer samples than filters", "samples");
            if (quaternions != null && quaternions.Length < filters.Length)
                throw new ArgumentException("quaternions is shorter than the rig", "quaternions");
            if (filters.Length == 0) return;
            for (int i = 0; i < filters.Length; i++)
            {
                handles[i] = filters[i].NativeHandle;
            }
            Status s;
            fixed (IntPtr* ph = handles)
            fixed (Sample* ps = samples)
            {
                if (quaternions != null)
                {
                    fixed (Native.Quaternion* pq = quaternions)
                    {
                        s = NativeMethods.orient_filters_update(ph, ps, (UIntPtr)filters.Length, pq, null);
                    }
                }
                else
                {
                    s = NativeMethods.orient_filters_update(ph, ps, (UIntPtr)filters.Length, null, null);
                }
            }
            GC.KeepAlive(filters);
            OrientException.Check(s);
        }

        /// <summary>
        /// Rig calibration while the segments hold a reference posture (N-pose, T-pose, a
        /// hand flat on a table): references[i] is filter i's segment orientation. Sets a
        /// common heading offset and every mounting so that each filter reads its
        /// reference now and its segment afterwards. heading is the posture frame's yaw in
        /// the filters' earth frame (radians); NaN (the default) estimates it. The filters
        /// share one earth frame (a magnetometer); 6D rigs take CalibrateEach.
        /// </summary>
        public void Calibrate(Native.Quaternion[] references, double heading = double.NaN)
        {
            RigCall(references, heading, RigCallKind.Calibrate);
        }

        /// <summary>
        /// Rig calibration of 6D filters, each heading its own (orient_rig_calibrate_each):
        /// each sensor taken as strapped along its segment, each mounting is its tilt there,
        /// each heading offset its own.
        /// </summary>
        public void CalibrateEach(Native.Quaternion[] references)
        {
            RigCall(references, double.NaN, RigCallKind.CalibrateEach);
        }

        /// <summary>Heading-only alignment to the reference posture: mountings kept.</summary>
        public void AlignHeading(Native.Quaternion[] references)
        {
            RigCall(references, double.NaN, RigCallKind.AlignHeading);
        }

        private enum RigCallKind { Calibrate, CalibrateEach, AlignHeading }

        private unsafe void RigCall(Native.Quaternion[] references, double heading, RigCallKind call)
        {
            if (references == null) throw new ArgumentNullException("references");
            if (references.Length != filters.Length)
                throw new ArgumentException("one reference per filter", "references");
            for (int i = 0; i < filters.Length; i++)
            {
                handles[i] = filters[i].NativeHandle;
            }
            Status s;
            fixed (IntPtr* ph = handles)
            fixed (Native.Quaternion* pr = references)
            {
                s = call == RigCallKind.AlignHeading
                        ? NativeMethods.orient_rig_align_heading(ph, pr, (UIntPtr)filters.Length)
                    : call == RigCallKind.CalibrateEach
                        ? NativeMethods.orient_rig_calibrate_each(ph, pr, (UIntPtr)filters.Length)
                    : NativeMethods.orient_rig_calibrate(ph, pr, (UIntPtr)filters.Length, heading);
            }
            GC.KeepAlive(filters);
            OrientException.Check(s);
        }
    }

    /// <summary>Owns one OrientJoints handle; releases it exactly once.</summary>
    public sealed class JointsHandle : SafeHandle
    {
        public JointsHandle() : base(IntPtr.Zero, true) { }

        public override bool IsInvalid
        {
            get { return handle == IntPtr.Zero; }
        }

        internal void Set(IntPtr h)
        {
            SetHandle(h);
        }

        protected override bool ReleaseHandle()
        {
            return NativeMethods.orient_joints_free(handle) == Status.Ok;
        }
    }

    /// <summary>
    /// A rig's joints: each child segment held to its parent without a magnetometer (a
    /// hand's phalanges, a leg's segments). Built over an OrientRig, whose filter i is
    /// segment i; after each OrientRig.Update, Update gives every joint the same samples,
    /// then Segment gives the bone rotations and Angles the joint angles. Update allocates
    /// nothing. Dispose releases the joints (not the filters).
    /// </summary>
    public sealed unsafe class OrientJoints : IDisposable
    {
        private readonly JointsHandle handle = new JointsHandle();
        private readonly OrientRig rig;
        private readonly IntPtr[] handles;

        /// <summary>A hinge: one axis, in the parent's and in the child's sensor frame (or,
        /// with inSegmentFrames, in the segments' frames, turned into the sensors' through
        /// the mountings).</summary>
        public static Joint Hinge(int parent, int child, Vec3 axisParent, Vec3 axisChild, bool inSegmentFrames = false)
        {
            return Make(Consts.JointHinge, parent, child, axisParent, axisChild, inSegmentFrames);
        }

        /// <summary>A 2-DoF joint: the first axis fixed in the parent, the second in the child.</summary>
        public static Joint TwoDof(int parent, int child, Vec3 axisParent, Vec3 axisChild, bool inSegmentFrames = false)
        {
            return Make(Consts.JointTwoDof, parent, child, axisParent, axisChild, inSegmentFrames);
        }

        private static Joint Make(uint kind, int parent, int child, Vec3 a, Vec3 b, bool inSegmentFrames)
        {
            if (parent < 0) throw new ArgumentOutOfRangeException("parent");
            if (child < 0) throw new ArgumentOutOfRangeException("child");
            return new Joint
            {
                Kind = (int)kind, Parent = (uint)parent, Child = (uint)child, AxisParent = a, AxisChild = b,
                AxesFrame = inSegmentFrames ? Consts.JointAxesSegment : Consts.JointAxesSensor,
            };
        }

        /// <summary>
        /// The joints over the rig's filters (segment i is filter i). mountings (sensor to
        /// segment, one per filter; null for the identity) give the angles' zero, the
        /// reference pose, and the segments' outputs; the filters' own mountings are not
        /// read: pass each filter's Mounting. Throws OrientException (Status.InvalidJoint names the joint).
        /// </summary>
        public OrientJoints(OrientRig rig, Joint[] joints, Native.Quaternion[] mountings = null)
        {
            if (rig == null) throw new ArgumentNullException("rig");
            if (joints == null) throw new ArgumentNullException("joints");
            if (mountings != null && mountings.Length != rig.Count)
                throw new ArgumentException("one mounting per filter", "mountings");
            IntPtr h;
            Status s;
            fixed (Joint* pj = joints)
            fixed (Native.Quaternion* pm = mountings)
            {
                s = NativeMethods.orient_joints_new(pj, (UIntPtr)joints.Length, (UIntPtr)rig.Count, pm, &h);
            }
            OrientException.Check(s);
            handle.Set(h);
            this.rig = rig;
            handles = new IntPtr[rig.Count];
            JointCount = joints.Length;
        }

        public int JointCount { get; private set; }

        private IntPtr H
        {
            get
            {
                if (handle.IsClosed || handle.IsInvalid) throw new ObjectDisposedException("OrientJoints");
                return handle.DangerousGetHandle();
            }
        }

        public void Dispose()
        {
            handle.Dispose();
        }

        /// <summary>
        /// One row, after rig.Update(samples, ...): every joint from the filters'
        /// orientations and the same samples. Throws OrientException and changes nothing on
        /// a bad sample (NaN, unknown flags).
        /// </summary>
        public void Update(Sample[] samples)
        {
            if (samples == null) throw new ArgumentNullException("samples");
            if (samples.Length != rig.Count) throw new ArgumentException("one sample per filter", "samples");
            rig.CopyHandles(handles);
            Status s;
            fixed (IntPtr* ph = handles)
            fixed (Sample* ps = samples)
            {
                s = NativeMethods.orient_joints_update(H, ph, ps, (UIntPtr)samples.Length);
            }
            GC.KeepAlive(rig);
            GC.KeepAlive(this);
            OrientException.Check(s);
        }

        /// <summary>Segment i's orientation (segment to earth): the bone rotation.</summary>
        public Native.Quaternion Segment(int segment)
        {
            Native.Quaternion q;
            OrientException.Check(NativeMethods.orient_joints_segment_quaternion(H, (UIntPtr)Index(segment), &q));
            GC.KeepAlive(this);
            return q;
        }

        /// <summary>
        /// Joint k's angles (radians), zero in the reference pose, right-handed about its
        /// axes: a hinge's in first (second NaN), a 2-DoF joint's about its first and then
        /// its second axis.
        /// </summary>
        public void Angles(int joint, out double first, out double second)
        {
            double* a = stackalloc double[2];
            OrientException.Check(NativeMethods.orient_joints_angles(H, (UIntPtr)Index(joint), a));
            GC.KeepAlive(this);
            first = a[0];
            second = a[1];
        }

        /// <summary>Joint k's observability rating in [0, 1] (0 at rest or with a vertical hinge).</summary>
        public double Rating(int joint)
        {
            double r;
            OrientException.Check(NativeMethods.orient_joints_rating(H, (UIntPtr)Index(joint), &r));
            GC.KeepAlive(this);
            return r;
        }

        /// <summary>Joint k's correction of the child's heading relative to its parent (radians).</summary>
        public double RelativeHeading(int joint, out double sigma)
        {
            double h, s;
            OrientException.Check(NativeMethods.orient_joints_relative_heading(H, (UIntPtr)Index(joint), &h, &s));
            GC.KeepAlive(this);
            sigma = s;
            return h;
        }

        /// <summary>Joint k's axes as refined from motion (unit, sensor frames).</summary>
        public void Axes(int joint, out Vec3 axisParent, out Vec3 axisChild)
        {
            Vec3 a, b;
            OrientException.Check(NativeMethods.orient_joints_axes(H, (UIntPtr)Index(joint), &a, &b));
            GC.KeepAlive(this);
            axisParent = a;
            axisChild = b;
        }

        /// <summary>Starts every joint over (after the filters' headings were aligned again).</summary>
        public void Reset()
        {
            OrientException.Check(NativeMethods.orient_joints_reset(H));
            GC.KeepAlive(this);
        }

        /// <summary>The joint parameter called `name` (see <see cref="Parameters"/>), shared
        /// by every joint of the rig. Setting it takes effect from the next update (an
        /// initial standard deviation, a name ending in _std0, at the next Reset, at once
        /// before the first update, and while rows contradict a joint's estimate, which then
        /// widens its variances to the initial ones again); a name or value out of range throws OrientException
        /// (UnknownParam, ParamOutOfRange) with nothing changed.</summary>
        public double this[string name]
        {
            get
            {
                byte[] bytes = OrientFilter.NameBytes(name);
                double v;
                fixed (byte* p = bytes)
                {
                    OrientException.Check(NativeMethods.orient_joints_get_param(H, p, &v));
                }
                GC.KeepAlive(this);
                return v;
            }
            set
            {
                byte[] bytes = OrientFilter.NameBytes(name);
                fixed (byte* p = bytes)
                {
                    OrientException.Check(NativeMethods.orient_joints_set_param(H, p, value));
                }
                GC.KeepAlive(this);
            }
        }

        /// <summary>Every joint parameter with its unit, meaning, default and range, for
        /// inspectors.</summary>
        public static IList<ParameterInfo> Parameters()
        {
            uint n;
            OrientException.Check(NativeMethods.orient_joint_param_count(&n));
            List<ParameterInfo> list = new List<ParameterInfo>((int)n);
            for (uint i = 0; i < n; i++)
            {
                Native.ParamInfo info;
                OrientException.Check(NativeMethods.orient_joint_param_info(i, &info));
                list.Add(OrientFilter.FromNative(info));
            }
            return list;
        }

        /// <summary>A snapshot of the joints' estimates with the rig's description; save
        /// each filter too (SaveState), and both continue bit for bit.</summary>
        public byte[] SaveState()
        {
            UIntPtr size;
            OrientException.Check(NativeMethods.orient_joints_state_size(H, &size));
            byte[] blob = new byte[(int)size];
            UIntPtr written;
            fixed (byte* p = blob)
            {
                OrientException.Check(NativeMethods.orient_joints_save(H, p, size, &written));
            }
            GC.KeepAlive(this);
            return blob;
        }

        /// <summary>Restores SaveState's snapshot into joints of the same rig; throws
        /// OrientException (InvalidState) for another rig's, a filter's or a damaged blob,
        /// changing nothing.</summary>
        public void LoadState(byte[] blob)
        {
            if (blob == null) throw new ArgumentNullException("blob");
            byte empty = 0;
            fixed (byte* p = blob)
            {
                byte* data = blob.Length == 0 ? &empty : p;
                OrientException.Check(NativeMethods.orient_joints_load(H, data, (UIntPtr)blob.Length));
            }
            GC.KeepAlive(this);
        }

        /// <summary>
        /// A hinge's axes from gyroscope readings of its two sensors at the same instants
        /// (a few seconds of the joint turning), started from guesses; quality below 0.1
        /// means the axes can be trusted.
        /// </summary>
        public static JointAxes EstimateHingeAxes(Vec3[] gyroParent, Vec3[] gyroChild, Vec3 guessParent, Vec3 guessChild)
        {
            if (gyroParent == null) throw new ArgumentNullException("gyroParent");
            if (gyroChild == null) throw new ArgumentNullException("gyroChild");
            if (gyroParent.Length != gyroChild.Length)
                throw new ArgumentException("as many child readings as parent readings", "gyroChild");
            JointAxes h;
            Status s;
            Vec3 empty = new Vec3();
            fixed (Vec3* pp = gyroParent)
            fixed (Vec3* pc = gyroChild)
            {
                // Empty arrays pin as NULL; the library wants pointers even for n = 0 (and
                // says INVALID_ARGUMENT for it).
                Vec3* a = gyroParent.Length == 0 ? &empty : pp;
                Vec3* b = gyroChild.Length == 0 ? &empty : pc;
                s = NativeMethods.orient_estimate_hinge_axes(a, b, (UIntPtr)gyroParent.Length, guessParent, guessChild, &h);
            }
            OrientException.Check(s);
            return h;
        }

        /// <summary>
        /// A 2-DoF joint's axes from its two sensors' orientations (sensor to earth; 6D
        /// estimates will do) at the same instants (a few seconds of the joint turning about
        /// both axes), started from guesses: the first axis in the parent's frame, the second
        /// in the child's; quality below 0.1 means the axes can be trusted.
        /// </summary>
        public static JointAxes EstimateTwoDofAxes(Quaternion[] parent, Quaternion[] child, Vec3 guessParent, Vec3 guessChild)
        {
            if (parent == null) throw new ArgumentNullException("parent");
            if (child == null) throw new ArgumentNullException("child");
            if (parent.Length != child.Length)
                throw new ArgumentException("as many child orientations as parent orientations", "child");
            JointAxes h;
            Status s;
            Quaternion empty = new Quaternion();
            fixed (Quaternion* pp = parent)
            fixed (Quaternion* pc = child)
            {
                // Empty arrays pin as NULL; the library wants pointers even for n = 0.
                Quaternion* a = parent.Length == 0 ? &empty : pp;
                Quaternion* b = child.Length == 0 ? &empty : pc;
                s = NativeMethods.orient_estimate_two_dof_axes(a, b, (UIntPtr)parent.Length, guessParent, guessChild, &h);
            }
            OrientException.Check(s);
            return h;
        }

        private static int Index(int i)
        {
            if (i < 0) throw new ArgumentOutOfRangeException("index");
            return i;
        }
    }
}
