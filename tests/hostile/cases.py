# SPDX-License-Identifier: MIT
"""The hostile-input corpus: files, sizes, numbers, geometry, drawings, SVG,
paths and options given to posemorph-bake and posemorph-view. Each case makes
its own files in an empty folder ({w} in arguments and names), runs one
command, and says what must come out (replay.py checks it)."""
import json
import os
import struct
import subprocess
import zlib


class Case:
    def __init__(self, name, tool, args, status, message, files=None, names=(), writes=(), setup=None, one_line=True):
        self.one_line = one_line
        self.name, self.tool, self.args, self.status, self.message = name, tool, args, status, message
        self.files, self.names, self.writes, self.extra = files or {}, names, writes, setup

    def setup(self, folder):
        for rel, content in self.files.items():
            path = os.path.join(folder, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            if callable(content):
                content(path)
            else:
                with open(path, 'wb') as f:
                    f.write(content.encode() if isinstance(content, str) else content)
        if self.extra:
            self.extra(folder)


# --- makers -----------------------------------------------------------------

def png(width, height, alpha=None, idat=None, color_type=6, bit_depth=8, chunks=()):
    """A PNG; alpha(x, y) -> 0..255 for RGBA, or raw IDAT bytes."""
    def chunk(tag, data):
        return struct.pack('>I', len(data)) + tag + data + struct.pack('>I', zlib.crc32(tag + data) & 0xffffffff)
    if idat is None:
        rows = bytearray()
        for y in range(height):
            rows.append(0)
            for x in range(width):
                a = alpha(x, y)
                rows += bytes((200, 120, 40, a))
        idat = zlib.compress(bytes(rows), 6)
    out = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, bit_depth, color_type, 0, 0, 0))
    for tag, data in chunks:
        out += chunk(tag, data)
    return out + chunk(b'IDAT', idat) + chunk(b'IEND', b'')


def square_png(size, margin):
    """An RGBA PNG of size x size with an opaque square inset by margin, written row by row."""
    row_in = b'\x00' + b'\x00\x00\x00\x00' * margin + b'\xc8\x78\x28\xff' * (size - 2 * margin) + b'\x00\x00\x00\x00' * margin
    row_out = b'\x00' + b'\x00\x00\x00\x00' * size
    z = zlib.compressobj(6)
    data = b''.join(z.compress(row_in if margin <= y < size - margin else row_out) for y in range(size)) + z.flush()
    return png(size, size, idat=data)


def comb_png(size, pitch):
    """A comb: a bar along the bottom with teeth `pitch` pixels apart, each a pixel narrower than the gap."""
    tooth = (b'\xc8\x78\x28\xff' * (pitch - 1) + b'\x00\x00\x00\x00') * (size // pitch)
    tooth = tooth[:size * 4].ljust(size * 4, b'\x00')
    bar = b'\xc8\x78\x28\xff' * size
    z = zlib.compressobj(6)
    data = b''.join(z.compress(b'\x00' + (bar if y >= size - 16 else tooth if y >= 8 else b'\x00' * (4 * size)))
                    for y in range(size)) + z.flush()
    return png(size, size, idat=data)


def star_png(size, spikes, inner):
    """An RGBA PNG of a star with `spikes` points (inner radius `inner` of the outer), written row by row."""
    import math
    c, r = size / 2, size * 0.45
    z = zlib.compressobj(6)
    out = []
    for y in range(size):
        row = bytearray(1 + 4 * size)
        dy = y + 0.5 - c
        for x in range(size):
            dx = x + 0.5 - c
            d = math.hypot(dx, dy)
            if d > r:
                continue
            t = (math.atan2(dy, dx) * spikes / (2 * math.pi)) % 1.0
            if d <= r * (inner + (1 - inner) * (1 - 2 * abs(t - 0.5))):
                row[1 + 4 * x:5 + 4 * x] = b'\xc8\x78\x28\xff'
        out.append(z.compress(bytes(row)))
    return png(size, size, idat=b''.join(out) + z.flush())


def spiral(n):
    """A thick square spiral outline of about n points (a long corridor that winds inward)."""
    import math
    pts_out, pts_in = [], []
    for k in range(n // 2):
        t = 40 * math.pi * k / (n // 2)
        r = 10 + 3 * t
        pts_out.append([round(r * math.cos(t) * 10) / 10, round(r * math.sin(t) * 10) / 10])
        pts_in.append([round((r - 4) * math.cos(t) * 10) / 10, round((r - 4) * math.sin(t) * 10) / 10])
    return pts_out + pts_in[::-1]


def disc(cx, cy, r):
    return lambda x, y: 255 if (x - cx) ** 2 + (y - cy) ** 2 <= r * r else 0


def ellipse(cx, cy, rx, ry):
    return lambda x, y: 255 if ((x - cx) / rx) ** 2 + ((y - cy) / ry) ** 2 <= 1 else 0


def description(poses, **extra):
    d = {'posemorph': 1, 'poses': poses}
    d.update(extra)
    return json.dumps(d)


TRIANGLE = [[0, 1, 2]]


def vertex_rig(a=((0, 0), (1, 0), (0, 1)), b=((0, 0), (1, 0), (0, 1.5)), pa=(0, 0), pb=(1, 0), triangles=TRIANGLE,
               **extra):
    return description([{'name': 'a', 'point': list(pa), 'vertices': [list(v) for v in a]},
                        {'name': 'b', 'point': list(pb), 'vertices': [list(v) for v in b]}],
                       triangles=triangles, **extra)


def drawn_rig(drawings=('a.png', 'b.png'), landmarks=([[32, 12]], [[32, 8]]), points=((0, 0), (1, 0)), **extra):
    return description([{'name': 'p%d' % i, 'point': list(points[i]), 'drawing': drawings[i],
                         'landmarks': landmarks[i]} for i in range(len(drawings))], **extra)


def outline_rig(outline_a, outline_b=None, landmarks=None, **extra):
    outline_b = outline_b or outline_a
    la, lb = landmarks or ([outline_a[0]], [outline_b[0]])
    return description([{'name': 'a', 'point': [0, 0], 'outline': outline_a, 'landmarks': la},
                        {'name': 'b', 'point': [1, 0], 'outline': outline_b, 'landmarks': lb}], **extra)


def svg(body, size=64):
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d">%s</svg>'
            % (size, size, size, size, body))


def fifo(path):
    os.mkfifo(path)


def sparse(size):
    def make(path):
        with open(path, 'wb') as f:
            f.truncate(size)
    return make


def symlink_to(target):
    return lambda path: os.symlink(target, path)


def copy_of(name):
    def make(path):
        with open(os.path.join(PREPARED, name), 'rb') as f, open(path, 'wb') as g:
            g.write(f.read())
    return make


PREPARED = None
DISC_A = DISC_B = None


def prepare(work, tools):
    """Files shared by several cases: two small drawings and a baked rig."""
    global PREPARED, DISC_A, DISC_B
    PREPARED = os.path.join(work, '.prepared')
    os.makedirs(PREPARED)
    DISC_A = png(64, 64, disc(32, 36, 24))
    DISC_B = png(64, 64, ellipse(32, 36, 18, 28))
    for name, data in (('a.png', DISC_A), ('b.png', DISC_B)):
        with open(os.path.join(PREPARED, name), 'wb') as f:
            f.write(data)
    with open(os.path.join(PREPARED, 'rig.json'), 'w') as f:
        f.write(drawn_rig())
    # rig.pmrig without an atlas (the viewer's cases read its drawings);
    # atlas.pmrig with one (atlas.page0.png beside it).
    subprocess.run([tools['bake'], os.path.join(PREPARED, 'rig.json'), '-o', os.path.join(PREPARED, 'rig.pmrig'),
                    '--no-atlas'], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([tools['bake'], os.path.join(PREPARED, 'rig.json'), '-o', os.path.join(PREPARED, 'atlas.pmrig')],
                   check=True, stdout=subprocess.DEVNULL)
    rig = open(os.path.join(PREPARED, 'rig.pmrig'), 'rb').read()
    with open(os.path.join(PREPARED, 'truncated.pmrig'), 'wb') as f:
        f.write(rig[:len(rig) // 2])
    escape = json.loads(drawn_rig())
    escape['poses'][0]['image'] = '../../etc/passwd'
    with open(os.path.join(PREPARED, 'escape.json'), 'w') as f:
        json.dump(escape, f)
    subprocess.run([tools['bake'], os.path.join(PREPARED, 'escape.json'), '-o', os.path.join(PREPARED, 'escape.pmrig')],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def drawings():
    return {'a.png': copy_of('a.png'), 'b.png': copy_of('b.png')}


def with_drawings(**files):
    d = drawings()
    d.update(files)
    return d


B = 'bake'
V = 'view'
OUT = ['-o', '{w}/out.pmrig']
RIG = '{w}/rig.json'
SQUARE = [[0, 0], [40, 0], [40, 40], [0, 40]]

CASES = [
    # --- files ---------------------------------------------------------------
    Case('description-missing', B, [RIG] + OUT, 1, r'rig\.json: .*(no such file|cannot open|does not exist)', names=[RIG]),
    Case('description-is-dev-zero', B, ['/dev/zero'] + OUT, 1, r'/dev/zero: is not a regular file'),
    Case('description-is-fifo', B, [RIG] + OUT, 1, r'rig\.json: is not a regular file', {'rig.json': fifo}, [RIG]),
    Case('description-is-folder', B, ['{w}/dir'] + OUT, 1, r'dir: is not a regular file', {'dir/x': ''}),
    Case('description-65-mib', B, [RIG] + OUT, 1, r'rig\.json: is 68157440 bytes, more than the limit of 67108864',
         {'rig.json': sparse(65 << 20)}, [RIG]),
    Case('description-empty', B, [RIG] + OUT, 1, r'rig\.json: .*JSON', {'rig.json': ''}, [RIG]),
    Case('description-not-json', B, [RIG] + OUT, 1, r'rig\.json: .*JSON', {'rig.json': '{"posemorph": 1,'}, [RIG]),
    Case('description-nul-bytes', B, [RIG] + OUT, 1, r'rig\.json: .*JSON', {'rig.json': b'\0' * 4096}, [RIG]),
    Case('description-array', B, [RIG] + OUT, 1, r'rig\.json: .*object', {'rig.json': '[1, 2, 3]'}, [RIG]),
    Case('description-nested-200000', B, [RIG] + OUT, 1, r'rig\.json: ', {'rig.json': '[' * 200000 + ']' * 200000}, [RIG]),
    Case('description-version-2', B, [RIG] + OUT, 1, r'rig\.json: .*posemorph', {'rig.json': '{"posemorph": 2, "poses": []}'}, [RIG]),
    Case('mesh-file-is-dev-zero', B, [RIG] + OUT, 1, r'/dev/zero: is not a regular file',
         {'rig.json': description([{'name': 'a', 'point': [0, 0], 'mesh': '/dev/zero'},
                                   {'name': 'b', 'point': [1, 0], 'mesh': '/dev/zero'}])}, [RIG]),
    Case('mesh-file-is-fifo', B, [RIG] + OUT, 1, r'm\.json: is not a regular file',
         {'rig.json': description([{'name': 'a', 'point': [0, 0], 'mesh': 'm.json'},
                                   {'name': 'b', 'point': [1, 0], 'mesh': 'm.json'}]), 'm.json': fifo}, ['m.json']),
    Case('mesh-file-missing', B, [RIG] + OUT, 1, r'm\.json',
         {'rig.json': description([{'name': 'a', 'point': [0, 0], 'mesh': 'm.json'},
                                   {'name': 'b', 'point': [1, 0], 'mesh': 'm.json'}])}, [RIG]),
    Case('drawing-missing', B, [RIG] + OUT, 1, r'a\.png', {'rig.json': drawn_rig()}, [RIG]),
    Case('drawing-is-folder', B, [RIG] + OUT, 1, r'a\.png.*not a regular file',
         {'rig.json': drawn_rig(), 'a.png/x': '', 'b.png': copy_of('b.png')}, [RIG]),
    Case('drawing-is-dev-zero', B, [RIG] + OUT, 1, r'zero\.png: is not a regular file',
         {'rig.json': drawn_rig(drawings=('zero.png', 'b.png')), 'zero.png': symlink_to('/dev/zero'), 'b.png': copy_of('b.png')},
         [RIG]),
    Case('drawing-wrong-extension', B, [RIG] + OUT, 1, r"neither \.png, \.svg nor a layered file",
         {'rig.json': drawn_rig(drawings=('a.gif', 'b.png'))}, [RIG]),
    # --- outputs -------------------------------------------------------------
    Case('output-is-input', B, [RIG, '-o', RIG], 1, r'is the input .*refusing to overwrite it', {'rig.json': vertex_rig()}, [RIG]),
    Case('output-is-folder', B, [RIG, '-o', '{w}/dir'], 1, r'dir: .*(folder|directory)',
         {'rig.json': vertex_rig(), 'dir/x': ''}),
    Case('output-is-device', B, [RIG, '-o', '/dev/null'], 1, r'/dev/null: .*not a regular file', {'rig.json': vertex_rig()}),
    Case('output-is-symlink', B, [RIG, '-o', '{w}/link.pmrig'], 1, r'link\.pmrig: exists and is not a regular file .*link.*refusing to replace it',
         {'rig.json': vertex_rig(), 'target.pmrig': 'keep', 'link.pmrig': symlink_to('target.pmrig')}),
    Case('output-is-fifo', B, [RIG, '-o', '{w}/out.pmrig'], 1, r'out\.pmrig: .*not a regular file',
         {'rig.json': vertex_rig(), 'out.pmrig': fifo}),
    Case('output-folder-missing', B, [RIG, '-o', '{w}/no/out.pmrig'], 1, r'no/out\.pmrig', {'rig.json': vertex_rig()}),
    Case('output-kept-on-failure', B, [RIG] + OUT, 1, r'triangle 0 is flipped',
         {'rig.json': vertex_rig(b=((0, 0), (1, 0), (0, -1))), 'out.pmrig': 'previous rig'}, [RIG]),
    # --- options -------------------------------------------------------------
    Case('no-arguments', B, [], 2, r'usage', one_line=False),
    Case('unknown-option', B, [RIG, '--frobnicate'] + OUT, 2, r'--frobnicate', {'rig.json': vertex_rig()}),
    Case('precision-half', B, [RIG, '--precision', 'half'] + OUT, 2, r'--precision must be compact or exact', {'rig.json': vertex_rig()}),
    Case('max-error-text', B, [RIG, '--max-error', 'abc'] + OUT, 2, r'--max-error', {'rig.json': vertex_rig()}),
    Case('max-error-zero', B, [RIG, '--max-error', '0'] + OUT, 2, r'--max-error', {'rig.json': vertex_rig()}),
    Case('max-error-nan', B, [RIG, '--max-error', 'nan'] + OUT, 2, r'--max-error', {'rig.json': vertex_rig()}),
    Case('output-option-missing-value', B, [RIG, '-o'], 2, r'-o|usage', {'rig.json': vertex_rig()}),
    # --- numbers -------------------------------------------------------------
    Case('points-1e308-apart', B, [RIG] + OUT, 1, r'pose .*point', {'rig.json': vertex_rig(pb=(1e308, 0))}, [RIG]),
    Case('points-5e-324-apart', B, [RIG] + OUT, 1, r'point', {'rig.json': vertex_rig(pb=(5e-324, 0))}, [RIG]),
    Case('points-coincide', B, [RIG] + OUT, 1, r'point', {'rig.json': vertex_rig(pb=(0, 0))}, [RIG]),
    Case('point-overflows-double', B, [RIG] + OUT, 1, r'rig\.json: ', {'rig.json': vertex_rig().replace('[1, 0]', '[1e999, 0]', 1)}, [RIG]),
    Case('point-is-string', B, [RIG] + OUT, 1, r'point', {'rig.json': vertex_rig().replace('"point": [1, 0]', '"point": "far"')}, [RIG]),
    Case('grid-resolution-100000', B, [RIG] + OUT, 1, r'grid_resolution', {'rig.json': vertex_rig(bake={'grid_resolution': 100000})}, [RIG]),
    Case('grid-resolution-negative', B, [RIG] + OUT, 1, r'grid_resolution', {'rig.json': vertex_rig(bake={'grid_resolution': -1})}, [RIG]),
    Case('grid-resolution-fraction', B, [RIG] + OUT, 1, r'grid_resolution', {'rig.json': vertex_rig(bake={'grid_resolution': 1.5})}, [RIG]),
    Case('sigma-negative', B, [RIG] + OUT, 1, r'sigma', {'rig.json': vertex_rig(bake={'sigma': -2})}, [RIG]),
    Case('max-error-in-file-zero', B, [RIG] + OUT, 1, r'bake\.max_error', {'rig.json': vertex_rig(bake={'max_error': 0})}, [RIG]),
    Case('spacing-1e-6', B, [RIG] + OUT, 0, r'', with_drawings(**{'rig.json': drawn_rig(mapping={'spacing': 1e-6})}),
         writes=['out.pmrig']),
    Case('spacing-negative', B, [RIG] + OUT, 1, r'spacing', with_drawings(**{'rig.json': drawn_rig(mapping={'spacing': -1})}), [RIG]),
    Case('max-edge-length-tiny', B, [RIG] + OUT, 1, r'max_edge_length|vertices',
         {'rig.json': outline_rig(SQUARE, mapping={'max_edge_length': 0.05})}, [RIG]),
    Case('max-vertices-too-many', B, [RIG] + OUT, 1, r'mapping\.max_vertices: expected an integer in 16\.\.100000',
         {'rig.json': outline_rig(SQUARE, mapping={'max_vertices': 10 ** 9})}, [RIG]),
    Case('max-edge-length-1e-300', B, [RIG] + OUT, 1, r'max_edge_length',
         {'rig.json': outline_rig(SQUARE, mapping={'max_edge_length': 1e-300})}, [RIG]),
    Case('steiner-points-huge', B, [RIG] + OUT, 1, r'max_steiner_points',
         {'rig.json': outline_rig(SQUARE, mapping={'max_steiner_points': 1 << 40})}, [RIG]),
    # --- geometry ------------------------------------------------------------
    Case('one-pose', B, [RIG] + OUT, 1, r'pose', {'rig.json': description(
        [{'name': 'a', 'point': [0, 0], 'vertices': [[0, 0], [1, 0], [0, 1]]}], triangles=TRIANGLE)}, [RIG]),
    Case('triangle-index-out-of-range', B, [RIG] + OUT, 1, r'triangle 0', {'rig.json': vertex_rig(triangles=[[0, 1, 7]])}, [RIG]),
    Case('triangle-repeats-vertex', B, [RIG] + OUT, 1, r'triangle 0', {'rig.json': vertex_rig(triangles=[[0, 1, 1]])}, [RIG]),
    Case('triangle-flipped', B, [RIG] + OUT, 1, r"pose 'b' \(index 1\): triangle 0 is flipped",
         {'rig.json': vertex_rig(b=((0, 0), (1, 0), (0, -1)))}, [RIG]),
    Case('triangle-degenerate', B, [RIG] + OUT, 1, r'triangle 0', {'rig.json': vertex_rig(a=((0, 0), (1, 0), (2, 0)))}, [RIG]),
    Case('vertex-counts-differ', B, [RIG] + OUT, 1, r'vertices', {'rig.json': vertex_rig(b=((0, 0), (1, 0), (0, 1), (1, 1)))}, [RIG]),
    Case('vertex-1e308', B, [RIG] + OUT, 1, r'rig\.json: ', {'rig.json': vertex_rig(b=((0, 0), (1e308, 0), (0, 1e308)))}, [RIG]),
    Case('non-manifold-edge', B, [RIG] + OUT, 1, r'edge', {'rig.json': description(
        [{'name': n, 'point': p, 'vertices': [[0, 0], [1, 0], [0.5, 1], [0.5, 2], [0.5, 3]]} for n, p in (('a', [0, 0]), ('b', [1, 0]))],
        triangles=[[0, 1, 2], [0, 1, 3], [0, 1, 4]])}, [RIG]),
    Case('outline-bow-tie', B, [RIG] + OUT, 1, r'crosses or touches itself',
         {'rig.json': outline_rig([[0, 0], [10, 10], [10, 0], [0, 10]])}, [RIG]),
    Case('outline-two-points', B, [RIG] + OUT, 1, r'outline: needs at least 3 points', {'rig.json': outline_rig([[0, 0], [10, 10]])}, [RIG]),
    Case('outline-1e308', B, [RIG] + OUT, 1, r'outline|coordinate', {'rig.json': outline_rig([[0, 0], [1e308, 0], [0, 1e308]])}, [RIG]),
    Case('outline-10000-units', B, [RIG] + OUT, 0, r'', {'rig.json': outline_rig([[0, 0], [10000, 0], [10000, 10000], [0, 10000]])},
         writes=['out.pmrig']),
    Case('outline-300000-vertices', B, [RIG] + OUT, 1, r'outline', {'rig.json': outline_rig(
        [[1000 * __import__('math').cos(6.283185307 * k / 300000), 1000 * __import__('math').sin(6.283185307 * k / 300000)]
         for k in range(300000)])}, [RIG]),
    Case('outline-spiral-20000', B, [RIG] + OUT, 0, r'matched at a spacing of',
         {'rig.json': lambda p: open(p, 'w').write(outline_rig(spiral(20000)))}, writes=['out.pmrig']),
    # Traced at alpha 0.5 (the default is 0.05 since the fringe is meshed): at
    # 0.05 the anti-aliased spike tips at the matching's capped spacing leave
    # no enclosing polygon, which the 300-spike case below covers.
    Case('png-star-1024-60-spikes', B, [RIG] + OUT, 0, r'matched at a spacing of', {'rig.json': drawn_rig(landmarks=([[972, 512]], [[972, 512]]), mapping={'alpha_threshold': 0.5, 'working_size': 0}),
         'a.png': lambda p: open(p, 'wb').write(star_png(1024, 60, 0.6)), 'b.png': lambda p: open(p, 'wb').write(star_png(1024, 60, 0.5))},
         writes=['out.pmrig']),
    # The limits below are met at full resolution (mapping.working_size 0);
    # by default such drawings are traced on a 256-pixel level and bake.
    Case('png-star-1024-300-spikes', B, [RIG] + OUT, 1, r'cannot build a polygon enclosing the outline .*8192 samples',
         {'rig.json': drawn_rig(landmarks=([[972, 512]], [[972, 512]]), mapping={'working_size': 0}),
          'a.png': lambda p: open(p, 'wb').write(star_png(1024, 300, 0.8)), 'b.png': lambda p: open(p, 'wb').write(star_png(1024, 300, 0.7))},
         [RIG]),
    Case('png-comb-4096', B, [RIG] + OUT, 1, r"a\.png: the shape's border crosses more than 1000000 pixel edges",
         {'rig.json': drawn_rig(landmarks=([[8, 4090]], [[8, 4090]]), mapping={'working_size': 0}),
          'a.png': lambda p: open(p, 'wb').write(comb_png(4096, 4)), 'b.png': lambda p: open(p, 'wb').write(comb_png(4096, 6))},
         [RIG]),
    Case('png-comb-512', B, [RIG] + OUT, 1, r"a\.png.*the outline has [0-9]+ points, more than the limit of 100000",
         {'rig.json': drawn_rig(landmarks=([[8, 506]], [[8, 506]]), mapping={'working_size': 0}),
          'a.png': lambda p: open(p, 'wb').write(comb_png(512, 2)), 'b.png': lambda p: open(p, 'wb').write(comb_png(512, 3))},
         [RIG]),
    Case('png-comb-4096-working-level', B, [RIG] + OUT, 0, r'baked .*vertices',
         {'rig.json': drawn_rig(landmarks=([[8, 4090]], [[8, 4090]])),
          'a.png': lambda p: open(p, 'wb').write(comb_png(4096, 4)), 'b.png': lambda p: open(p, 'wb').write(comb_png(4096, 6))},
         writes=['out.pmrig']),
    Case('landmark-counts-differ', B, [RIG] + OUT, 1, r'landmark', {'rig.json': outline_rig(
        SQUARE, landmarks=([[0, 0], [40, 40]], [[0, 0]]))}, [RIG]),
    Case('landmark-far-away', B, [RIG] + OUT, 1, r'landmark 0 is', {'rig.json': outline_rig(
        SQUARE, landmarks=([[500, 500]], [[0, 0]]))}, [RIG]),
    Case('landmarks-out-of-order', B, [RIG] + OUT, 1, r'out of order', {'rig.json': outline_rig(
        SQUARE, landmarks=([[0, 0], [40, 0], [40, 40]], [[0, 0], [40, 40], [40, 0]]))}, [RIG]),
    Case('landmarks-5000', B, [RIG] + OUT, 1, r'landmark', {'rig.json': outline_rig(
        [[0, 0], [5000, 0], [5000, 1], [0, 1]], landmarks=([[k, 0] for k in range(5000)], [[k, 0] for k in range(5000)]))}, [RIG]),
    Case('pose-name-900-kb', B, [RIG] + OUT, 1, r'\.\.\.', {'rig.json': vertex_rig(b=((0, 0), (1, 0), (0, -1))).replace(
        '"name": "b"', '"name": "%s"' % ('x' * 900000))}, [RIG]),
    Case('pose-name-escapes', B, [RIG] + OUT, 1, r'\\x1b\[31m', {'rig.json': vertex_rig(b=((0, 0), (1, 0), (0, -1))).replace(
        '"name": "b"', '"name": "\\u001b[31mred"')}, [RIG]),
    Case('pose-names-duplicate', B, [RIG] + OUT, 1, r'name', {'rig.json': vertex_rig().replace('"name": "b"', '"name": "a"')}, [RIG]),
    Case('path-unknown-pose-key', B, [RIG] + OUT, 1, r'path', {'rig.json': vertex_rig(paths=[{'name': 'p', 'keys': [[0, 'x', 0]]}])}, [RIG]),
    Case('path-time-backwards', B, [RIG] + OUT, 1, r'path', {'rig.json': vertex_rig(paths=[{'name': 'p', 'keys': [[1, 0, 0], [0, 1, 0]]}])}, [RIG]),
    Case('path-1-million-keys', B, [RIG] + OUT, 0, r'', {'rig.json': lambda p: open(p, 'w').write(vertex_rig().rstrip('}') +
         ', "paths": [{"name": "p", "keys": [' + ','.join('[%d,0,0]' % k for k in range(1000000)) + ']}]}')}, writes=['out.pmrig']),
    # --- drawings --------------------------------------------------------------
    Case('png-truncated', B, [RIG] + OUT, 1, r'a\.png', with_drawings(**{'rig.json': drawn_rig(), 'a.png': lambda p: open(p, 'wb').write(png(64, 64, disc(32, 36, 24))[:60])}), [RIG]),
    Case('png-not-a-png', B, [RIG] + OUT, 1, r'a\.png', with_drawings(**{'rig.json': drawn_rig(), 'a.png': 'GIF89a not a png'}), [RIG]),
    Case('png-8192x2049-header', B, [RIG] + OUT, 1, r'a\.png.*16777216', with_drawings(**{'rig.json': drawn_rig(), 'a.png': lambda p: open(p, 'wb').write(png(8192, 2049, idat=zlib.compress(b'\0' * 1000)))}), [RIG]),
    Case('png-16384-squared-bomb', B, [RIG] + OUT, 1, r'a\.png.*16777216', with_drawings(**{'rig.json': drawn_rig(), 'a.png': lambda p: open(p, 'wb').write(png(16384, 16384, idat=zlib.compress(b'\0' * (1 << 20))))}), [RIG]),
    Case('png-transparent', B, [RIG] + OUT, 1, r'a\.png', with_drawings(**{'rig.json': drawn_rig(), 'a.png': lambda p: open(p, 'wb').write(png(32, 32, lambda x, y: 0))}), [RIG]),
    Case('png-without-alpha', B, [RIG] + OUT, 1, r'a\.png: has no alpha channel', with_drawings(**{'rig.json': drawn_rig(),
         'a.png': lambda p: open(p, 'wb').write(png(8, 8, idat=zlib.compress(b''.join(b'\0' + b'\x80' * 24 for _ in range(8))), color_type=2))}),
         [RIG]),
    Case('png-crc-wrong', B, [RIG] + OUT, 1, r'a\.png', with_drawings(**{'rig.json': drawn_rig(), 'a.png': lambda p: open(p, 'wb').write(png(64, 64, disc(32, 36, 24))[:29] + b'\0\0\0\0' + png(64, 64, disc(32, 36, 24))[33:])}), [RIG]),
    Case('png-4000-square-in-4096', B, [RIG] + OUT, 0, r'', {'rig.json': drawn_rig(landmarks=([[48, 48]], [[48, 48]])),
         'a.png': lambda p: open(p, 'wb').write(square_png(4096, 48)), 'b.png': lambda p: open(p, 'wb').write(square_png(4096, 60))},
         writes=['out.pmrig']),
    Case('svg-not-xml', B, [RIG] + OUT, 1, r'a\.svg', {'rig.json': drawn_rig(drawings=('a.svg', 'a.svg')), 'a.svg': '<svg'}, [RIG]),
    Case('svg-no-path', B, [RIG] + OUT, 1, r'a\.svg', {'rig.json': drawn_rig(drawings=('a.svg', 'a.svg')), 'a.svg': svg('')}, [RIG]),
    Case('svg-1000000-segments', B, [RIG] + OUT, 1, r'a\.svg', {'rig.json': drawn_rig(drawings=('a.svg', 'a.svg')), 'a.svg': svg(
        '<path d="M 10 10 ' + 'l 0.01 0.01 l 0.01 -0.01 ' * 500000 + 'L 50 10 Z"/>')}, [RIG]),
    Case('svg-curves-too-fine', B, [RIG] + OUT, 1, r'a\.svg: the path flattens to more than 100000 outline points',
         {'rig.json': drawn_rig(drawings=('a.svg', 'a.svg'), mapping={'curve_tolerance': 1e-6}), 'a.svg': svg(
             '<path d="M 10 10 ' + 'C 1e6 0 0 1e6 10 10 ' * 4 + 'L 50 10 Z"/>')}, [RIG]),
    Case('svg-number-1e400', B, [RIG] + OUT, 1, r'a\.svg', {'rig.json': drawn_rig(drawings=('a.svg', 'a.svg')), 'a.svg': svg(
        '<path d="M 10 10 L 1e400 10 L 10 50 Z"/>')}, [RIG]),
    Case('svg-bad-path-data', B, [RIG] + OUT, 1, r'a\.svg', {'rig.json': drawn_rig(drawings=('a.svg', 'a.svg')), 'a.svg': svg(
        '<path d="M 10 10 Q"/>')}, [RIG]),
    Case('svg-viewbox-zero', B, [RIG] + OUT, 1, r'a\.svg', {'rig.json': drawn_rig(drawings=('a.svg', 'a.svg')), 'a.svg':
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 0 0"><path d="M 10 10 L 50 10 L 10 50 Z"/></svg>'}, [RIG]),
    Case('svg-entity-expansion', B, [RIG] + OUT, 1, r'a\.svg', {'rig.json': drawn_rig(drawings=('a.svg', 'a.svg')), 'a.svg':
        '<?xml version="1.0"?><!DOCTYPE s [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">'
        '<!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;">]><svg>&c;</svg>'}, [RIG]),
    # --- other commands --------------------------------------------------------
    Case('info-truncated-rig', B, ['info', '{w}/t.pmrig'], 1, r't\.pmrig: ', {'t.pmrig': copy_of('truncated.pmrig')}),
    Case('info-dev-zero', B, ['info', '/dev/zero'], 1, r'/dev/zero: is not a regular file'),
    Case('info-random-bytes', B, ['info', '{w}/r.pmrig'], 1, r'r\.pmrig: ', {'r.pmrig': bytes(range(256)) * 64}),
    Case('eval-nan-point', B, ['eval', '{w}/rig.pmrig', '--at', 'nan,0', '-o', '{w}/f.svg'], 2, r'--at',
         {'rig.pmrig': copy_of('rig.pmrig')}),
    Case('eval-unknown-path', B, ['eval', '{w}/rig.pmrig', '--path', 'nope', '-o', '{w}/f.svg'], 1, r'nope',
         {'rig.pmrig': copy_of('rig.pmrig')}),
    Case('sheet-columns-huge', B, ['sheet', '{w}/rig.pmrig', '--columns', '100000000', '-o', '{w}/s.svg'], 2, r'--columns',
         {'rig.pmrig': copy_of('rig.pmrig')}),
    # --- the viewer ------------------------------------------------------------
    Case('view-rig-missing', V, ['{w}/none.pmrig', '--headless', '-o', '{w}/f.png'], 1, r'none\.pmrig'),
    Case('view-rig-truncated', V, ['{w}/t.pmrig', '--headless', '-o', '{w}/f.png'], 1, r't\.pmrig: ', {'t.pmrig': copy_of('truncated.pmrig')}),
    Case('view-rig-random', V, ['{w}/r.pmrig', '--headless', '-o', '{w}/f.png'], 1, r'r\.pmrig: ', {'r.pmrig': os.urandom(4096)}),
    Case('view-rig-is-dev-zero', V, ['/dev/zero', '--headless', '-o', '{w}/f.png'], 1, r'/dev/zero'),
    Case('view-frames-negative', V, ['{w}/rig.pmrig', '--headless', '--path', 'x', '--frames', '-1', '-o', '{w}/f.png'], 2, r'--frames',
         dict(drawings(), **{'rig.pmrig': copy_of('rig.pmrig')})),
    Case('view-sigma-text', V, ['{w}/rig.pmrig', '--headless', '--sigma', 'abc', '-o', '{w}/f.png'], 2, r'--sigma',
         dict(drawings(), **{'rig.pmrig': copy_of('rig.pmrig')})),
    Case('view-crowd-2000000', V, ['{w}/rig.pmrig', '--headless', '--crowd', '2000000', '-o', '{w}/f.png'], 2, r'--crowd',
         dict(drawings(), **{'rig.pmrig': copy_of('rig.pmrig')})),
    Case('view-size-huge', V, ['{w}/rig.pmrig', '--headless', '--size', '100000x100000', '-o', '{w}/f.png'], 2, r'--size',
         dict(drawings(), **{'rig.pmrig': copy_of('rig.pmrig')})),
    Case('view-camera-bad', V, ['{w}/rig.pmrig', '--headless', '--camera', '1,2', '-o', '{w}/f.png'], 2, r'--camera',
         dict(drawings(), **{'rig.pmrig': copy_of('rig.pmrig')})),
    Case('view-transform-bad', V, ['{w}/rig.pmrig', '--headless', '--transform', 'rotate=abc', '-o', '{w}/f.png'], 2, r'--transform',
         dict(drawings(), **{'rig.pmrig': copy_of('rig.pmrig')})),
    Case('view-drawing-missing', V, ['{w}/rig.pmrig', '--headless', '-o', '{w}/f.png'], 1, r'a\.png',
         {'rig.pmrig': copy_of('rig.pmrig'), 'b.png': copy_of('b.png')}),
    Case('view-drawing-bomb', V, ['{w}/rig.pmrig', '--headless', '-o', '{w}/f.png'], 1, r'a\.png',
         {'rig.pmrig': copy_of('rig.pmrig'), 'b.png': copy_of('b.png'),
          'a.png': lambda p: open(p, 'wb').write(png(16384, 16384, idat=zlib.compress(b'\0' * (1 << 20))))}),
    Case('view-drawings-long-and-tall', V, ['{w}/rig.pmrig', '--headless', '-o', '{w}/f.png'], 1, r'share a texture',
         {'rig.pmrig': copy_of('rig.pmrig'),
          'a.png': lambda p: open(p, 'wb').write(png(20000, 1, idat=zlib.compress(b'\0' * 80001))),
          'b.png': lambda p: open(p, 'wb').write(png(1, 20000, idat=zlib.compress(b'\0' * 100000)))}, names=['{w}/rig.pmrig']),
    Case('view-drawing-is-fifo', V, ['{w}/rig.pmrig', '--headless', '-o', '{w}/f.png'], 1, r'a\.png',
         {'rig.pmrig': copy_of('rig.pmrig'), 'b.png': copy_of('b.png'), 'a.png': fifo}),
    Case('view-image-leaves-folder', V, ['{w}/rig.pmrig', '--headless', '-o', '{w}/f.png'], 1,
         r"image reference '\.\./\.\./etc/passwd' leaves the images folder", dict(drawings(), **{'rig.pmrig': copy_of('escape.pmrig')})),
    Case('view-atlas-page-missing', V, ['{w}/atlas.pmrig', '--headless', '-o', '{w}/f.png'], 1, r'atlas\.page0\.png',
         {'atlas.pmrig': copy_of('atlas.pmrig')}),
    Case('view-atlas-page-wrong-size', V, ['{w}/atlas.pmrig', '--headless', '-o', '{w}/f.png'], 1,
         r'atlas\.page0\.png: the atlas page is 16x16, the rig says',
         {'atlas.pmrig': copy_of('atlas.pmrig'), 'atlas.page0.png': png(16, 16, disc(8, 8, 4))}),
    Case('view-atlas-page-bomb', V, ['{w}/atlas.pmrig', '--headless', '-o', '{w}/f.png'], 1, r'atlas\.page0\.png',
         {'atlas.pmrig': copy_of('atlas.pmrig'),
          'atlas.page0.png': lambda p: open(p, 'wb').write(png(16384, 16384, idat=zlib.compress(b'\0' * (1 << 20))))}),
    Case('view-images-folder-missing', V, ['{w}/rig.pmrig', '--images', '{w}/none', '--headless', '-o', '{w}/f.png'], 1, r'none',
         {'rig.pmrig': copy_of('rig.pmrig')}),
    Case('view-unknown-path', V, ['{w}/rig.pmrig', '--headless', '--path', 'nope', '-o', '{w}/f.png'], 1, r'rig\.pmrig: .*nope',
         dict(drawings(), **{'rig.pmrig': copy_of('rig.pmrig')})),
    Case('view-output-folder', V, ['{w}/rig.pmrig', '--headless', '-o', '{w}/dir'], 1, r'dir',
         dict(drawings(), **{'rig.pmrig': copy_of('rig.pmrig'), 'dir/x': ''})),
]
