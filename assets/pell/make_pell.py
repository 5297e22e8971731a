#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Writes Pell, the layered sample, beside this script: one SVG per pose
# (rest, wave, cross, lean), each part a top-level group whose id is the
# part's name, and pell.json, the rig description. The build rasterises
# each part of each pose on its own (assets/CMakeLists.txt hides the other
# groups with a stylesheet), so every part has a PNG per pose on one
# 256 x 256 canvas. Landmarks and joints follow the parts' rotations here,
# so run it again after changing the geometry.
#
# It also writes Pell's face channel: one SVG per expression (face-calm,
# face-joy, face-surprise, face-sleepy), holding the eyes and the mouth
# drawn on the rest pose's head, and pell-face.json, Pell with two control
# channels: "body" (the four poses above) drives the body, arms and head,
# "face" (the four expressions) the eyes and the mouth, each glued to the
# head at one joint (bake/RIG_DESCRIPTION.md, "channels").
import json, math, os, re

HERE = os.path.dirname(os.path.abspath(__file__))
BASE, NECK = (128, 216), (128, 110)
SHOULDERS = {"arm-left": (96, 126), "arm-right": (160, 126)}
EYES = {"eye-left": (114, 78), "eye-right": (142, 78)}
MOUTH = (128, 102)

def rotate(p, about, degrees):
    # SVG's rotate(degrees cx cy): clockwise on screen (y down).
    t = math.radians(degrees)
    x, y = p[0] - about[0], p[1] - about[1]
    return (about[0] + math.cos(t) * x - math.sin(t) * y, about[1] + math.sin(t) * x + math.cos(t) * y)

# name, pose-space point, body lean, head tilt, left arm, right arm, the right arm's draw order
POSES = [
    ("rest", [0, 0], 0, 0, 18, -18, -1),
    ("wave", [1, 0], 0, -8, 18, -150, -1),
    ("cross", [0, 1], 0, 6, 22, 62, 1),
    ("lean", [-1, 0], -10, 10, 30, -30, -1),
]

def svg(name, lean, tilt, left, right):
    body_t = f"rotate({lean} {BASE[0]} {BASE[1]})"
    head_t = f"{body_t} rotate({tilt} {NECK[0]} {NECK[1]})"
    def arm(part, angle):
        sx, sy = SHOULDERS[part]
        return (f'  <g id="{part}" transform="{body_t} rotate({angle} {sx} {sy})">\n'
                f'    <rect x="{sx - 9}" y="{sy - 9}" width="18" height="74" rx="9" fill="#e9b07a" '
                f'stroke="#7a4a25" stroke-width="3"/>\n'
                f'    <circle cx="{sx}" cy="{sy + 54}" r="5" fill="#c98a55"/>\n  </g>\n')
    def eye(part):
        ex, ey = EYES[part]
        return (f'  <g id="{part}" transform="{head_t}">\n'
                f'    <ellipse cx="{ex}" cy="{ey}" rx="7" ry="9" fill="#2b2b2b"/>\n'
                f'    <circle cx="{ex + 2}" cy="{ey - 3}" r="2.5" fill="#ffffff"/>\n  </g>\n')
    return (
        '<!-- SPDX-License-Identifier: MIT -->\n'
        '<svg xmlns="http://www.w3.org/2000/svg" width="256" height="256" viewBox="0 0 256 256">\n'
        f'  <!-- Pell, pose "{name}": written by make_pell.py. Drawn for posemorph. -->\n'
        + arm("arm-left", left) +
        f'  <g id="body" transform="{body_t}">\n'
        '    <ellipse cx="128" cy="160" rx="44" ry="56" fill="#3aa6a0" stroke="#1d4f4c" stroke-width="3"/>\n'
        '    <path d="M 100 150 H 156 V 176 H 100 Z" fill="#2f8c87"/>\n'
        '    <circle cx="128" cy="190" r="6" fill="#f6d365"/>\n  </g>\n'
        + arm("arm-right", right) +
        f'  <g id="head" transform="{head_t}">\n'
        '    <path d="M 118 46 L 124 28 L 130 40 L 138 30 L 140 47 Z" fill="#6b3f17" stroke="#6b3f17" '
        'stroke-width="3" stroke-linejoin="round"/>\n'
        '    <circle cx="128" cy="80" r="38" fill="#f4c48a" stroke="#7a4a25" stroke-width="3"/>\n'
        '    <path d="M 92 70 Q 128 30 164 70 Q 150 48 128 46 Q 106 48 92 70 Z" fill="#6b3f17"/>\n'
        '    <circle cx="104" cy="96" r="6" fill="#f29f8a"/><circle cx="152" cy="96" r="6" fill="#f29f8a"/>\n  </g>\n'
        + eye("eye-left") + eye("eye-right") +
        f'  <g id="mouth" transform="{head_t}">\n'
        '    <path d="M 114 95 Q 128 98 142 95 Q 141 110 128 110 Q 115 110 114 95 Z" fill="#8a2b2b"/>\n'
        '    <path d="M 120 106 Q 128 101 136 106 Q 128 109 120 106 Z" fill="#e0707a"/>\n  </g>\n'
        '</svg>\n')

PARTS = ["body", "arm-left", "arm-right", "head", "eye-left", "eye-right", "mouth"]
ORDER = {"body": 0, "arm-left": -1, "head": 2, "eye-left": 3, "eye-right": 3, "mouth": 3}
poses, part_poses, joints = [], {p: [] for p in PARTS}, {p: [] for p in PARTS if p != "body"}
for name, point, lean, tilt, left, right, _ in POSES:
    with open(os.path.join(HERE, name + ".svg"), "w") as f:
        f.write(svg(name, lean, tilt, left, right))
    poses.append({"name": name, "point": point})
    body = lambda p: rotate(p, BASE, lean)
    head = lambda p: body(rotate(p, NECK, tilt))
    arm = lambda part, angle, p: body(rotate(p, SHOULDERS[part], angle))
    r = lambda p: [round(p[0], 3), round(p[1], 3)]
    # Each part's start point: a point of its outline that moves with it.
    starts = {
        "body": body((128, 217.5)),
        "arm-left": arm("arm-left", left, (96, 126 + 66.5)),
        "arm-right": arm("arm-right", right, (160, 126 + 66.5)),
        "head": head((124, 26.5)),  # the tuft's tip
        "eye-left": head((114, 87)),
        "eye-right": head((142, 87)),
        "mouth": head((128, 110)),
    }
    for part in PARTS:
        part_poses[part].append({"drawing": f"{name}-{part}.png", "landmarks": [r(starts[part])]})
    joints["head"].append(r(body(NECK)))
    joints["arm-left"].append(r(body(SHOULDERS["arm-left"])))
    joints["arm-right"].append(r(body(SHOULDERS["arm-right"])))
    for eye in EYES:
        joints[eye].append(r(head(EYES[eye])))
    joints["mouth"].append(r(head(MOUTH)))

parts = []
for part in PARTS:
    order = ORDER.get(part)
    if part == "arm-right":
        order = [p[6] for p in POSES]  # behind the body, in front when it crosses
    parts.append({"name": part, "order": order, "poses": part_poses[part]})
glue = [{"part": p, "to": "head" if p in EYES or p == "mouth" else "body", "at": joints[p]} for p in joints]
rig = {
    "posemorph": 1,
    "name": "pell",
    "poses": poses,
    "parts": parts,
    "glue": glue,
    "mapping": {"simplify_tolerance": 1.0, "min_angle": 20},
    "bake": {"grid_resolution": 64, "sigma": 0.25},
    "paths": [
        {"name": "greet", "loop": True, "interpolation": "catmull-rom",
         "keys": [[0, 0, 0], [0.8, 1, 0], [1.6, 0, 0], [2.4, 0, 1], [3.2, 0, 0], [4, -1, 0], [4.8, 0, 0]]},
    ],
}
def write_json(name, value):
    text = json.dumps(value, indent=1)
    text = re.sub(r"\[\s*(-?[\d.]+),\s*(-?[\d.]+)\s*\]", r"[\1, \2]", text)
    text = re.sub(r"\[\s*(-?[\d.]+),\s*(-?[\d.]+),\s*(-?[\d.]+)\s*\]", r"[\1, \2, \3]", text)
    text = re.sub(r"\[\s*(-?[\d.]+),\s*(-?[\d.]+),\s*(-?[\d.]+),\s*(-?[\d.]+)\s*\]", r"[\1, \2, \3, \4]", text)
    # events, [time, "name"], and a list of them, on one line
    text = re.sub(r'\[\s*(-?[\d.]+),\s*("[^"]*")\s*\]', r"[\1, \2]", text)
    text = re.sub(r'\[\s*((?:\[-?[\d.]+, "[^"]*"\],?\s*)+)\]',
                  lambda m: "[" + re.sub(r"\],\s*", "], ", m.group(1).strip()) + "]", text)
    with open(os.path.join(HERE, name), "w") as f:
        f.write(text + "\n")

write_json("pell.json", rig)

# The face channel. Each expression: the eyes' half-height (they stay
# centred on their joints), and the mouth as a closed path around its joint
# with the lowest point of its outline (the mouth's start point).
FACES = [
    # name, point, eye rx, eye ry, mouth path, mouth's lowest point
    ("calm", [0, 0], 7, 9, "M 114 95 Q 128 98 142 95 Q 141 110 128 110 Q 115 110 114 95 Z", (128, 110)),
    ("joy", [1, 0], 8, 5, "M 110 93 Q 128 99 146 93 Q 144 116 128 116 Q 112 116 110 93 Z", (128, 116)),
    ("surprise", [0, 1], 8, 11, "M 121 103 Q 121 94 128 94 Q 135 94 135 103 Q 135 112 128 112 Q 121 112 121 103 Z",
     (128, 112)),
    ("sleepy", [-1, 0], 8, 4, "M 118 99 Q 128 101 138 99 Q 137 106 128 106 Q 119 106 118 99 Z", (128, 106)),
]

def face_svg(name, rx, ry, mouth):
    def eye(part):
        ex, ey = EYES[part]
        return (f'  <g id="{part}">\n'
                f'    <ellipse cx="{ex}" cy="{ey}" rx="{rx}" ry="{ry}" fill="#2b2b2b"/>\n'
                f'    <circle cx="{ex + 2}" cy="{ey - ry / 3:g}" r="{min(2.5, ry / 3):g}" fill="#ffffff"/>\n  </g>\n')
    return (
        '<!-- SPDX-License-Identifier: MIT -->\n'
        '<svg xmlns="http://www.w3.org/2000/svg" width="256" height="256" viewBox="0 0 256 256">\n'
        f'  <!-- Pell\'s face, expression "{name}", on the rest pose\'s head: written by make_pell.py. -->\n'
        + eye("eye-left") + eye("eye-right") +
        '  <g id="mouth">\n'
        f'    <path d="{mouth}" fill="#8a2b2b"/>\n  </g>\n'
        '</svg>\n')

FACE_PARTS = ["eye-left", "eye-right", "mouth"]
face_poses, face_part_poses = [], {p: [] for p in FACE_PARTS}
face_joints = {p: [] for p in FACE_PARTS}
for name, point, rx, ry, mouth, lowest in FACES:
    with open(os.path.join(HERE, f"face-{name}.svg"), "w") as f:
        f.write(face_svg(name, rx, ry, mouth))
    face_poses.append({"name": name, "point": point})
    for eye in EYES:
        face_part_poses[eye].append({"drawing": f"face-{name}-{eye}.png",
                                     "landmarks": [[EYES[eye][0], EYES[eye][1] + ry]]})
        face_joints[eye].append(list(EYES[eye]))
    face_part_poses["mouth"].append({"drawing": f"face-{name}-mouth.png", "landmarks": [list(lowest)]})
    face_joints["mouth"].append(list(MOUTH))

# Pell with a face: the body's gesture and the face's chatter carry named
# events, and a state machine drives both channels (docs/animation.md).
greet = {"name": "greet", "loop": True,
         "events": [[0.8, "wave-peak"], [2.4, "cross"], [4.0, "lean"], [4.8, "cycle"]],
         "interpolation": "catmull-rom", "keys": rig["paths"][0]["keys"]}
chatter = {"name": "chatter", "loop": True,
           "events": [[0.0, "open"], [0.6, "smile"], [1.8, "gasp"], [1.8, "blink"], [3.0, "yawn"]],
           "interpolation": "catmull-rom",
           "keys": [[0, 0, 0], [0.6, 1, 0], [1.2, 0, 0], [1.8, 0, 1], [2.4, 0, 0], [3, -1, 0], [3.6, 0, 0]]}
state_machine = {
    "inputs": [
        {"name": "wave", "type": "trigger"},
        {"name": "sway", "type": "number", "default": 0},
        {"name": "talking", "type": "bool"},
        {"name": "looking", "type": "bool"},
        {"name": "gaze", "type": "point", "default": [0, 0]},
        {"name": "ghost", "type": "bool"},
        {"name": "vanish", "type": "bool"},
    ],
    "layers": [
        {"channel": "body", "initial": "idle",
         "behaviours": {"breath": {"period": 3.5, "offset": [0, 0.04]},
                        "spring": {"frequency": 2.5, "damping": 0.35}},
         "states": [{"name": "idle", "stop": True},
                    {"name": "waving", "play": "greet", "loop": False},
                    {"name": "swaying", "blend": "greet", "by": "sway"},
                    # Colour set by states (format 1.10): a blue ghost whose
                    # body fades under its head, and a fade out.
                    {"name": "ghost", "stop": True, "colour": [0.7, 0.85, 1.0],
                     "parts": {"body": 0.3, "arm-left": 0.3, "arm-right": 0.3}},
                    {"name": "vanished", "stop": True, "opacity": 0}],
         "transitions": [
             {"from": "idle", "to": "waving", "when": ["wave"], "mix": 0.3},
             {"from": "waving", "to": "idle", "exit_time": 1.0, "mix": 0.5},
             {"from": "*", "to": "swaying", "when": [["sway", ">", 0]], "mix": 0.4},
             {"from": "swaying", "to": "idle", "when": [["sway", "<=", 0]], "mix": 0.4},
             {"from": "*", "to": "vanished", "when": ["vanish"], "mix": 1.0},
             {"from": "vanished", "to": "idle", "when": ["!vanish"], "mix": 0.5},
             {"from": "*", "to": "ghost", "when": ["ghost", "!vanish"], "mix": 0.6},
             {"from": "ghost", "to": "idle", "when": ["!ghost"], "mix": 0.6}]},
        {"channel": "face", "initial": "calm",
         "behaviours": {"blink": {"pose": "sleepy", "interval": 3.2, "jitter": 0.4, "duration": 0.16},
                        "look_at": {"target": "gaze", "smoothing": 0.15, "strength": 0.3}},
         "states": [{"name": "calm", "stop": True},
                    {"name": "chatting", "play": "chatter"},
                    {"name": "looking-at", "pad": "gaze"}],
         "transitions": [
             {"from": "*", "to": "looking-at", "when": ["looking"], "mix": 0.25},
             {"from": "looking-at", "to": "calm", "when": ["!looking"], "mix": 0.25},
             {"from": "calm", "to": "chatting", "when": ["talking"], "mix": 0.2},
             {"from": "chatting", "to": "calm", "when": ["!talking"], "mix": 0.3}]},
    ],
}
layered = {
    "posemorph": 1,
    "name": "pell-face",
    "channels": [
        {"name": "body", "poses": poses, "paths": [greet]},
        {"name": "face", "poses": face_poses, "paths": [chatter]},
    ],
    "parts": [p for p in parts if p["name"] not in FACE_PARTS]
    + [{"name": p, "channel": "face", "order": ORDER[p], "poses": face_part_poses[p]} for p in FACE_PARTS],
    "glue": [g for g in glue if g["part"] not in FACE_PARTS]
    + [{"part": p, "to": "head", "at": face_joints[p]} for p in FACE_PARTS],
    "mapping": rig["mapping"],
    "bake": rig["bake"],
    "state_machine": state_machine,
}
write_json("pell-face.json", layered)
