// SPDX-License-Identifier: MIT
// Types of posemorph.mjs: the posemorph runtime compiled to WebAssembly.

export declare const MAX_DRAWINGS: 8;

/** A refusal by the runtime: the message names the file and the problem; code is the C API's status. */
export declare class PosemorphError extends Error {
  readonly code: number;
}

/** [a, b, c, d, tx, ty]: x' = a x + c y + tx, y' = b x + d y + ty. */
export type Transform = Float32Array;

export interface LoadOptions {
  /** Emscripten's: where posemorph_wasm.wasm is (default: beside posemorph_wasm.mjs). */
  locateFile?: (path: string, prefix: string) => string;
  /** The module's bytes, when the caller fetched them. */
  wasmBinary?: ArrayBuffer;
}
/** Instantiates the WebAssembly module. */
export declare function load(options?: LoadOptions): Promise<Posemorph>;

export declare class Posemorph {
  /** The runtime's version, e.g. "0.5.0". */
  readonly version: string;
  /** A rig from its bytes; `name` names it in errors. untrusted: the loader's limits for rigs from others. */
  loadRig(bytes: Uint8Array | ArrayBuffer, name?: string, options?: { untrusted?: boolean }): Rig;
  /** fetch() and loadRig; an HTTP failure names the file and the status. */
  fetchRig(url: string | URL, options?: { untrusted?: boolean }): Promise<Rig>;
  /** Scale, flip, rotate (counter-clockwise), move. */
  transform(x: number, y: number, radians?: number, scaleX?: number, scaleY?: number, flipX?: boolean): Transform;
  /** outer after inner. */
  compose(outer: ArrayLike<number>, inner: ArrayLike<number>): Transform;
}

export interface Bounds { minX: number; minY: number; maxX: number; maxY: number; }
export interface Pose { name: string | null; x: number; y: number; }
export interface ChannelEvent { name: string | null; path: number; time: number; }
export interface Channel {
  index: number;
  name: string | null;
  poses: Pose[];
  paths: (string | null)[];
  events: ChannelEvent[];
  defaultSigma: number;
  /** The pose points' bounds plus a margin: where a pad or stick should reach. */
  padRange: Bounds;
}
export interface Part {
  name: string;
  firstTriangle: number;
  triangleCount: number;
  drawOrder: number;
  /** The part's drawing in each of the list's poses (as the bake wrote the reference). */
  images: (string | null)[];
  /** Where that drawing lies in each pose: on page `page` of the list, at uv * scale + offset, inside x, y, width, height. */
  regions: Region[];
}
export interface Region {
  page: number;
  scaleU: number; offsetU: number; scaleV: number; offsetV: number;
  x: number; y: number; width: number; height: number;
}
/** A texture page: an atlas page beside the rig file (premultiplied), or, without an atlas, one drawing. */
export interface Page { name: string | null; width: number; height: number; atlas: boolean; premultiplied: boolean; }
export interface Canvas { width: number; height: number; pivotX: number; pivotY: number; }
/** A list of a character: 0 is the body, a + 1 attachment a. */
export interface List {
  index: number;
  /** The channel whose pose space drives it. */
  channel: number;
  vertexCount: number;
  triangleCount: number;
  poseCount: number;
  triangles: Uint32Array;
  parts: Part[];
  canvases: Canvas[];
  /** The textures a renderer uploads (Rig::page): the atlas's pages, or one per part and pose. */
  pages: Page[];
  /** The rig was baked with an atlas. */
  atlas: boolean;
  textureFilter: 'linear' | 'nearest';
}

export declare class Rig {
  readonly name: string;
  readonly vertexCount: number;
  readonly triangleCount: number;
  readonly poseCount: number;
  readonly pathCount: number;
  readonly channelCount: number;
  readonly attachmentCount: number;
  readonly listCount: number;
  readonly formatVersion: [number, number];
  readonly drawingFolder: string;
  readonly channels: Channel[];
  readonly lists: List[];
  /** The point the character stands on (rig units, y up) and which way its drawings face. */
  readonly anchor: { x: number; y: number };
  readonly facingLeft: boolean;
  findPath(name: string, channel?: number): number;
  samplePath(channel: number, path: number, time: number): [number, number];
  quantize(x: number, y: number, channel?: number): number;
  dequantize(packed: number, channel?: number): [number, number];
  /** Stands the anchor at world (x, y), turned and scaled about it, facing left when asked. */
  place(x: number, y: number, radians?: number, scale?: number, faceLeft?: boolean): Transform;
  posePositions(pose: number): Float64Array;
  bounds(): Bounds;
  crowd(count: number): Crowd;
  /** Frees the rig and every crowd made from it; idempotent. */
  free(): void;
}

export interface EvaluateOptions {
  sigma?: number;
  maxDrawings?: number;
  limitWeights?: boolean;
  linear?: boolean;
  /** Default: 'animator' once createAnimator() was called, else 'points'. */
  from?: 'points' | 'animator';
}
export interface BlendedDrawing { pose: number; weight: number; }
export interface Appearance {
  transform: Transform;
  colour: Float32Array;
  partOpacity: Float32Array;
  mirrored: boolean;
}
export interface ListFrame extends Appearance {
  positions: Float32Array;
  drawings: (BlendedDrawing & { uvs: Float32Array })[];
}

export declare class Crowd {
  readonly rig: Rig;
  readonly count: number;
  setPoint(k: number, x: number, y: number, channel?: number): void;
  setQuantizedPoint(k: number, packed: number, channel?: number): void;
  setTransform(k: number, transform: ArrayLike<number> | null): void;
  setColour(k: number, r: number, g: number, b: number, a?: number): void;
  setPartOpacity(k: number, part: number, opacity: number): void;
  evaluate(options?: EvaluateOptions): void;
  positions(k: number, list?: number): Float32Array;
  copyPositions<T extends Float32Array>(k: number, list: number, target: T, offset?: number): T;
  drawings(k: number, list?: number): BlendedDrawing[];
  copyUvs(k: number, list: number, drawing: number, target?: Float32Array, offset?: number): Float32Array;
  appearance(k: number, list?: number): Appearance;
  list(k: number, list?: number): ListFrame;
  /** Back to front: [list0, part0, list1, part1, ...]. */
  steps(k: number): Uint32Array;
  /** The character digest (integrations/README.md) of the last frame. */
  digest(): string;
  createAnimator(): Animator;
  readonly animator: Animator | null;
  free(): void;
}

export interface PlayOptions {
  channel?: number;
  speed?: number;
  /** -1: as the path says; 0: once; 1: looped. */
  loop?: number;
  mix?: number;
  start?: number;
  queue?: boolean;
}
export interface AnimatorEvent {
  character: number;
  channel: number;
  event: number;
  name: string;
  outgoing: boolean;
  time: number;
}
export declare class Animator {
  readonly crowd: Crowd;
  play(k: number, path: number | string, options?: PlayOptions): void;
  setPoint(k: number, x: number, y: number, options?: { channel?: number; mix?: number }): void;
  stop(k: number, options?: { channel?: number; mix?: number }): void;
  setSpeed(k: number, speed: number, options?: { channel?: number }): void;
  lookAt(k: number, x: number, y: number, options?: { channel?: number }): void;
  update(dt: number): AnimatorEvent[];
  useMachine(): void;
  setBool(k: number, input: string, value: boolean): void;
  setNumber(k: number, input: string, value: number): void;
  setMachinePoint(k: number, input: string, x: number, y: number): void;
  fire(k: number, input: string): void;
  state(k: number, layer?: number): string | null;
}
