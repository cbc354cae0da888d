using Orient; using Orient.Native; using UnityEngine;

public class OrientHand : MonoBehaviour {              // a glove: one IMU on each bone
    public Transform[] bones;                          // the wrist, then each finger joint
    public System.Func<Sample[]> readGlove;            // your driver: one sample per bone
    OrientRig rig; Orient.Native.Quaternion[] q;
    void Start() {
        rig = new OrientRig(System.Array.ConvertAll(bones, b => new OrientFilter(Kind.Robust)));
        q = new Orient.Native.Quaternion[bones.Length];
    }
    void Update() {                                    // one native call for the whole hand
        rig.Update(readGlove(), q);
        for (int i = 0; i < bones.Length; i++) bones[i].rotation = q[i].ToUnity(Frame.Enu);
    }
}
