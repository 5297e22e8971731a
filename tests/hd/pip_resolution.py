#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Resolution independence of the bake (issue 38, docs/DESIGN.md section 4):
# Pip's five SVG drawings rasterised with rsvg-convert at 256 and at a
# larger sizes S (default 1024; several may be given, 256 px is baked once),
# landmarks and features scaled by S / 256,
# everything else as in assets/pip/pip.json, baked with the defaults. The
# same drawing at a higher resolution should give about the same mesh:
#
# - vertex counts within 15% of each other;
# - in every pose, the mesh boundaries within BOUNDARY_PX pixels of each
#   other, measured at 256 px (the symmetric Hausdorff distance of the two
#   boundary polylines, sampled every 0.25 px): each boundary is its
#   outline simplified within mapping.simplify_tolerance (1 px by default),
#   so two of them may lie up to 2 px apart; 1.2-1.4 px is measured;
# - the smallest angle at S no worse than at 256 px, or with --min-angle A
#   at least A degrees (the quality floor is half of mapping.min_angle).
#
#   tests/hd/pip_resolution.py --bake BAKE --work DIR [--size S...] [--min-angle A]
#
# Exit 77 (ctest's skip) without rsvg-convert.
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
POSES = ['rest', 'stretch', 'squash', 'wave', 'lean']
VERTEX_TOLERANCE = 0.15
BOUNDARY_PX = 1.5


def fail(message):
    sys.exit('pip_resolution: ' + message)


def bake_at(bake, work, size):
    """Rasterises and bakes Pip at size x size; returns (vertices, min angle, boundaries per pose)."""
    folder = os.path.join(work, 'pip-%d' % size)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    scale = size / 256
    for name in POSES:
        subprocess.run(['rsvg-convert', '-w', str(size), '-h', str(size),
                        os.path.join(ROOT, 'assets', 'pip', name + '.svg'), '-o',
                        os.path.join(folder, name + '.png')], check=True)
    with open(os.path.join(ROOT, 'assets', 'pip', 'pip.json')) as f:
        description = json.load(f)
    for pose in description['poses']:
        for key in ('landmarks', 'features'):
            if key in pose:
                pose[key] = [[x * scale, y * scale] for x, y in pose[key]]
    with open(os.path.join(folder, 'pip.json'), 'w') as f:
        json.dump(description, f)
    run = subprocess.run([bake, 'pip.json', '-o', 'pip.pmrig'], cwd=folder, capture_output=True, text=True)
    output = run.stdout + run.stderr
    if run.returncode != 0:
        fail('Pip at %d px does not bake (exit %d):\n%s' % (size, run.returncode, output[-3000:]))
    vertices = re.search(r'-> \S+: ([0-9]+) vertices', output)
    angle = re.search(r'min angle ([0-9.]+) degrees over all poses', output)
    if not vertices or not angle:
        fail('no vertex count or min angle in the bake output at %d px:\n%s' % (size, output[-3000:]))
    boundaries = []
    for k, pose in enumerate(description['poses']):
        x, y = pose['point']
        out = os.path.join(folder, 'pose-%d.json' % k)
        subprocess.run([bake, 'eval', 'pip.pmrig', '--at', '%r,%r' % (x, y), '-o', out], cwd=folder, check=True,
                       capture_output=True)
        with open(out) as f:
            frame = json.load(f)
        points = [(px / scale, py / scale) for px, py in frame['frames'][0]['vertices']]
        boundaries.append(boundary_segments(points, frame['triangles']))
    return int(vertices.group(1)), float(angle.group(1)), boundaries


def boundary_segments(points, triangles):
    """The mesh's boundary: the edges that only one triangle uses."""
    count = {}
    for t in triangles:
        for i in range(3):
            a, b = t[i], t[(i + 1) % 3]
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
    return [(points[a], points[b]) for (a, b), n in count.items() if n == 1]


def distance_to_segment(p, s):
    (ax, ay), (bx, by) = s
    dx, dy = bx - ax, by - ay
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / length2))
    return math.hypot(p[0] - ax - t * dx, p[1] - ay - t * dy)


def samples(segments, step=0.25):
    for (ax, ay), (bx, by) in segments:
        n = max(1, int(math.ceil(math.hypot(bx - ax, by - ay) / step)))
        for i in range(n):
            yield (ax + (bx - ax) * i / n, ay + (by - ay) * i / n)


def one_way(a, b):
    """The largest distance from a sample of a to the segments of b, and where."""
    worst, where = 0.0, None
    # A coarse bucket grid over b's segments keeps this fast enough for ctest.
    cell = 4.0
    grid = {}
    for s in b:
        (ax, ay), (bx, by) = s
        for gx in range(int(math.floor(min(ax, bx) / cell)), int(math.floor(max(ax, bx) / cell)) + 1):
            for gy in range(int(math.floor(min(ay, by) / cell)), int(math.floor(max(ay, by) / cell)) + 1):
                grid.setdefault((gx, gy), []).append(s)
    for p in samples(a):
        gx, gy = int(math.floor(p[0] / cell)), int(math.floor(p[1] / cell))
        best = math.inf
        for r in range(0, 64):
            for ix in range(gx - r, gx + r + 1):
                for iy in range(gy - r, gy + r + 1):
                    if max(abs(ix - gx), abs(iy - gy)) != r:
                        continue
                    for s in grid.get((ix, iy), ()):
                        best = min(best, distance_to_segment(p, s))
            if best <= r * cell:
                break
        if best > worst:
            worst, where = best, p
    return worst, where


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--bake', required=True)
    parser.add_argument('--work', required=True)
    parser.add_argument('--size', type=int, nargs='+', default=[1024])
    parser.add_argument('--min-angle', type=float, default=None)
    args = parser.parse_args()
    args.bake = os.path.abspath(args.bake)
    if not shutil.which('rsvg-convert'):
        print('pip_resolution: rsvg-convert not found (Debian librsvg2-bin); skipped')
        return 77
    os.makedirs(args.work, exist_ok=True)
    v0, angle0, boundary0 = bake_at(args.bake, args.work, 256)
    print('Pip at 256 px: %d vertices, min angle %.2f deg' % (v0, angle0))
    failures = []
    for size in args.size:
        v1, angle1, boundary1 = bake_at(args.bake, args.work, size)
        print('Pip at %d px: %d vertices, min angle %.2f deg' % (size, v1, angle1))
        ratio = v1 / v0
        if abs(ratio - 1) > VERTEX_TOLERANCE:
            failures.append('vertex count %d at %d px is %.1f%% off the %d at 256 px (allowed %.0f%%)' %
                            (v1, size, 100 * (ratio - 1), v0, 100 * VERTEX_TOLERANCE))
        for k, name in enumerate(POSES):
            d01, p01 = one_way(boundary0[k], boundary1[k])
            d10, p10 = one_way(boundary1[k], boundary0[k])
            d, p = (d01, p01) if d01 >= d10 else (d10, p10)
            print('  pose %d %s: boundaries within %.3f px (at 256 px), worst near (%.1f, %.1f)' %
                  (k, name, d, p[0], -p[1]))
            if d > BOUNDARY_PX:
                failures.append('pose %d %s: the boundaries at 256 and %d px differ by %.3f px near (%.1f, %.1f) '
                                '(allowed %.2f)' % (k, name, size, d, p[0], -p[1], BOUNDARY_PX))
        if args.min_angle is not None:
            if angle1 < args.min_angle:
                failures.append('min angle %.2f deg at %d px is below %.2f deg' % (angle1, size, args.min_angle))
        elif angle1 < angle0:
            failures.append('min angle %.2f deg at %d px is worse than the %.2f deg at 256 px' %
                            (angle1, size, angle0))
    for f in failures:
        print('FAIL ' + f)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
