// SPDX-License-Identifier: MIT
// posemorph for JavaScript: a thin wrapper over the runtime's C API compiled
// to WebAssembly (posemorph_wasm.js + .wasm, built from bindings.c).
//
//   const pm = await Posemorph.create(createPosemorphWasm);
//   const rig = pm.loadRig(bytes, 'pip.pmrig');      // throws Error('pip.pmrig: ...') on bad bytes
//   const lists = rig.drawLists(1, [x, y]);           // [{positions, indices, drawings: [{pose, weight, uvs}], colour, ...}]
//   rig.drawLists(1, [x, y], { tint: [r, g, b, a] }); // every character tinted (multiply) at opacity a
//   const { raw, limited, texture } = rig.weights(x, y); // the pose-space weights alone
//   const pages = rig.pages();                         // [{name, width, height, atlas, premultiplied}]: what to upload
//   const { page, map } = rig.region(i);               // where pose i's drawing lies: page, uv map [su, ou, sv, ov]
//
// Arrays returned are views into wasm memory, valid until the next call.

const LAYOUT = [424, 0, 16, 20, 12, 4, 8, 140, 32, 48, 32, 32, 152, 20, 16, 36];  // wasm32 (bindings.c checks them)

export class Posemorph {
  static async create(createWasm) {
    return new Posemorph(await createWasm());
  }
  constructor(wasm) {
    this.wasm = wasm;
    const at = wasm._pmw_layout() >> 2;
    const actual = Array.from(wasm.HEAPU32.subarray(at, at + LAYOUT.length));
    if (actual.join() !== LAYOUT.join()) throw new Error(`posemorph.js: struct layout ${actual} is not ${LAYOUT}`);
    this.version = wasm.UTF8ToString(wasm._pm_version());
  }
  loadRig(bytes, name) {
    return new Rig(this.wasm, bytes, name);
  }
}

export class Rig {
  constructor(wasm, bytes, name) {
    const m = (this.wasm = wasm);
    const data = m._malloc(bytes.length), out = m._malloc(4), err = m._malloc(260);
    m.HEAPU8.set(bytes, data);
    m.HEAPU32[out >> 2] = 0;
    const status = m._pm_rig_load(data, bytes.length, out, err);
    const message = m.UTF8ToString(err + 4);
    this.handle = m.HEAPU32[out >> 2];
    [data, out, err].forEach((p) => m._free(p));
    if (status !== 0) throw new Error(`${name}: ${message}`);
    const info = m._malloc(48);
    m._pm_rig_get_info(this.handle, info);
    const u = m.HEAPU32.subarray(info >> 2);
    this.vertexCount = u[0];
    this.triangleCount = u[1];
    this.poseCount = u[2];
    this.pathCount = u[3];
    this.defaultSigma = m.HEAPF64[(info + 16) >> 3];
    m._pm_rig_grid(this.handle, info);
    const g = m.HEAPF64.subarray(info >> 3);
    this.grid = { minX: g[0], minY: g[1], maxX: g[2], maxY: g[3] };
    m._free(info);
    this.capacity = 0;
  }
  // The reference to pose i's drawing, as the bake wrote it.
  poseImage(i) {
    const m = this.wasm, s = m._malloc(1024);
    m._pm_rig_pose_image(this.handle, i, s, 1024, 0);
    const name = m.UTF8ToString(s);
    m._free(s);
    return name;
  }
  // The texture pages to upload (the body's list): with an atlas
  // (hasAtlas), the pages the bake packed beside the rig file, premultiplied;
  // without, one per pose, the drawing itself (a name like poseImage's).
  get hasAtlas() {
    return this.wasm._pm_rig_has_atlas(this.handle) === 1;
  }
  pages() {
    const m = this.wasm, n = m._pm_character_page_count(this.handle, 0), p = m._malloc(16), s = m._malloc(1024);
    const pages = [];
    for (let k = 0; k < n; ++k) {
      m._pm_character_page(this.handle, 0, k, p);
      m._pm_character_page_name(this.handle, 0, k, s, 1024, 0);
      const u = m.HEAPU32.subarray(p >> 2);
      pages.push({ name: m.UTF8ToString(s), width: u[0], height: u[1], atlas: u[2] === 1, premultiplied: u[3] === 1 });
    }
    [p, s].forEach((q) => m._free(q));
    return pages;
  }
  // Pose i's region: its page and the map from its uvs to the page's,
  // (u map[0] + map[1], v map[2] + map[3]).
  region(i) {
    const m = this.wasm, r = m._malloc(36);
    const status = m._pm_character_part_region(this.handle, 0, 0, i, r);
    const page = m.HEAPU32[r >> 2], map = Array.from(m.HEAPF32.subarray((r >> 2) + 1, (r >> 2) + 5));
    m._free(r);
    if (status !== 0) throw new Error(`pm_character_part_region failed (${status})`);
    return { page, map };
  }
  // Pose i's uvs into its own drawing (2 x vertexCount).
  uvs(i) {
    const p = this.wasm._pm_rig_uvs(this.handle, i) >> 2;
    return this.wasm.HEAPF32.subarray(p, p + 2 * this.vertexCount);
  }
  // {width, height} of pose i's drawing canvas; the union of the poses' bounds (rig units, y up).
  canvas(i) {
    const m = this.wasm, c = m._malloc(32);
    m._pm_rig_pose_canvas(this.handle, i, c);
    const d = m.HEAPF64.subarray(c >> 3, (c >> 3) + 2);
    const result = { width: d[0], height: d[1] };
    m._free(c);
    return result;
  }
  bounds() {
    const m = this.wasm, b = m._malloc(32);
    const r = { minX: Infinity, minY: Infinity, maxX: -Infinity, maxY: -Infinity };
    for (let i = 0; i < this.poseCount; ++i) {
      m._pm_rig_pose_bounds(this.handle, i, b);
      const d = m.HEAPF64.subarray(b >> 3, (b >> 3) + 4);
      r.minX = Math.min(r.minX, d[0]), r.minY = Math.min(r.minY, d[1]);
      r.maxX = Math.max(r.maxX, d[2]), r.maxY = Math.max(r.maxY, d[3]);
    }
    m._free(b);
    return r;
  }
  // The weights at a pose-space point: raw (the blend), limited (phi(w) renormalised: what the stretches
  // blend with), and texture (the cross-fade), N each. limitWeights false: limited = raw.
  weights(x, y, { sigma = -1, limitWeights = true } = {}) {
    const m = this.wasm, n = this.poseCount, w = m._malloc(24 * n);
    const status = m._pm_weights(this.handle, x, y, sigma < 0 ? this.defaultSigma : sigma, limitWeights ? 1 : 0, w,
                                 w + 8 * n, w + 16 * n, n);
    const all = Array.from(m.HEAPF64.subarray(w >> 3, (w >> 3) + 3 * n));
    m._free(w);
    if (status !== 0) throw new Error(`pm_weights failed (${status})`);
    return { raw: all.slice(0, n), limited: all.slice(n, 2 * n), texture: all.slice(2 * n) };
  }
  // Draw lists for `count` characters at points [x0, y0, x1, y1, ...]; maxDrawings K in 1..8;
  // tint [r, g, b, a] (each 0..1) for every character, or null: as drawn.
  drawLists(count, points, { sigma = -1, maxDrawings = 8, tint = null } = {}) {
    const m = this.wasm;
    if (count > this.capacity) this.reserve(count);
    m.HEAPF64.set(points, this.points >> 3);
    const o = this.options;
    m.HEAPF64[o >> 3] = sigma;
    m.HEAP32[(o + 8) >> 2] = 1;  // limit_weights
    m.HEAP32[(o + 12) >> 2] = 0;  // rigid
    m.HEAPU32[(o + 16) >> 2] = maxDrawings;
    if (tint) for (let k = 0; k < count; ++k) m.HEAPF32.set(tint, (this.colours >> 2) + 4 * k);
    m.HEAPU32[(o + LAYOUT[13]) >> 2] = tint ? this.colours : 0;  // colours: count, or NULL
    m.HEAPU32[(o + LAYOUT[13] + 4) >> 2] = 0;  // part_opacities: NULL
    const status = m._pm_draw_lists(this.handle, o, count, this.points, 0, this.work, this.workSize, this.positions,
                                    this.positionSize, this.lists, count);
    if (status !== 0) throw new Error(`pm_draw_lists failed (${status})`);
    const lists = [];
    for (let k = 0; k < count; ++k) {
      const at = this.lists + LAYOUT[0] * k, u = m.HEAPU32, f = m.HEAPF32;
      const drawings = [];
      for (let d = 0; d < u[(at + 16) >> 2]; ++d) {
        const e = at + 20 + 12 * d;
        drawings.push({ pose: u[e >> 2], weight: f[(e + 4) >> 2],
                        uvs: f.subarray(u[(e + 8) >> 2] >> 2, (u[(e + 8) >> 2] >> 2) + 2 * this.vertexCount) });
      }
      lists.push({
        positions: f.subarray(u[at >> 2] >> 2, (u[at >> 2] >> 2) + 2 * this.vertexCount),
        indices: u.subarray(u[(at + 4) >> 2] >> 2, (u[(at + 4) >> 2] >> 2) + 3 * this.triangleCount),
        drawings,
        mirrored: m.HEAP32[(at + 140) >> 2] !== 0,
        parts: u.subarray(u[(at + 144) >> 2] >> 2, (u[(at + 144) >> 2] >> 2) + u[(at + 148) >> 2]),  // back to front
        colour: Array.from(f.subarray((at + LAYOUT[12]) >> 2, ((at + LAYOUT[12]) >> 2) + 4)),  // r, g, b, a
        partOpacity: f.subarray((at + LAYOUT[12] + 16) >> 2, ((at + LAYOUT[12] + 16) >> 2) + 64),  // by part index
      });
    }
    return lists;
  }
  reserve(count) {
    const m = this.wasm;
    this.free();
    const sizes = m._malloc(8);
    m._pm_draw_list_buffers(this.handle, count, sizes, sizes + 4);
    this.workSize = m.HEAPU32[sizes >> 2];
    this.positionSize = m.HEAPU32[(sizes + 4) >> 2];
    m._free(sizes);
    this.work = m._malloc(8 * this.workSize);
    this.positions = m._malloc(4 * this.positionSize);
    this.points = m._malloc(16 * count);
    this.lists = m._malloc(LAYOUT[0] * count);
    this.options = m._malloc(LAYOUT[11]);
    this.colours = m._malloc(16 * count);
    this.capacity = count;
  }
  free() {
    if (!this.capacity) return;
    [this.work, this.positions, this.points, this.lists, this.options, this.colours].forEach((p) => this.wasm._free(p));
    this.capacity = 0;
  }
}
