// A C# console program: replays a recording through a filter and prints its
// orientation in orient's ENU and in Unity's convention.
//
//   mcs -unsafe -out:example.exe bindings/csharp/*.cs examples/csharp/ConsoleExample.cs
//   LD_LIBRARY_PATH=target/release mono example.exe examples/data/broad_01_excerpt.csv
using System;
using System.Globalization;
using System.IO;
using Orient;
using Orient.Native;

public static class ConsoleExample
{
    public static int Main(string[] args)
    {
        if (args.Length < 1)
        {
            Console.Error.WriteLine("usage: example.exe RECORDING.csv [KIND]");
            return 2;
        }
        Kind kind = args.Length > 1 ? (Kind)Enum.Parse(typeof(Kind), args[1], true) : Kind.Gmvdk;
        string[] lines = File.ReadAllLines(args[0]);
        string[] header = lines[0].Split(',');
        int t = Array.IndexOf(header, "t"), gx = Array.IndexOf(header, "gyr_x");
        int ax = Array.IndexOf(header, "acc_x"), mx = Array.IndexOf(header, "mag_x");
        using (var filter = new OrientFilter(kind))
        {
            Console.WriteLine("orient " + OrientFilter.Version + ", " + kind + ", parameters:");
            foreach (ParameterInfo p in OrientFilter.ParametersOf(kind))
            {
                Console.WriteLine("  " + p.Name + " = " + filter[p.Id] + " " + p.Unit);
            }
            double previous = double.NaN;
            for (int i = 1; i < lines.Length; i++)
            {
                string[] c = lines[i].Split(',');
                Func<int, double> v = k => double.Parse(c[k], CultureInfo.InvariantCulture);
                double dt = double.IsNaN(previous) ? 0.01 : v(t) - previous;
                previous = v(t);
                filter.Update(OrientFilter.Marg(dt, new Vec3(v(gx), v(gx + 1), v(gx + 2)),
                    new Vec3(v(ax), v(ax + 1), v(ax + 2)), new Vec3(v(mx), v(mx + 1), v(mx + 2))));
            }
            Orient.Native.Quaternion q = filter.Quaternion;
            double x, y, z, w;
            UnityConvert.ToUnity(q, filter.Frame, out x, out y, out z, out w);
            Console.WriteLine(string.Format(CultureInfo.InvariantCulture,
                "{0} samples; ENU q = ({1:F5}, {2:F5}, {3:F5}, {4:F5}); Unity (x,y,z,w) = ({5:F5}, {6:F5}, {7:F5}, {8:F5})",
                lines.Length - 1, q.W, q.X, q.Y, q.Z, x, y, z, w));
            Diagnostics d = filter.Diagnostics;
            if ((d.Present & Consts.DiagAlpha) != 0)
            {
                Console.WriteLine(string.Format(CultureInfo.InvariantCulture, "alpha {0:F3}, mu_K {1:F3}", d.Alpha, d.MuK));
            }
        }
        return 0;
    }
}
