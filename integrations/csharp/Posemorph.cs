// SPDX-License-Identifier: MIT
// posemorph for C#: P/Invoke over the runtime's C API (posemorph/posemorph.h,
// posemorph_character.h, posemorph_animation.h) in the shared library
// (libposemorph.so, posemorph.dll, libposemorph.dylib) -- the shape a Unity
// native plugin, Godot C# or MonoGame/FNA take. Builds with mcs -unsafe.
//
//   using (var rig = Posemorph.Rig.Load("pell-face.pmrig"))
//   using (var crowd = new Posemorph.Crowd(rig, 200))
//   using (var animator = new Posemorph.Animator(rig, 200)) {
//     animator.Play(0, 0, rig.FindPath("walk"));
//     animator.Update(dt);                  // each frame
//     crowd.Evaluate(animator);             // positions of every list
//     foreach (var step in crowd.Steps(k)) { ... crowd.List(k, step.List) ... }
//   }
//
// Memory: every buffer the runtime writes is unmanaged memory owned by the
// object that allocated it (Rig, Crowd, Animator) and freed by Dispose (or
// its finaliser). A DrawList is a copy of the list's values; its Positions
// are copied out with CopyPositions, so nothing the caller holds changes
// under it when the next frame is evaluated. The runtime's errors become
// PosemorphException, whose message names the file and the problem.
using System;
using System.IO;
using System.Runtime.InteropServices;
using System.Text;

namespace Posemorph {

public class PosemorphException : Exception {
  public readonly int Code;
  public PosemorphException(int code, string message) : base(message) { Code = code; }
}

[StructLayout(LayoutKind.Sequential)]
public struct Transform {
  public float A, B, C, D, Tx, Ty;  // x' = a x + c y + tx, y' = b x + d y + ty
  public static readonly Transform Identity = new Transform { A = 1, D = 1 };
  // Scale, flip horizontally, rotate counter-clockwise, move (pm_transform_make).
  public static Transform Make(double x, double y, double radians = 0, double scaleX = 1, double scaleY = 1,
                               bool flipX = false) {
    Transform t;
    Native.pm_transform_make(x, y, radians, scaleX, scaleY, flipX ? 1 : 0, out t);
    return t;
  }
  // The rig's anchor (the point it stands on) at world (x, y), turned and
  // scaled about it, facing left or right (pm_transform_place).
  public static Transform Place(Rig rig, double x, double y, double radians = 0, double scale = 1,
                                bool faceLeft = false) {
    Transform t;
    Native.pm_transform_place(rig.H, x, y, radians, scale, faceLeft ? 1 : 0, out t);
    return t;
  }
  // outer after inner (pm_transform_compose).
  public static Transform Compose(Transform outer, Transform inner) {
    Transform t;
    Native.pm_transform_compose(ref outer, ref inner, out t);
    return t;
  }
}

[StructLayout(LayoutKind.Sequential)]
public struct Colour {
  public float R, G, B, A;
}

[StructLayout(LayoutKind.Sequential)]
public struct Part {
  public uint FirstTriangle, TriangleCount;
  public int DrawOrder;
}

[StructLayout(LayoutKind.Sequential)]
public struct Bounds {
  public double MinX, MinY, MaxX, MaxY;
}

[StructLayout(LayoutKind.Sequential)]
public struct Canvas {
  public double Width, Height, PivotX, PivotY;
}

// A texture page (pm_page): an atlas page beside the rig file (premultiplied),
// or, for a rig without an atlas, one drawing (straight alpha).
[StructLayout(LayoutKind.Sequential)]
public struct Page {
  public uint Width, Height;
  public int Atlas, Premultiplied;
}

// Where a part's drawing in a pose lies on its page (pm_region): sample page
// Page at (u ScaleU + OffsetU, v ScaleV + OffsetV), inside X, Y, Width, Height.
[StructLayout(LayoutKind.Sequential)]
public struct Region {
  public uint Page;
  public float ScaleU, OffsetU, ScaleV, OffsetV;
  public uint X, Y, Width, Height;
}

// One drawing of a list's cross-fade.
public struct BlendedDrawing {
  public uint Pose;
  public float Weight;
}

// One step of drawing a character: part Part of list List (0: the body, a + 1: attachment a).
[StructLayout(LayoutKind.Sequential)]
public struct DrawStep {
  public uint List, Part;
}

// A list's values for one frame (copied: they do not change with the next frame).
public sealed class DrawList {
  public uint VertexCount, IndexCount;
  public BlendedDrawing[] Drawings;
  public Transform Transform;
  public bool Mirrored;
  public uint[] Parts;  // back to front
  public Colour Colour;
  public float[] PartOpacity;
}

internal static class Native {
  const string Lib = "posemorph";

  [StructLayout(LayoutKind.Sequential, CharSet = CharSet.Ansi)]
  public struct Error {
    public int code;
    [MarshalAs(UnmanagedType.ByValTStr, SizeConst = 256)] public string message;
  }

  [StructLayout(LayoutKind.Sequential)]
  public struct RigInfo {
    public uint vertex_count, triangle_count, pose_count, path_count;
    public double default_sigma, size;
  }

  [StructLayout(LayoutKind.Sequential)]
  public struct ListInfo {
    public uint vertex_count, triangle_count, pose_count, part_count, channel;
  }

  [StructLayout(LayoutKind.Sequential)]
  public unsafe struct Blended {
    public uint pose;
    public float weight;
    public float* uvs;
  }

  // pm_draw_list, field for field.
  [StructLayout(LayoutKind.Sequential)]
  public unsafe struct DrawListC {
    public float* positions;
    public uint* indices;
    public uint vertex_count, index_count, drawing_count;
    public Blended d0, d1, d2, d3, d4, d5, d6, d7;
    public Transform transform;
    public int mirrored;
    public uint* parts;
    public uint part_count;
    public Colour colour;
    public fixed float part_opacity[64];
    public Blended Drawing(uint i) {
      switch (i) {
        case 0: return d0; case 1: return d1; case 2: return d2; case 3: return d3;
        case 4: return d4; case 5: return d5; case 6: return d6; default: return d7;
      }
    }
  }

  [StructLayout(LayoutKind.Sequential)]
  public struct BufferSizes {
    public UIntPtr workspace_doubles, position_floats, attached_position_floats, attached_lists;
  }

  [StructLayout(LayoutKind.Sequential)]
  public struct Inputs {
    public IntPtr points, channel_points, weights, limited_weights, texture_weights;
    public IntPtr attached_weights, attached_limited_weights, attached_texture_weights, transforms;
  }

  [StructLayout(LayoutKind.Sequential)]
  public struct DrawOptions {
    public double sigma;
    public int limit_weights, linear;
    public uint max_drawings;
    public IntPtr colours, part_opacities;
  }

  [StructLayout(LayoutKind.Sequential)]
  public struct PlayOptions {
    public double speed;
    public int loop;
    public double mix, start;
  }

  [DllImport(Lib)] public static extern IntPtr pm_version();
  [DllImport(Lib)] public static extern int pm_rig_load(byte[] bytes, UIntPtr size, out IntPtr rig, out Error err);
  [DllImport(Lib)] public static extern void pm_rig_free(IntPtr rig);
  [DllImport(Lib)] public static extern void pm_rig_get_info(IntPtr rig, out RigInfo info);
  [DllImport(Lib)] public static extern int pm_rig_pose_name(IntPtr rig, uint pose, byte[] o, UIntPtr c, out UIntPtr n);
  [DllImport(Lib)] public static extern int pm_rig_path_name(IntPtr rig, uint path, byte[] o, UIntPtr c, out UIntPtr n);
  [DllImport(Lib)] public static extern int pm_rig_pose_point(IntPtr rig, uint pose, out double x, out double y);
  [DllImport(Lib)] public static extern int pm_path_find(IntPtr rig, byte[] name);
  [DllImport(Lib)] public static extern int pm_path_sample(IntPtr rig, uint path, double t, out double x, out double y);
  [DllImport(Lib)] public static extern uint pm_rig_channel_count(IntPtr rig);
  [DllImport(Lib)] public static extern int pm_rig_channel_name(IntPtr rig, uint c, byte[] o, UIntPtr cap, out UIntPtr n);
  [DllImport(Lib)] public static extern int pm_rig_find_channel(IntPtr rig, byte[] name);
  [DllImport(Lib)] public static extern int pm_rig_channel_poses(IntPtr rig, uint c, out uint count, double[] points,
                                                                 UIntPtr capacity);
  [DllImport(Lib)] public static extern uint pm_channel_path_count(IntPtr rig, uint c);
  [DllImport(Lib)] public static extern int pm_channel_path_name(IntPtr rig, uint c, uint path, byte[] o, UIntPtr cap,
                                                                 out UIntPtr n);
  [DllImport(Lib)] public static extern int pm_channel_path_find(IntPtr rig, uint c, byte[] name);
  [DllImport(Lib)] public static extern int pm_channel_path_sample(IntPtr rig, uint c, uint path, double t, out double x,
                                                                   out double y);
  [DllImport(Lib)] public static extern int pm_channel_pose_name(IntPtr rig, uint c, uint pose, byte[] o, UIntPtr cap,
                                                                 out UIntPtr n);
  [DllImport(Lib)] public static extern int pm_channel_default_sigma(IntPtr rig, uint c, out double sigma);
  [DllImport(Lib)] public static extern uint pm_rig_attachment_count(IntPtr rig);
  [DllImport(Lib)] public static extern uint pm_rig_attached_weight_count(IntPtr rig);
  [DllImport(Lib)] public static extern uint pm_channel_quantize_point(IntPtr rig, uint c, double x, double y);
  [DllImport(Lib)] public static extern void pm_channel_dequantize_point(IntPtr rig, uint c, uint packed, out double x,
                                                                         out double y);
  [DllImport(Lib)] public static extern uint pm_character_list_count(IntPtr rig);
  [DllImport(Lib)] public static extern int pm_character_list(IntPtr rig, uint list, out ListInfo info);
  [DllImport(Lib)] public static extern int pm_character_part(IntPtr rig, uint list, uint part, out Part p);
  [DllImport(Lib)] public static extern int pm_character_part_name(IntPtr rig, uint list, uint part, byte[] o,
                                                                   UIntPtr cap, out UIntPtr n);
  [DllImport(Lib)] public static extern int pm_character_part_image(IntPtr rig, uint list, uint part, uint pose,
                                                                    byte[] o, UIntPtr cap, out UIntPtr n);
  [DllImport(Lib)] public static extern int pm_character_canvas(IntPtr rig, uint list, uint pose, out Canvas c);
  [DllImport(Lib)] public static extern int pm_character_texture_filter(IntPtr rig, uint list);
  [DllImport(Lib)] public static extern int pm_rig_has_atlas(IntPtr rig);
  [DllImport(Lib)] public static extern uint pm_character_page_count(IntPtr rig, uint list);
  [DllImport(Lib)] public static extern int pm_character_page(IntPtr rig, uint list, uint page, out Page p);
  [DllImport(Lib)] public static extern int pm_character_page_name(IntPtr rig, uint list, uint page, byte[] o,
                                                                   UIntPtr cap, out UIntPtr n);
  [DllImport(Lib)] public static extern int pm_character_part_region(IntPtr rig, uint list, uint part, uint pose,
                                                                     out Region r);
  [DllImport(Lib)] public static extern void pm_transform_make(double x, double y, double r, double sx, double sy,
                                                               int flip, out Transform t);
  [DllImport(Lib)] public static extern void pm_transform_compose(ref Transform o, ref Transform i, out Transform t);
  [DllImport(Lib)] public static extern void pm_transform_place(IntPtr rig, double x, double y, double r, double s,
                                                                int face_left, out Transform t);
  [DllImport(Lib)] public static extern int pm_rig_placement(IntPtr rig, out double x, out double y, out int left);
  [DllImport(Lib)] public static extern int pm_channel_pad_range(IntPtr rig, uint c, out Bounds b);
  [DllImport(Lib)] public static extern int pm_rig_pose_bounds(IntPtr rig, uint pose, out Bounds b);
  [DllImport(Lib)] public static extern void pm_draw_options_default(out DrawOptions o);
  [DllImport(Lib)] public static extern int pm_character_buffers(IntPtr rig, UIntPtr count, out BufferSizes s);
  [DllImport(Lib)] public static extern int pm_character_draw_lists(
      IntPtr rig, ref DrawOptions options, UIntPtr count, ref Inputs inputs, IntPtr workspace, UIntPtr wc,
      IntPtr positions, UIntPtr pc, IntPtr attached_positions, UIntPtr apc, IntPtr lists, UIntPtr lc,
      IntPtr attached_lists, UIntPtr alc);
  [DllImport(Lib)] public static extern uint pm_character_draw_steps(IntPtr rig, IntPtr body, IntPtr attached,
                                                                     [Out] DrawStep[] o, uint capacity);
  [DllImport(Lib)] public static extern UIntPtr pm_animator_size(IntPtr rig, UIntPtr count);
  [DllImport(Lib)] public static extern int pm_animator_reset(IntPtr rig, IntPtr tracks, UIntPtr cap, UIntPtr count);
  [DllImport(Lib)] public static extern void pm_play_options_default(out PlayOptions o);
  [DllImport(Lib)] public static extern int pm_animator_play(IntPtr rig, IntPtr tracks, UIntPtr cap, UIntPtr character,
                                                             uint channel, uint path, ref PlayOptions o);
  [DllImport(Lib)] public static extern int pm_animator_set_point(IntPtr rig, IntPtr tracks, UIntPtr cap,
                                                                  UIntPtr character, uint channel, double x, double y,
                                                                  double mix);
  [DllImport(Lib)] public static extern int pm_animator_update(
      IntPtr rig, IntPtr tracks, UIntPtr cap, UIntPtr count, double dt, double sigma, int limit, IntPtr w, IntPtr wl,
      IntPtr wt, UIntPtr wc, IntPtr aw, IntPtr awl, IntPtr awt, UIntPtr ac, IntPtr events, UIntPtr ec,
      IntPtr event_count, IntPtr missed);

  public static string Utf8(byte[] b, UIntPtr n) { return Encoding.UTF8.GetString(b, 0, (int)n); }
  public static byte[] Z(string s) { return Encoding.UTF8.GetBytes(s + "\0"); }
  // A name through one of the C API's (out, capacity, length) calls.
  public delegate int NameCall(byte[] o, UIntPtr cap, out UIntPtr n);
  public static string Name(NameCall call, string what) {
    UIntPtr n;
    var buf = new byte[256];
    int r = call(buf, (UIntPtr)buf.Length, out n);
    if (r == 11) {  // PM_ERROR_BUFFER_TOO_SMALL: n is the length
      buf = new byte[(int)n + 1];
      r = call(buf, (UIntPtr)buf.Length, out n);
    }
    if (r != 0) throw new PosemorphException(r, what + ": out of range");
    return Utf8(buf, n);
  }
  public static IntPtr Alloc(ulong bytes) { return Marshal.AllocHGlobal((IntPtr)(long)Math.Max(bytes, 8UL)); }
}

// A loaded rig: immutable; many Crowds and Animators may share it.
public sealed class Rig : IDisposable {
  internal IntPtr handle;
  public readonly string File;
  Native.RigInfo info;

  Rig(IntPtr h, string file) {
    handle = h;
    File = file;
    Native.pm_rig_get_info(h, out info);
  }
  // The rig in `path`; PosemorphException "PATH: MESSAGE" when it cannot be read or is refused.
  public static Rig Load(string path) {
    byte[] bytes;
    try {
      bytes = System.IO.File.ReadAllBytes(path);
    } catch (Exception e) {
      throw new PosemorphException(1, path + ": cannot read the file (" + e.Message + ")");
    }
    return Load(bytes, path);
  }
  // The rig in `bytes` (copied: the array may be reused); `name` names it in errors.
  public static Rig Load(byte[] bytes, string name) {
    IntPtr h;
    Native.Error err;
    int r = Native.pm_rig_load(bytes, (UIntPtr)bytes.Length, out h, out err);
    if (r != 0) throw new PosemorphException(r, name + ": " + err.message);
    return new Rig(h, name);
  }
  public static string Version { get { return Marshal.PtrToStringAnsi(Native.pm_version()); } }

  public uint VertexCount { get { return info.vertex_count; } }
  public uint TriangleCount { get { return info.triangle_count; } }
  public uint PoseCount { get { return info.pose_count; } }
  public uint PathCount { get { return info.path_count; } }
  public double DefaultSigma { get { return info.default_sigma; } }
  public uint ChannelCount { get { return Native.pm_rig_channel_count(H); } }
  public uint AttachmentCount { get { return Native.pm_rig_attachment_count(H); } }
  public uint AttachedWeightCount { get { return Native.pm_rig_attached_weight_count(H); } }
  public uint ListCount { get { return Native.pm_character_list_count(H); } }

  internal IntPtr H {
    get {
      if (handle == IntPtr.Zero) throw new ObjectDisposedException("Rig " + File);
      return handle;
    }
  }

  public string ChannelName(uint c) {
    return Native.Name((byte[] o, UIntPtr cap, out UIntPtr n) => Native.pm_rig_channel_name(H, c, o, cap, out n),
                       "channel " + c);
  }
  public int FindChannel(string name) { return Native.pm_rig_find_channel(H, Native.Z(name)); }
  public uint ChannelPoseCount(uint c) {
    uint n;
    if (Native.pm_rig_channel_poses(H, c, out n, null, UIntPtr.Zero) != 0)
      throw new PosemorphException(1, File + ": no channel " + c);
    return n;
  }
  public double[] ChannelPosePoints(uint c) {
    uint n = ChannelPoseCount(c);
    var p = new double[2 * n];
    Native.pm_rig_channel_poses(H, c, out n, p, (UIntPtr)p.Length);
    return p;
  }
  public string PoseName(uint c, uint pose) {
    return Native.Name((byte[] o, UIntPtr cap, out UIntPtr n) => Native.pm_channel_pose_name(H, c, pose, o, cap, out n),
                       "channel " + c + " pose " + pose);
  }
  public uint PathCountOf(uint c) { return Native.pm_channel_path_count(H, c); }
  public string PathName(uint c, uint path) {
    return Native.Name((byte[] o, UIntPtr cap, out UIntPtr n) => Native.pm_channel_path_name(H, c, path, o, cap, out n),
                       "channel " + c + " path " + path);
  }
  // The path's index in channel c, or -1.
  public int FindPath(string name, uint c = 0) { return Native.pm_channel_path_find(H, c, Native.Z(name)); }
  public void SamplePath(uint c, uint path, double time, out double x, out double y) {
    int r = Native.pm_channel_path_sample(H, c, path, time, out x, out y);
    if (r != 0) throw new PosemorphException(r, File + ": channel " + c + " has no path " + path);
  }
  public double ChannelDefaultSigma(uint c) {
    double s;
    if (Native.pm_channel_default_sigma(H, c, out s) != 0) throw new PosemorphException(1, File + ": no channel " + c);
    return s;
  }
  // A pose-space point in 4 bytes, and back.
  public uint Quantize(uint c, double x, double y) { return Native.pm_channel_quantize_point(H, c, x, y); }
  public void Dequantize(uint c, uint packed, out double x, out double y) {
    x = y = 0;
    Native.pm_channel_dequantize_point(H, c, packed, out x, out y);
  }

  // List `list` of a character (0: the body, a + 1: attachment a): counts, parts, drawings, canvases, filter.
  public void ListCounts(uint list, out uint vertices, out uint triangles, out uint poses, out uint parts) {
    Native.ListInfo i;
    if (Native.pm_character_list(H, list, out i) != 0) throw new PosemorphException(1, File + ": no list " + list);
    vertices = i.vertex_count;
    triangles = i.triangle_count;
    poses = i.pose_count;
    parts = i.part_count;
  }
  public Part ListPart(uint list, uint part) {
    Part p;
    if (Native.pm_character_part(H, list, part, out p) != 0)
      throw new PosemorphException(1, File + ": no part " + part + " in list " + list);
    return p;
  }
  public string PartName(uint list, uint part) {
    return Native.Name(
        (byte[] o, UIntPtr cap, out UIntPtr n) => Native.pm_character_part_name(H, list, part, o, cap, out n),
        "list " + list + " part " + part);
  }
  public string PartImage(uint list, uint part, uint pose) {
    return Native.Name(
        (byte[] o, UIntPtr cap, out UIntPtr n) => Native.pm_character_part_image(H, list, part, pose, o, cap, out n),
        "list " + list + " part " + part + " pose " + pose);
  }
  public Canvas ListCanvas(uint list, uint pose) {
    Canvas c;
    if (Native.pm_character_canvas(H, list, pose, out c) != 0)
      throw new PosemorphException(1, File + ": no pose " + pose + " in list " + list);
    return c;
  }
  // Where the character stands (rig units) and whether its drawings face left.
  public void Placement(out double anchorX, out double anchorY, out bool facingLeft) {
    int left;
    Native.pm_rig_placement(H, out anchorX, out anchorY, out left);
    facingLeft = left != 0;
  }
  // Channel c's useful pad range: the box a pad or joystick maps to.
  public Bounds PadRange(uint c) {
    Bounds b;
    if (Native.pm_channel_pad_range(H, c, out b) != 0) throw new PosemorphException(1, File + ": no channel " + c);
    return b;
  }
  // The body's bounds in pose `pose` (rig units, y up); Bounds() over them all.
  public Bounds PoseBounds(uint pose) {
    Bounds b;
    if (Native.pm_rig_pose_bounds(H, pose, out b) != 0) throw new PosemorphException(1, File + ": no pose " + pose);
    return b;
  }
  public Bounds Bounds() {
    Bounds all = PoseBounds(0);
    for (uint i = 1; i < PoseCount; ++i) {
      Bounds b = PoseBounds(i);
      all.MinX = Math.Min(all.MinX, b.MinX);
      all.MinY = Math.Min(all.MinY, b.MinY);
      all.MaxX = Math.Max(all.MaxX, b.MaxX);
      all.MaxY = Math.Max(all.MaxY, b.MaxY);
    }
    return all;
  }
  public bool NearestFilter(uint list) { return Native.pm_character_texture_filter(H, list) == 1; }
  // Texture pages (Rig::page): what a renderer uploads for list `list`, and
  // where part `part`'s drawing in pose `pose` lies on them.
  public bool HasAtlas { get { return Native.pm_rig_has_atlas(H) == 1; } }
  public uint PageCount(uint list) { return Native.pm_character_page_count(H, list); }
  public Page ListPage(uint list, uint page) {
    Page p;
    if (Native.pm_character_page(H, list, page, out p) != 0)
      throw new PosemorphException(1, File + ": no page " + page + " in list " + list);
    return p;
  }
  public string PageName(uint list, uint page) {
    return Native.Name(
        (byte[] o, UIntPtr cap, out UIntPtr n) => Native.pm_character_page_name(H, list, page, o, cap, out n),
        "list " + list + " page " + page);
  }
  public Region PartRegion(uint list, uint part, uint pose) {
    Region r;
    if (Native.pm_character_part_region(H, list, part, pose, out r) != 0)
      throw new PosemorphException(1, File + ": no part " + part + " or pose " + pose + " in list " + list);
    return r;
  }

  public void Dispose() {
    if (handle != IntPtr.Zero) Native.pm_rig_free(handle);
    handle = IntPtr.Zero;
    GC.SuppressFinalize(this);
  }
  ~Rig() {
    if (handle != IntPtr.Zero) Native.pm_rig_free(handle);
  }
}

// Unmanaged memory that a Crowd or an Animator owns.
internal sealed class Block : IDisposable {
  public IntPtr Ptr;
  public readonly ulong Bytes;
  public Block(ulong bytes) {
    Bytes = bytes;
    Ptr = Native.Alloc(bytes);
    unsafe {
      byte* p = (byte*)Ptr;
      for (ulong i = 0; i < Math.Max(bytes, 8UL); ++i) p[i] = 0;
    }
  }
  public void Dispose() {
    if (Ptr != IntPtr.Zero) Marshal.FreeHGlobal(Ptr);
    Ptr = IntPtr.Zero;
  }
}

// The tracks of `count` characters (posemorph/animator.h) in unmanaged memory,
// and the weights their last Update wrote.
public sealed class Animator : IDisposable {
  readonly Rig rig;
  public readonly int Count;
  Block tracks, w, wl, wt, aw, awl, awt;
  internal IntPtr Weights { get { return w.Ptr; } }
  internal IntPtr LimitedWeights { get { return wl.Ptr; } }
  internal IntPtr TextureWeights { get { return wt.Ptr; } }
  internal IntPtr AttachedWeights { get { return aw.Ptr; } }
  internal IntPtr AttachedLimitedWeights { get { return awl.Ptr; } }
  internal IntPtr AttachedTextureWeights { get { return awt.Ptr; } }
  internal Rig RigOf { get { return rig; } }

  public Animator(Rig rig, int count) {
    this.rig = rig;
    Count = count;
    ulong size = (ulong)Native.pm_animator_size(rig.H, (UIntPtr)count);
    if (size == 0) throw new PosemorphException(1, rig.File + ": no animator for " + count + " characters");
    tracks = new Block(size);
    Check(Native.pm_animator_reset(rig.H, tracks.Ptr, (UIntPtr)size, (UIntPtr)count), "reset");
    ulong n = (ulong)count * rig.PoseCount * 8, na = (ulong)count * Math.Max(rig.AttachedWeightCount, 1u) * 8;
    w = new Block(n);
    wl = new Block(n);
    wt = new Block(n);
    aw = new Block(na);
    awl = new Block(na);
    awt = new Block(na);
  }
  void Check(int r, string what) {
    if (r != 0) throw new PosemorphException(r, rig.File + ": animator " + what + " refused (code " + r + ")");
  }
  public void Play(int character, uint channel, int path, double speed = 1, int loop = -1, double mix = 0.2) {
    if (path < 0) throw new PosemorphException(1, rig.File + ": no such path");
    Native.PlayOptions o;
    Native.pm_play_options_default(out o);
    o.speed = speed;
    o.loop = loop;
    o.mix = mix;
    Check(Native.pm_animator_play(rig.H, tracks.Ptr, (UIntPtr)tracks.Bytes, (UIntPtr)character, channel, (uint)path,
                                  ref o),
          "play");
  }
  public void SetPoint(int character, uint channel, double x, double y, double mix = 0.2) {
    Check(Native.pm_animator_set_point(rig.H, tracks.Ptr, (UIntPtr)tracks.Bytes, (UIntPtr)character, channel, x, y,
                                       mix),
          "set point");
  }
  // Advances every character by dt seconds and writes their weights.
  public void Update(double dt) {
    bool attached = rig.AttachmentCount > 0;
    ulong n = (ulong)Count * rig.PoseCount, na = (ulong)Count * rig.AttachedWeightCount;
    Check(Native.pm_animator_update(rig.H, tracks.Ptr, (UIntPtr)tracks.Bytes, (UIntPtr)Count, dt, -1, 1, w.Ptr, wl.Ptr,
                                    wt.Ptr, (UIntPtr)n, attached ? aw.Ptr : IntPtr.Zero,
                                    attached ? awl.Ptr : IntPtr.Zero, attached ? awt.Ptr : IntPtr.Zero,
                                    (UIntPtr)na, IntPtr.Zero, UIntPtr.Zero, IntPtr.Zero, IntPtr.Zero),
          "update");
  }
  public void Dispose() {
    foreach (var b in new[] { tracks, w, wl, wt, aw, awl, awt })
      if (b != null) b.Dispose();
  }
}

// Draw lists of `count` characters of one rig: every channel, the
// attachments, the steps back to front (pm_character_draw_lists).
public sealed class Crowd : IDisposable {
  readonly Rig rig;
  public readonly int Count;
  readonly uint attachments;
  readonly int maxSteps;
  Native.BufferSizes sizes;
  Block work, positions, attachedPositions, lists, attachedLists, inputs;
  readonly int listBytes = Marshal.SizeOf(typeof(Native.DrawListC));

  public Crowd(Rig rig, int count) {
    this.rig = rig;
    Count = count;
    attachments = rig.AttachmentCount;
    for (uint l = 0; l < rig.ListCount; ++l) {
      uint v, t, p, parts;
      rig.ListCounts(l, out v, out t, out p, out parts);
      maxSteps += (int)parts;
    }
    int r = Native.pm_character_buffers(rig.H, (UIntPtr)count, out sizes);
    if (r != 0) throw new PosemorphException(r, rig.File + ": no buffers for " + count + " characters");
    work = new Block((ulong)sizes.workspace_doubles * 8);
    positions = new Block((ulong)sizes.position_floats * 4);
    attachedPositions = new Block((ulong)sizes.attached_position_floats * 4);
    lists = new Block((ulong)count * (ulong)listBytes);
    attachedLists = new Block((ulong)sizes.attached_lists * (ulong)listBytes);
    // points, channel points, transforms
    inputs = new Block((ulong)count * (16 + 16 * Math.Max(rig.ChannelCount, 1u) + 24));
  }

  // Evaluates every character at its points: points (2 x Count, the body's
  // pose space), channelPoints (per character channels 1 .. C-1's x, y; null:
  // their first poses), transforms (Count, or null), sigma < 0: the rig's.
  public void Evaluate(double[] points, double[] channelPoints = null, Transform[] transforms = null,
                       double sigma = -1, uint maxDrawings = 8) {
    if (points == null || points.Length < 2 * Count)
      throw new PosemorphException(1, rig.File + ": " + Count + " characters need " + 2 * Count + " point values");
    uint later = rig.ChannelCount - 1;
    if (channelPoints != null && channelPoints.Length < 2 * Count * later)
      throw new PosemorphException(1, rig.File + ": channel points need " + 2 * Count * later + " values");
    var input = new Native.Inputs();
    IntPtr at = inputs.Ptr;
    Marshal.Copy(points, 0, at, 2 * Count);
    input.points = at;
    at = (IntPtr)((long)at + 16L * Count);
    if (channelPoints != null && later > 0) {
      Marshal.Copy(channelPoints, 0, at, (int)(2 * Count * later));
      input.channel_points = at;
    }
    at = (IntPtr)((long)at + 16L * Count * Math.Max(later, 1u));
    SetTransforms(ref input, transforms, at);
    Run(ref input, sigma, maxDrawings);
  }

  // Evaluates every character from an animator's last Update (its weights).
  public void Evaluate(Animator animator, Transform[] transforms = null, uint maxDrawings = 8) {
    if (animator.RigOf != rig || animator.Count != Count)
      throw new PosemorphException(1, rig.File + ": the animator is not this crowd's (rig and count must agree)");
    var input = new Native.Inputs();
    input.weights = animator.Weights;
    input.limited_weights = animator.LimitedWeights;
    input.texture_weights = animator.TextureWeights;
    if (attachments > 0) {
      input.attached_weights = animator.AttachedWeights;
      input.attached_limited_weights = animator.AttachedLimitedWeights;
      input.attached_texture_weights = animator.AttachedTextureWeights;
    }
    IntPtr at = (IntPtr)((long)inputs.Ptr + 16L * Count + 16L * Count * Math.Max(rig.ChannelCount - 1, 1u));
    SetTransforms(ref input, transforms, at);
    Run(ref input, -1, maxDrawings);
  }

  void SetTransforms(ref Native.Inputs input, Transform[] transforms, IntPtr at) {
    if (transforms == null) return;
    if (transforms.Length < Count) throw new PosemorphException(1, rig.File + ": " + Count + " transforms needed");
    unsafe {
      Transform* t = (Transform*)at;
      for (int k = 0; k < Count; ++k) t[k] = transforms[k];
    }
    input.transforms = at;
  }

  void Run(ref Native.Inputs input, double sigma, uint maxDrawings) {
    Native.DrawOptions o;
    Native.pm_draw_options_default(out o);
    o.sigma = sigma;
    o.max_drawings = maxDrawings;
    int r = Native.pm_character_draw_lists(
        rig.H, ref o, (UIntPtr)Count, ref input, work.Ptr, sizes.workspace_doubles, positions.Ptr,
        sizes.position_floats, attachments > 0 ? attachedPositions.Ptr : IntPtr.Zero,
        sizes.attached_position_floats, lists.Ptr, (UIntPtr)Count,
        attachments > 0 ? attachedLists.Ptr : IntPtr.Zero, sizes.attached_lists);
    if (r != 0) throw new PosemorphException(r, rig.File + ": the frame was refused (code " + r + ")");
  }

  unsafe Native.DrawListC* ListPtr(int character, uint list) {
    if (character < 0 || character >= Count || list > attachments)
      throw new PosemorphException(1, rig.File + ": no list " + list + " of character " + character);
    if (list == 0) return (Native.DrawListC*)((byte*)lists.Ptr + (long)character * listBytes);
    return (Native.DrawListC*)((byte*)attachedLists.Ptr + ((long)character * attachments + list - 1) * listBytes);
  }

  // List `list` of character k (0: the body, a + 1: attachment a), copied.
  public DrawList List(int character, uint list) {
    unsafe {
      Native.DrawListC* l = ListPtr(character, list);
      var d = new DrawList();
      d.VertexCount = l->vertex_count;
      d.IndexCount = l->index_count;
      d.Drawings = new BlendedDrawing[l->drawing_count];
      for (uint i = 0; i < l->drawing_count; ++i) {
        Native.Blended b = l->Drawing(i);
        d.Drawings[i] = new BlendedDrawing { Pose = b.pose, Weight = b.weight };
      }
      d.Transform = l->transform;
      d.Mirrored = l->mirrored != 0;
      d.Parts = new uint[l->part_count];
      for (uint i = 0; i < l->part_count; ++i) d.Parts[i] = l->parts[i];
      d.Colour = l->colour;
      d.PartOpacity = new float[64];
      for (int i = 0; i < 64; ++i) d.PartOpacity[i] = l->part_opacity[i];
      return d;
    }
  }

  // The list's positions (2 x its vertex count floats, rig units, y up) into dest.
  public void CopyPositions(int character, uint list, float[] dest, int offset = 0) {
    unsafe {
      Native.DrawListC* l = ListPtr(character, list);
      int n = (int)(2 * l->vertex_count);
      if (dest == null || dest.Length - offset < n) throw new PosemorphException(1, rig.File + ": " + n + " floats needed");
      Marshal.Copy((IntPtr)l->positions, dest, offset, n);
    }
  }
  // The list's triangles (3 x triangle count indices) into dest.
  public void CopyIndices(int character, uint list, uint[] dest) {
    unsafe {
      Native.DrawListC* l = ListPtr(character, list);
      if (dest == null || dest.Length < l->index_count) throw new PosemorphException(1, rig.File + ": short index array");
      for (uint i = 0; i < l->index_count; ++i) dest[i] = l->indices[i];
    }
  }
  // The uvs of drawing `drawing` of the list (2 x vertex count, v down) into dest.
  public void CopyUvs(int character, uint list, uint drawing, float[] dest) {
    unsafe {
      Native.DrawListC* l = ListPtr(character, list);
      if (drawing >= l->drawing_count) throw new PosemorphException(1, rig.File + ": no drawing " + drawing);
      int n = (int)(2 * l->vertex_count);
      if (dest == null || dest.Length < n) throw new PosemorphException(1, rig.File + ": short uv array");
      Marshal.Copy((IntPtr)l->Drawing(drawing).uvs, dest, 0, n);
    }
  }
  // Without garbage, for a game's frame loop: the list's drawings into
  // `into` (at most 8; returns how many), its transform and colour, and a
  // part's opacity.
  public int CopyDrawings(int character, uint list, BlendedDrawing[] into) {
    unsafe {
      Native.DrawListC* l = ListPtr(character, list);
      if (into == null || into.Length < l->drawing_count)
        throw new PosemorphException(1, rig.File + ": " + l->drawing_count + " drawings need room");
      for (uint i = 0; i < l->drawing_count; ++i) {
        Native.Blended b = l->Drawing(i);
        into[i].Pose = b.pose;
        into[i].Weight = b.weight;
      }
      return (int)l->drawing_count;
    }
  }
  public void Appearance(int character, uint list, out Transform transform, out Colour colour, out bool mirrored) {
    unsafe {
      Native.DrawListC* l = ListPtr(character, list);
      transform = l->transform;
      colour = l->colour;
      mirrored = l->mirrored != 0;
    }
  }
  public float PartOpacity(int character, uint list, uint part) {
    unsafe {
      Native.DrawListC* l = ListPtr(character, list);
      return part < 64 ? l->part_opacity[part] : 1;
    }
  }
  // The most steps a character of this rig draws (every part of every list):
  // the size of the array CopySteps fills.
  public int MaxSteps { get { return maxSteps; } }
  // Character k's draw steps back to front into `into`; returns how many.
  public int CopySteps(int character, DrawStep[] into) {
    if (into == null || into.Length < maxSteps) throw new PosemorphException(1, rig.File + ": " + maxSteps + " steps need room");
    unsafe {
      IntPtr body = (IntPtr)ListPtr(character, 0);
      IntPtr att = attachments > 0 ? (IntPtr)ListPtr(character, 1) : IntPtr.Zero;
      return (int)Native.pm_character_draw_steps(rig.H, body, att, into, (uint)into.Length);
    }
  }

  // Character k's draw steps back to front (pm_character_draw_steps).
  public DrawStep[] Steps(int character) {
    var steps = new DrawStep[1 + 64 * (1 + (int)attachments)];
    unsafe {
      IntPtr body = (IntPtr)ListPtr(character, 0);
      IntPtr att = attachments > 0 ? (IntPtr)ListPtr(character, 1) : IntPtr.Zero;
      uint n = Native.pm_character_draw_steps(rig.H, body, att, steps, (uint)steps.Length);
      Array.Resize(ref steps, (int)Math.Min(n, (uint)steps.Length));
    }
    return steps;
  }

  public void Dispose() {
    foreach (var b in new[] { work, positions, attachedPositions, lists, attachedLists, inputs })
      if (b != null) b.Dispose();
  }
}

}  // namespace Posemorph
