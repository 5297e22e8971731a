#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# posemorph-view --watch (ctest viewer.window_watch), on a copy of Pip's
# folder, under Xvfb with the validation layer: the window opens on the
# description baked in memory; the smoke session saves a gesture and an
# edited pose into the description, which is baked again and swapped in
# (6 poses, pose 1 moved on the pad); a landmark placed by clicking the
# outline in edit mode is added to every pose and baked in; a description
# broken on disk gives a failed re-bake whose
# message names the file, and the window keeps the last rig; the description
# mended is baked and swapped in again; the window then writes its shot and
# exits 0 after those three re-bakes, without having been closed.
#
# With --layered ORA PELL_JSON: Pell's own description (assets/pell/pell.json)
# with an "import" of Krita's pell.ora, beside that file alone: the watch
# imports its drawings before the first bake; then pell.ora is saved again
# with the wave pose's body at 80% opacity: the watch imports it again,
# wave-body.png changes (and no other drawing), and the re-bake swaps in.
#   viewer_watch_test.py VIEW XVFB_RUN PIP_FOLDER WORK [--layered ORA PELL_JSON]
import json, os, re, shutil, subprocess, sys, threading, time, zipfile

view, xvfb, pip, work = sys.argv[1:5]
layered = len(sys.argv) > 5 and sys.argv[5] == "--layered"
shutil.rmtree(work, ignore_errors=True)
if layered:
    ora, pell_json = sys.argv[6:8]
    os.makedirs(work)
    shutil.copy(ora, work)
    pell = json.load(open(pell_json))
    pell["import"] = {"files": ["pell.ora"]}
    description = os.path.join(work, "pell.json")
    with open(description, "w") as f:
        json.dump(pell, f, indent=1)
else:
    shutil.copytree(pip, work)
    description = os.path.join(work, "pip.json")
shot = os.path.join(work, "watch-shot.png")
process = subprocess.Popen(
    [xvfb, "-a", "-s", "-screen 0 1400x900x24", view, "--watch", description, "--validation", "--size", "1024x640",
     "--smoke-test", shot, "--frames", "20", "--rebakes", "2" if layered else "4"],
    stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
lines = []
seen = threading.Condition()

def read():
    for line in process.stdout:
        sys.stdout.write(line)
        sys.stdout.flush()
        with seen:
            lines.append(line.rstrip("\n"))
            seen.notify_all()
    with seen:
        lines.append(None)
        seen.notify_all()

threading.Thread(target=read, daemon=True).start()

def wait_for(text, after, seconds=300):
    # The index of the first line after line `after` (-1: from the first) that holds `text`.
    deadline = time.time() + seconds
    with seen:
        while True:
            for i in range(after + 1, len(lines)):
                if lines[i] is None:
                    sys.exit(f"FAIL: the viewer ended before printing '{text}'")
                if text in lines[i]:
                    return i
            if time.time() > deadline:
                process.kill()
                sys.exit(f"FAIL: no '{text}' within {seconds} s")
            seen.wait(1)

if layered:
    i = wait_for("watching it and its drawings", -1)
    if not os.path.exists(os.path.join(work, "lean-mouth.png")):
        sys.exit("FAIL: the watch did not import pell.ora's drawings before the first bake")
    # The smoke session's own saves: one re-bake.
    i = wait_for("swapped in", i)
    before = {f: open(os.path.join(work, f), "rb").read() for f in os.listdir(work) if f.endswith(".png")}
    time.sleep(0.3)
    # pell.ora saved again: in the wave group, the body layer at 80%.
    with zipfile.ZipFile(os.path.join(work, "pell.ora")) as z:
        entries = [(info, z.read(info.filename)) for info in z.infolist()]
    with zipfile.ZipFile(os.path.join(work, "pell.ora.tmp"), "w") as z:
        for info, data in entries:
            if info.filename == "stack.xml":
                xml = data.decode()
                wave = xml.index('name="wave"')
                body = xml.index('name="body', wave)
                start = xml.rindex("<layer", 0, body)
                layer = xml[start:xml.index("/>", body)]
                xml = xml[:start] + re.sub(r'opacity="1"', 'opacity="0.8"', layer) + xml[start + len(layer):]
                data = xml.encode()
            z.writestr(info, data)
    os.replace(os.path.join(work, "pell.ora.tmp"), os.path.join(work, "pell.ora"))
    i = wait_for("swapped in", i)
    changed = sorted(f for f, b in before.items() if open(os.path.join(work, f), "rb").read() != b)
    if changed != ["wave-body.png"]:
        sys.exit(f"FAIL: after pell.ora was saved again, the drawings that changed are {changed}, not wave-body.png")
    wait_for("wrote " + shot, i)
    status = process.wait(timeout=120)
    if status != 0:
        sys.exit(f"FAIL: exit status {status}")
    print("watch: pell.ora saved again was imported again (wave-body.png alone changed) and its re-bake swapped in")
    sys.exit(0)

i = wait_for("watching it and its drawings", -1)
# The smoke session saves into the description (a gesture, an edited pose,
# pose 1's point dragged on the pad): one re-bake with 6 poses.
wait_for('moved pose "stretch" to (0.25, 1) in ' + description + " (baked again)", i)
i = wait_for("saved pose", i)
i = wait_for("swapped in", i)
if "6 poses" not in lines[i]:
    sys.exit(f"FAIL: the re-bake after the save is not the saved rig: {lines[i]}")
saved = open(description).read()
# Written in the description's own key order, points on one line.
if not saved.startswith('{\n  "posemorph": 1,\n  "name": "pip",') or '"point": [0.25, 1.0]' not in saved:
    sys.exit("FAIL: the saved description is not laid out as written, or lacks the moved point:\n" + saved[:400])
# Edit mode's landmarks: a click on the outline's upper right adds a
# landmark to every pose, between the right side's (1) and the top's (2).
i = wait_for("added landmark 2 to every pose in " + description + " (baked again)", i)
i = wait_for("swapped in", i)
saved = open(description).read()
import json
poses = json.loads(saved)["poses"]
counts = [len(p.get("landmarks", [])) for p in poses if "drawing" in p]
if counts != [5] * 5:
    sys.exit(f"FAIL: the drawn poses' landmark counts after the click are {counts}, not 5 each")
# Broken on disk: the re-bake fails naming the file; the last rig stays.
time.sleep(0.3)
with open(description + ".tmp", "w") as f:
    f.write(saved[: len(saved) // 2])
os.replace(description + ".tmp", description)
i = wait_for("the re-bake failed; still showing the last rig", i)
if description not in lines[i]:
    sys.exit(f"FAIL: the failure does not name the description: {lines[i]}")
# Mended: baked and swapped in again.
time.sleep(0.3)
with open(description + ".tmp", "w") as f:
    f.write(saved)
os.replace(description + ".tmp", description)
i = wait_for("swapped in", i)
i = wait_for("wrote " + shot, i)
status = process.wait(timeout=120)
output = "\n".join(l for l in lines if l is not None)
if status != 0 or "validation" in output or not os.path.getsize(shot):
    sys.exit(f"FAIL: exit status {status}, or validation messages, or no shot")
print("watch: 3 re-bakes swapped in (after the window's saves, after a landmark placed by a click, after mending), "
      "1 failure shown; the window stayed open")
