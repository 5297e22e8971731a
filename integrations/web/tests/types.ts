// SPDX-License-Identifier: MIT
// A program against the package's types (posemorph.d.mts, pixi.d.mts),
// checked by tsc --strict in tests/run.sh: it compiles only if the types
// declare what the modules export, as a TypeScript game would use them.
import { load, PosemorphError, MAX_DRAWINGS, type Rig, type Crowd, type Transform } from 'posemorph';
import { loadDrawings, CharacterView } from 'posemorph/pixi';
import * as PIXI from 'pixi.js';

async function main(): Promise<void> {
  const pm = await load();
  const rig: Rig = await pm.fetchRig('pell-face.compact.pmrig', { untrusted: true });
  const crowd: Crowd = rig.crowd(2);
  const t: Transform = pm.compose(rig.place(1, 2, 0, 1, true), pm.transform(0, 0));
  crowd.setTransform(0, t);
  crowd.setPoint(0, rig.channels[0].poses[0].x, rig.channels[0].poses[0].y, 0);
  crowd.setQuantizedPoint(1, rig.quantize(0.1, 0.2));
  crowd.evaluate({ maxDrawings: MAX_DRAWINGS });
  const steps: Uint32Array = crowd.steps(0);
  const weight: number = crowd.drawings(0, 0)[0].weight;
  const animator = crowd.createAnimator();
  animator.play(0, 'walk', { loop: 1, mix: 0.1 });
  const events = animator.update(1 / 60);
  const app = new PIXI.Application({ width: 10, height: 10 });
  const view = new CharacterView(rig, await loadDrawings(rig, 'pell/'));
  app.stage.addChild(view);
  view.update(crowd, 0);
  const calls: number = view.drawCalls;
  console.log(steps.length, weight, events.length, calls, rig.anchor.x, rig.lists[0].parts[0].images[0]);
  try { pm.loadRig(new Uint8Array(0)); } catch (e) { if (e instanceof PosemorphError) console.log(e.code); }
  rig.free();
}
main();
