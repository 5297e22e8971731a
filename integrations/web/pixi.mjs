// SPDX-License-Identifier: MIT
// The PixiJS (v7) renderer for posemorph: every list of a character (body
// and attachments) drawn back to front, one mesh per draw step, with a
// shader that cross-fades up to eight drawings in premultiplied alpha
// exactly as posemorph-view does (the weighted sum of the drawings' texels,
// each in its region of its texture page, times the list's colour and the
// part's opacity).
//
//   import { loadDrawings, CharacterView } from 'posemorph/pixi';
//   const drawings = await loadDrawings(rig, 'drawings/', 'rigs/');  // PIXI textures of every list's pages
//   const view = new CharacterView(rig, drawings);           // a PIXI.Container; add it to the stage
//   crowd.evaluate(); view.update(crowd, k);                 // each frame, after the crowd's frame
//
// Textures: a rig baked with an atlas (list.atlas) needs its pages only
// (one texture for Pell with a face, beside the rig file: `pagesUrl`);
// an older rig, every drawing (from `baseUrl`). Draw calls: one per step,
// that is one per part of each list (Pip 1, Pell with a face 7), whatever
// the number of drawings blended.
import * as PIXI from 'pixi.js';

const vertex = `
precision highp float;
attribute vec2 aPosition;
attribute vec2 aUv0, aUv1, aUv2, aUv3, aUv4, aUv5, aUv6, aUv7;
uniform mat3 projectionMatrix;
uniform mat3 translationMatrix;
uniform vec4 uMap0, uMap1, uMap2, uMap3, uMap4, uMap5, uMap6, uMap7;  // each drawing's region: uv * xz + yw
varying vec2 v0, v1, v2, v3, v4, v5, v6, v7;
void main() {
  v0 = aUv0 * uMap0.xz + uMap0.yw; v1 = aUv1 * uMap1.xz + uMap1.yw; v2 = aUv2 * uMap2.xz + uMap2.yw;
  v3 = aUv3 * uMap3.xz + uMap3.yw; v4 = aUv4 * uMap4.xz + uMap4.yw; v5 = aUv5 * uMap5.xz + uMap5.yw;
  v6 = aUv6 * uMap6.xz + uMap6.yw; v7 = aUv7 * uMap7.xz + uMap7.yw;
  gl_Position = vec4((projectionMatrix * translationMatrix * vec3(aPosition, 1.0)).xy, 0.0, 1.0);
}`;
const fragment = `
precision highp float;
varying vec2 v0, v1, v2, v3, v4, v5, v6, v7;
uniform sampler2D d0, d1, d2, d3, d4, d5, d6, d7;
uniform vec4 uWeightsA, uWeightsB, uTint;
void main() {
  vec4 c = uWeightsA.x * texture2D(d0, v0) + uWeightsA.y * texture2D(d1, v1) + uWeightsA.z * texture2D(d2, v2)
         + uWeightsA.w * texture2D(d3, v3) + uWeightsB.x * texture2D(d4, v4) + uWeightsB.y * texture2D(d5, v5)
         + uWeightsB.z * texture2D(d6, v6) + uWeightsB.w * texture2D(d7, v7);
  gl_FragColor = c * uTint;
}`;
const K = 8;
let program = null;

// Every list's texture pages (list.pages: an atlas's pages, beside the rig
// file, from `pagesUrl`; or, for a rig without an atlas, each part's drawing
// in each pose, from `baseUrl`, the folder the rig's image references are
// relative to) as PIXI.Textures: drawings[list][page]. A page loads once
// whatever the lists that show it. Premultiplied (an atlas page is stored
// so; a drawing on decode), no mipmaps, the list's filter. A page that does
// not load, or whose name leaves its folder, is an Error naming it.
export async function loadDrawings(rig, baseUrl, pagesUrl = baseUrl) {
  const folder = (url) => (url.endsWith('/') || url === '' ? url : `${url}/`);
  const drawingsBase = folder(baseUrl), pagesBase = folder(pagesUrl);
  const byUrl = new Map();
  const textures = rig.lists.map((list) => {
    const scaleMode = list.textureFilter === 'nearest' ? PIXI.SCALE_MODES.NEAREST : PIXI.SCALE_MODES.LINEAR;
    return list.pages.map((page, k) => {
      if (!page.name || /^\/|(^|\/)\.\.(\/|$)|[\\:\x00-\x1f]/.test(page.name))
        throw new Error(`${rig.name}: list ${list.index} page ${k}: no name, or a name that leaves its folder`);
      const url = (page.atlas ? pagesBase : drawingsBase) + page.name;
      if (!byUrl.has(url)) byUrl.set(url, loadTexture(url, scaleMode, page.premultiplied));
      return byUrl.get(url);
    });
  });
  const settled = await Promise.all(textures.flat());
  let i = 0;
  return textures.map((pages) => pages.map(() => settled[i++]));
}

async function loadTexture(url, scaleMode, premultiplied) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url.split('/').pop()}: HTTP ${response.status}`);
  let bitmap;
  try {
    bitmap = await createImageBitmap(await response.blob(),
                                     { premultiplyAlpha: premultiplied ? 'none' : 'premultiply', colorSpaceConversion: 'none' });
  } catch (e) {
    throw new Error(`${url.split('/').pop()}: not an image the browser reads (${e.message})`);
  }
  const base = new PIXI.BaseTexture(bitmap, {
    scaleMode, mipmap: PIXI.MIPMAP_MODES.OFF, wrapMode: PIXI.WRAP_MODES.CLAMP, alphaMode: PIXI.ALPHA_MODES.PMA,
  });
  return new PIXI.Texture(base);
}

// One character: a PIXI.Container of meshes, one per draw step.
export class CharacterView extends PIXI.Container {
  constructor(rig, drawings) {
    super();
    program ??= PIXI.Program.from(vertex, fragment, 'posemorph');
    this.rig = rig;
    this.drawings = drawings;
    this.lists = rig.lists.map((list) => {
      const positions = new PIXI.Buffer(new Float32Array(2 * list.vertexCount), false, false);
      const uvs = new PIXI.Buffer(new Float32Array(2 * K * list.vertexCount), false, false);
      const geometry = new PIXI.Geometry().addAttribute('aPosition', positions, 2, false, PIXI.TYPES.FLOAT);
      for (let s = 0; s < K; ++s) geometry.addAttribute(`aUv${s}`, uvs, 2, false, PIXI.TYPES.FLOAT, 4 * 2 * K, 4 * 2 * s);
      geometry.addIndex(new PIXI.Buffer(list.triangles, false, true));
      return { positions, uvs, geometry, scratch: new Float32Array(2 * list.vertexCount), matrix: new PIXI.Matrix(),
               filled: false };
    });
    this.meshes = [];
    this.steps = 0;
  }
  #mesh(s) {
    while (this.meshes.length <= s) {
      const uniforms = { uWeightsA: new Float32Array(4), uWeightsB: new Float32Array(4), uTint: new Float32Array(4) };
      for (let d = 0; d < K; ++d) uniforms[`d${d}`] = PIXI.Texture.EMPTY, uniforms[`uMap${d}`] = new Float32Array([1, 0, 1, 0]);
      const mesh = new PIXI.Mesh(this.lists[0].geometry, new PIXI.Shader(program, uniforms));
      mesh.state.blendMode = PIXI.BLEND_MODES.NORMAL;  // premultiplied: ONE, ONE_MINUS_SRC_ALPHA
      this.addChild(mesh);
      this.meshes.push(mesh);
    }
    return this.meshes[s];
  }
  // Character k of the crowd's last frame (Crowd.evaluate), back to front.
  update(crowd, k) {
    const rig = this.rig;
    for (const l of this.lists) l.filled = false;
    const steps = crowd.steps(k);
    const frames = [];
    for (let s = 0; s < steps.length / 2; ++s) {
      const l = steps[2 * s], p = steps[2 * s + 1];
      const list = this.lists[l], info = rig.lists[l];
      if (!frames[l]) frames[l] = { drawings: crowd.drawings(k, l), ...crowd.appearance(k, l) };
      const frame = frames[l];
      if (!list.filled) {  // positions and the picked drawings' uvs, once per list
        crowd.copyPositions(k, l, list.positions.data);
        list.positions.update();
        // Only the blended drawings' uvs: a slot past them has weight 0, so what it samples does not count.
        const uvs = list.uvs.data, one = list.scratch, n = info.vertexCount;
        for (let d = 0; d < frame.drawings.length; ++d) {
          crowd.copyUvs(k, l, d, one);
          for (let i = 0; i < n; ++i) {
            uvs[2 * (K * i + d)] = one[2 * i];
            uvs[2 * (K * i + d) + 1] = one[2 * i + 1];
          }
        }
        list.uvs.update();
        const t = frame.transform;
        list.matrix.set(t[0], t[1], t[2], t[3], t[4], t[5]);
        list.filled = true;
      }
      const mesh = this.#mesh(s), u = mesh.shader.uniforms, part = info.parts[p];
      mesh.geometry = list.geometry;
      mesh.start = 3 * part.firstTriangle;
      mesh.size = 3 * part.triangleCount;
      for (let d = 0; d < K; ++d) {
        const drawing = frame.drawings[d < frame.drawings.length ? d : 0];
        const region = part.regions[drawing.pose];  // where the part's drawing in that pose lies on its page
        u[`d${d}`] = this.drawings[l][region.page];
        u[`uMap${d}`].set([region.scaleU, region.offsetU, region.scaleV, region.offsetV]);
        (d < 4 ? u.uWeightsA : u.uWeightsB)[d % 4] = d < frame.drawings.length ? drawing.weight : 0;
      }
      const c = frame.colour, a = c[3] * (p < 64 ? frame.partOpacity[p] : 1);
      u.uTint.set([c[0] * a, c[1] * a, c[2] * a, a]);
      mesh.transform.setFromMatrix(list.matrix);
      mesh.visible = true;
    }
    for (let s = steps.length / 2; s < this.meshes.length; ++s) this.meshes[s].visible = false;
    this.steps = steps.length / 2;
  }
  // Draw calls this character makes per frame (one per step).
  get drawCalls() {
    return this.steps;
  }
}
