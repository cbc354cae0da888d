// Drives one bone of a hand model from recorded IMU/MARG samples. Assign a TextAsset
// holding a recording in orient's CSV layout (header with t, gyr_x..z, acc_x..z and
// optionally mag_x..z; rad/s, m/s^2, any magnetometer unit) and the bone's Transform.
// Each frame, the samples whose time has come are fed to the filter in one batch call.
using System;
using System.Collections.Generic;
using System.Globalization;
using Orient;
using Orient.Native;
using UnityEngine;

public class OrientBoneDriver : MonoBehaviour
{
    [Tooltip("Recording: CSV with t, gyr_*, acc_* and optionally mag_* columns")]
    public TextAsset recording;

    [Tooltip("The bone to rotate (defaults to this object's Transform)")]
    public Transform bone;

    [Tooltip("Filter kind")]
    public Kind kind = Kind.Madgwick;

    [Tooltip("Use the magnetometer columns when present")]
    public bool useMagnetometer = true;

    [Tooltip("Rotation of the sensor on the bone (applied after the filter's orientation)")]
    public UnityEngine.Quaternion mounting = UnityEngine.Quaternion.identity;

    private OrientFilter filter;
    private Sample[] samples = new Sample[0];
    private double[] times = new double[0];
    private int next;
    private double clock;

    void Start()
    {
        if (bone == null) bone = transform;
        filter = new OrientFilter(kind);
        Load();
    }

    void Load()
    {
        if (recording == null) return;
        string[] lines = recording.text.Split('\n');
        string[] header = lines[0].Trim().Split(',');
        int t = Array.IndexOf(header, "t");
        int gx = Array.IndexOf(header, "gyr_x");
        int ax = Array.IndexOf(header, "acc_x");
        int mx = Array.IndexOf(header, "mag_x");
        var s = new List<Sample>();
        var ts = new List<double>();
        double previous = double.NaN;
        for (int i = 1; i < lines.Length; i++)
        {
            string[] c = lines[i].Trim().Split(',');
            if (c.Length < header.Length) continue;
            Func<int, double> Get = k => double.Parse(c[k], CultureInfo.InvariantCulture);
            double time = Get(t);
            var gyro = new Vec3(Get(gx), Get(gx + 1), Get(gx + 2));
            var accel = new Vec3(Get(ax), Get(ax + 1), Get(ax + 2));
            double dt = double.IsNaN(previous) ? 0.01 : time - previous;
            previous = time;
            s.Add(useMagnetometer && mx >= 0
                ? OrientFilter.Marg(dt, gyro, accel, new Vec3(Get(mx), Get(mx + 1), Get(mx + 2)))
                : OrientFilter.Imu(dt, gyro, accel));
            ts.Add(time);
        }
        samples = s.ToArray();
        times = ts.ToArray();
    }

    void Update()
    {
        if (filter == null || next >= samples.Length) return;
        if (next == 0) clock = times[0];
        clock += Time.deltaTime;
        int count = 0;
        while (next + count < samples.Length && times[next + count] <= clock) count++;
        if (count == 0) return;
        try
        {
            filter.UpdateBatch(samples, next, count, null);
        }
        catch (OrientException e)
        {
            Debug.LogWarning("orient: " + e.Message);
        }
        next += count;
        bone.localRotation = filter.UnityRotation() * mounting;
    }

    void OnDestroy()
    {
        if (filter != null) filter.Dispose();
    }
}
