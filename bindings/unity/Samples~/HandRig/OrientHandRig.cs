// Drives a whole hand rig from recorded IMU/MARG streams, one sensor per bone (a data
// glove: one IMU on the back of the hand and one on each finger segment). Each bone has
// its own filter; every frame, the samples whose time has come are fed to all of them
// together through OrientRig (one native call per sample step), and each bone's world
// rotation is set from its sensor's orientation.
//
// Flat-hand calibration (rig calibration, orient_rig_calibrate): the avatar's hand as it
// stands in the scene at Start is the reference posture (model it lying flat, palm
// down). At Calibrate At seconds into the recording, while the real hand lies flat on a
// table, every bone's mounting and a common heading are computed natively, so that each
// bone reads its rest rotation then and follows its segment afterwards; the per-bone
// Mounting fields below are then no longer needed. Without a magnetometer each bone's
// heading is its filter's own, which one common heading would take into its mounting:
// then each bone's heading is set on its own (orient_rig_calibrate_each), the sensors
// taken as strapped along their bones. Call CalibrateFlatHand() from a key
// or a button to calibrate again (e.g. after a sensor slipped).
//
// Joints (orient_joints_*): with Use Joints, the calibration also binds the bones through
// the hand's joints, each finger's proximal bone to the hand by a 2-DoF joint (MCP:
// abduction about the hand's Abduction Axis, then flexion about the bone's Flexion Axis)
// and each further bone to the one before by a hinge (PIP, DIP: about Flexion Axis).
// Each bone is then drawn as its joints hold it to its parent: without a magnetometer
// every sensor's heading drifts on its own and the fingers twist apart after minutes;
// through the joints they stay on the hand. The axes are given in each bone's local
// frame (most humanoid hands flex about local X) and refined from motion.
//
// Setup: put this on any GameObject. Either assign a Humanoid Animator (the wrist and the
// three joints of each finger, 16 bones, are filled in) or fill Bones by hand. Give each
// bone a TextAsset recording in orient's CSV layout (header with t, gyr_x..z, acc_x..z
// and optionally mag_x..z; rad/s, m/s^2, any magnetometer unit), or leave it empty to
// replay Default Recording (Recordings/broad_01_15s.csv in this sample).
using System;
using System.Collections.Generic;
using System.Globalization;
using Orient;
using Orient.Native;
using UnityEngine;

[Serializable]
public class OrientRigBone
{
    [Tooltip("Name shown in the list (filled from the avatar)")]
    public string name = "";

    [Tooltip("The bone's Transform")]
    public Transform bone;

    [Tooltip("This bone's sensor recording; empty: the rig's default recording")]
    public TextAsset recording;

    [Tooltip("Rotation from the sensor to the bone (how the sensor sits on it)")]
    public UnityEngine.Quaternion mounting = UnityEngine.Quaternion.identity;
}

public class OrientHandRig : MonoBehaviour
{
    [Tooltip("Optional Humanoid Animator: fills Bones with the wrist and finger joints")]
    public Animator animator;

    [Tooltip("Which hand of the avatar to fill in")]
    public bool rightHand = true;

    [Tooltip("Recording for bones without their own")]
    public TextAsset defaultRecording;

    [Tooltip("Filter kind for every bone (Robust is the recommended one)")]
    public Kind kind = Kind.Robust;

    [Tooltip("Use the magnetometer columns when present (near a hand the field is rarely clean: leave it off under joints)")]
    public bool useMagnetometer = false;

    [Tooltip("Rotation applied in front of every bone: aligns the recording's north with the scene")]
    public UnityEngine.Quaternion worldAlignment = UnityEngine.Quaternion.identity;

    [Tooltip("Seconds into the recording at which the hand lies flat in the avatar's rest pose; negative: never")]
    public float calibrateAt = 0.5f;

    [Tooltip("Hold each finger bone to its parent through the hand's joints (bones from the avatar)")]
    public bool useJoints = true;

    [Tooltip("The axis each finger bone flexes about, in the bone's local frame")]
    public Vector3 flexionAxis = new Vector3(1, 0, 0);

    [Tooltip("The axis the fingers spread about (MCP abduction), in the hand bone's local frame")]
    public Vector3 abductionAxis = new Vector3(0, 1, 0);

    public OrientRigBone[] bones = new OrientRigBone[0];

    // Each bone's rotation at Start, as an ENU orientation: the flat-hand reference posture.
    private Orient.Native.Quaternion[] flatPose = new Orient.Native.Quaternion[0];
    private bool calibrated;
    // Some bone runs without a magnetometer (6D): its heading is its filter's own.
    private bool sixD;

    private OrientFilter[] filters = new OrientFilter[0];
    private OrientRigBone[] driven = new OrientRigBone[0];
    private OrientRig rig;
    private OrientJoints joints;
    private Sample[][] streams = new Sample[0][];
    private double[] times = new double[0];
    private Sample[] step = new Sample[0];
    private Orient.Native.Quaternion[] orientations = new Orient.Native.Quaternion[0];
    private int next;
    private int steps;
    private double clock;

    // The wrist, then each finger's three joints: HumanBodyBones names after "Left"/"Right".
    private static readonly string[] HandJoints =
    {
        "Hand",
        "ThumbProximal", "ThumbIntermediate", "ThumbDistal",
        "IndexProximal", "IndexIntermediate", "IndexDistal",
        "MiddleProximal", "MiddleIntermediate", "MiddleDistal",
        "RingProximal", "RingIntermediate", "RingDistal",
        "LittleProximal", "LittleIntermediate", "LittleDistal",
    };

    void Start()
    {
        if (animator != null && bones.Length == 0) bones = FromAvatar(animator, rightHand);
        var used = new List<OrientRigBone>();
        var loaded = new List<Sample[]>();
        double[] clockTimes = null;
        var cache = new Dictionary<TextAsset, KeyValuePair<Sample[], double[]>>();
        foreach (var b in bones)
        {
            TextAsset rec = b.recording != null ? b.recording : defaultRecording;
            if (b.bone == null || rec == null) continue;
            KeyValuePair<Sample[], double[]> data;
            if (!cache.TryGetValue(rec, out data))
            {
                double[] t;
                Sample[] s = Load(rec.text, useMagnetometer, out t);
                data = new KeyValuePair<Sample[], double[]>(s, t);
                cache[rec] = data;
            }
            used.Add(b);
            loaded.Add(data.Key);
            if (data.Key.Length > 0 && (data.Key[0].Flags & Consts.SampleMag) == 0) sixD = true;
            if (clockTimes == null || data.Value.Length < clockTimes.Length) clockTimes = data.Value;
        }
        driven = used.ToArray();
        streams = loaded.ToArray();
        times = clockTimes ?? new double[0];
        steps = times.Length;
        filters = new OrientFilter[driven.Length];
        for (int i = 0; i < driven.Length; i++)
        {
            // Under joints each filter may follow its gyroscope's drifting bias faster: the
            // joints hold the headings (orient_config_for_joints). Until the flat-hand
            // calibration binds the joints the filters run alone with these settings too.
            var settings = new OrientSettings(kind);
            if (useJoints) settings.ForJoints();
            filters[i] = new OrientFilter(settings);
        }
        rig = new OrientRig(filters);
        step = new Sample[driven.Length];
        orientations = new Orient.Native.Quaternion[driven.Length];
        flatPose = new Orient.Native.Quaternion[driven.Length];
        for (int i = 0; i < driven.Length; i++)
        {
            // The filters work in ENU (their default frame), as ToOrient gives it.
            flatPose[i] = (UnityEngine.Quaternion.Inverse(worldAlignment) * driven[i].bone.rotation).ToOrient();
        }
        if (driven.Length == 0) Debug.LogWarning("orient: no bone has a Transform and a recording");
    }

    /// <summary>Rig calibration from the flat-hand pose: call while the hand lies flat as
    /// the avatar's hand did at Start. With a magnetometer the heading the hand faces is
    /// estimated from the rig (sensors strapped along their bones, tilted as they may
    /// be); with 6D bones each bone's heading is set on its own, the sensors taken as
    /// strapped along their bones.</summary>
    public void CalibrateFlatHand()
    {
        try
        {
            if (sixD) rig.CalibrateEach(flatPose);
            else rig.Calibrate(flatPose);
            calibrated = true;
            if (useJoints) BindJoints();
        }
        catch (OrientException e)
        {
            Debug.LogWarning("orient: flat-hand calibration: " + e.Message);
        }
    }

    /// <summary>The hand's joints from the bones' names (the avatar's: "...Hand",
    /// "...IndexProximal", "...IndexIntermediate", ...), their axes in the bones' frames,
    /// with the mountings the calibration set.</summary>
    private void BindJoints()
    {
        var list = new List<Joint>();
        var mountings = new Orient.Native.Quaternion[driven.Length];
        for (int i = 0; i < driven.Length; i++) mountings[i] = filters[i].Mounting;
        for (int c = 0; c < driven.Length; c++)
        {
            string name = driven[c].name;
            string parentName = name.EndsWith("Proximal") ? "Hand"
                : name.Replace("Intermediate", "Proximal").Replace("Distal", "Intermediate");
            if (parentName == name) continue;
            int p = Array.FindIndex(driven, b => name.EndsWith("Proximal") ? b.name.EndsWith("Hand") : b.name == parentName);
            if (p < 0) continue;
            // Axes in the bones' frames; the library turns them into the sensors' through
            // the mountings.
            Vec3 flexion = flexionAxis.ToOrient();
            if (name.EndsWith("Proximal"))
                list.Add(OrientJoints.TwoDof(p, c, abductionAxis.ToOrient(), flexion, true));
            else
                list.Add(OrientJoints.Hinge(p, c, flexion, flexion, true));
        }
        if (joints != null) joints.Dispose();
        joints = list.Count > 0 ? new OrientJoints(rig, list.ToArray(), mountings) : null;
    }

    /// <summary>The wrist and finger joints of a Humanoid avatar that the avatar maps.</summary>
    public static OrientRigBone[] FromAvatar(Animator avatar, bool right)
    {
        var list = new List<OrientRigBone>();
        foreach (var joint in HandJoints)
        {
            var id = (HumanBodyBones)Enum.Parse(typeof(HumanBodyBones), (right ? "Right" : "Left") + joint);
            Transform t = avatar.GetBoneTransform(id);
            if (t == null) continue;
            var b = new OrientRigBone();
            b.name = id.ToString();
            b.bone = t;
            list.Add(b);
        }
        return list.ToArray();
    }

    /// <summary>Samples and times from a recording in orient's CSV layout.</summary>
    public static Sample[] Load(string text, bool useMag, out double[] times)
    {
        string[] lines = text.Split('\n');
        string[] header = lines[0].Trim().Split(',');
        int t = Array.IndexOf(header, "t");
        int gx = Array.IndexOf(header, "gyr_x");
        int ax = Array.IndexOf(header, "acc_x");
        int mx = useMag ? Array.IndexOf(header, "mag_x") : -1;
        if (t < 0 || gx < 0 || ax < 0) throw new FormatException("recording needs t, gyr_x..z and acc_x..z columns");
        var rows = new List<string[]>();
        var ts = new List<double>();
        for (int i = 1; i < lines.Length; i++)
        {
            string[] c = lines[i].Trim().Split(',');
            if (c.Length < header.Length) continue;
            rows.Add(c);
            ts.Add(double.Parse(c[t], CultureInfo.InvariantCulture));
        }
        var samples = new Sample[rows.Count];
        for (int i = 0; i < rows.Count; i++)
        {
            string[] c = rows[i];
            Func<int, double> get = k => double.Parse(c[k], CultureInfo.InvariantCulture);
            // dt is the time since the previous sample; the first takes the second's spacing.
            double dt = i > 0 ? ts[i] - ts[i - 1] : (rows.Count > 1 ? ts[1] - ts[0] : 0.01);
            var gyro = new Vec3(get(gx), get(gx + 1), get(gx + 2));
            var accel = new Vec3(get(ax), get(ax + 1), get(ax + 2));
            samples[i] = mx >= 0
                ? OrientFilter.Marg(dt, gyro, accel, new Vec3(get(mx), get(mx + 1), get(mx + 2)))
                : OrientFilter.Imu(dt, gyro, accel);
        }
        times = ts.ToArray();
        return samples;
    }

    void Update()
    {
        if (rig == null || driven.Length == 0 || next >= steps) return;
        clock += Time.deltaTime;
        bool moved = false;
        while (next < steps && times[next] - times[0] <= clock)
        {
            for (int i = 0; i < driven.Length; i++) step[i] = streams[i][next];
            try
            {
                rig.Update(step, orientations);
                if (joints != null) joints.Update(step);
            }
            catch (OrientException e)
            {
                Debug.LogWarning("orient: sample " + next + ": " + e.Message);
            }
            next++;
            moved = true;
            if (!calibrated && calibrateAt >= 0 && times[next - 1] - times[0] >= calibrateAt) CalibrateFlatHand();
        }
        if (!moved) return;
        for (int i = 0; i < driven.Length; i++)
        {
            // After calibration the mounting is inside the filter (and the joints); before,
            // the manual one.
            Orient.Native.Quaternion o = joints != null ? joints.Segment(i) : orientations[i];
            UnityEngine.Quaternion q = worldAlignment * o.ToUnity(filters[i].Frame);
            driven[i].bone.rotation = calibrated ? q : q * driven[i].mounting;
        }
    }

    void OnDestroy()
    {
        if (joints != null) joints.Dispose();
        foreach (var f in filters)
        {
            if (f != null) f.Dispose();
        }
    }
}
