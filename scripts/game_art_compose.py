#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Poses of a layered game character from the game's own part images, for
# the game-art corpus (scripts/game-art.py): a game that draws its
# character as parts (Teeworlds' tee: a body, two feet and eyes, each a
# region of the skin's images) ships no drawn poses, only the parts; an
# animator lays them out per pose. A recipe (tests/game-art/NAME.compose.json)
# says how: the canvas, each part's layers (a region of an image, tinted or
# or filled with a colour, laid over each other), and per pose where each part goes (its pivot
# at a canvas point, turned by an angle). This writes one PNG per pose and
# part, POSE-PART.png, on one canvas: the drawings the description names;
# with "flatten", one per pose, POSE.png, the parts laid over each other in
# the recipe's order. A layer may also be an ellipse of one colour at an
# alpha (a shadow the game draws beneath a sprite that has none).
#
#   scripts/game_art_compose.py RECIPE.json SOURCE_FOLDER OUT_FOLDER
#
# Plain Python (zlib for PNG): CMake's Python may not see Debian's Pillow.
import json
import math
import os
import struct
import sys
import zlib


def read_png(path):
    """(width, height, RGBA bytes) of an 8-bit PNG, not interlaced."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, idat, header = 8, bytearray(), None
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
    if header is None:
        raise ValueError(f"{path}: no IHDR")
    width, height, depth, colour, _, _, interlace = header
    channels = {6: 4, 2: 3, 4: 2, 0: 1}.get(colour)
    if depth != 8 or channels is None or interlace != 0:
        raise ValueError(f"{path}: only 8-bit, not interlaced PNGs are read here")
    raw, stride = zlib.decompress(bytes(idat)), width * channels
    rows, previous, at = [], bytearray(stride), 0
    for _ in range(height):
        kind, row = raw[at], bytearray(raw[at + 1:at + 1 + stride])
        at += 1 + stride
        for x in range(stride):
            a = row[x - channels] if x >= channels else 0
            b = previous[x]
            c = previous[x - channels] if x >= channels else 0
            if kind == 1:
                row[x] = (row[x] + a) & 255
            elif kind == 2:
                row[x] = (row[x] + b) & 255
            elif kind == 3:
                row[x] = (row[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[x] = (row[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(row)
        previous = row
    rgba = bytearray()
    for row in rows:
        for x in range(width):
            px = row[x * channels:(x + 1) * channels]
            if channels == 4:
                rgba += px
            elif channels == 3:
                rgba += px + b"\xff"
            elif channels == 2:
                rgba += bytes((px[0], px[0], px[0], px[1]))
            else:
                rgba += bytes((px[0], px[0], px[0], 255))
    return width, height, rgba


def write_png(path, width, height, rgba):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xffffffff)
    raw = b"".join(b"\x00" + bytes(rgba[y * 4 * width:(y + 1) * 4 * width]) for y in range(height))
    with open(path + ".part", "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    os.replace(path + ".part", path)


def part_image(part, source, cache):
    """The part's layers laid over each other, premultiplied floats:
    (width, height, [r, g, b, a] per pixel)."""
    w, h = part["size"]
    out = [[0.0, 0.0, 0.0, 0.0] for _ in range(w * h)]
    for layer in part["layers"]:
        if "ellipse" in layer:
            # A shape the game draws itself (a cast shadow): that colour at
            # `alpha`, its edge anti-aliased over about a pixel.
            cx, cy, rx, ry = layer["ellipse"]
            for y in range(h):
                for x in range(w):
                    r = math.hypot((x + 0.5 - cx) / rx, (y + 0.5 - cy) / ry)
                    a = layer["alpha"] * max(0.0, min(1.0, (1 - r) * min(rx, ry) + 0.5))
                    if a > 0:
                        d = out[y * w + x]
                        for k in range(3):
                            d[k] = layer["fill"][k] * a + d[k] * (1 - a)
                        d[3] = a + d[3] * (1 - a)
            continue
        name = layer["image"]
        if name not in cache:
            cache[name] = read_png(os.path.join(source, name))
        iw, _, px = cache[name]
        x0, y0 = layer["from"]
        tint = layer.get("tint", [1, 1, 1])
        for y in range(h):
            for x in range(w):
                i = 4 * ((y0 + y) * iw + x0 + x)
                a = px[i + 3] / 255
                if a == 0:
                    continue
                # "fill": that colour at the image's alpha (a silhouette the
                # game colours); "tint": its colour times the tint.
                colour = layer["fill"] if "fill" in layer else [px[i + k] / 255 * tint[k] for k in range(3)]
                d = out[y * w + x]
                for k in range(3):
                    d[k] = colour[k] * a + d[k] * (1 - a)
                d[3] = a + d[3] * (1 - a)
    return w, h, out


def place(canvas, size, image, pivot, at, degrees):
    """The image, its pivot at canvas point `at`, turned by `degrees`
    (counter-clockwise as seen), sampled bilinearly; the canvas's pixels."""
    cw, ch = size
    w, h, px = image
    t = math.radians(degrees)
    c, s = math.cos(t), math.sin(t)
    reach = math.hypot(max(pivot[0], w - pivot[0]), max(pivot[1], h - pivot[1])) + 2
    for y in range(max(0, int(at[1] - reach)), min(ch, int(at[1] + reach) + 1)):
        for x in range(max(0, int(at[0] - reach)), min(cw, int(at[0] + reach) + 1)):
            dx, dy = x + 0.5 - at[0], y + 0.5 - at[1]
            # Turned counter-clockwise on screen (y down): undo it.
            u = c * dx - s * dy + pivot[0] - 0.5
            v = s * dx + c * dy + pivot[1] - 0.5
            i, j = math.floor(u), math.floor(v)
            fu, fv = u - i, v - j
            sample = [0.0, 0.0, 0.0, 0.0]
            for (ii, jj, wt) in ((i, j, (1 - fu) * (1 - fv)), (i + 1, j, fu * (1 - fv)), (i, j + 1, (1 - fu) * fv),
                                 (i + 1, j + 1, fu * fv)):
                if 0 <= ii < w and 0 <= jj < h and wt > 0:
                    p = px[jj * w + ii]
                    for k in range(4):
                        sample[k] += wt * p[k]
            canvas[y * cw + x] = sample


def compose(recipe_path, source, out):
    with open(recipe_path) as f:
        recipe = json.load(f)
    size = recipe["canvas"]
    cache = {}
    images = {name: part_image(part, source, cache) for name, part in recipe["parts"].items()}
    os.makedirs(out, exist_ok=True)
    written = []
    flatten = recipe.get("flatten", False)

    def write(canvas, path):
        rgba = bytearray()
        for r, g, b, a in canvas:  # back to straight alpha
            a8 = max(0, min(255, round(a * 255)))
            rgba += bytes([max(0, min(255, round(v / a * 255))) if a > 0 else 0 for v in (r, g, b)] + [a8])
        write_png(path, size[0], size[1], rgba)
        written.append(path)

    for pose, parts in recipe["poses"].items():
        flat = [[0.0, 0.0, 0.0, 0.0] for _ in range(size[0] * size[1])]
        for name, where in parts.items():
            image = images[where.get("image", name)]
            canvas = [[0.0, 0.0, 0.0, 0.0] for _ in range(size[0] * size[1])]
            pivot = recipe["parts"][where.get("image", name)]["pivot"]
            place(canvas, size, image, pivot, where["at"], where.get("angle", 0))
            if not flatten:
                write(canvas, os.path.join(out, f"{pose}-{name}.png"))
                continue
            for d, c in zip(flat, canvas):  # over what the parts before drew (premultiplied)
                for k in range(4):
                    d[k] = c[k] + d[k] * (1 - c[3])
        if flatten:
            write(flat, os.path.join(out, f"{pose}.png"))
    return written


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: game_art_compose.py RECIPE.json SOURCE_FOLDER OUT_FOLDER")
    for p in compose(*sys.argv[1:]):
        print(p)
