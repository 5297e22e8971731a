// SPDX-License-Identifier: MIT
// A crowd as a C# game runs it (MonoGame, FNA, Godot C#, Unity would draw
// where this prints): load a rig, animate N characters on their paths,
// evaluate every frame, and walk one character's draw steps -- the part,
// its texture per blended drawing, the weights -- as a renderer's draw calls;
// or draw a frame of them into a PNG with Picture.cs's software renderer.
//   mono Example.exe RIG.pmrig [N]
//   mono Example.exe RIG.pmrig --picture OUT.png [--crowd N] [--at X,Y] [--size WxH] [--images DIR]
using System;
using System.Collections.Generic;
using System.IO;
using Posemorph;

static class Example {
  const string Usage =
      "usage: Example.exe RIG.pmrig [N]\n" +
      "       Example.exe RIG.pmrig --picture OUT.png [--crowd N] [--at X,Y] [--size WxH] [--images DIR]";

  static int Main(string[] args) {
    if (args.Length < 1) {
      Console.Error.WriteLine(Usage);
      return 2;
    }
    if (args.Length > 1 && args[1].StartsWith("--")) return DrawPicture(args);
    int n = args.Length > 1 ? int.Parse(args[1]) : 50;
    try {
      using (var rig = Rig.Load(args[0]))
      using (var animator = new Animator(rig, n))
      using (var crowd = new Crowd(rig, n)) {
        var place = new Transform[n];
        for (int k = 0; k < n; ++k) {
          // Each channel on its first path, at its own speed; every other character faces left.
          for (uint c = 0; c < rig.ChannelCount; ++c)
            if (rig.PathCountOf(c) > 0) animator.Play(k, c, 0, 0.8 + 0.01 * k);
          place[k] = Transform.Make(40.0 * (k % 20), 60.0 * (k / 20), 0, 0.5, 0.5, k % 2 == 1);
        }
        int drawCalls = 0;
        var steps = new DrawStep[crowd.MaxSteps];  // made once: the frame loop makes no garbage
        for (int frame = 0; frame < 60; ++frame) {
          animator.Update(1.0 / 60);
          crowd.Evaluate(animator, place);
          drawCalls = 0;
          for (int k = 0; k < n; ++k) drawCalls += crowd.CopySteps(k, steps);  // one draw per step
        }
        var textures = new HashSet<string>();  // what a renderer uploads: each page once
        for (uint l = 0; l < rig.ListCount; ++l)
          for (uint p = 0; p < rig.PageCount(l); ++p) textures.Add(rig.PageName(l, p));
        Console.WriteLine("{0}: {1} characters, {2} lists each, {3} draw calls a frame ({4} per character), {5} " +
                          "texture(s) ({6})", rig.File, n, rig.ListCount, drawCalls, drawCalls / n, textures.Count,
                          rig.HasAtlas ? "an atlas" : "one per drawing");
        // Character 0's draw calls, back to front.
        foreach (DrawStep s in crowd.Steps(0)) {
          DrawList l = crowd.List(0, s.List);
          Part part = rig.ListPart(s.List, s.Part);
          Console.Write("  list {0} part '{1}': triangles {2}..{3}", s.List, rig.PartName(s.List, s.Part),
                        part.FirstTriangle, part.FirstTriangle + part.TriangleCount - 1);
          foreach (BlendedDrawing d in l.Drawings) {
            Region g = rig.PartRegion(s.List, s.Part, d.Pose);
            Console.Write(", {0} ({1} at {2},{3}) x {4:0.000}", rig.PartImage(s.List, s.Part, d.Pose),
                          rig.PageName(s.List, g.Page), g.X, g.Y, d.Weight);
          }
          Console.WriteLine();
        }
      }
    } catch (PosemorphException e) {
      Console.Error.WriteLine("Example: " + e.Message);
      return 1;
    }
    return 0;
  }

  // A frame of N characters in a grid (every other one facing left), fitted
  // to the picture as posemorph-view frames one: each character's bounds
  // over its poses with a 6% margin. With --at every character is at that
  // point (the other channels at their first pose); else they walk their
  // paths for a second.
  static int DrawPicture(string[] args) {
    string output = null, images = null;
    int n = 1, width = 640, height = 640;
    double[] at = null;
    for (int i = 1; i < args.Length; ++i) {
      string value = i + 1 < args.Length ? args[i + 1] : null;
      if (value == null) return Fail("Example: " + args[i] + " needs a value\n" + Usage, 2);
      string[] pair = value.Split(args[i] == "--size" ? 'x' : ',');
      if (args[i] == "--picture") output = value;
      else if (args[i] == "--images") images = value;
      else if (args[i] == "--crowd" && int.TryParse(value, out n) && n >= 1 && n <= 10000) { }
      else if (args[i] == "--at" && pair.Length == 2)
        at = new[] { double.Parse(pair[0], System.Globalization.CultureInfo.InvariantCulture),
                     double.Parse(pair[1], System.Globalization.CultureInfo.InvariantCulture) };
      else if (args[i] == "--size" && pair.Length == 2 && int.TryParse(pair[0], out width) &&
               int.TryParse(pair[1], out height) && width >= 1 && height >= 1 && width <= 8192 && height <= 8192) { }
      else return Fail("Example: " + args[i] + " " + value + ": not an option here\n" + Usage, 2);
      ++i;
    }
    if (output == null) return Fail(Usage, 2);
    try {
      using (var rig = Rig.Load(args[0]))
      using (var crowd = new Crowd(rig, n)) {
        Bounds b = rig.Bounds();
        double margin = 0.06 * Math.Max(b.MaxX - b.MinX, b.MaxY - b.MinY);
        double cw = b.MaxX - b.MinX + 2 * margin, ch = b.MaxY - b.MinY + 2 * margin;
        int columns = (int)Math.Ceiling(Math.Sqrt(n)), rows = (n + columns - 1) / columns;
        var place = new Transform[n];
        Transform centre = Transform.Make(-(b.MinX + b.MaxX) / 2, -(b.MinY + b.MaxY) / 2);
        for (int k = 0; k < n; ++k)
          place[k] = Transform.Compose(Transform.Make(cw * (k % columns), -ch * (k / columns), 0, 1, 1, k % 2 == 1),
                                       centre);
        uint later = rig.ChannelCount - 1;
        if (at != null) {
          var points = new double[2 * n];
          var channelPoints = new double[Math.Max(2 * n * (int)later, 1)];
          for (int k = 0; k < n; ++k) {
            points[2 * k] = at[0];
            points[2 * k + 1] = at[1];
            for (uint c = 1; c <= later; ++c) {
              double[] first = rig.ChannelPosePoints(c);
              channelPoints[2 * (k * later + c - 1)] = first[0];
              channelPoints[2 * (k * later + c - 1) + 1] = first[1];
            }
          }
          crowd.Evaluate(points, later > 0 ? channelPoints : null, place);
        } else {
          using (var animator = new Animator(rig, n)) {
            for (int k = 0; k < n; ++k)
              for (uint c = 0; c < rig.ChannelCount; ++c)
                if (rig.PathCountOf(c) > 0) animator.Play(k, c, 0, 0.8 + 0.01 * k);
            for (int frame = 0; frame < 60; ++frame) animator.Update(1.0 / 60);
            crowd.Evaluate(animator, place);
          }
        }
        var picture = new Picture(width, height);
        picture.Clear(0.93f, 0.94f, 0.95f);
        var renderer = new SoftwareRenderer(rig, images);
        renderer.Zoom = Math.Min(width / (cw * columns), height / (ch * rows));
        renderer.CentreX = cw * (columns - 1) / 2;
        renderer.CentreY = -ch * (rows - 1) / 2;
        int steps = 0;
        for (int k = 0; k < n; ++k) steps += renderer.Draw(picture, crowd, k);
        Png.Write(output, picture);
        Console.WriteLine("wrote {0}: {1} character(s) of {2}, {3}x{4}, {5} draw steps", output, n, rig.File, width,
                          height, steps);
      }
    } catch (PosemorphException e) {
      return Fail("Example: " + e.Message, 1);
    } catch (InvalidDataException e) {
      return Fail("Example: " + e.Message, 1);
    }
    return 0;
  }

  static int Fail(string message, int status) {
    Console.Error.WriteLine(message);
    return status;
  }
}
