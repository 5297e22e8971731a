// SPDX-License-Identifier: MIT
// The C# binding's test (integrations/csharp/tests/run.sh runs it under mono):
//   BindingTest.exe RIG=DIGEST ...        each rig's character digest equals
//                                         the native runtime's (posemorph-positions-hash
//                                         RIG --characters K prints it), bit for bit
//   BindingTest.exe --refuse RIG MESSAGE  loading RIG throws PosemorphException with
//                                         exactly the native loader's message
// plus the binding's own checks on each rig (names, lists, the animator).
using System;
using System.Collections.Generic;
using System.Globalization;
using Posemorph;

static class BindingTest {
  static int failures = 0;
  static void Expect(bool ok, string what) {
    if (ok) return;
    Console.Error.WriteLine("BindingTest: failed: " + what);
    ++failures;
  }

  sealed class Fnv {
    public ulong H = 14695981039346656037UL;
    public void U32(uint v) {
      for (int i = 0; i < 4; ++i) H = (H ^ ((v >> (8 * i)) & 0xFF)) * 1099511628211UL;
    }
    public void F32(float f) { U32(BitConverter.ToUInt32(BitConverter.GetBytes(f), 0)); }
  }

  // The character digest (integrations/README.md), as posemorph-positions-hash computes it.
  static string Digest(Rig rig, int count) {
    uint later = rig.ChannelCount - 1;
    var points = new double[2 * count];
    var channelPoints = new double[2 * count * Math.Max(later, 1u)];
    for (int k = 0; k < count; ++k) {
      if (rig.PathCount > 0) {
        rig.SamplePath(0, 0, 0.37 * k, out points[2 * k], out points[2 * k + 1]);
      } else {
        double[] p = rig.ChannelPosePoints(0);
        long pose = k % rig.PoseCount;
        points[2 * k] = p[2 * pose];
        points[2 * k + 1] = p[2 * pose + 1];
      }
      for (uint c = 1; c <= later; ++c) {
        long at = 2 * (k * later + (c - 1));
        if (rig.PathCountOf(c) > 0) {
          rig.SamplePath(c, 0, 0.23 * k * c, out channelPoints[at], out channelPoints[at + 1]);
        } else {
          double[] p = rig.ChannelPosePoints(c);
          channelPoints[at] = p[0];
          channelPoints[at + 1] = p[1];
        }
      }
    }
    using (var crowd = new Crowd(rig, count)) {
      crowd.Evaluate(points, later > 0 ? channelPoints : null);
      var f = new Fnv();
      uint A = rig.AttachmentCount;
      for (int k = 0; k < count; ++k) Hash(f, crowd, k, 0);
      for (uint a = 1; a <= A; ++a)
        for (int k = 0; k < count; ++k) Hash(f, crowd, k, a);
      long steps = 0;
      for (int k = 0; k < count; ++k) {
        for (uint l = 0; l <= A; ++l) {
          DrawList d = crowd.List(k, l);
          f.U32((uint)d.Drawings.Length);
          foreach (var b in d.Drawings) {
            f.U32(b.Pose);
            f.F32(b.Weight);
          }
        }
        foreach (var s in crowd.Steps(k)) {
          f.U32(s.List);
          f.U32(s.Part);
          ++steps;
        }
      }
      return string.Format("character-fnv1a64={0:x16} characters={1} steps={2}", f.H, count, steps);
    }
  }

  static void Hash(Fnv f, Crowd crowd, int k, uint list) {
    DrawList d = crowd.List(k, list);
    var p = new float[2 * d.VertexCount];
    crowd.CopyPositions(k, list, p);
    foreach (float v in p) f.F32(v);
  }

  // What a game reads of a rig, checked against itself: names round-trip,
  // every list's parts cover its triangles, an animator's frame is finite.
  static void Checks(Rig rig) {
    for (uint c = 0; c < rig.ChannelCount; ++c) {
      for (uint p = 0; p < rig.PathCountOf(c); ++p) Expect(rig.FindPath(rig.PathName(c, p), c) == p, "path names");
      Expect(rig.PoseName(c, 0).Length > 0, "pose names");
      if (rig.ChannelCount > 1) Expect(rig.FindChannel(rig.ChannelName(c)) == c, "channel names");
      double x, y, qx, qy;
      double[] pp = rig.ChannelPosePoints(c);
      x = pp[0];
      y = pp[1];
      rig.Dequantize(c, rig.Quantize(c, x, y), out qx, out qy);
      Expect(Math.Abs(qx - x) < 1e-2 && Math.Abs(qy - y) < 1e-2, "4-byte points");
    }
    Expect(rig.ListCount == 1 + rig.AttachmentCount, "list count");
    for (uint l = 0; l < rig.ListCount; ++l) {
      uint v, t, n, parts;
      rig.ListCounts(l, out v, out t, out n, out parts);
      uint covered = 0;
      for (uint p = 0; p < parts; ++p) covered += rig.ListPart(l, p).TriangleCount;
      Expect(covered == t, "parts cover the triangles");
      Expect(rig.ListCanvas(l, 0).Width >= 0, "canvas");
      // Texture pages: every part's region in every pose lies inside its page.
      for (uint p = 0; p < parts; ++p)
        for (uint pose = 0; pose < n; ++pose) {
          Region g = rig.PartRegion(l, p, pose);
          Page page = rig.ListPage(l, g.Page);
          Expect(g.Page < rig.PageCount(l) && (page.Width == 0 || g.X + g.Width <= page.Width) &&
                     (page.Atlas == 1) == rig.HasAtlas && (!rig.HasAtlas || rig.PageName(l, g.Page).Length > 0),
                 "regions on their pages");
        }
    }
    using (var animator = new Animator(rig, 3))
    using (var crowd = new Crowd(rig, 3)) {
      for (int k = 0; k < 3; ++k)
        for (uint c = 0; c < rig.ChannelCount; ++c)
          if (rig.PathCountOf(c) > 0) animator.Play(k, c, 0, 1 + 0.5 * k);
      var place = new[] { Transform.Make(0, 0), Transform.Make(100, 0, 0, 1, 1, true), Transform.Make(200, 10, 0.2) };
      for (int frame = 0; frame < 30; ++frame) {
        animator.Update(1.0 / 30);
        crowd.Evaluate(animator, place);
      }
      bool finite = true;
      for (int k = 0; k < 3; ++k)
        for (uint l = 0; l < rig.ListCount; ++l) {
          DrawList d = crowd.List(k, l);
          var p = new float[2 * d.VertexCount];
          crowd.CopyPositions(k, l, p);
          foreach (float x in p) finite &= !float.IsNaN(x) && !float.IsInfinity(x);
          float sum = 0;
          foreach (var b in d.Drawings) sum += b.Weight;
          Expect(Math.Abs(sum - 1) < 1e-5, "drawing weights sum to 1");
        }
      Expect(finite, "animated frames are finite");
      // The garbage-free readers give what the copying ones give.
      var steps = new DrawStep[crowd.MaxSteps];
      var drawings = new BlendedDrawing[8];
      for (int k = 0; k < 3; ++k) {
        DrawStep[] copied = crowd.Steps(k);
        int n = crowd.CopySteps(k, steps);
        bool same = n == copied.Length;
        for (int i = 0; same && i < n; ++i) same = steps[i].List == copied[i].List && steps[i].Part == copied[i].Part;
        Expect(same && n <= crowd.MaxSteps, "CopySteps is Steps");
        for (uint l = 0; l < rig.ListCount; ++l) {
          DrawList d = crowd.List(k, l);
          int m = crowd.CopyDrawings(k, l, drawings);
          bool sameDrawings = m == d.Drawings.Length;
          for (int i = 0; sameDrawings && i < m; ++i)
            sameDrawings = drawings[i].Pose == d.Drawings[i].Pose && drawings[i].Weight == d.Drawings[i].Weight;
          Transform t;
          Colour c;
          bool mirrored;
          crowd.Appearance(k, l, out t, out c, out mirrored);
          Expect(sameDrawings && t.Tx == d.Transform.Tx && c.A == d.Colour.A && mirrored == d.Mirrored &&
                     crowd.PartOpacity(k, l, 0) == d.PartOpacity[0],
                 "CopyDrawings and Appearance are List");
        }
      }
      Expect(crowd.List(1, 0).Mirrored && !crowd.List(0, 0).Mirrored, "a flipped transform mirrors");
      double ax, ay;
      bool left;
      rig.Placement(out ax, out ay, out left);
      Transform placed = Transform.Place(rig, 7, 9, 0, 2, !left);  // the anchor lands at (7, 9), mirrored
      Expect(Math.Abs(placed.A * ax + placed.C * ay + placed.Tx - 7) < 1e-3 && placed.A < 0, "place the anchor");
      Bounds pad = rig.PadRange(0);
      Expect(pad.MinX < pad.MaxX && pad.MinY < pad.MaxY, "pad range");
      Transform both = Transform.Compose(Transform.Make(5, 0), Transform.Make(0, 0, 0, 2, 2));
      Expect(both.A == 2 && both.Tx == 5, "compose");
      bool threw = false;
      try {
        crowd.Evaluate(new double[1]);
      } catch (PosemorphException e) {
        threw = e.Message.StartsWith(rig.File + ": ");
      }
      Expect(threw, "too few points are refused with the rig's name");
    }
  }

  static int Main(string[] args) {
    Console.WriteLine("BindingTest: posemorph " + Rig.Version);
    for (int i = 0; i < args.Length; ++i) {
      if (args[i] == "--refuse" && i + 2 < args.Length) {
        string path = args[i + 1], expected = args[i + 2];
        i += 2;
        string got = "(loaded)";
        try {
          using (Rig.Load(path)) {}
        } catch (PosemorphException e) {
          got = e.Message;
        }
        Expect(got == expected, "refusal of " + path + ": got \"" + got + "\", expected \"" + expected + "\"");
        Console.WriteLine("BindingTest: refused " + path + ": " + got);
        continue;
      }
      int eq = args[i].IndexOf('=');
      string rigPath = args[i].Substring(0, eq), want = args[i].Substring(eq + 1);
      using (Rig rig = Rig.Load(rigPath)) {
        int count = int.Parse(want.Substring(want.IndexOf("characters=") + 11).Split(' ')[0], CultureInfo.InvariantCulture);
        string got = Digest(rig, count);
        Expect(got == want, rigPath + ": C# " + got + ", native " + want);
        Console.WriteLine("BindingTest: " + rigPath + ": " + got + (got == want ? " (the native runtime's)" : " (DIFFERS)"));
        Checks(rig);
      }
    }
    Console.WriteLine("BindingTest: " + (failures == 0 ? "ok" : failures + " failures"));
    return failures == 0 ? 0 : 1;
  }
}
