// SPDX-License-Identifier: MIT
// The frame a game pays for in the browser, timed: every character's points
// from the rig's paths, then Crowd.evaluate (every list, attachment and draw
// step). bench/frame_native.c is the same frame natively; scripts/bench-web.sh
// runs both and reports the ratio (docs/performance.md).
import { load } from 'posemorph';

const query = new URLSearchParams(location.search);
const say = (text) => { document.getElementById('result').textContent = text; document.title = text.split('\n')[0]; };

// As frame_native.c's pose(): body path 0 at f / 60 + 0.37 k, channel c path 0 at 0.8 f / 60 + 0.23 k c.
function pose(rig, crowd, n, f) {
  for (let k = 0; k < n; ++k) {
    const [x, y] = rig.pathCount > 0 ? rig.samplePath(0, 0, f / 60 + 0.37 * k)
                                     : [rig.channels[0].poses[k % rig.poseCount].x, rig.channels[0].poses[k % rig.poseCount].y];
    crowd.setPoint(k, x, y);
    for (let c = 1; c < rig.channelCount; ++c) {
      const ch = rig.channels[c];
      const [cx, cy] = ch.paths.length > 0 ? rig.samplePath(c, 0, (0.8 * f) / 60 + 0.23 * k * c) : [ch.poses[0].x, ch.poses[0].y];
      crowd.setPoint(k, cx, cy, c);
    }
  }
}

async function main() {
  const pm = await load();
  const frames = Number(query.get('frames') ?? 100), reps = Number(query.get('reps') ?? 7);
  const lines = [];
  for (const spec of (query.get('cases') ?? 'pip.compact.pmrig:1').split(',')) {
    const [file, count] = spec.split(':');
    const n = Number(count);
    const rig = await pm.fetchRig(file);
    const crowd = rig.crowd(n);
    // Warm up for two seconds: the engine compiles wasm in tiers (a baseline compiler first, the optimising
    // one for hot functions later), and a game runs for minutes, so the optimised code is what is timed.
    for (let w = 0, start = performance.now(); performance.now() - start < 2000; ++w) {
      pose(rig, crowd, n, w);
      crowd.evaluate();
    }
    const times = [];
    for (let r = 0; r < reps; ++r) {
      const start = performance.now();
      for (let f = 0; f < frames; ++f) {
        pose(rig, crowd, n, f);
        crowd.evaluate();
      }
      times.push((1000 * (performance.now() - start)) / frames);
    }
    times.sort((a, b) => a - b);
    lines.push(`${file}:${n} ${times[Math.floor(reps / 2)].toFixed(3)}`);
    rig.free();
  }
  say(`done ${lines.join(' ')}`);
}

main().catch((e) => say(`error (${e.name}): ${e.message}`));
