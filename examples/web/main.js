// SPDX-License-Identifier: MIT
// A character drawn with WebGL2, following the pointer through pose space:
// posemorph.js gives a draw list per frame, this file draws it with the
// exact cross-fade (the weighted sum of premultiplied drawings, then "over"),
// sampled from the rig's texture pages (its atlas, or without one its drawings).
// The smallest web example: the body channel of one rig through the C API by
// hand. A game takes integrations/web instead, the npm package (every
// channel, part and attachment, transforms, 4-byte points, the animator, a
// PixiJS renderer).
import { Posemorph } from './posemorph.js';

const result = document.getElementById('result');
const query = new URLSearchParams(location.search);

const vertexShader = `#version 300 es
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 uv0;  // each picked drawing's own uvs (GLSL ES has no input arrays)
layout(location = 2) in vec2 uv1;
layout(location = 3) in vec2 uv2;
layout(location = 4) in vec2 uv3;
layout(location = 5) in vec2 uv4;
layout(location = 6) in vec2 uv5;
layout(location = 7) in vec2 uv6;
layout(location = 8) in vec2 uv7;
uniform vec2 view_scale, view_offset;
out vec2 v_uv[8];
void main() {
  gl_Position = vec4(position * view_scale + view_offset, 0.0, 1.0);
  v_uv = vec2[8](uv0, uv1, uv2, uv3, uv4, uv5, uv6, uv7);
}`;
const fragmentShader = `#version 300 es
precision highp float;
precision highp sampler2DArray;
uniform sampler2DArray pages;
uniform float weights[8];
uniform int layers[8];  // each picked drawing's page
uniform vec4 maps[8];   // and where it lies there: page uv = (u x + y, v z + w)
uniform vec4 tint;  // the draw list's colour, premultiplied: (r a, g a, b a, a)
in vec2 v_uv[8];
out vec4 colour;
void main() {
  colour = vec4(0.0);
  for (int k = 0; k < 8; ++k)
    if (weights[k] != 0.0)
      colour += weights[k] * texture(pages, vec3(v_uv[k] * maps[k].xz + maps[k].yw, float(layers[k])));
  colour *= tint;
}`;

function loadPage(url, name) {
  return new Promise((resolve, reject) => {
    const image = new Image();
    image.onload = () => resolve(image);
    image.onerror = () => reject(new Error(`${name}: cannot load the page`));
    image.src = url;
  });
}

// FNV-1a over the bytes of the positions: the test compares it with the native runtime's.
function hash(floats) {
  const bytes = new Uint8Array(floats.buffer, floats.byteOffset, floats.byteLength);
  let h = 0xcbf29ce484222325n;
  for (const b of bytes) h = ((h ^ BigInt(b)) * 0x100000001b3n) & 0xffffffffffffffffn;
  return h.toString(16).padStart(16, '0');
}

async function main() {
  const pm = await Posemorph.create(window.createPosemorphWasm);
  const rigName = query.get('rig') || 'pip.pmrig';
  const response = await fetch(rigName);
  if (!response.ok) throw new Error(`${rigName}: HTTP ${response.status}`);
  const rig = pm.loadRig(new Uint8Array(await response.arrayBuffer()), rigName);
  const N = rig.poseCount, V = rig.vertexCount;
  // The texture pages: the atlas the bake packed beside the rig (one size,
  // premultiplied), or for a rig without one each pose's drawing.
  const pages = rig.pages(), { width, height } = pages[0] || {};
  if (!width || !pages[0].name) throw new Error(`${rigName}: the rig was not baked from drawings`);
  const folder = rigName.slice(0, rigName.lastIndexOf('/') + 1);
  const images = await Promise.all(pages.map((p) => loadPage(p.atlas ? folder + p.name : p.name, p.name)));
  images.forEach((image, k) => {
    const p = pages[k];
    if (image.width !== width || image.height !== height)
      throw new Error(p.atlas ? `${p.name}: the atlas page is ${image.width}x${image.height}, the rig's pages are ${width}x${height}`
                              : `${p.name}: the drawing is ${image.width}x${image.height}, the rig was baked from ${width}x${height}`);
  });
  const regions = [...Array(N).keys()].map((i) => rig.region(i));

  const size = Number(query.get('size') || 512);
  const canvas = document.getElementById('view');
  canvas.width = canvas.height = size;
  const gl = canvas.getContext('webgl2', { premultipliedAlpha: true, antialias: false });
  if (!gl) throw new Error('no WebGL2');
  const program = gl.createProgram();
  for (const [type, source] of [[gl.VERTEX_SHADER, vertexShader], [gl.FRAGMENT_SHADER, fragmentShader]]) {
    const s = gl.createShader(type);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    gl.attachShader(program, s);
  }
  gl.linkProgram(program);
  gl.useProgram(program);

  // Once: the pages (premultiplied) as a texture array, every pose's uvs, the triangles.
  const texture = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
  gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, gl.RGBA8, width, height, pages.length);
  gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);  // the pixels as stored
  images.forEach((image, k) => {
    gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, !pages[k].premultiplied);  // a drawing: straight alpha
    gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, k, width, height, 1, gl.RGBA, gl.UNSIGNED_BYTE, image);
  });
  gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);  // WebGL has no border colour:
  gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);  // drawings keep a clear edge
  const first = rig.drawLists(1, [0, 0])[0];
  const uvs = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, uvs);
  gl.bufferData(gl.ARRAY_BUFFER, 8 * V * N, gl.STATIC_DRAW);
  for (let i = 0; i < N; ++i) gl.bufferSubData(gl.ARRAY_BUFFER, 8 * V * i, rig.uvs(i));  // pose i's own uvs
  const indices = gl.createBuffer();
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, indices);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, first.indices, gl.STATIC_DRAW);
  const positions = gl.createBuffer();
  for (let a = 0; a <= 8; ++a) gl.enableVertexAttribArray(a);

  // The camera: the character's bounds with a 6% margin, as posemorph-view frames it.
  const b = rig.bounds(), margin = 0.06 * Math.max(b.maxX - b.minX, b.maxY - b.minY);
  const x0 = b.minX - margin, x1 = b.maxX + margin, y0 = b.minY - margin, y1 = b.maxY + margin;
  const zoom = Math.min(size / (x1 - x0), size / (y1 - y0));
  gl.uniform2f(gl.getUniformLocation(program, 'view_scale'), 2 * zoom / size, 2 * zoom / size);
  gl.uniform2f(gl.getUniformLocation(program, 'view_offset'), -(x0 + x1) / 2 * 2 * zoom / size, -(y0 + y1) / 2 * 2 * zoom / size);

  let point = (query.get('at') || '').split(',').map(Number);
  const fixed = point.length === 2 && point.every(Number.isFinite);
  if (!fixed) point = [0, 0];
  canvas.addEventListener('pointermove', (e) => {
    const g = rig.grid;
    point = [g.minX + (g.maxX - g.minX) * e.offsetX / size, g.maxY - (g.maxY - g.minY) * e.offsetY / size];
  });

  const weightsAt = gl.getUniformLocation(program, 'weights'), layersAt = gl.getUniformLocation(program, 'layers');
  const mapsAt = gl.getUniformLocation(program, 'maps');
  const tintAt = gl.getUniformLocation(program, 'tint');
  let tint = (query.get('tint') || '').split(',').map(Number);  // ?tint=r,g,b,a
  if (tint.length !== 4 || !tint.every(Number.isFinite)) tint = null;
  function draw() {
    const list = rig.drawLists(1, point, { tint })[0];
    gl.viewport(0, 0, size, size);
    gl.clearColor(0.93, 0.94, 0.95, 1);
    gl.clear(gl.COLOR_BUFFER_BIT);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.ONE, gl.ONE_MINUS_SRC_ALPHA);
    gl.bindBuffer(gl.ARRAY_BUFFER, positions);
    gl.bufferData(gl.ARRAY_BUFFER, list.positions, gl.STREAM_DRAW);
    gl.vertexAttribPointer(0, 2, gl.FLOAT, false, 0, 0);
    gl.bindBuffer(gl.ARRAY_BUFFER, uvs);
    const weights = new Float32Array(8), layers = new Int32Array(8), maps = new Float32Array(32);
    for (let s = 0; s < 8; ++s) {
      const d = list.drawings[s < list.drawings.length ? s : 0];
      weights[s] = s < list.drawings.length ? d.weight : 0;
      layers[s] = regions[d.pose].page;
      maps.set(regions[d.pose].map, 4 * s);
      gl.vertexAttribPointer(1 + s, 2, gl.FLOAT, false, 0, 8 * V * d.pose);
    }
    gl.uniform1fv(weightsAt, weights);
    gl.uniform1iv(layersAt, layers);
    gl.uniform4fv(mapsAt, maps);
    const [r, g, b, a] = list.colour;
    gl.uniform4f(tintAt, r * a * list.partOpacity[0], g * a * list.partOpacity[0], b * a * list.partOpacity[0],
                 a * list.partOpacity[0]);
    gl.drawElements(gl.TRIANGLES, 3 * rig.triangleCount, gl.UNSIGNED_INT, 0);
    return list;
  }

  const list = draw();
  const w = rig.weights(point[0], point[1]);
  const strongest = w.texture.indexOf(Math.max(...w.texture));
  // What the test reads: the positions' hash, and the runtime's time per frame here.
  const frames = 2000, start = performance.now();
  for (let f = 0; f < frames; ++f) rig.drawLists(1, point);
  const perFrame = (performance.now() - start) / frames;
  result.textContent = `ready posemorph ${pm.version}: ${V} vertices, point ${point.join(',')}, ` +
                       `strongest drawing ${rig.poseImage(strongest)}, ` +
                       (N > 8 ? `${N} poses: each frame blends the 8 most weighted drawings, ` : '') +
                       `positions-fnv1a64=${hash(list.positions)}, evaluation ${(1000 * perFrame).toFixed(1)} us per frame`;
  document.title = result.textContent;  // what a test polling the browser can read
  if (!fixed) (function loop() { draw(); requestAnimationFrame(loop); })();
}

main().catch((e) => { document.title = result.textContent = `error: ${e.message}`; });
