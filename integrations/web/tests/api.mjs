// SPDX-License-Identifier: MIT
// What posemorph.mjs promises about memory and values, checked in the
// browser on the installed package (tests/run.sh reads the result).
import { load, PosemorphError, MAX_DRAWINGS } from 'posemorph';

const checks = [];
function check(what, ok) {
  checks.push(what);
  if (!ok) throw new Error(`failed: ${what}`);
}
function throws(what, call, text) {
  try {
    call();
  } catch (e) {
    check(`${what} (${e.message})`, e instanceof PosemorphError && e.message.includes(text));
    return;
  }
  check(`${what} throws`, false);
}

async function main() {
  const pm = await load();
  const pkg = await (await fetch('node_modules/posemorph/package.json')).json();
  check(`the package's version is the runtime's (${pm.version})`, pkg.version === pm.version);
  const rig = await pm.fetchRig('pell-face.compact.pmrig');
  check('Pell with a face: 2 lists or more, 4 body parts', rig.listCount >= 2 && rig.lists[0].parts.length === 4);
  check('one atlas page for every list, premultiplied, beside the rig',
        rig.lists.every((l) => l.atlas && l.pages.length === 1 && l.pages[0].name === 'pell-face.compact.page0.png' &&
                               l.pages[0].premultiplied && l.pages[0].width === rig.lists[0].pages[0].width));
  check('every part in every pose has its region on that page',
        rig.lists.every((l) => l.parts.every((p) => p.regions.length === l.poseCount && p.regions.every((g) =>
          g.page === 0 && g.width > 0 && g.x + g.width <= l.pages[0].width && g.y + g.height <= l.pages[0].height &&
          Math.abs(g.scaleU * l.pages[0].width - l.canvases[0].width) < 1e-3))));
  check('channel names and paths', rig.channels.every((c) => typeof c.name === 'string') && rig.channels[0].paths.length > 0);
  const crowd = rig.crowd(3);
  const [x, y] = rig.samplePath(0, 0, 0.5);
  crowd.setPoint(1, x, y);
  crowd.evaluate();
  const before = crowd.positions(1), list = crowd.list(1), steps = crowd.steps(1);
  const [x2, y2] = rig.samplePath(0, 0, 1.7);
  crowd.setPoint(1, x2, y2);
  crowd.evaluate();
  const after = crowd.positions(1);
  check('the next frame differs', after.some((v, i) => v !== before[i]));
  check('a copy does not change under the caller', list.positions.every((v, i) => v === before[i]));
  check('7 draw steps (4 body parts, 3 face parts)', steps.length === 2 * 7);
  const d = crowd.drawings(1);
  check(`1..${MAX_DRAWINGS} drawings, weights summing to 1`, d.length >= 1 && d.length <= MAX_DRAWINGS &&
        Math.abs(d.reduce((s, w) => s + w.weight, 0) - 1) < 1e-5);
  const packed = rig.quantize(x, y), [qx, qy] = rig.dequantize(packed);
  check('a 4-byte point round-trips to the pad cell', Number.isInteger(packed) && packed >= 0 &&
        rig.quantize(qx, qy) === packed);
  const place = rig.place(10, 20), t = pm.compose(pm.transform(1, 2), place);
  check('place then move', Math.abs(t[4] - (place[4] + 1)) < 1e-4 && Math.abs(t[5] - (place[5] + 2)) < 1e-4);
  throws('a character out of range', () => crowd.setPoint(3, 0, 0), 'no character 3');
  throws('a channel out of range', () => crowd.setPoint(0, 0, 0, rig.channelCount), 'no channel');
  const animator = crowd.createAnimator();
  animator.play(0, 0);
  animator.update(0.25);
  crowd.evaluate();
  check('the animator drives the frame', crowd.drawings(0).length >= 1);
  crowd.free();
  crowd.free();
  throws('a freed crowd', () => crowd.evaluate(), 'the crowd was freed');
  const other = rig.crowd(1);
  rig.free();
  rig.free();
  throws('a freed rig', () => rig.samplePath(0, 0, 0), 'the rig was freed');
  throws('a crowd of a freed rig', () => other.evaluate(), 'the crowd was freed');
  throws('an empty file', () => pm.loadRig(new Uint8Array(0), 'empty.pmrig'), 'empty.pmrig: ');
  return `ok: ${checks.length} checks: ${checks.join('; ')}`;
}

const result = document.getElementById('result');
main().then((text) => { result.textContent = text; }, (e) => { result.textContent = `error (${e.name}): ${e.message}`; });
