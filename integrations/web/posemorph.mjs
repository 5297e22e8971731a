// SPDX-License-Identifier: MIT
// posemorph for the web: the whole runtime compiled to WebAssembly (SIMD128),
// as an ES module. Types: posemorph.d.mts; the PixiJS renderer: pixi.mjs.
//
//   import { load } from 'posemorph';
//   const pm = await load();                                  // instantiates posemorph_wasm.wasm
//   const rig = pm.loadRig(bytes, 'pell.pmrig');              // throws PosemorphError('pell.pmrig: ...')
//   const crowd = rig.crowd(200);
//   crowd.setPoint(k, x, y);                                  // body; channel c: crowd.setPoint(k, x, y, c)
//   crowd.setTransform(k, rig.place(wx, wy));                 // where character k stands
//   crowd.evaluate();                                         // one frame of every character
//   crowd.positions(k, list);  crowd.drawings(k, list);  crowd.steps(k);   // copies
//   crowd.free(); rig.free();                                 // explicit: wasm memory is not collected
//
// Memory: the runtime's buffers live in wasm memory that the Rig and Crowd
// own; every value handed to the caller is a copy (a typed array or a plain
// object) that no later call changes, or is written into an array the
// caller passes (copyPositions, copyUvs). free() is explicit and idempotent;
// using a freed object throws. A FinalizationRegistry frees what the caller
// forgot, as a safety net only.
import createPosemorphWasm from './posemorph_wasm.mjs';

export const MAX_DRAWINGS = 8;

// Every refusal: the message names the file (or object) and the problem; code is the C API's status.
export class PosemorphError extends Error {
  constructor(message, code = 1) {
    super(message);
    this.name = 'PosemorphError';
    this.code = code;
  }
}

const finalizer = typeof FinalizationRegistry === 'function' ? new FinalizationRegistry((free) => free()) : null;

// Instantiates the WebAssembly module. options: passed to Emscripten (e.g. locateFile, wasmBinary).
export async function load(options = {}) {
  return new Posemorph(await createPosemorphWasm(options));
}

export class Posemorph {
  constructor(wasm) {
    this.wasm = wasm;
    this.version = wasm.UTF8ToString(wasm._pm_version());
  }
  // A rig from its bytes; `name` names it in errors. untrusted: the loader's limits for rigs from others.
  loadRig(bytes, name = 'rig', { untrusted = false } = {}) {
    return new Rig(this, bytes instanceof ArrayBuffer ? new Uint8Array(bytes) : bytes, name, untrusted);
  }
  // fetch() and loadRig; an HTTP failure names the URL and the status.
  async fetchRig(url, options = {}) {
    const name = String(url).split('/').pop();
    const response = await fetch(url);
    if (!response.ok) throw new PosemorphError(`${name}: HTTP ${response.status}`);
    return this.loadRig(new Uint8Array(await response.arrayBuffer()), name, options);
  }
  // A transform [a, b, c, d, tx, ty] (x' = a x + c y + tx, y' = b x + d y + ty): scale, flip, rotate, move.
  transform(x, y, radians = 0, scaleX = 1, scaleY = 1, flipX = false) {
    const m = this.wasm;
    m._pmw_transform_make(x, y, radians, scaleX, scaleY, flipX ? 1 : 0);
    return readTransform(m, 12);
  }
  // outer after inner.
  compose(outer, inner) {
    const m = this.wasm, at = m._pmw_transforms() >> 2;
    m.HEAPF32.set(outer, at);
    m.HEAPF32.set(inner, at + 6);
    m._pmw_transform_compose();
    return readTransform(m, 12);
  }
}

function readTransform(m, offset) {
  const at = (m._pmw_transforms() >> 2) + offset;
  return m.HEAPF32.slice(at, at + 6);
}
function out(m, n) {
  const at = m._pmw_out() >> 3;
  return m.HEAPF64.slice(at, at + n);
}
function text(m, pointer) {
  return pointer ? m.UTF8ToString(pointer) : null;
}
function withString(m, s, call) {
  const size = m.lengthBytesUTF8(s) + 1, p = m._malloc(size);
  try {
    m.stringToUTF8(s, p, size);
    return call(p);
  } finally {
    m._free(p);
  }
}

export class Rig {
  constructor(posemorph, bytes, name, untrusted) {
    const m = (this.wasm = posemorph.wasm);
    this.posemorph = posemorph;
    this.name = name;
    const data = m._malloc(Math.max(1, bytes.length));
    m.HEAPU8.set(bytes, data);
    const handle = m._pmw_rig_load(data, bytes.length, untrusted ? 1 : 0);
    m._free(data);
    if (!handle) throw new PosemorphError(`${name}: ${m.UTF8ToString(m._pmw_error())}`);
    this.handle = handle;
    this.crowds = new Set();
    this.token = {};
    finalizer?.register(this, () => m._pm_rig_free(handle), this.token);
    const count = (what) => m._pmw_rig_count(handle, what) >>> 0;
    this.vertexCount = count(0);
    this.triangleCount = count(1);
    this.poseCount = count(2);
    this.pathCount = count(3);
    this.channelCount = count(4);
    this.attachmentCount = count(5);
    this.listCount = count(6);
    this.attachedWeightCount = count(7);
    this.formatVersion = [count(8), count(9)];
    this.drawingFolder = text(m, m._pmw_name(handle, 6, 0, 0, 0)) ?? '';
    this.channels = [];
    for (let c = 0; c < this.channelCount; ++c) this.channels.push(this.#channel(c));
    this.lists = [];
    for (let l = 0; l < this.listCount; ++l) this.lists.push(this.#list(l));
    m._pmw_placement(handle);
    const [ax, ay, left] = out(m, 3);
    this.anchor = { x: ax, y: ay };
    this.facingLeft = left !== 0;
  }
  #check() {
    if (!this.handle) throw new PosemorphError(`${this.name}: the rig was freed`);
    return this.handle;
  }
  #name(what, a, b = 0, c = 0) {
    return text(this.wasm, this.wasm._pmw_name(this.handle, what, a, b, c));
  }
  #channel(c) {
    const m = this.wasm, h = this.handle;
    const poses = [];
    for (let p = 0, n = m._pmw_channel_pose_count(h, c) >>> 0; p < n; ++p) {
      m._pmw_channel_pose_point(h, c, p);
      const [x, y] = out(m, 2);
      poses.push({ name: this.#name(1, c, p), x, y });
    }
    const paths = [];
    for (let p = 0, n = m._pmw_channel_path_count(h, c) >>> 0; p < n; ++p) paths.push(this.#name(2, c, p));
    const events = [];
    for (let e = 0, n = m._pmw_channel_event_count(h, c) >>> 0; e < n; ++e) {
      m._pmw_channel_event(h, c, e);
      const [path, time] = out(m, 2);
      events.push({ name: this.#name(5, c, e), path, time });
    }
    m._pmw_channel_default_sigma(h, c);
    const [defaultSigma] = out(m, 1);
    m._pmw_channel_pad_range(h, c);
    const [minX, minY, maxX, maxY] = out(m, 4);
    return { index: c, name: this.#name(0, c), poses, paths, events, defaultSigma, padRange: { minX, minY, maxX, maxY } };
  }
  #list(l) {
    const m = this.wasm, h = this.handle;
    m._pmw_list(h, l);
    const [vertexCount, triangleCount, poseCount, partCount, channel, filter, pageCount, atlas] = out(m, 8);
    const at = m._pmw_list_triangles(h, l) >> 2;
    const triangles = m.HEAPU32.slice(at, at + 3 * triangleCount);
    const parts = [];
    for (let p = 0; p < partCount; ++p) {
      m._pmw_list_part(h, l, p);
      const [firstTriangle, count, drawOrder] = out(m, 3);
      const images = [], regions = [];
      for (let pose = 0; pose < poseCount; ++pose) {
        images.push(this.#name(4, l, p, pose));
        m._pmw_list_region(h, l, p, pose);
        const [page, scaleU, offsetU, scaleV, offsetV, x, y, width, height] = out(m, 9);
        regions.push({ page, scaleU, offsetU, scaleV, offsetV, x, y, width, height });
      }
      parts.push({ name: this.#name(3, l, p) ?? '', firstTriangle, triangleCount: count, drawOrder, images, regions });
    }
    // The texture pages (an atlas beside the rig file, or one per drawing).
    const pages = [];
    for (let k = 0; k < pageCount; ++k) {
      m._pmw_list_page(h, l, k);
      const [width, height, isAtlas, premultiplied] = out(m, 4);
      pages.push({ name: this.#name(8, l, k), width, height, atlas: isAtlas === 1, premultiplied: premultiplied === 1 });
    }
    const canvases = [];
    for (let pose = 0; pose < poseCount; ++pose) {
      m._pmw_list_canvas(h, l, pose);
      const [width, height, pivotX, pivotY] = out(m, 4);
      canvases.push({ width, height, pivotX, pivotY });
    }
    return { index: l, channel, vertexCount, triangleCount, poseCount, triangles, parts, canvases, pages,
             atlas: atlas === 1, textureFilter: filter === 1 ? 'nearest' : 'linear' };
  }
  // A path's index in channel `channel` by name, or -1.
  findPath(name, channel = 0) {
    this.#check();
    return withString(this.wasm, name, (p) => this.wasm._pmw_channel_path_find(this.handle, channel, p));
  }
  // [x, y] on channel `channel`'s path `path` at `time` seconds.
  samplePath(channel, path, time) {
    const status = this.wasm._pmw_channel_path_sample(this.#check(), channel, path, time);
    if (status !== 0) throw new PosemorphError(`${this.name}: channel ${channel} has no path ${path}`, status);
    return Array.from(out(this.wasm, 2));
  }
  // A point of channel `channel`'s pose space in 4 bytes (a uint32), and back.
  quantize(x, y, channel = 0) {
    return this.wasm._pmw_channel_quantize(this.#check(), channel, x, y) >>> 0;
  }
  dequantize(packed, channel = 0) {
    this.wasm._pmw_channel_dequantize(this.#check(), channel, packed >>> 0);
    return Array.from(out(this.wasm, 2));
  }
  // The transform that stands the rig's anchor at world (x, y), turned and scaled about it, facing left when asked.
  place(x, y, radians = 0, scale = 1, faceLeft = false) {
    this.wasm._pmw_transform_place(this.#check(), x, y, radians, scale, faceLeft ? 1 : 0);
    return readTransform(this.wasm, 12);
  }
  // The body's vertex positions in pose `pose` (rig units, y up): a copy.
  posePositions(pose) {
    const at = this.wasm._pmw_pose_positions(this.#check(), pose) >> 3;
    if (!at) throw new PosemorphError(`${this.name}: no pose ${pose}`);
    return this.wasm.HEAPF64.slice(at, at + 2 * this.vertexCount);
  }
  // The body's bounds over its poses (rig units, y up).
  bounds() {
    const b = { minX: Infinity, minY: Infinity, maxX: -Infinity, maxY: -Infinity };
    for (let pose = 0; pose < this.poseCount; ++pose) {
      const p = this.posePositions(pose);
      for (let i = 0; i < p.length; i += 2) {
        b.minX = Math.min(b.minX, p[i]), b.maxX = Math.max(b.maxX, p[i]);
        b.minY = Math.min(b.minY, p[i + 1]), b.maxY = Math.max(b.maxY, p[i + 1]);
      }
    }
    return b;
  }
  crowd(count) {
    return new Crowd(this, count);
  }
  // Frees the rig and every crowd made from it.
  free() {
    if (!this.handle) return;
    for (const crowd of this.crowds) crowd.free();
    finalizer?.unregister(this.token);
    this.wasm._pm_rig_free(this.handle);
    this.handle = 0;
  }
}

const kUse = { channelPoints: 1, transforms: 2, colours: 4, partOpacities: 8 };

export class Crowd {
  constructor(rig, count) {
    const m = (this.wasm = rig.wasm);
    if (!Number.isInteger(count) || count < 1) throw new PosemorphError(`${rig.name}: a crowd of ${count} characters`);
    if (!rig.handle) throw new PosemorphError(`${rig.name}: the rig was freed`);
    const handle = m._pmw_crowd_new(rig.handle, count);
    if (!handle) throw new PosemorphError(`${rig.name}: ${m.UTF8ToString(m._pmw_error())}`);
    this.rig = rig;
    this.count = count;
    this.handle = handle;
    this.use = 0;
    this.evaluated = false;
    this.partStride = m._pmw_crowd_part_stride(handle) >>> 0;
    this.token = {};
    finalizer?.register(this, () => m._pmw_crowd_free(handle), this.token);
    rig.crowds.add(this);
    this.animator = null;
  }
  #check(k) {
    if (!this.handle) throw new PosemorphError(`${this.rig.name}: the crowd was freed`);
    if (k !== undefined && !(Number.isInteger(k) && k >= 0 && k < this.count)) {
      throw new PosemorphError(`${this.rig.name}: no character ${k} in a crowd of ${this.count}`);
    }
    return this.handle;
  }
  // Character k's point in channel `channel` (0: the body).
  setPoint(k, x, y, channel = 0) {
    const m = this.wasm, h = this.#check(k);
    if (!(channel >= 0 && channel < this.rig.channelCount)) throw new PosemorphError(`${this.rig.name}: no channel ${channel}`);
    const at = channel === 0 ? (m._pmw_crowd_points(h) >> 3) + 2 * k
                             : (m._pmw_crowd_channel_points(h) >> 3) + 2 * (k * (this.rig.channelCount - 1) + channel - 1);
    m.HEAPF64[at] = x;  // two stores, no array per call: games set points every frame
    m.HEAPF64[at + 1] = y;
    if (channel > 0) this.use |= kUse.channelPoints;
  }
  // A point received as 4 bytes (Rig.quantize) for character k's channel.
  setQuantizedPoint(k, packed, channel = 0) {
    const [x, y] = this.rig.dequantize(packed, channel);
    this.setPoint(k, x, y, channel);
  }
  // Character k's transform ([a, b, c, d, tx, ty]; Rig.place, Posemorph.transform), null: the identity.
  setTransform(k, t) {
    const m = this.wasm, h = this.#check(k);
    m.HEAPF32.set(t ?? [1, 0, 0, 1, 0, 0], (m._pmw_crowd_transforms(h) >> 2) + 6 * k);
    this.use |= kUse.transforms;
  }
  // Character k's tint and opacity (each 0..1; multiplies the drawings).
  setColour(k, r, g, b, a = 1) {
    const m = this.wasm, h = this.#check(k);
    m.HEAPF32.set([r, g, b, a], (m._pmw_crowd_colours(h) >> 2) + 4 * k);
    this.use |= kUse.colours;
  }
  // Character k's body part `part`'s opacity (0..1).
  setPartOpacity(k, part, opacity) {
    const m = this.wasm, h = this.#check(k);
    if (!(part >= 0 && part < this.partStride)) throw new PosemorphError(`${this.rig.name}: no part ${part}`);
    m.HEAPF32[(m._pmw_crowd_part_opacities(h) >> 2) + this.partStride * k + part] = opacity;
    this.use |= kUse.partOpacities;
  }
  // One frame of every character: from their points, or from the animator's last update
  // (from: 'animator', the default once crowd.createAnimator() was called).
  evaluate({ sigma = -1, maxDrawings = MAX_DRAWINGS, limitWeights = true, linear = false, from } = {}) {
    const h = this.#check();
    const fromAnimator = (from ?? (this.animator ? 'animator' : 'points')) === 'animator';
    if (fromAnimator && !this.animator) throw new PosemorphError(`${this.rig.name}: the crowd has no animator`);
    let use = this.use;
    if (this.animator?.machine) use |= kUse.colours | kUse.partOpacities;
    const status = this.wasm._pmw_crowd_evaluate(h, fromAnimator ? 1 : 0, use, sigma, maxDrawings, limitWeights ? 1 : 0,
                                                 linear ? 1 : 0);
    if (status !== 0) throw new PosemorphError(`${this.rig.name}: the frame was refused (code ${status})`, status);
    this.evaluated = true;
  }
  #list(k, list) {
    const h = this.#check(k);
    if (!this.evaluated) throw new PosemorphError(`${this.rig.name}: evaluate() the crowd first`);
    if (!(list >= 0 && list < this.rig.listCount)) throw new PosemorphError(`${this.rig.name}: no list ${list}`);
    return h;
  }
  // Character k's list `list` (0: the body, a + 1: attachment a) positions: a copy (2 x vertices, rig units).
  positions(k, list = 0) {
    return this.copyPositions(k, list, new Float32Array(2 * this.rig.lists[list].vertexCount));
  }
  // The same into `target` (at `offset`), for renderers that keep their own buffers.
  copyPositions(k, list, target, offset = 0) {
    const m = this.wasm, at = m._pmw_list_positions(this.#list(k, list), k, list) >> 2;
    target.set(m.HEAPF32.subarray(at, at + 2 * this.rig.lists[list].vertexCount), offset);
    return target;
  }
  // The drawings the list blends: [{pose, weight}] (at most maxDrawings, weights summing to 1).
  drawings(k, list = 0) {
    const m = this.wasm, h = this.#list(k, list), result = [];
    for (let i = 0, n = m._pmw_list_drawing_count(h, k, list); i < n; ++i) {
      m._pmw_list_drawing(h, k, list, i);
      const [pose, weight] = out(m, 2);
      result.push({ pose, weight });
    }
    return result;
  }
  // Drawing i's uvs into its drawing (2 x vertices, 0..1, v down) into `target`, or a copy.
  copyUvs(k, list, i, target = new Float32Array(2 * this.rig.lists[list].vertexCount), offset = 0) {
    const m = this.wasm, at = m._pmw_list_drawing(this.#list(k, list), k, list, i) >> 2;
    if (!at) throw new PosemorphError(`${this.rig.name}: list ${list} of character ${k} has no drawing ${i}`);
    target.set(m.HEAPF32.subarray(at, at + 2 * this.rig.lists[list].vertexCount), offset);
    return target;
  }
  // How the list is drawn, copied: transform, colour, part opacities (by part), mirrored.
  appearance(k, list = 0) {
    const m = this.wasm, h = this.#list(k, list);
    const floats = (p, n) => m.HEAPF32.slice(p >> 2, (p >> 2) + n);
    return {
      transform: floats(m._pmw_list_transform(h, k, list), 6),
      colour: floats(m._pmw_list_colour(h, k, list), 4),
      partOpacity: floats(m._pmw_list_part_opacity(h, k, list), 64),
      mirrored: m._pmw_list_mirrored(h, k, list) !== 0,
    };
  }
  // Everything about one list, copied: positions, drawings with uvs, and its appearance.
  list(k, list = 0) {
    const drawings = this.drawings(k, list).map((d, i) => ({ ...d, uvs: this.copyUvs(k, list, i) }));
    return { positions: this.positions(k, list), drawings, ...this.appearance(k, list) };
  }
  // Character k's draw steps back to front: a copy, [list0, part0, list1, part1, ...].
  steps(k) {
    const m = this.wasm, h = this.#list(k, 0);
    const at = m._pmw_crowd_steps(h, k) >> 2, n = m._pmw_crowd_step_count(h, k) >>> 0;
    return m.HEAPU32.slice(at, at + 2 * n);
  }
  // The character digest of the last frame (integrations/README.md).
  digest() {
    const m = this.wasm, h = this.#list(0, 0), prime = 1099511628211n, mask = (1n << 64n) - 1n;
    let hash = 14695981039346656037n;
    const word = (v) => {
      for (let i = 0; i < 4; ++i) hash = ((hash ^ BigInt((v >>> (8 * i)) & 0xff)) * prime) & mask;
    };
    for (const attached of [0, 1]) {
      const at = m._pmw_crowd_positions(h, attached) >> 2, n = m._pmw_crowd_position_count(h, attached) >>> 0;
      for (const v of m.HEAPU32.slice(at, at + n)) word(v);
    }
    const bits = new Uint32Array(1), f = new Float32Array(bits.buffer);
    let steps = 0;
    for (let k = 0; k < this.count; ++k) {
      for (let l = 0; l < this.rig.listCount; ++l) {
        const drawings = this.drawings(k, l);
        word(drawings.length);
        for (const d of drawings) {
          f[0] = d.weight;
          word(d.pose), word(bits[0]);
        }
      }
      const s = this.steps(k);
      for (const v of s) word(v);
      steps += s.length / 2;
    }
    return `character-fnv1a64=${hash.toString(16).padStart(16, '0')} characters=${this.count} steps=${steps}`;
  }
  // An animator for every character (paths played, mixed, queued; Animator below). Once per crowd.
  createAnimator() {
    if (!this.animator) {
      const status = this.wasm._pmw_crowd_animator(this.#check());
      if (status !== 0) throw new PosemorphError(`${this.rig.name}: no animator (code ${status})`, status);
      this.animator = new Animator(this);
    }
    return this.animator;
  }
  free() {
    if (!this.handle) return;
    finalizer?.unregister(this.token);
    this.wasm._pmw_crowd_free(this.handle);
    this.handle = 0;
    this.rig.crowds.delete(this);
  }
}

export class Animator {
  constructor(crowd) {
    this.crowd = crowd;
    this.wasm = crowd.wasm;
    this.machine = false;
  }
  #call(what, status) {
    if (status !== 0) throw new PosemorphError(`${this.crowd.rig.name}: animator ${what} refused (code ${status})`, status);
  }
  #h() {
    if (!this.crowd.handle) throw new PosemorphError(`${this.crowd.rig.name}: the crowd was freed`);
    return this.crowd.handle;
  }
  #path(path, channel) {
    const index = typeof path === 'string' ? this.crowd.rig.findPath(path, channel) : path;
    if (!(index >= 0)) throw new PosemorphError(`${this.crowd.rig.name}: channel ${channel} has no path '${path}'`);
    return index;
  }
  // Plays a path (index or name) on character k's channel; queue: after the current one ends.
  play(k, path, { channel = 0, speed = 1, loop = -1, mix = 0.2, start = 0, queue = false } = {}) {
    const p = this.#path(path, channel);
    this.#call('play', this.wasm._pmw_animator_play(this.#h(), k, channel, p, speed, loop, mix, start, queue ? 1 : 0));
  }
  setPoint(k, x, y, { channel = 0, mix = 0.2 } = {}) {
    this.#call('set point', this.wasm._pmw_animator_set_point(this.#h(), k, channel, x, y, mix));
  }
  stop(k, { channel = 0, mix = 0.2 } = {}) {
    this.#call('stop', this.wasm._pmw_animator_stop(this.#h(), k, channel, mix));
  }
  setSpeed(k, speed, { channel = 0 } = {}) {
    this.#call('set speed', this.wasm._pmw_animator_set_speed(this.#h(), k, channel, speed));
  }
  lookAt(k, x, y, { channel = 0 } = {}) {
    this.#call('look at', this.wasm._pmw_animator_look_at(this.#h(), k, channel, x, y));
  }
  // Advances every character by dt seconds; returns the events crossed: [{character, channel, event, name, outgoing, time}].
  update(dt) {
    const m = this.wasm, h = this.#h();
    this.#call('update', m._pmw_animator_update(h, dt));
    const events = [];
    for (let i = 0, n = m._pmw_animator_event_count(h) >>> 0; i < n; ++i) {
      m._pmw_animator_event(h, i);
      const [character, channel, event, outgoing, time] = out(m, 5);
      events.push({ character, channel, event, name: this.crowd.rig.channels[channel].events[event]?.name ?? '',
                    outgoing: outgoing !== 0, time });
    }
    return events;
  }
  // The rig's state machine drives the animator from here on (update() steps it first).
  useMachine() {
    this.#call('machine', this.wasm._pmw_crowd_machine(this.#h()));
    this.machine = true;
  }
  #input(name) {
    const i = withString(this.wasm, name, (p) => this.wasm._pmw_machine_find_input(this.crowd.rig.handle, p));
    if (i < 0) throw new PosemorphError(`${this.crowd.rig.name}: the machine has no input '${name}'`);
    return i;
  }
  setBool(k, input, value) {
    this.#call('input', this.wasm._pmw_machine_set_bool(this.#h(), k, this.#input(input), value ? 1 : 0));
  }
  setNumber(k, input, value) {
    this.#call('input', this.wasm._pmw_machine_set_number(this.#h(), k, this.#input(input), value));
  }
  setMachinePoint(k, input, x, y) {
    this.#call('input', this.wasm._pmw_machine_set_point(this.#h(), k, this.#input(input), x, y));
  }
  fire(k, input) {
    this.#call('input', this.wasm._pmw_machine_fire(this.#h(), k, this.#input(input)));
  }
  // The name of the state character k's layer `layer` is in (null before the first update).
  state(k, layer = 0) {
    const s = this.wasm._pmw_machine_state(this.#h(), k, layer);
    return s < 0 ? null : text(this.wasm, this.wasm._pmw_name(this.crowd.rig.handle, 7, s, 0, 0));
  }
}
