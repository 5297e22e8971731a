#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Bake times: prints the "bakes" table of docs/performance.md (rewritten by
# `scripts/docs-tables.py bakes`). Minutes, on a quiet machine; never in CI.
#
#   scripts/bench-bake.py [BUILD]     (default build/release)
#
# Rows, each one bake with posemorph-bake from BUILD, timed with GNU time
# (wall seconds, peak resident memory):
# - Pip's five SVG drawings rasterised with rsvg-convert at S x S pixels,
#   S = 256 ... 4096, landmarks and features scaled by S / 256, everything
#   else as in assets/pip/pip.json (how an HD drawing bakes);
# - a 300 x 300 vertex grid (90,000 vertices, 178,802 triangles) in three
#   poses, straight and bent either way, with two paths, given as vertices,
#   compact (the default) and --precision exact (how a large mesh bakes).
import json
import math
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
POSES = ['rest', 'stretch', 'squash', 'wave', 'lean']


def timed(command, cwd):
    """(seconds, peak MB, output, exit status) of one run under GNU time."""
    run = subprocess.run(['/usr/bin/time', '-f', 'TIME %e %M'] + command, cwd=cwd, capture_output=True, text=True)
    m = re.search(r'TIME ([0-9.]+) ([0-9]+)\s*$', run.stderr)
    if not m:
        sys.exit('scripts/bench-bake.py: no timing from ' + ' '.join(command) + ':\n' + run.stderr[-2000:])
    return float(m.group(1)), int(m.group(2)) / 1024, run.stdout + run.stderr[:m.start()], run.returncode


def fields(output):
    vertices = re.search(r'-> \S+: ([0-9]+) vertices', output)
    angle = re.search(r'min angle ([0-9.]+) degrees over all poses', output)
    size = re.search(r'vertices, [0-9]+ triangles, [0-9]+ poses, [0-9]+ paths, ([0-9]+) bytes', output)
    return (vertices.group(1) if vertices else '-', '%.2f deg' % float(angle.group(1)) if angle else '-',
            size.group(1) if size else '-')


def failure(output):
    for line in output.splitlines():
        if 'error' in line or 'cannot' in line:
            return line.strip()[:160].replace('|', '/')
    return output.strip().splitlines()[-1][:160] if output.strip() else 'no output'


def pip_rows(bake, work):
    with open(os.path.join(ROOT, 'assets', 'pip', 'pip.json')) as f:
        pip = json.load(f)
    rows = []
    for size in [256, 512, 1024, 2048, 4096]:
        folder = os.path.join(work, 'pip-%d' % size)
        os.makedirs(folder)
        scale = size / 256
        for name in POSES:
            subprocess.run(['rsvg-convert', '-w', str(size), '-h', str(size),
                            os.path.join(ROOT, 'assets', 'pip', name + '.svg'), '-o',
                            os.path.join(folder, name + '.png')], check=True)
        description = json.loads(json.dumps(pip))
        for pose in description['poses']:
            for key in ('landmarks', 'features'):
                pose[key] = [[x * scale, y * scale] for x, y in pose.get(key, [])]
        with open(os.path.join(folder, 'pip.json'), 'w') as f:
            json.dump(description, f)
        seconds, mb, output, status = timed([bake, 'pip.json', '-o', 'pip.pmrig'], folder)
        vertices, angle, size_bytes = fields(output)
        if status == 0:
            rows.append('| Pip at %d px | %.1f s | %.0f MB | %s | %s | %s |' %
                        (size, seconds, mb, vertices, angle, size_bytes))
        else:
            rows.append('| Pip at %d px | fails after %.1f s: %s | %.0f MB | | | |' % (size, seconds, failure(output), mb))
    return rows


def grid_description(n):
    length = 3.0

    def pose(bend):
        out = []
        for i in range(n):
            x = length * i / (n - 1)
            for j in range(n):
                y = -0.5 + j / (n - 1)
                if bend == 0:
                    out.append([x, y])
                else:
                    r, a = 1 / bend, bend * x / length
                    out.append([round((r - y) * math.sin(a), 6), round(r - (r - y) * math.cos(a), 6)])
        return out

    triangles = []
    for i in range(n - 1):
        for j in range(n - 1):
            a = i * n + j
            triangles += [[a, a + n, a + 1], [a + 1, a + n, a + n + 1]]
    return {'posemorph': 1, 'name': 'grid-%d' % (n * n), 'bake': {'grid_resolution': 64},
            'poses': [{'name': 'straight', 'point': [0, 0], 'vertices': pose(0)},
                      {'name': 'up', 'point': [0, 1], 'vertices': pose(0.8)},
                      {'name': 'down', 'point': [0, -1], 'vertices': pose(-0.8)}],
            'triangles': triangles,
            'paths': [{'name': 'wave', 'loop': True, 'interpolation': 'catmull-rom',
                       'keys': [[0, 0, -0.9], [0.5, 0, 0.9], [1, 0, -0.9]]},
                      {'name': 'bend', 'loop': False, 'interpolation': 'linear',
                       'keys': [[0, 0, 0], [1, 0, 1], [2, 0, -1]]}]}


def grid_rows(bake, work):
    folder = os.path.join(work, 'grid')
    os.makedirs(folder)
    with open(os.path.join(folder, 'grid.json'), 'w') as f:
        json.dump(grid_description(300), f)
    rows = []
    for label, extra in [('compact', []), ('exact', ['--precision', 'exact'])]:
        seconds, mb, output, status = timed([bake, 'grid.json', '-o', 'grid.pmrig'] + extra, folder)
        if status != 0:
            sys.exit('scripts/bench-bake.py: the 90,000-vertex grid does not bake:\n' + output[-2000:])
        vertices, _, size_bytes = fields(output)
        frames = re.search(r'over ([0-9]+) frames', output)
        note = ' (error measured over %s frames)' % frames.group(1) if frames else ''
        rows.append('| %s-vertex grid, 3 poses, 2 paths, %s%s | %.1f s | %.0f MB | %s | - | %s |' %
                    (f'{int(vertices):,}', label, note, seconds, mb, vertices, size_bytes))
    return rows


def main(argv):
    build = os.path.join(ROOT, argv[1] if len(argv) > 1 else 'build/release')
    bake = os.path.join(build, 'bin', 'posemorph-bake')
    if not os.path.exists(bake):
        sys.exit('scripts/bench-bake.py: no %s (build it first)' % os.path.relpath(bake, ROOT))
    cpu = subprocess.run(['nproc'], capture_output=True, text=True).stdout.strip()
    when = subprocess.run(['date', '-u', '+%Y-%m-%dT%H:%M:%SZ'], capture_output=True, text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as work:
        rows = pip_rows(bake, work) + grid_rows(bake, work)
    print('%s cores, %s; one bake each, wall time and peak resident memory (GNU time)' % (cpu, when))
    print()
    print('| bake | time | peak memory | vertices | min angle | rig bytes |')
    print('|---|---|---|---|---|---|')
    for row in rows:
        print(row)


if __name__ == '__main__':
    main(sys.argv)
