// SPDX-License-Identifier: MIT
// What a C# engine's renderer does with a crowd's draw steps, done on the
// CPU so that the example can show a frame without a graphics API: for each
// step (back to front), the part's triangles with the exact cross-fade of
// the list's drawings (premultiplied, sampled from the rig's texture pages
// through each drawing's region), times the list's colour and the part's
// opacity, laid "over" what is drawn. Unity, Godot or MonoGame do the same
// in a shader (integrations/opengl's is the reference). And the PNG reading
// and writing it needs, over System.IO.Compression's deflate.
using System;
using System.Collections.Generic;
using System.IO;
using System.IO.Compression;
using Posemorph;

// RGBA floats 0..1, premultiplied.
sealed class Picture {
  public readonly int Width, Height;
  public readonly float[] Rgba;
  public Picture(int width, int height) {
    Width = width;
    Height = height;
    Rgba = new float[4 * width * height];
  }
  public void Clear(float r, float g, float b) {
    for (int i = 0; i < Width * Height; ++i) {
      Rgba[4 * i] = r;
      Rgba[4 * i + 1] = g;
      Rgba[4 * i + 2] = b;
      Rgba[4 * i + 3] = 1;
    }
  }
}

// 8-bit RGB or RGBA PNGs, not interlaced: what the bake writes (atlas
// pages) and what drawings usually are.
static class Png {
  static readonly byte[] Signature = { 137, 80, 78, 71, 13, 10, 26, 10 };
  static uint BigEndian(byte[] b, int at) {
    return (uint)(b[at] << 24 | b[at + 1] << 16 | b[at + 2] << 8 | b[at + 3]);
  }

  // The image premultiplied: as stored when `premultiplied` (an atlas
  // page), else its straight alpha multiplied in.
  public static Picture Read(string path, bool premultiplied) {
    byte[] file;
    try {
      file = File.ReadAllBytes(path);
    } catch (IOException e) {
      throw new InvalidDataException(path + ": cannot read the page (" + e.Message + ")");
    }
    for (int i = 0; i < 8; ++i)
      if (file.Length < 8 || file[i] != Signature[i]) throw new InvalidDataException(path + ": not a PNG");
    int width = 0, height = 0, channels = 0;
    var idat = new MemoryStream();
    for (int at = 8; at + 12 <= file.Length;) {
      uint length = BigEndian(file, at);
      string type = System.Text.Encoding.ASCII.GetString(file, at + 4, 4);
      if (length > file.Length - at - 12) throw new InvalidDataException(path + ": a chunk runs past the file's end");
      if (type == "IHDR") {
        width = (int)Math.Min(BigEndian(file, at + 8), 16385u);
        height = (int)Math.Min(BigEndian(file, at + 12), 16385u);
        byte depth = file[at + 16], colour = file[at + 17], interlace = file[at + 20];
        if (depth != 8 || (colour != 2 && colour != 6) || interlace != 0 || width > 16384 || height > 16384)
          throw new InvalidDataException(path + ": only 8-bit RGB or RGBA, not interlaced, up to 16384 px is read here");
        channels = colour == 6 ? 4 : 3;
      } else if (type == "IDAT") {
        idat.Write(file, at + 8, (int)length);
      } else if (type == "IEND") {
        break;
      }
      at += 12 + (int)length;
    }
    if (channels == 0 || idat.Length < 2) throw new InvalidDataException(path + ": no image header or data");
    int stride = width * channels;
    var raw = new byte[(long)height * (stride + 1)];
    idat.Position = 2;  // the zlib header; DeflateStream reads the raw deflate after it
    using (var inflate = new DeflateStream(idat, CompressionMode.Decompress)) {
      int got = 0, n;
      while (got < raw.Length && (n = inflate.Read(raw, got, raw.Length - got)) > 0) got += n;
      if (got < raw.Length) throw new InvalidDataException(path + ": the image data is short");
    }
    var image = new Picture(width, height);
    var row = new byte[stride];
    var previous = new byte[stride];
    for (int y = 0; y < height; ++y) {
      int at = y * (stride + 1) + 1;
      byte filter = raw[at - 1];
      for (int i = 0; i < stride; ++i) {
        int a = i >= channels ? row[i - channels] : 0, b = previous[i], c = i >= channels ? previous[i - channels] : 0;
        int predicted = 0;
        if (filter == 1) predicted = a;
        else if (filter == 2) predicted = b;
        else if (filter == 3) predicted = (a + b) / 2;
        else if (filter == 4) {
          int p = a + b - c, pa = Math.Abs(p - a), pb = Math.Abs(p - b), pc = Math.Abs(p - c);
          predicted = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
        } else if (filter != 0) {
          throw new InvalidDataException(path + ": row " + y + " has filter " + filter);
        }
        row[i] = (byte)(raw[at + i] + predicted);
      }
      for (int x = 0; x < width; ++x) {
        float alpha = channels == 4 ? row[4 * x + 3] / 255f : 1;
        float scale = premultiplied ? 1 : alpha;
        int o = 4 * (y * width + x);
        for (int k = 0; k < 3; ++k) image.Rgba[o + k] = row[channels * x + k] / 255f * scale;
        image.Rgba[o + 3] = alpha;
      }
      var swap = previous;
      previous = row;
      row = swap;
    }
    return image;
  }

  static readonly uint[] CrcTable = MakeCrcTable();
  static uint[] MakeCrcTable() {
    var t = new uint[256];
    for (uint n = 0; n < 256; ++n) {
      uint c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) != 0 ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }
  static void Chunk(Stream o, string type, byte[] data) {
    var head = new byte[8];
    head[0] = (byte)(data.Length >> 24);
    head[1] = (byte)(data.Length >> 16);
    head[2] = (byte)(data.Length >> 8);
    head[3] = (byte)data.Length;
    for (int i = 0; i < 4; ++i) head[4 + i] = (byte)type[i];
    uint crc = 0xffffffffu;
    for (int i = 4; i < 8; ++i) crc = CrcTable[(crc ^ head[i]) & 0xff] ^ (crc >> 8);
    foreach (byte b in data) crc = CrcTable[(crc ^ b) & 0xff] ^ (crc >> 8);
    crc ^= 0xffffffffu;
    o.Write(head, 0, 8);
    o.Write(data, 0, data.Length);
    o.Write(new[] { (byte)(crc >> 24), (byte)(crc >> 16), (byte)(crc >> 8), (byte)crc }, 0, 4);
  }

  // An RGBA PNG of the picture (its colour divided by its alpha).
  public static void Write(string path, Picture p) {
    var raw = new byte[p.Height * (4 * p.Width + 1)];
    for (int y = 0; y < p.Height; ++y)
      for (int x = 0; x < p.Width; ++x) {
        int o = 4 * (y * p.Width + x), at = y * (4 * p.Width + 1) + 1 + 4 * x;
        float a = p.Rgba[o + 3];
        for (int k = 0; k < 3; ++k)
          raw[at + k] = (byte)Math.Round(Math.Min(Math.Max(a > 0 ? p.Rgba[o + k] / a : 0, 0), 1) * 255);
        raw[at + 3] = (byte)Math.Round(Math.Min(Math.Max(a, 0), 1) * 255);
      }
    var zlib = new MemoryStream();
    zlib.WriteByte(0x78);
    zlib.WriteByte(0x01);
    using (var deflate = new DeflateStream(zlib, CompressionMode.Compress, true)) deflate.Write(raw, 0, raw.Length);
    uint s1 = 1, s2 = 0;  // Adler-32 of the uncompressed bytes
    foreach (byte b in raw) {
      s1 = (s1 + b) % 65521;
      s2 = (s2 + s1) % 65521;
    }
    uint adler = s2 << 16 | s1;
    zlib.Write(new[] { (byte)(adler >> 24), (byte)(adler >> 16), (byte)(adler >> 8), (byte)adler }, 0, 4);
    var header = new byte[13];
    header[0] = (byte)(p.Width >> 24);
    header[1] = (byte)(p.Width >> 16);
    header[2] = (byte)(p.Width >> 8);
    header[3] = (byte)p.Width;
    header[4] = (byte)(p.Height >> 24);
    header[5] = (byte)(p.Height >> 16);
    header[6] = (byte)(p.Height >> 8);
    header[7] = (byte)p.Height;
    header[8] = 8;  // bit depth
    header[9] = 6;  // RGBA
    string temporary = path + ".part";
    using (var o = File.Create(temporary)) {
      o.Write(Signature, 0, 8);
      Chunk(o, "IHDR", header);
      Chunk(o, "IDAT", zlib.ToArray());
      Chunk(o, "IEND", new byte[0]);
    }
    if (File.Exists(path)) File.Delete(path);
    File.Move(temporary, path);
  }
}

// Draws characters of a crowd into a picture: rig units (y up) to pixels by
// a zoom about a centre, the pages loaded once.
sealed class SoftwareRenderer {
  readonly Rig rig;
  readonly string rigFolder, imageFolder;
  readonly Dictionary<string, Picture> pages = new Dictionary<string, Picture>();
  public double Zoom = 1, CentreX, CentreY;

  public SoftwareRenderer(Rig rig, string imageFolder) {
    this.rig = rig;
    rigFolder = Path.GetDirectoryName(Path.GetFullPath(rig.File));
    this.imageFolder = imageFolder ?? rigFolder;
  }

  Picture PageOf(uint list, uint page) {
    Page p = rig.ListPage(list, page);
    string name = rig.PageName(list, page);
    string path = Path.Combine(p.Atlas == 1 ? rigFolder : imageFolder, name);
    Picture image;
    if (!pages.TryGetValue(path, out image)) {
      image = Png.Read(path, p.Premultiplied == 1);
      if (p.Width != 0 && (image.Width != p.Width || image.Height != p.Height))
        throw new InvalidDataException(path + ": the page is " + image.Width + "x" + image.Height + ", the rig says " +
                                       p.Width + "x" + p.Height);
      pages.Add(path, image);
    }
    return image;
  }

  // Bilinear (or nearest) at page uv (u, v), clamped to the edge, added
  // into sum times w.
  static void Sample(Picture t, float u, float v, bool nearest, float w, float[] sum) {
    if (nearest) {
      int x = Math.Min(Math.Max((int)Math.Floor(u * t.Width), 0), t.Width - 1);
      int y = Math.Min(Math.Max((int)Math.Floor(v * t.Height), 0), t.Height - 1);
      for (int k = 0; k < 4; ++k) sum[k] += w * t.Rgba[4 * (y * t.Width + x) + k];
      return;
    }
    float fx = u * t.Width - 0.5f, fy = v * t.Height - 0.5f;
    int x0 = (int)Math.Floor(fx), y0 = (int)Math.Floor(fy);
    float ax = fx - x0, ay = fy - y0;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        int x = Math.Min(Math.Max(x0 + i, 0), t.Width - 1), y = Math.Min(Math.Max(y0 + j, 0), t.Height - 1);
        float c = w * (i == 0 ? 1 - ax : ax) * (j == 0 ? 1 - ay : ay);
        for (int k = 0; k < 4; ++k) sum[k] += c * t.Rgba[4 * (y * t.Width + x) + k];
      }
  }

  // Pixel centres on edge a -> b of a triangle of positive area go to one
  // of the two triangles sharing it (the one seeing it this way round).
  static bool Inside(double e, double dx, double dy) { return e > 0 || (e == 0 && (dy > 0 || (dy == 0 && dx > 0))); }

  // Draws the character's steps back to front; returns how many it drew.
  public int Draw(Picture into, Crowd crowd, int character) {
    var uvs = new float[8][];
    var pictures = new Picture[8];
    var maps = new Region[8];
    var sum = new float[4];
    DrawStep[] steps = crowd.Steps(character);
    foreach (DrawStep step in steps) {
      DrawList list = crowd.List(character, step.List);
      int V = (int)list.VertexCount, D = list.Drawings.Length;
      var positions = new float[2 * V];
      var indices = new uint[list.IndexCount];
      crowd.CopyPositions(character, step.List, positions);
      crowd.CopyIndices(character, step.List, indices);
      bool nearest = rig.NearestFilter(step.List);
      for (int d = 0; d < D; ++d) {
        if (uvs[d] == null || uvs[d].Length < 2 * V) uvs[d] = new float[2 * V];
        crowd.CopyUvs(character, step.List, (uint)d, uvs[d]);
        maps[d] = rig.PartRegion(step.List, step.Part, list.Drawings[d].Pose);
        pictures[d] = PageOf(step.List, maps[d].Page);
      }
      Transform m = list.Transform;
      var sx = new double[V];
      var sy = new double[V];
      for (int i = 0; i < V; ++i) {
        double x = m.A * positions[2 * i] + m.C * positions[2 * i + 1] + m.Tx;
        double y = m.B * positions[2 * i] + m.D * positions[2 * i + 1] + m.Ty;
        sx[i] = into.Width / 2.0 + (x - CentreX) * Zoom;
        sy[i] = into.Height / 2.0 - (y - CentreY) * Zoom;
      }
      float alpha = list.Colour.A * (step.Part < 64 ? list.PartOpacity[step.Part] : 1);
      float[] tint = { list.Colour.R * alpha, list.Colour.G * alpha, list.Colour.B * alpha, alpha };
      Part part = rig.ListPart(step.List, step.Part);
      for (uint t = part.FirstTriangle; t < part.FirstTriangle + part.TriangleCount; ++t) {
        uint a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
        double area = (sx[b] - sx[a]) * (sy[c] - sy[a]) - (sx[c] - sx[a]) * (sy[b] - sy[a]);
        if (area == 0) continue;
        if (area < 0) {
          uint swap = b;
          b = c;
          c = swap;
          area = -area;
        }
        int x0 = Math.Max((int)Math.Floor(Math.Min(sx[a], Math.Min(sx[b], sx[c]))), 0);
        int x1 = Math.Min((int)Math.Ceiling(Math.Max(sx[a], Math.Max(sx[b], sx[c]))), into.Width - 1);
        int y0 = Math.Max((int)Math.Floor(Math.Min(sy[a], Math.Min(sy[b], sy[c]))), 0);
        int y1 = Math.Min((int)Math.Ceiling(Math.Max(sy[a], Math.Max(sy[b], sy[c]))), into.Height - 1);
        for (int py = y0; py <= y1; ++py)
          for (int px = x0; px <= x1; ++px) {
            double cx = px + 0.5, cy = py + 0.5;
            double ea = (sx[c] - sx[b]) * (cy - sy[b]) - (sy[c] - sy[b]) * (cx - sx[b]);  // weight of a
            double eb = (sx[a] - sx[c]) * (cy - sy[c]) - (sy[a] - sy[c]) * (cx - sx[c]);  // of b
            double ec = (sx[b] - sx[a]) * (cy - sy[a]) - (sy[b] - sy[a]) * (cx - sx[a]);  // of c
            if (!Inside(ea, sx[c] - sx[b], sy[c] - sy[b]) || !Inside(eb, sx[a] - sx[c], sy[a] - sy[c]) ||
                !Inside(ec, sx[b] - sx[a], sy[b] - sy[a]))
              continue;
            float la = (float)(ea / area), lb = (float)(eb / area), lc = (float)(ec / area);
            sum[0] = sum[1] = sum[2] = sum[3] = 0;
            for (int d = 0; d < D; ++d) {
              float[] uv = uvs[d];
              float u = la * uv[2 * a] + lb * uv[2 * b] + lc * uv[2 * c];
              float v = la * uv[2 * a + 1] + lb * uv[2 * b + 1] + lc * uv[2 * c + 1];
              Region g = maps[d];
              Sample(pictures[d], u * g.ScaleU + g.OffsetU, v * g.ScaleV + g.OffsetV, nearest, list.Drawings[d].Weight,
                     sum);
            }
            int o = 4 * (py * into.Width + px);
            float cover = 1 - sum[3] * tint[3];
            for (int k = 0; k < 4; ++k) into.Rgba[o + k] = sum[k] * tint[k] + into.Rgba[o + k] * cover;
          }
      }
    }
    return steps.Length;
  }
}
