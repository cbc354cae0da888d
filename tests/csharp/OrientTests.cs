// The C# binding under Mono: golden vectors bit for bit through the wrapper (single and
// batch), every status path, disposal, struct layout, Unity conversions.
// Built and run by tests/csharp_binding.rs; ends with "N passed, N failed".
using System;
using System.Collections.Generic;
using System.Globalization;
using System.IO;
using System.Runtime.InteropServices;
using Orient;
using Orient.Native;

public static class OrientTests
{
    static int passed, failed;

    static void Check(bool ok, string what)
    {
        if (ok) { passed++; }
        else { failed++; Console.WriteLine("FAIL " + what); }
    }

    /// The action throws an OrientException with this status (and, when given, a message
    /// that contains `detail`).
    static void Throws(Status expected, Action action, string what, string detail = null)
    {
        try
        {
            action();
            Check(false, what + ": no exception");
        }
        catch (OrientException e)
        {
            Check(e.Status == expected && (detail == null || e.Message.Contains(detail)),
                what + ": got " + e.Status + " (" + e.Message + ")");
        }
    }

    static double Unhex(string s)
    {
        return BitConverter.Int64BitsToDouble(unchecked((long)ulong.Parse(s, NumberStyles.HexNumber)));
    }

    static bool Same(Orient.Native.Quaternion a, Orient.Native.Quaternion b)
    {
        return BitConverter.DoubleToInt64Bits(a.W) == BitConverter.DoubleToInt64Bits(b.W)
            && BitConverter.DoubleToInt64Bits(a.X) == BitConverter.DoubleToInt64Bits(b.X)
            && BitConverter.DoubleToInt64Bits(a.Y) == BitConverter.DoubleToInt64Bits(b.Y)
            && BitConverter.DoubleToInt64Bits(a.Z) == BitConverter.DoubleToInt64Bits(b.Z);
    }

    static void Layout()
    {
        Check(Marshal.SizeOf(typeof(Sample)) == 88, "sizeof Sample");
        Check(Marshal.SizeOf(typeof(Config)) == 1072, "sizeof Config");
        Check(Marshal.SizeOf(typeof(Diagnostics)) == 176, "sizeof Diagnostics");
        Check(Marshal.SizeOf(typeof(ParamInfo)) == 56, "sizeof ParamInfo");
        Check((int)Marshal.OffsetOf(typeof(Sample), "Flags") == 80, "offset Sample.Flags");
        Check((int)Marshal.OffsetOf(typeof(Config), "Params") == 48, "offset Config.Params");
        Check((int)Marshal.OffsetOf(typeof(Diagnostics), "Covariance") == 96, "offset Diagnostics.Covariance");
        Check(NativeMethods.orient_abi_version() == Consts.AbiVersion, "ABI version");
        Check(OrientFilter.Version.Length > 0, "version");
    }

    static void Golden(string path)
    {
        int cases = 0;
        OrientSettings settings = null;
        string name = "";
        var samples = new List<Sample>();
        var expected = new List<Orient.Native.Quaternion>();
        foreach (string line in File.ReadAllLines(path))
        {
            string[] t = line.Split(new[] { ' ' }, StringSplitOptions.RemoveEmptyEntries);
            if (t.Length == 0 || t[0].StartsWith("#")) continue;
            if (t[0] == "case")
            {
                name = t[1];
                settings = new OrientSettings((Kind)int.Parse(t[2]));
                settings.Frame = (Frame)int.Parse(t[3]);
                settings.Init = (Init)int.Parse(t[4]);
                settings.Initial = new Orient.Native.Quaternion(Unhex(t[5]), Unhex(t[6]), Unhex(t[7]), Unhex(t[8]));
                int n = int.Parse(t[9]);
                for (int i = 0; i < n; i++)
                {
                    settings[uint.Parse(t[10 + 2 * i])] = Unhex(t[11 + 2 * i]);
                }
                samples.Clear();
                expected.Clear();
            }
            else if (t[0] == "s")
            {
                Sample s = new Sample();
                s.Dt = Unhex(t[1]);
                s.Gyro = new Vec3(Unhex(t[2]), Unhex(t[3]), Unhex(t[4]));
                s.Accel = new Vec3(Unhex(t[5]), Unhex(t[6]), Unhex(t[7]));
                s.Mag = new Vec3(Unhex(t[8]), Unhex(t[9]), Unhex(t[10]));
                s.Flags = uint.Parse(t[11]);
                samples.Add(s);
                expected.Add(new Orient.Native.Quaternion(Unhex(t[12]), Unhex(t[13]), Unhex(t[14]), Unhex(t[15])));
            }
            else if (t[0] == "end")
            {
                cases++;
                int mismatches = 0;
                using (var f = new OrientFilter(settings))
                {
                    for (int i = 0; i < samples.Count; i++)
                    {
                        f.Update(samples[i]);
                        if (!Same(f.Quaternion, expected[i])) mismatches++;
                    }
                }
                Check(mismatches == 0, "golden " + name + " single: " + mismatches + " mismatches");
                using (var f = new OrientFilter(settings))
                {
                    var output = new Orient.Native.Quaternion[samples.Count];
                    int done = f.UpdateBatch(samples.ToArray(), output);
                    Check(done == samples.Count, "golden " + name + " batch count");
                    mismatches = 0;
                    for (int i = 0; i < output.Length; i++)
                    {
                        if (!Same(output[i], expected[i])) mismatches++;
                    }
                    Check(mismatches == 0, "golden " + name + " batch: " + mismatches + " mismatches");
                }
            }
        }
        Check(cases >= 9, "golden cases: " + cases);
        Console.WriteLine("golden: " + cases + " cases");
    }

    static Sample Good()
    {
        return OrientFilter.Marg(0.01, new Vec3(0.1, -0.2, 0.3), new Vec3(0.5, 0.2, 9.7), new Vec3(10, 20, -40));
    }

    static void StatusPaths()
    {
        Throws(Status.InvalidArgument, () => new OrientSettings((Kind)42), "unknown kind");
        var settings = new OrientSettings(Kind.Madgwick);
        Throws(Status.ParamOutOfRange, () => settings["beta_imu"] = -1.0, "beta out of range");
        Throws(Status.UnknownParam, () => settings["no_such"] = 1.0, "unknown name");
        Throws(Status.UnknownParam, () => settings[99u] = 1.0, "unknown slot");
        settings["beta_marg"] = 0.05;
        Check(settings[Consts.ParamMadgwickBetaMarg] == 0.05, "set by name, read by id");
        Check(settings.Parameters.Count == 9, "parameter list");
        Check(settings.Gravity == 9.80665, "gravity default");

        // Every kind the generated enum has, so a new kind is tested here too.
        foreach (Kind kind in (Kind[])Enum.GetValues(typeof(Kind)))
        {
            using (var f = new OrientFilter(kind))
            {
                f.GyroRangeForTest(30.0);
                // Warm up past any start-up period.
                Sample still = Good();
                still.Gyro = new Vec3(0, 0, 0);
                int n = 0;
                while (!f.Initialized && n++ < 1000) f.Update(still);
                Check(f.Initialized, kind + " initialises");
                f.Update(Good());
                Orient.Native.Quaternion before = f.Quaternion;
                Sample s;
                s = Good(); s.Dt = 0; Throws(Status.InvalidDt, () => f.Update(s), kind + " dt 0");
                s = Good(); s.Dt = double.NaN; Throws(Status.InvalidDt, () => f.Update(s), kind + " dt NaN");
                s = Good(); s.Gyro.Y = double.NaN; Throws(Status.NonFinite, () => f.Update(s), kind + " gyro NaN");
                s = Good(); s.Accel = new Vec3(0, 0, 0); Throws(Status.ZeroVector, () => f.Update(s), kind + " zero accel");
                s = Good(); s.Mag.X = double.PositiveInfinity; Throws(Status.NonFinite, () => f.Update(s), kind + " mag inf");
                s = Good(); s.Gyro.X = 31; Throws(Status.Saturated, () => f.Update(s), kind + " saturated");
                s = Good(); s.Flags = Consts.SampleAccel; Throws(Status.MissingSensor, () => f.Update(s), kind + " no gyro");
                s = Good(); s.Flags |= 8; Throws(Status.InvalidArgument, () => f.Update(s), kind + " unknown flag");
                Check(Same(before, f.Quaternion), kind + " state unchanged after rejections");
                Diagnostics d = f.Diagnostics;
                Check((d.Present != 0) == (kind != Kind.Madgwick), kind + " diagnostics present");
                Check(kind == Kind.Gmvdk ? d.Alpha >= 0 && d.Alpha <= 1 : double.IsNaN(d.Alpha), kind + " alpha");
                Uncertainty u = f.Uncertainty;
                bool models = kind == Kind.Ekf || kind == Kind.Robust;
                Check(((u.Present & Consts.UncertaintyHeading) != 0) == models, kind + " heading uncertainty present");
                Check(models ? u.Heading > 0 && u.Heading < 2 : double.IsNaN(u.Heading), kind + " heading sigma");
                Check(((u.Present & Consts.UncertaintyInclination) != 0) == (kind == Kind.Ekf), kind + " inclination sigma");
            }
        }

        // Batch: stops at the first bad sample, reports its index, keeps the ones before.
        using (var f = new OrientFilter(Kind.Madgwick))
        using (var twin = new OrientFilter(Kind.Madgwick))
        {
            var batch = new[] { Good(), Good(), Good(), Good() };
            batch[2].Accel.X = double.NaN;
            Throws(Status.NonFinite, () => f.UpdateBatch(batch, null), "batch error", "sample 2");
            twin.UpdateBatch(batch, 0, 2, null);
            Check(Same(f.Quaternion, twin.Quaternion), "batch keeps the samples before the bad one");
            Throws(Status.NoData, () => new OrientFilter(Kind.Ekf).LinearAcceleration.ToString(), "no data yet");
        }

        // A rig: one native call per frame, the same bits as separate updates.
        {
            var kinds = new[] { Kind.Madgwick, Kind.Mahony, Kind.Ekf, Kind.Robust };
            var rigFilters = new OrientFilter[kinds.Length];
            var twins = new OrientFilter[kinds.Length];
            for (int k = 0; k < kinds.Length; k++)
            {
                rigFilters[k] = new OrientFilter(kinds[k]);
                twins[k] = new OrientFilter(kinds[k]);
            }
            var rig = new OrientRig(rigFilters);
            var frame = new Sample[kinds.Length];
            var outQ = new Orient.Native.Quaternion[kinds.Length];
            for (int i = 0; i < 100; i++)
            {
                for (int k = 0; k < kinds.Length; k++) { frame[k] = Good(); frame[k].Gyro.Z = 0.1 * k; }
                rig.Update(frame, outQ);
                for (int k = 0; k < kinds.Length; k++) twins[k].Update(frame[k]);
            }
            bool same = true;
            for (int k = 0; k < kinds.Length; k++) same &= Same(outQ[k], twins[k].Quaternion);
            Check(same && rig.Count == kinds.Length, "rig matches separate updates");
            frame[2].Accel.X = double.NaN;
            Throws(Status.NonFinite, () => rig.Update(frame, null), "rig error", "filter 2");
            Check(Same(rigFilters[3].Quaternion, twins[3].Quaternion), "rig leaves the filters after a bad sample");
            foreach (var f in rigFilters) f.Dispose();
            foreach (var f in twins) f.Dispose();
            try
            {
                rig.Update(frame, null);
                Check(false, "rig with disposed filters should throw");
            }
            catch (ObjectDisposedException)
            {
                Check(true, "rig refuses disposed filters");
            }
        }

        // Snapshots: a split run equals an unbroken one; damaged blobs are refused.
        using (var whole = new OrientFilter(Kind.Ekf))
        using (var first = new OrientFilter(Kind.Ekf))
        using (var second = new OrientFilter(Kind.Ekf))
        {
            for (int i = 0; i < 50; i++) { whole.Update(Good()); first.Update(Good()); }
            byte[] blob = first.SaveState();
            byte[] bad = (byte[])blob.Clone();
            bad[30] ^= 1;
            Throws(Status.InvalidState, () => second.LoadState(bad), "corrupted blob");
            second.LoadState(blob);
            for (int i = 0; i < 50; i++) { whole.Update(Good()); second.Update(Good()); }
            Check(Same(whole.Quaternion, second.Quaternion), "split run equals unbroken run");
            using (var other = new OrientFilter(Kind.Madgwick))
            {
                Throws(Status.InvalidState, () => other.LoadState(blob), "blob of another kind");
            }
        }

        // Disposal: twice is harmless, use afterwards is an ObjectDisposedException.
        var g = new OrientFilter(Kind.Mahony);
        g.Dispose();
        g.Dispose();
        Check(g.IsDisposed, "disposed");
        try
        {
            g.Update(Good());
            Check(false, "use after dispose");
        }
        catch (ObjectDisposedException)
        {
            passed++;
        }
        // The native free reports a stale handle instead of crashing.
        Check(NativeMethods.orient_filter_free(IntPtr.Zero) == Status.Ok, "free(NULL)");
        Check(Math.Abs(OrientFilter.MadgwickBeta(0.1) - Math.Sqrt(0.75) * 0.1) < 1e-15, "beta eq. 33");
    }

    static void Conversions()
    {
        // ENU yaw +90° (east -> north) is a turn to the left seen from above; in Unity that
        // is -90° about +Y and takes +X (east) to +Z (north).
        var q = new Orient.Native.Quaternion(Math.Sqrt(0.5), 0, 0, Math.Sqrt(0.5));
        double x, y, z, w;
        UnityConvert.ToUnity(q, Frame.Enu, out x, out y, out z, out w);
        Check(Math.Abs(x) < 1e-15 && Math.Abs(y + Math.Sqrt(0.5)) < 1e-15 && Math.Abs(z) < 1e-15, "yaw to Unity");
        // Rotate Unity's +X with (x, y, z, w): q v q*.
        var u = new Orient.Native.Quaternion(w, x, y, z);
        var v = UnityConvert.Mul(UnityConvert.Mul(u, new Orient.Native.Quaternion(0, 1, 0, 0)),
                                 new Orient.Native.Quaternion(u.W, -u.X, -u.Y, -u.Z));
        Check(Math.Abs(v.X) < 1e-12 && Math.Abs(v.Y) < 1e-12 && Math.Abs(v.Z - 1) < 1e-12, "east goes to north (+Z)");
        // Round trips, and frames agree: the same physical orientation from NED and ENU.
        var back = UnityConvert.FromUnity(x, y, z, w);
        Check(Same(back, q), "Unity round trip");
        var ned = UnityConvert.Mul(new Orient.Native.Quaternion(0, Math.Sqrt(0.5), Math.Sqrt(0.5), 0), q);
        double x2, y2, z2, w2;
        UnityConvert.ToUnity(ned, Frame.Ned, out x2, out y2, out z2, out w2);
        // The same rotation (q and -q are one rotation).
        Check(Math.Abs(Math.Abs(x2 * x + y2 * y + z2 * z + w2 * w) - 1) < 1e-12, "NED = ENU in Unity");
        Vec3 up = UnityConvert.FromUnity(0, 1, 0);
        Check(up.X == 0 && up.Y == 0 && up.Z == 1, "Unity up is ENU up");
    }

    // OrientFilter.Smooth: the offline mode finds the tilt of a still, rolled recording
    // and names a bad sample.
    static void Offline()
    {
        int n = 400;
        double roll = 0.4, c = Math.Cos(roll), s = Math.Sin(roll);
        var gyro = new double[3 * n];
        var accel = new double[3 * n];
        var mag = new double[3 * n];
        for (int i = 0; i < n; i++)
        {
            accel[3 * i + 1] = 9.81 * s; accel[3 * i + 2] = 9.81 * c;
            mag[3 * i + 1] = 20.0 * c - 40.0 * s; mag[3 * i + 2] = -20.0 * s - 40.0 * c;
        }
        var settings = new OrientSettings(Kind.Robust);
        var q = OrientFilter.Smooth(settings, new[] { 0.01 }, gyro, accel, mag);
        Check(q.Length == n, "Smooth length");
        bool tilted = true;
        foreach (var x in q)
            tilted &= Math.Abs(x.W * Math.Cos(roll / 2) + x.X * Math.Sin(roll / 2)) > Math.Cos(0.005);
        Check(tilted, "Smooth finds the tilt");
        var offline = OrientSettings.Offline();
        Check(offline.Kind == Kind.Robust && offline[Consts.ParamRobustTauMag] == 27.0, "Offline settings");
        Check(OrientFilter.Smooth(offline, new[] { 0.01 }, gyro, accel, mag).Length == n, "Smooth with Offline");
        accel[3 * 5 + 2] = double.NaN;
        Throws(Status.NonFinite, () => OrientFilter.Smooth(settings, new[] { 0.01 }, gyro, accel, mag), "Smooth bad sample", "sample 5");
        Check(OrientFilter.SmoothMemory((ulong)n) == 8 * (ulong)n + 32768, "SmoothMemory");
        Throws(Status.CountTooLarge, () => OrientFilter.SmoothMemory(ulong.MaxValue), "SmoothMemory too large", "cannot fit");
        Check((int)Status.OutOfMemory == 21, "Status.OutOfMemory");
    }

    /// The rotation angle from a to b (radians), well conditioned near 0.
    static double Angle(Orient.Native.Quaternion a, Orient.Native.Quaternion b)
    {
        double w = a.W * b.W + a.X * b.X + a.Y * b.Y + a.Z * b.Z;
        double x = a.W * b.X - a.X * b.W - a.Y * b.Z + a.Z * b.Y;
        double y = a.W * b.Y + a.X * b.Z - a.Y * b.W - a.Z * b.X;
        double z = a.W * b.Z - a.X * b.Y + a.Y * b.X - a.Z * b.W;
        return 2 * Math.Atan2(Math.Sqrt(x * x + y * y + z * z), Math.Abs(w));
    }

    /// Issue 20: mounting, heading, declination and rig calibration.
    static void MountingAndHeading()
    {
        var fs = new OrientFilter[3];
        for (int k = 0; k < 3; k++)
        {
            fs[k] = new OrientFilter(Kind.Mahony);
            for (int i = 0; i < 50; i++)
            {
                fs[k].Update(OrientFilter.Marg(0.01, new Vec3(0.1 * k, 0.2, 0), new Vec3(0.3 * k, 0.5, 9.7),
                    new Vec3(20, 3 * k, -40)));
            }
        }
        var f = fs[0];
        var sensor = f.SensorQuaternion;
        Check(Same(sensor, f.Quaternion), "sensor = output without mounting");
        f.Mounting = new Orient.Native.Quaternion(0.8, 0.2, 0.5, -0.1);
        Check(Angle(f.SensorQuaternion, sensor) < 1e-9, "mounting leaves the sensor's orientation");
        Check(Angle(f.Quaternion, sensor) > 0.1, "mounting changes the output");
        Check(f.Mounting.W != 1.0, "mounting read back");
        Throws(Status.NonFinite, () => { f.Mounting = new Orient.Native.Quaternion(double.NaN, 0, 0, 0); }, "NaN mounting");
        f.SetHeading(1.25);
        Check(Math.Abs(f.Euler.Yaw - 1.25) < 1e-12, "SetHeading");
        Check(f.HeadingOffset != 0, "HeadingOffset");
        f.ResetHeading();
        Check(Math.Abs(f.Euler.Yaw) < 1e-12, "ResetHeading");
        f.Declination = 0.1;
        Check(f.Declination == 0.1, "Declination");
        Throws(Status.TooLarge, () => { f.Declination = 4; }, "declination beyond pi");
        using (var fresh = new OrientFilter(Kind.Ekf))
        {
            Throws(Status.NotInitialized, () => fresh.SetHeading(1), "SetHeading before init");
        }

        var rig = new OrientRig(fs);
        var refs = new[]
        {
            new Orient.Native.Quaternion(1, 0, 0, 0),
            new Orient.Native.Quaternion(Math.Cos(0.3), 0, Math.Sin(0.3), 0),
            new Orient.Native.Quaternion(0, 0, 0, 1),
        };
        rig.Calibrate(refs, 0.4);
        for (int k = 0; k < 3; k++) Check(Angle(fs[k].Quaternion, refs[k]) < 1e-9, "calibrated filter " + k);
        rig.Calibrate(refs);
        for (int k = 0; k < 3; k++) Check(Angle(fs[k].Quaternion, refs[k]) < 1e-9, "estimated heading " + k);
        fs[1].SetHeading(-2);
        rig.AlignHeading(refs);
        Check(Angle(fs[1].Quaternion, refs[1]) < 1e-9, "AlignHeading");
        fs[1].SetHeading(2);
        rig.CalibrateEach(refs);
        for (int k = 0; k < 3; k++) Check(Angle(fs[k].Quaternion, refs[k]) < 1e-9, "CalibrateEach " + k);
        Throws(Status.NotInitialized, () => new OrientRig(fs[0], new OrientFilter(Kind.Ekf)).Calibrate(
            new[] { refs[0], refs[1] }), "rig with an uninitialised filter", "filter 1");
        foreach (var g in fs) g.Dispose();
    }

    /// Issue 20: sensor models and the magnetometer calibrator.
    static unsafe void Calibration()
    {
        var still = new[] { new Vec3(0.011, -0.02, 0.03), new Vec3(0.009, -0.02, 0.03) };
        double spread;
        SensorModel gm = MagCalibration.GyroOffset(still, out spread);
        Check(Math.Abs(gm.Offset.X - 0.01) < 1e-12 && gm.Matrix[0] == 1.0 && spread > 0, "GyroOffset");
        using (var f = new OrientFilter(Kind.Madgwick))
        using (var g = new OrientFilter(Kind.Madgwick))
        {
            Check(f.GetSensorModel(Consts.SensorGyro) == null, "no model set");
            f.SetSensorModel(Consts.SensorGyro, gm);
            Check(f.GetSensorModel(Consts.SensorGyro).Value.Offset.X == gm.Offset.X, "model read back");
            for (int i = 0; i < 50; i++)
            {
                f.Update(OrientFilter.Imu(0.01, new Vec3(0.21, -0.02, 0.03), new Vec3(0.3, 0.2, 9.7)));
                g.Update(OrientFilter.Imu(0.01, new Vec3(0.21 - gm.Offset.X, -0.02 - gm.Offset.Y, 0.03 - gm.Offset.Z),
                    new Vec3(0.3, 0.2, 9.7)));
            }
            Check(Same(f.Quaternion, g.Quaternion), "a model gives the calibrated readings' bits");
            f.SetSensorModel(Consts.SensorGyro, null);
            Check(f.GetSensorModel(Consts.SensorGyro) == null, "model cleared");
        }
        var cal = new MagCalibration();
        Check(cal.Solve() == null, "no fit without readings");
        for (int k = 0; k < 288; k++)
        {
            int idx = (k * 97) % 288;
            double th = Math.PI * (idx / 24 + 0.5) / 12, ph = 2 * Math.PI * (idx % 24) / 24;
            cal.Add(new Vec3(60 * Math.Sin(th) * Math.Cos(ph) + 10, 45 * Math.Sin(th) * Math.Sin(ph) - 20,
                50 * Math.Cos(th) + 5));
        }
        MagFit fit = cal.Solve().Value;
        Check(Math.Abs(fit.Model.Offset.X - 10) < 1e-6 && Math.Abs(fit.Model.Offset.Y + 20) < 1e-6, "hard iron");
        Check(fit.Trustworthy == 1 && fit.Samples == 288, "trustworthy fit");
    }

    static Orient.Native.Quaternion QMul(Orient.Native.Quaternion a, Orient.Native.Quaternion b)
    {
        return new Orient.Native.Quaternion
        {
            W = a.W * b.W - a.X * b.X - a.Y * b.Y - a.Z * b.Z,
            X = a.W * b.X + a.X * b.W + a.Y * b.Z - a.Z * b.Y,
            Y = a.W * b.Y - a.X * b.Z + a.Y * b.W + a.Z * b.X,
            Z = a.W * b.Z + a.X * b.Y - a.Y * b.X + a.Z * b.W,
        };
    }

    static Orient.Native.Quaternion QConj(Orient.Native.Quaternion a)
    {
        return new Orient.Native.Quaternion { W = a.W, X = -a.X, Y = -a.Y, Z = -a.Z };
    }

    static Orient.Native.Quaternion QAxis(double x, double y, double z, double angle)
    {
        double n = Math.Sqrt(x * x + y * y + z * z), s = Math.Sin(0.5 * angle);
        return new Orient.Native.Quaternion { W = Math.Cos(0.5 * angle), X = x / n * s, Y = y / n * s, Z = z / n * s };
    }

    static Orient.Native.Quaternion HandAt(double t)
    {
        return QMul(QMul(QAxis(0, 0, 1, 0.5 * Math.Sin(0.3 * t)), QAxis(0, 1, 0, 0.6 * Math.Sin(0.7 * t))),
            QAxis(1, 0, 0, 0.4 * Math.Sin(1.1 * t)));
    }

    static double FlexionAt(double t)
    {
        return 0.5 + 0.8 * Math.Sin(1.9 * t);
    }

    static Orient.Native.Quaternion FingerAt(double t)
    {
        return QMul(HandAt(t), QAxis(1, 0, 0, FlexionAt(t)));
    }

    /// A sensor at the joint centre turning from a to b in dt: body rates and gravity.
    static Sample Moving(Orient.Native.Quaternion a, Orient.Native.Quaternion b, double dt)
    {
        var d = QMul(QConj(a), b);
        if (d.W < 0) d = new Orient.Native.Quaternion { W = -d.W, X = -d.X, Y = -d.Y, Z = -d.Z };
        double n = Math.Sqrt(d.X * d.X + d.Y * d.Y + d.Z * d.Z);
        double k = n > 1e-15 ? 2.0 * Math.Atan2(n, d.W) / n / dt : 0.0;
        var g = QMul(QMul(QConj(b), new Orient.Native.Quaternion { W = 0, X = 0, Y = 0, Z = 9.81 }), b);
        return OrientFilter.Imu(dt, new Vec3 { X = d.X * k, Y = d.Y * k, Z = d.Z * k }, new Vec3 { X = g.X, Y = g.Y, Z = g.Z });
    }

    /// OrientJoints over an OrientRig: a hand and a finger on a hinge about both sensors'
    /// x axis, each sensor's filter robust 6D.
    static void Joints()
    {
        const double dt = 0.01;
        using (var hand = new OrientFilter(Kind.Robust))
        using (var finger = new OrientFilter(Kind.Robust))
        {
            var rig = new OrientRig(hand, finger);
            var x = new Vec3 { X = 1, Y = 0, Z = 0 };
            var joints = new OrientJoints(rig, new[] { OrientJoints.Hinge(0, 1, x, x) });
            var samples = new Sample[2];
            var gp = new Vec3[500];
            var gc = new Vec3[500];
            for (int i = 1; i <= 1000; i++)
            {
                double t0 = (i - 1) * dt, t1 = i * dt;
                samples[0] = Moving(HandAt(t0), HandAt(t1), dt);
                samples[1] = Moving(FingerAt(t0), FingerAt(t1), dt);
                rig.Update(samples, null);
                joints.Update(samples);
                if (i <= 500)
                {
                    gp[i - 1] = samples[0].Gyro;
                    gc[i - 1] = samples[1].Gyro;
                }
            }
            double first, second;
            joints.Angles(0, out first, out second);
            Check(Math.Abs(first - FlexionAt(10.0)) < 0.035 && double.IsNaN(second), "OrientJoints: the hinge angle " + first);
            var rel = QMul(QConj(joints.Segment(0)), joints.Segment(1));
            var truth = QAxis(1, 0, 0, FlexionAt(10.0));
            double dot = Math.Abs(rel.W * truth.W + rel.X * truth.X + rel.Y * truth.Y + rel.Z * truth.Z);
            Check(dot > 1.0 - 2e-4, "OrientJoints: the finger relative to the hand");
            double r = joints.Rating(0);
            Check(r > 0.1 && r <= 1.0, "OrientJoints: rating " + r);
            double sigma;
            joints.RelativeHeading(0, out sigma);
            Check(sigma >= 0.0, "OrientJoints: sigma");
            Vec3 ap, ac;
            joints.Axes(0, out ap, out ac);
            Check(ap.X > 0.99 && ac.X > 0.99, "OrientJoints: axes");
            Throws(Status.InvalidArgument, () => joints.Rating(1), "OrientJoints: a joint beyond the rig");
            var bad = (Sample[])samples.Clone();
            bad[1].Gyro.Y = double.NaN;
            Throws(Status.NonFinite, () => joints.Update(bad), "OrientJoints: NaN", "segment 1");
            byte[] blob = joints.SaveState();
            using (var twin = new OrientJoints(rig, new[] { OrientJoints.Hinge(0, 1, x, x) }))
            {
                twin.LoadState(blob);
                Check(Same(twin.Segment(1), joints.Segment(1)), "OrientJoints: a snapshot restores the segments");
                Throws(Status.InvalidState, () => twin.LoadState(hand.SaveState()), "OrientJoints: a filter's blob");
            }
            joints.Reset();
            Check(joints.RelativeHeading(0, out sigma) == 0.0, "OrientJoints: reset");
            var jp = OrientJoints.Parameters();
            Check(jp.Count == 22 && jp[18].Name == "gate" && jp[18].Default == 3.0, "OrientJoints: the parameter table");
            Check(joints["gate"] == 3.0, "OrientJoints: a parameter's default");
            joints["gate"] = 2.5;
            Check(joints["gate"] == 2.5, "OrientJoints: a parameter set");
            Throws(Status.ParamOutOfRange, () => joints["gate"] = -1.0, "OrientJoints: out of range");
            Check(joints["gate"] == 2.5, "OrientJoints: a refused value changes nothing");
            Throws(Status.UnknownParam, () => joints["beta"].ToString(), "OrientJoints: an unknown name");
            Throws(Status.InvalidJoint, () => new OrientJoints(rig, new[] { OrientJoints.Hinge(0, 1, x, x), OrientJoints.Hinge(1, 0, x, x) }),
                "OrientJoints: a cycle", "joint 1");
            Throws(Status.InvalidJoint, () => new OrientJoints(rig, new[] { OrientJoints.Hinge(0, 1, new Vec3(), x) }),
                "OrientJoints: a zero axis", "joint 0");
            var axes = OrientJoints.EstimateHingeAxes(gp, gc, new Vec3 { X = 1, Y = 0.08, Z = 0 }, new Vec3 { X = 1, Y = 0, Z = -0.08 });
            Check(axes.AxisParent.X > 0.9999 && axes.AxisChild.X > 0.9999 && axes.Quality < 0.01, "OrientJoints: hinge axes");
            Throws(Status.InvalidArgument, () => OrientJoints.EstimateHingeAxes(new Vec3[0], new Vec3[0], x, x),
                "OrientJoints: no readings");
            // A 2-DoF joint (the hand's z, then the finger's y) from orientations, the
            // finger's 40 degrees off in heading.
            var qp = new Orient.Native.Quaternion[1000];
            var qc = new Orient.Native.Quaternion[1000];
            for (int i = 0; i < qp.Length; i++)
            {
                double t = i * 0.01;
                qp[i] = HandAt(t);
                qc[i] = QMul(QAxis(0, 0, 1, 0.7), QMul(HandAt(t), QMul(QAxis(0, 0, 1, 0.25 * Math.Sin(2.1 * t)), QAxis(0, 1, 0, FlexionAt(t)))));
            }
            var two = OrientJoints.EstimateTwoDofAxes(qp, qc, new Vec3 { X = 0, Y = 0.08, Z = 1 }, new Vec3 { X = 0.08, Y = 1, Z = 0 });
            Check(two.AxisParent.Z > 0.9999 && two.AxisChild.Y > 0.9999 && two.Quality < 0.05, "OrientJoints: 2-DoF axes");
            Throws(Status.InvalidArgument, () => OrientJoints.EstimateTwoDofAxes(new Orient.Native.Quaternion[0], new Orient.Native.Quaternion[0], x, x),
                "OrientJoints: no orientations");
            var under = new OrientSettings(Kind.Robust).ForJoints();
            Check(Math.Abs(under["bias_walk"] - 0.05 * Math.PI / 180) < 1e-15 && Math.Abs(under["bias_limit"] - 4.0 * Math.PI / 180) < 1e-15
                && Math.Abs(under["rest_gyro"] - 4.0 * Math.PI / 180) < 1e-15,
                "OrientSettings.ForJoints: the three settings");
            Check(new OrientSettings(Kind.Madgwick).ForJoints()["beta_imu"] == new OrientSettings(Kind.Madgwick)["beta_imu"],
                "OrientSettings.ForJoints: other kinds unchanged");
            joints.Dispose();
            Check(IsDisposedThrows(() => joints.Rating(0)), "OrientJoints: disposed");
        }
    }

    static bool IsDisposedThrows(Action a)
    {
        try { a(); return false; }
        catch (ObjectDisposedException) { return true; }
    }

    public static int Main(string[] args)
    {
        if (args.Length != 1)
        {
            Console.Error.WriteLine("usage: OrientTests.exe GOLDEN_FILE");
            return 2;
        }
        Layout();
        StatusPaths();
        Conversions();
        Offline();
        MountingAndHeading();
        Calibration();
        Joints();
        Golden(args[0]);
        Console.WriteLine(passed + " passed, " + failed + " failed");
        return failed == 0 ? 0 : 1;
    }
}

static class TestExtensions
{
    public static void GyroRangeForTest(this OrientFilter f, double range)
    {
        f[Consts.ParamGyroRange] = range;
    }
}
