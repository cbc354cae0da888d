// Unity-facing helpers: orient's right-handed earth-frame values as UnityEngine types.
// The math is in Orient.UnityConvert (no UnityEngine dependency, tested under Mono).
using Orient.Native;
using UnityEngine;

namespace Orient
{
    public static class OrientUnity
    {
        /// <summary>An orientation (sensor to earth, in `frame`) as a Unity rotation in a
        /// left-handed, Y-up world whose +X is east and +Z is north.</summary>
        public static UnityEngine.Quaternion ToUnity(this Native.Quaternion q, Frame frame)
        {
            double x, y, z, w;
            UnityConvert.ToUnity(q, frame, out x, out y, out z, out w);
            return new UnityEngine.Quaternion((float)x, (float)y, (float)z, (float)w);
        }

        /// <summary>A Unity rotation as an ENU orientation.</summary>
        public static Native.Quaternion ToOrient(this UnityEngine.Quaternion q)
        {
            return UnityConvert.FromUnity(q.x, q.y, q.z, q.w);
        }

        /// <summary>An ENU vector (e.g. linear acceleration in the earth frame) in Unity's world.</summary>
        public static Vector3 ToUnity(this Vec3 v)
        {
            double x, y, z;
            UnityConvert.ToUnity(v, out x, out y, out z);
            return new Vector3((float)x, (float)y, (float)z);
        }

        /// <summary>A Unity world vector as ENU.</summary>
        public static Vec3 ToOrient(this Vector3 v)
        {
            return UnityConvert.FromUnity(v.x, v.y, v.z);
        }

        /// <summary>The filter's current orientation as a Unity rotation.</summary>
        public static UnityEngine.Quaternion UnityRotation(this OrientFilter filter)
        {
            return filter.Quaternion.ToUnity(filter.Frame);
        }
    }
}
