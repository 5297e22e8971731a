// SPDX-License-Identifier: MIT
// posemorph in a PixiJS game: a crowd walks the rig's paths (every channel on
// its own), drawn by posemorph/pixi; or one character at a fixed pose-space
// point, framed as posemorph-view frames it (the test compares the two).
import { load } from 'posemorph';
import { loadDrawings, CharacterView } from 'posemorph/pixi';
import * as PIXI from 'pixi.js';

const result = document.getElementById('result');
const query = new URLSearchParams(location.search);
const say = (text) => { result.textContent = text; document.title = text.split('\n')[0]; };

async function main() {
  const pm = await load();
  const rig = await pm.fetchRig(query.get('rig') ?? 'pell-face.compact.pmrig');
  const n = Number(query.get('digest') ?? query.get('crowd') ?? 1);
  const crowd = rig.crowd(n);
  const at = query.get('at')?.split(',').map(Number);
  // Body: path 0 at t + 0.37 k (or pose k's point), or the point `at`; channel c: its path 0 at 0.8 t + 0.23 k c
  // (or its first pose when it has none or `at` is given).
  const pose = (t) => {
    for (let k = 0; k < n; ++k) {
      const body = at ?? (rig.pathCount > 0 ? rig.samplePath(0, 0, t + 0.37 * k)
                                            : [rig.channels[0].poses[k % rig.poseCount].x, rig.channels[0].poses[k % rig.poseCount].y]);
      crowd.setPoint(k, body[0], body[1]);
      for (let c = 1; c < rig.channelCount; ++c) {
        const ch = rig.channels[c];
        const p = ch.paths.length > 0 && !at ? rig.samplePath(c, 0, 0.8 * t + 0.23 * k * c) : [ch.poses[0].x, ch.poses[0].y];
        crowd.setPoint(k, p[0], p[1], c);
      }
    }
  };
  if (query.has('digest')) {  // integrations/README.md: the points pose(0) sets
    pose(0);
    crowd.evaluate();
    say(crowd.digest());
    return;
  }
  const [width, height] = (query.get('size') ?? '640x640').split('x').map(Number);
  const app = new PIXI.Application({ width, height, background: [0.93, 0.94, 0.95], antialias: false,
                                     preserveDrawingBuffer: true, autoStart: false });
  document.body.prepend(app.view);
  // The atlas's pages lie beside the rig file; a rig without one draws its drawings.
  const rigUrl = query.get('rig') ?? '';
  const drawings = await loadDrawings(rig, query.get('images') ?? 'pell/', rigUrl.slice(0, rigUrl.lastIndexOf('/') + 1));
  // Where each character stands: a grid, alternate ones facing left, fitted to the canvas.
  const b = rig.bounds(), margin = 0.06 * Math.max(b.maxX - b.minX, b.maxY - b.minY);
  const cw = b.maxX - b.minX + 2 * margin, ch = b.maxY - b.minY + 2 * margin;
  const columns = Math.ceil(Math.sqrt(n)), rows = Math.ceil(n / columns);
  const centre = pm.transform(-(b.minX + b.maxX) / 2, -(b.minY + b.maxY) / 2);
  const camera = new PIXI.Container();
  const zoom = Math.min(width / (cw * columns), height / (ch * rows));
  camera.scale.set(zoom, -zoom);  // rig units, y up
  camera.position.set(width / 2 - zoom * cw * (columns - 1) / 2, height / 2 - zoom * ch * (rows - 1) / 2);
  app.stage.addChild(camera);
  const views = [];
  for (let k = 0; k < n; ++k) {
    const place = pm.transform(cw * (k % columns), -ch * Math.floor(k / columns), 0, 1, 1, k % 2 === 1);
    crowd.setTransform(k, pm.compose(place, centre));
    views.push(camera.addChild(new CharacterView(rig, drawings)));
  }
  const frame = (t) => {
    pose(t);
    crowd.evaluate();
    views.forEach((view, k) => view.update(crowd, k));
    app.renderer.render(app.stage);
  };
  const frames = Number(query.get('frames') ?? 0);
  if (frames > 0) {
    for (let f = 0; f < frames; ++f) frame(f / 60);
    const calls = views.reduce((sum, v) => sum + v.drawCalls, 0);
    const textures = new Set(drawings.flat()).size;
    say(`ready: ${frames} frames of ${n} character(s), ${calls / n} draw calls per character, ${textures} texture(s), ` +
        `posemorph ${pm.version}`);
  } else {
    let t = 0;
    app.ticker.add(() => frame((t += app.ticker.deltaMS / 1000)));
    app.ticker.start();
    say(`ready: ${n} character(s), posemorph ${pm.version}`);
  }
}

main().catch((e) => say(`error (${e.name}): ${e.message}`));
