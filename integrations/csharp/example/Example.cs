// SPDX-License-Identifier: MIT
// A crowd as a C# game runs it (MonoGame, FNA, Godot C#, Unity would draw
// where this prints): load a rig, animate N characters on their paths,
// evaluate every frame, and walk one character's draw steps -- the part,
// its texture per blended drawing, the weights -- as a renderer's draw calls.
//   mono Example.exe RIG.pmrig [N]
using System;
using System.Collections.Generic;
using Posemorph;

static class Example {
  static int Main(string[] args) {
    if (args.Length < 1) {
      Console.Error.WriteLine("usage: Example.exe RIG.pmrig [N]");
      return 2;
    }
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
}
