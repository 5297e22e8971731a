#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Writes arm.json beside this script: a two-part layered test rig. A body
# (40 x 60 grid) and an arm (40 x 10 grid) glued at the shoulder (the body's
# top-right corner, the arm's end). The arm turns 120 degrees about the
# shoulder from rest to up, and the body leans 10 degrees about its base in
# up, so the joint moves too. Run it again after changing the geometry.
import json, math, os

def grid(xs, ys):
    verts = [[x, y] for y in ys for x in xs]
    n = len(xs)
    tris = []
    for j in range(len(ys) - 1):
        for i in range(n - 1):
            a, b, c, d = j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i
            tris += [[a, b, c], [a, c, d]]
    return verts, tris

def rotate(p, about, degrees):
    t = math.radians(degrees)
    x, y = p[0] - about[0], p[1] - about[1]
    return [about[0] + math.cos(t) * x - math.sin(t) * y, about[1] + math.sin(t) * x + math.cos(t) * y]

body, body_tris = grid([-20, -10, 0, 10, 20], [-60, -45, -30, -15, 0])
arm, arm_tris = grid([0, 10, 20, 30, 40], [-5, 0, 5])  # along +x from the joint at (0, 0)
base, shoulder = [0, -60], [20, 0]
poses = [("rest", [0, 0], -90, 0), ("mid", [1, 0], -30, 5), ("up", [2, 0], 30, 10)]
body_poses, arm_poses, joints = [], [], []
for name, point, arm_angle, lean in poses:
    b = [rotate(v, base, lean) for v in body]
    j = rotate(shoulder, base, lean)
    a = [[j[0] + p[0], j[1] + p[1]] for p in (rotate(v, [0, 0], arm_angle) for v in arm)]
    a[arm.index([0, 0])] = list(j)  # exactly the body's corner
    body_poses.append({"vertices": b})
    arm_poses.append({"vertices": a})
    joints.append(j)
rig = {
    "posemorph": 1,
    "name": "arm (tests/runtime/rigs/make_arm.py)",
    "poses": [{"name": n, "point": p} for n, p, _, _ in poses],
    "parts": [
        {"name": "body", "order": 0, "triangles": body_tris, "poses": body_poses},
        {"name": "arm", "order": 1, "triangles": arm_tris, "poses": arm_poses},
    ],
    "glue": [{"part": "arm", "to": "body", "at": joints}],
    "bake": {"grid_resolution": 16, "pixels_per_unit": 4},
    "paths": [{"name": "raise", "keys": [[0, 0, 0], [1, 1, 0], [2, 2, 0]]}],
}
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "arm.json"), "w") as f:
    json.dump(rig, f, separators=(",", ":"))
    f.write("\n")
