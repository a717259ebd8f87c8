#!/usr/bin/env python3
"""page_check.py: what tests/cli/test_animate.sh reads of a run's page and
of a screenshot of it (python3's standard library only).

  page_check.py json PAGE KEY           a value of the page's JSON block
  page_check.py frames PAGE             frames kept, the last frame's t, and
                                        the trajectory's bytes
  page_check.py pixel PAGE PNG CSV T X Y ITEM W H
      where the CSV's row at t = T puts the point (X, Y, 0), X and Y
      expressions of its columns (Python's, with math's functions:
      0.5*sin(theta), sin(th1) + sin(th2)), through the page's camera
      (position, target, up, vertical fov; aspect W / H), against the
      centroid of the pixels of ITEM's colour (the palette's) near it:
      prints "projected_x projected_y found_x found_y error count"
  page_check.py at PAGE PNG CSV T X Y Z COLOUR W H [R]
      the same for the point (X, Y, Z), against the pixels of COLOUR
      (#rrggbb, or an item's index for the palette's) within R px
      (default 20); prints "projected_x projected_y found_x found_y error
      count hit", hit 1 when the pixel at the projected point is COLOUR's
  page_check.py line PAGE PNG CSV T X0 Y0 Z0 X1 Y1 Z1 COLOUR W H
      the segment between two points, projected: of the pixels on it
      (sampled every px, strictly inside its ends), how many have a pixel
      of COLOUR within 1 px (COLOUR grid: the grid's pale grey): prints
      "sampled found"
  page_check.py near PAGE PNG X Y COLOUR R
      the centroid of COLOUR's pixels within R px of the pixel (X, Y):
      prints "found_x found_y error count"
  page_check.py box PAGE PNG CSV T X Y Z TURN A B C COLOUR W H
      a box of half-sizes A, B, C centred at (X, Y, Z), its axes turned by
      TURN (intrinsic turns about the axes of a sequence, the angles
      expressions of the CSV's columns: zxz:psi:theta:phi), its silhouette
      (the hull of its 8 corners, projected): of the pixels 3 px or more
      inside it and of those 3 to 30 px outside it, how many are COLOUR's:
      prints "inside found_inside outside found_outside"
"""
import json
import marshal
import math
import os
import re
import struct
import sys
import zlib


def page_json(path):
    text = open(path, encoding='utf-8').read()
    m = re.search(r'<script id="eomc-data" type="application/json">\n(.*?)\n</script>',
                  text, re.S)
    return json.loads(m.group(1)), m.group(1)


class Image:
    """Rows of RGB triples (rows[y][x]) over the bytes of a decoded image."""
    def __init__(self, w, h, rgb):
        self.w, self.h, self.rgb = w, h, rgb

    def __len__(self):
        return self.h

    def __getitem__(self, y):
        return Row(self, y)


class Row:
    def __init__(self, im, y):
        self.im, self.at = im, 3 * im.w * y

    def __len__(self):
        return self.im.w

    def __getitem__(self, x):
        o = self.at + 3 * x
        return tuple(self.im.rgb[o:o + 3])


def png(path):
    """Width, height and rows of RGB triples of an 8-bit RGB or RGBA PNG
    (kept decoded beside it, PATH.rgb, for the next check of it)."""
    cache = path + '.rgb'
    if os.path.exists(cache) and os.path.getmtime(cache) >= os.path.getmtime(path):
        with open(cache, 'rb') as f:
            w, h, rgb = marshal.load(f)
    else:
        w, h, rows = decode_png(path)
        rgb = b''.join(bytes(c for px in row for c in px) for row in rows)
        with open(cache, 'wb') as f:
            marshal.dump((w, h, rgb), f)
    return w, h, Image(w, h, rgb)


def decode_png(path):
    data = open(path, 'rb').read()
    assert data[:8] == b'\x89PNG\r\n\x1a\n'
    at, idat = 8, b''
    while at < len(data):
        n, kind = struct.unpack('>I4s', data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        if kind == b'IHDR':
            w, h, depth, ctype, _, _, interlace = struct.unpack('>IIBBBBB', body)
            assert depth == 8 and ctype in (2, 6) and interlace == 0
        elif kind == b'IDAT':
            idat += body
        at += 12 + n
    bpp = 3 if ctype == 2 else 4
    raw, stride = zlib.decompress(idat), w * bpp
    rows, prev, at = [], bytearray(stride), 0
    for _ in range(h):
        f, line = raw[at], bytearray(raw[at + 1:at + 1 + stride])
        at += 1 + stride
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[j:j + 3]) for j in range(0, stride, bpp)])
        prev = line
    return w, h, rows


def csv_row(path, t):
    lines = open(path).read().split('\n')
    names = lines[0].split(',')
    best = None
    for line in lines[1:]:
        if line:
            row = dict(zip(names, map(float, line.split(','))))
            if best is None or abs(row['t'] - t) < abs(best['t'] - t):
                best = row
    return best


def value(expr, row):
    """An expression of the row's columns (those named as identifiers)."""
    env = {k: getattr(math, k) for k in dir(math) if not k.startswith('_')}
    env.update({k: v for k, v in row.items() if k.isidentifier()})
    return float(eval(expr, {'__builtins__': {}}, env))


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a]


def project(cam, p, w, h):
    """The standard perspective projection (as gluLookAt and gluPerspective)."""
    f = unit(sub(cam['target'], cam['position']))
    r = unit(cross(f, cam['up']))
    u = cross(r, f)
    d = sub(p, cam['position'])
    th = math.tan(math.radians(cam['fov']) / 2)
    nx = dot(d, r) / (dot(d, f) * th * w / h)
    ny = dot(d, u) / (dot(d, f) * th)
    return (nx + 1) / 2 * w, (1 - ny) / 2 * h


PALETTE = [0xd62728, 0x1f77b4, 0x2ca02c, 0xff7f0e, 0x9467bd, 0x8c564b, 0xe377c2,
           0x17becf, 0xbcbd22, 0x7f7f7f]  # animate_page.js's


def like(px, rgb):
    """A saturated pixel whose channels are ordered as rgb's: the item's
    colour lit or shaded, not the grid, the links nor a pale trace."""
    if max(px) - min(px) < 90:
        return False
    order = sorted(range(3), key=lambda i: rgb[i])
    return sorted(range(3), key=lambda i: px[i]) == order and \
        abs((px[order[2]] - px[order[1]]) - (rgb[order[2]] - rgb[order[1]])) < 90


def dominant(px, rgb):
    """A pixel whose strongest channel is rgb's, by 60 or more: an axis's
    line (three.js's AxesHelper shades x from red to orange, y from green,
    z from blue), thin and blended with the background."""
    i = max(range(3), key=lambda k: rgb[k])
    return px[i] - max(px[k] for k in range(3) if k != i) >= 60


def grey(px):
    """A pixel of the grid's lines (0xdadada, blended with the 0xf7f7f7
    background), not the background itself."""
    return max(px) - min(px) <= 8 and 180 <= px[0] <= 238


def turn(seq, angles):
    """The rotation matrix of intrinsic turns about seq's axes."""
    R = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    for axis, a in zip(seq, angles):
        c, s = math.cos(a), math.sin(a)
        i = 'xyz'.index(axis)
        j, k = (i + 1) % 3, (i + 2) % 3
        T = [[0.0] * 3 for _ in range(3)]
        T[i][i] = 1.0
        T[j][j], T[j][k], T[k][j], T[k][k] = c, -s, s, c
        R = [[sum(R[r][m] * T[m][q] for m in range(3)) for q in range(3)] for r in range(3)]
    return R


def hull(points):
    """The convex hull of 2-D points, counter-clockwise (monotone chain)."""
    pts = sorted(set(points))
    def half(seq):
        h = []
        for p in seq:
            while len(h) >= 2 and ((h[-1][0] - h[-2][0]) * (p[1] - h[-2][1]) -
                                   (h[-1][1] - h[-2][1]) * (p[0] - h[-2][0])) <= 0:
                h.pop()
            h.append(p)
        return h
    lower, upper = half(pts), half(reversed(pts))
    return lower[:-1] + upper[:-1]


def signed_distance(poly, x, y):
    """Distance from (x, y) to a convex polygon's boundary: > 0 inside."""
    d = float('inf')
    for i in range(len(poly)):
        (ax, ay), (bx, by) = poly[i], poly[(i + 1) % len(poly)]
        n = math.hypot(bx - ax, by - ay)
        d = min(d, ((bx - ax) * (y - ay) - (by - ay) * (x - ax)) / n)
    return d


def rgb_of(spec):
    c = int(spec[1:], 16) if spec.startswith('#') else PALETTE[int(spec) % len(PALETTE)]
    return ((c >> 16) & 255, (c >> 8) & 255, c & 255)


def centroid(rows, px, py, rgb, R):
    H, W = len(rows), len(rows[0])
    sx, sy, n = 0.0, 0.0, 0
    for y in range(max(0, int(py) - R), min(H, int(py) + R + 1)):
        for x in range(max(0, int(px) - R), min(W, int(px) + R + 1)):
            if like(rows[y][x], rgb):
                sx, sy, n = sx + x + 0.5, sy + y + 0.5, n + 1
    fx, fy = (sx / n, sy / n) if n else (float('nan'), float('nan'))
    return fx, fy, n


def main():
    cmd, page = sys.argv[1], sys.argv[2]
    d, text = page_json(page)
    if cmd == 'json':
        v = d
        for k in sys.argv[3].split('.'):
            v = v[int(k)] if isinstance(v, list) else v[k]
        print(json.dumps(v))
    elif cmd == 'frames':
        traj = text[text.index('"frames":'):]
        print(len(d['frames']), d['frames'][-1][0], len(traj))
    elif cmd == 'pixel':
        shot, csv, t, xe, ye, item, w, h = sys.argv[3:11]
        row = csv_row(csv, float(t))
        px, py = project(d['camera'], [value(xe, row), value(ye, row), 0.0], int(w), int(h))
        rgb = rgb_of(item)
        fx, fy, n = centroid(png(shot)[2], px, py, rgb, 20)
        print('%.2f %.2f %.2f %.2f %.2f %d' % (px, py, fx, fy, math.hypot(fx - px, fy - py), n))
    elif cmd == 'at':
        shot, csv, t, xe, ye, ze, col, w, h = sys.argv[3:12]
        R = int(sys.argv[12]) if len(sys.argv) > 12 else 20
        row = csv_row(csv, float(t))
        px, py = project(d['camera'], [value(e, row) for e in (xe, ye, ze)], int(w), int(h))
        rgb, rows = rgb_of(col), png(shot)[2]
        fx, fy, n = centroid(rows, px, py, rgb, R)
        hit = 0 <= int(py) < len(rows) and 0 <= int(px) < len(rows[0]) and \
            like(rows[int(py)][int(px)], rgb)
        print('%.2f %.2f %.2f %.2f %.2f %d %d' % (px, py, fx, fy, math.hypot(fx - px, fy - py),
                                                  n, hit))
    elif cmd == 'line':
        shot, csv, t = sys.argv[3:6]
        ends, (col, w, h) = sys.argv[6:12], sys.argv[12:15]
        row = csv_row(csv, float(t))
        a = project(d['camera'], [value(e, row) for e in ends[:3]], int(w), int(h))
        b = project(d['camera'], [value(e, row) for e in ends[3:]], int(w), int(h))
        rows = png(shot)[2]
        H, W = len(rows), len(rows[0])
        if col == 'grid':
            found_at = grey
        else:
            rgb = rgb_of(col)
            found_at = lambda px: dominant(px, rgb)  # noqa: E731
        m = int(math.hypot(b[0] - a[0], b[1] - a[1]))
        sampled = found = 0
        for i in range(2, m - 1):
            x = a[0] + (b[0] - a[0]) * i / m
            y = a[1] + (b[1] - a[1]) * i / m
            sampled += 1
            found += any(found_at(rows[yy][xx])
                         for yy in range(max(0, int(y) - 1), min(H, int(y) + 2))
                         for xx in range(max(0, int(x) - 1), min(W, int(x) + 2)))
        print(sampled, found)
    elif cmd == 'near':
        shot, px, py, col, R = sys.argv[3:8]
        px, py = float(px), float(py)
        fx, fy, n = centroid(png(shot)[2], px, py, rgb_of(col), int(R))
        print('%.2f %.2f %.2f %d' % (fx, fy, math.hypot(fx - px, fy - py), n))
    elif cmd == 'box':
        shot, csv, t, xe, ye, ze, how, ha, hb, hc, col, w, h = sys.argv[3:16]
        row = csv_row(csv, float(t))
        c = [value(e, row) for e in (xe, ye, ze)]
        seq, *angles = how.split(':')
        R = turn(seq, [value(e, row) for e in angles])
        half = [float(ha), float(hb), float(hc)]
        corners = []
        for sx in (-1, 1):
            for sy in (-1, 1):
                for sz in (-1, 1):
                    b = [sx * half[0], sy * half[1], sz * half[2]]
                    corners.append(project(d['camera'], [c[r] + sum(R[r][k] * b[k]
                                                                    for k in range(3))
                                                         for r in range(3)], int(w), int(h)))
        poly = hull([(round(x, 6), round(y, 6)) for x, y in corners])
        rgb, rows = rgb_of(col), png(shot)[2]
        H, W = len(rows), len(rows[0])
        x0 = max(0, int(min(p[0] for p in poly)) - 30)
        x1 = min(W, int(max(p[0] for p in poly)) + 31)
        y0 = max(0, int(min(p[1] for p in poly)) - 30)
        y1 = min(H, int(max(p[1] for p in poly)) + 31)
        n_in = f_in = n_out = f_out = 0
        for y in range(y0, y1):
            for x in range(x0, x1):
                s = signed_distance(poly, x + 0.5, y + 0.5)
                if s >= 3:
                    n_in += 1
                    f_in += like(rows[y][x], rgb)
                elif -30 <= s <= -3:
                    n_out += 1
                    f_out += like(rows[y][x], rgb)
        print(n_in, f_in, n_out, f_out)


main()
