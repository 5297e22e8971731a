#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# The game-art corpus (tests/game-art/): characters from Debian game-data
# packages, fetched here at test time with `apt-get download` (their
# licences are their own, so nothing of them is committed), each baked with
# default settings from the description an animator would write.
#
#   scripts/game-art.py --bake BUILD/bin/posemorph-bake [--cache DIR] [--table FILE.md] [--check]
#
# A character a game draws as parts (Teeworlds' tee) has a recipe beside
# its description: scripts/game_art_compose.py lays out the game's part
# images in its poses first.
#
# Prints one row per character: baked with defaults or not (and the bake's
# first error line), folded in-between triangles, the smallest angle of the
# mesh over all poses, vertices, rig bytes (without its atlas section) against the drawings' PNG bytes,
# ghosting (mean over the pose hull, of 255), the bake's time, and whether
# `posemorph-bake init` on the drawings alone writes a description that
# bakes as written (no landmark placed by hand). --table
# writes the same table as Markdown (docs/game-art.md is made by it).
# --check fails when a character listed as baking in
# tests/game-art/expected.json no longer bakes (or, listed in init_bakes, no
# longer bakes from init's description alone), or a baked rig breaks one of
# its bounds (min angle, no fold, rig/PNG ratio for sprites under 128 px,
# vertices per point of the traced outline, a failure's time). A registry that cannot be reached skips the run with a
# line saying so (exit 77, ctest's skip).
#
# --sheets DIR draws before/after contact sheets of tux-relax and tux-yes
# (or of the characters named): "before" mapped once, as the paper maps
# (posemorph-bake --map-once, folds allowed), "after" as the bake maps with
# its defaults; per character a mesh sheet (SVG) and a textured sheet (PNG)
# each way, and DIR/index.html setting them side by side with each way's
# smallest angle, ghosting and folds. Nothing of the drawings is committed,
# so the docs cannot show these pictures; the corpus test writes them under
# the build's game-art/sheets.
import argparse
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import game_art_compose  # noqa: E402  (beside this script)
ROOT = os.path.dirname(HERE)
CORPUS = os.path.join(ROOT, "tests", "game-art")
SKIP = 77


def fetch(package, cache):
    """The package's files under cache/package, downloaded and unpacked once."""
    target = os.path.join(cache, package)
    done = os.path.join(target, ".unpacked")
    if os.path.exists(done):
        return target
    debs = os.path.join(cache, "debs")
    os.makedirs(debs, exist_ok=True)
    for name in os.listdir(debs):
        if name.startswith(package + "_") and name.endswith(".deb"):
            break
    else:
        r = subprocess.run(["apt-get", "download", package], cwd=debs, capture_output=True, text=True)
        if r.returncode != 0:
            last = (r.stderr.strip().splitlines() or ["no message"])[-1]
            print(f"game-art: skipped: cannot fetch {package} from the Debian registry ({last})")
            sys.exit(SKIP)
        name = next(n for n in os.listdir(debs) if n.startswith(package + "_") and n.endswith(".deb"))
    shutil.rmtree(target, ignore_errors=True)
    subprocess.run(["dpkg-deb", "-x", os.path.join(debs, name), target], check=True)
    open(done, "w").close()
    return target


def number(pattern, text, default=None):
    m = re.search(pattern, text)
    return float(m.group(1)) if m else default


def atlas_section_bytes(path):
    """The rig's texture atlas section (ATLS, runtime/FORMAT.md) with its
    table entry: it ships in place of the drawings' names, so the rig is
    weighed without it against the drawings."""
    data = open(path, "rb").read()
    count = struct.unpack_from("<I", data, 24)[0]
    for k in range(count):
        tag, _, _, size = struct.unpack_from("<4sIQQ", data, 64 + 24 * k)
        if tag == b"ATLS":
            return 24 + (size + 15) // 16 * 16
    return 0


def drawings_folder(character, cache):
    """The folder the character's description names drawings in: the
    unpacked package's, with the poses composed from the game's part images
    first where the character has a recipe (into posemorph-NAME/ there,
    again whenever the recipe changed)."""
    folder = os.path.join(fetch(character["package"], cache), character["folder"])
    if "compose" in character:
        recipe = os.path.join(CORPUS, character["compose"])
        out = os.path.join(folder, "posemorph-" + character["name"])
        stamp = os.path.join(out, ".recipe")
        with open(recipe) as f:
            text = f.read()
        if not os.path.exists(stamp) or open(stamp).read() != text:
            shutil.rmtree(out, ignore_errors=True)
            game_art_compose.compose(recipe, folder, out)
            with open(stamp, "w") as f:
                f.write(text)
    return folder


def baked_figures(out):
    """What a bake that wrote its rig printed: vertices, folded triangles,
    the smallest angle and the ghosting over the pose hull (None when not
    measured)."""
    return {"vertices": int(number(r"(\d+) vertices", out)),
            "folds": int(number(r"(\d+) folded triangles", out, 0)),
            "min_angle": number(r"min angle ([0-9.]+) degrees over all poses", out),
            "ghosting": number(r"ghosting over the pose hull[^\n]*mean ([0-9.]+)", out)}


def bake(binary, character, cache, out_dir):
    """Bakes one character with default settings; returns its row."""
    name = character["name"]
    folder = drawings_folder(character, cache)
    with open(os.path.join(CORPUS, name + ".json")) as f:
        description = json.load(f)
    # The description sits beside the drawings it names (a hidden name, so
    # nothing of the package's is overwritten).
    json_path = os.path.join(folder, f".game-art-{name}.json")
    with open(json_path, "w") as f:
        json.dump(description, f)
    drawings = set()
    for pose in description.get("poses", []):
        if "drawing" in pose:  # a layered character's poses are only points; its parts have the drawings
            drawings.add(pose["drawing"])
    for part in description.get("parts", []):
        for pose in part["poses"]:
            drawings.add(pose["drawing"])
    png_bytes = sum(os.path.getsize(os.path.join(folder, d)) for d in drawings)
    side = 0  # the longest side of any drawing (the PNG header's width and height)
    for d in drawings:
        with open(os.path.join(folder, d), "rb") as f:
            header = f.read(24)
        side = max(side, int.from_bytes(header[16:20], "big"), int.from_bytes(header[20:24], "big"))
    rig = os.path.join(out_dir, name + ".pmrig")
    start = time.monotonic()
    r = subprocess.run([binary, json_path, "-o", rig], capture_output=True, text=True)
    seconds = time.monotonic() - start
    row = {"name": name, "package": character["package"], "traits": character["traits"], "seconds": seconds,
           "png_bytes": png_bytes, "side": side, "baked": r.returncode == 0, "poses": len(description.get("poses", [])),
           "shadow": character.get("shadow", False), "description": json_path}
    out = r.stdout + r.stderr
    if r.returncode != 0:
        # The first line, with the unpacked package's folder left out.
        error = (r.stderr.strip().splitlines() or ["(no message)"])[0]
        row["error"] = error.replace("posemorph-bake: error: ", "").replace(folder + "/", "")
        row["folds"] = number(r"(\d+) triangles? turns? over", r.stderr)
        return row
    row.update(baked_figures(out))
    row["triangles"] = int(number(r"(\d+) triangles", out))
    row["rig_bytes"] = os.path.getsize(rig) - atlas_section_bytes(rig)
    row["outline_pixels"] = number(r"outlines (\d+)", out)
    row["warnings"] = [line for line in r.stderr.splitlines() if line.strip()]
    row["shadows"] = sum(1 for line in row["warnings"] if "is taken as its drop shadow" in line)
    return row


def init_alone(binary, character, cache, out_dir):
    """Whether `posemorph-bake init` on the character's drawings alone (one
    per pose, in the description's order; none placed by hand) writes a
    description that bakes as written: True, False, or None for a layered
    character (parts), which init takes as POSE-PART.png files; and what
    init said."""
    name = character["name"]
    folder = drawings_folder(character, cache)
    with open(os.path.join(CORPUS, name + ".json")) as f:
        description = json.load(f)
    if description.get("parts") or not description.get("poses"):
        return None, ""
    drawings = [os.path.join(folder, p["drawing"]) for p in description["poses"] if "drawing" in p]
    os.makedirs(os.path.join(out_dir, "init"), exist_ok=True)
    r = subprocess.run([binary, "init", *drawings, "-o", os.path.join(out_dir, "init", name + ".json"), "--force"],
                       capture_output=True, text=True)
    return r.returncode == 0 and "it bakes as written" in r.stdout, r.stdout + r.stderr


def alone(r):
    return "-" if r.get("init") is None else ("bakes" if r["init"] else "does not bake")


def table(rows):
    lines = ["| character | package | exercises | baked with defaults | folds | min angle | vertices | "
             "rig (no ATLS) / PNG bytes | ghosting | bake | `init` alone |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        traits = ", ".join(r["traits"])
        if r["baked"]:
            ghost = f"{r['ghosting']:.2f}" if r.get("ghosting") is not None else "-"
            lines.append(f"| {r['name']} | {r['package']} | {traits} | yes | {r['folds']} | "
                         f"{r['min_angle']:.1f} deg | {r['vertices']} | {r['rig_bytes']:,} / {r['png_bytes']:,} "
                         f"({r['rig_bytes'] / r['png_bytes']:.2f}x) | {ghost} | {r['seconds']:.1f} s | {alone(r)} |")
        else:
            error = r["error"].replace("|", "\\|")
            lines.append(f"| {r['name']} | {r['package']} | {traits} | no: {error} | - | - | - | - / "
                         f"{r['png_bytes']:,} | - | {r['seconds']:.1f} s | {alone(r)} |")
    baked = sum(1 for r in rows if r["baked"])
    lines.append("")
    lines.append(f"{baked} of {len(rows)} characters baked with default settings.")
    tried = [r for r in rows if r.get("init") is not None]
    lines.append(f"{sum(1 for r in tried if r['init'])} of {len(tried)} drawn without parts bake from "
                 "`posemorph-bake init` on their drawings alone (no landmark placed by hand).")
    return "\n".join(lines)


def check(rows, expected):
    problems = []
    for r in rows:
        name = r["name"]
        # A known gap holds the character to what it reaches today instead.
        gap = expected.get("known_gaps", {}).get(name, {})
        bound = dict(expected, **gap)
        for key, value in gap.items():
            print(f"game-art: known gap: {name}: {key} {value} (the bound is {expected[key]})")
        # An internal error is a bug whatever the drawings: in the bake, or in
        # init's trial bakes (its lowest points, the starts it suggests).
        for what, said in (("the bake", r.get("error") or ""), ("init", r.get("init_said", ""))):
            if "internal:" in said:
                problems.append(f"{name}: {what} says: " + next(l for l in said.splitlines() if "internal:" in l))
        if name in expected["bakes"] and not r["baked"]:
            problems.append(f"{name}: no longer bakes with default settings: {r['error']}")
        if name in expected.get("init_bakes", []) and r.get("init") is not True:
            problems.append(f"{name}: `posemorph-bake init` on its drawings alone no longer writes a description "
                            "that bakes: " + (r.get("init_said", "").strip().splitlines() or ["(not tried)"])[-1])
        if not r["baked"]:
            if r["seconds"] > expected["max_failure_seconds"]:
                problems.append(f"{name}: the failing bake took {r['seconds']:.1f} s (the bound is "
                                f"{expected['max_failure_seconds']} s)")
            continue
        if r.get("shadow") and r["shadows"] != r["poses"]:
            problems.append(f"{name}: a drop shadow recognised in {r['shadows']} of {r['poses']} poses; every "
                            "pose's drawing has one")
        if r["min_angle"] < bound["min_angle_degrees"]:
            problems.append(f"{name}: min angle {r['min_angle']:.2f} degrees, below "
                            f"{bound['min_angle_degrees']}")
        small = expected["small_sprite_pixels"]
        if r["side"] < small and r["rig_bytes"] > bound["max_rig_to_png"] * r["png_bytes"]:
            problems.append(f"{name}: the rig is {r['rig_bytes']} bytes, over {bound['max_rig_to_png']}x its "
                            f"drawings' {r['png_bytes']} PNG bytes (a sprite under {small} px)")
        if r["folds"] != 0:
            problems.append(f"{name}: {r['folds']} folded triangles in the in-betweens")
        if r.get("outline_pixels") and r["vertices"] > bound["max_vertices_per_outline_point"] * r["outline_pixels"]:
            problems.append(f"{name}: {r['vertices']} mesh vertices, more than "
                            f"{bound['max_vertices_per_outline_point']} per point of the first drawing's traced "
                            f"outline ({int(r['outline_pixels'])})")
    return problems


SHEET_CHARACTERS = ["tux-relax", "tux-yes"]


def sheets(binary, rows, out_dir, sheet_dir, names):
    """Before/after contact sheets (see the top of this file); returns the
    problems found (a bake or sheet that failed)."""
    os.makedirs(sheet_dir, exist_ok=True)
    problems, cells = [], []
    by_name = {r["name"]: r for r in rows}
    for name in names:
        r = by_name.get(name)
        if r is None or not r["baked"]:
            problems.append(f"{name}: no sheets: the character is not in this run or did not bake")
            continue
        json_path = r["description"]
        ways = []
        once = os.path.join(sheet_dir, name + "-once.pmrig")
        for way, extra, rig in (("before", ["--map-once", "--allow-folds"], once),
                                ("after", [], os.path.join(out_dir, name + ".pmrig"))):
            if extra:
                b = subprocess.run([binary, json_path, "-o", rig, "--no-atlas", *extra], capture_output=True, text=True)
                if b.returncode != 0:
                    problems.append(f"{name}: the bake mapped once failed: {b.stderr.strip()}")
                    break
                stats = baked_figures(b.stdout + b.stderr)
            else:
                stats = r
            stem = os.path.join(sheet_dir, f"{name}-{way}")
            for args in (["-o", stem + ".svg"], ["--textured", "--columns", "5", "--rows", "3", "-o", stem + ".png"]):
                s = subprocess.run([binary, "sheet", rig, *args], capture_output=True, text=True)
                if s.returncode != 0:
                    problems.append(f"{name}: the {way} sheet failed: {s.stderr.strip()}")
            ways.append((way, stats))
        cells.append((name, ways))
    html = ["<!doctype html><meta charset=utf-8><title>posemorph game-art contact sheets</title>",
            "<style>body{font-family:sans-serif}img{max-width:48vw;border:1px solid #ccc}td{vertical-align:top}</style>",
            "<h1>Before / after</h1><p>Before: the drawings mapped once, as the paper maps them "
            "(<code>posemorph-bake --map-once --allow-folds</code>). After: the bake's defaults (fold retries, "
            "further refinement, registration where each measures better). Rows: the mesh over the pose space, "
            "then the drawings cross-faded.</p>"]
    for name, ways in cells:
        html.append(f"<h2>{name}</h2><table><tr>")
        for way, st in ways:
            ghosting = "-" if st["ghosting"] is None else f"{st['ghosting']:.2f}"
            html.append(f"<th>{way}: min angle {st['min_angle']:.1f} degrees, {st['vertices']} vertices, "
                        f"ghosting {ghosting}, {st['folds']} folded triangles</th>")
        html.append("</tr><tr>")
        for way, _ in ways:
            html.append(f"<td><img src='{name}-{way}.svg'></td>")
        html.append("</tr><tr>")
        for way, _ in ways:
            html.append(f"<td><img src='{name}-{way}.png'></td>")
        html.append("</tr></table>")
    with open(os.path.join(sheet_dir, "index.html"), "w") as f:
        f.write("\n".join(html) + "\n")
    print(f"game-art: wrote before/after contact sheets of {', '.join(n for n, _ in cells)} to "
          f"{os.path.join(sheet_dir, 'index.html')}")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--bake", required=True)
    ap.add_argument("--cache", default=os.path.join(ROOT, "build", "game-art"))
    ap.add_argument("--table")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--sheets", metavar="DIR")
    ap.add_argument("names", nargs="*")
    args = ap.parse_args()
    with open(os.path.join(CORPUS, "characters.json")) as f:
        characters = json.load(f)["characters"]
    if args.names:
        characters = [c for c in characters if c["name"] in args.names]
    out_dir = os.path.join(args.cache, "rigs")
    os.makedirs(out_dir, exist_ok=True)
    rows = [bake(os.path.abspath(args.bake), c, args.cache, out_dir) for c in characters]
    for r, c in zip(rows, characters):
        r["init"], r["init_said"] = init_alone(os.path.abspath(args.bake), c, args.cache, out_dir)
    text = table(rows)
    print(text)
    for r in rows:
        for w in r.get("warnings", []):
            print(f"{r['name']}: {w}")
    if args.table:
        with open(args.table, "w") as f:
            f.write(text + "\n")
    problems = []
    if args.sheets:
        names = [n for n in SHEET_CHARACTERS if not args.names or n in args.names] or [r["name"] for r in rows]
        problems += sheets(os.path.abspath(args.bake), rows, out_dir, args.sheets, names)
    if args.check:
        with open(os.path.join(CORPUS, "expected.json")) as f:
            expected = json.load(f)
        problems += check(rows, expected)
    for p in problems:
        print("game-art: " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
