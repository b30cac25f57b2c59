#!/usr/bin/python3
"""Figures of a G-code program (the LinuxCNC subset rosmill and the FreeCAD bench write), the same for every planner.

    ngc_stats.py PROGRAM.ngc --stock x0,y0,z0,x1,y1,z1 --tool-diameter D [--engagement] [--cell 0.05] [--part STL]

Prints one JSON object:
- motion commands, G0 / G1 / G2-G3 counts, cutting (feed) and rapid lengths, the Z levels of the XY feed moves and
  the XY bounds of the feed moves;
- two time estimates: `time_feeds_s` at the programmed feeds, rapids at 5000 mm/min (what `rosmill plan --json`
  reports as estimated_seconds), and `time_exact_stop_s`, every move accelerating from rest and braking to rest at
  508 mm/s^2 per axis (config/machine.yaml: LinuxCNC's sim) with the feed capped at 1828 mm/min (the sim's axes)
  and the rapids at that cap too (what a job report's time_s does, rapids there at the job's rapid_feed);
- with --engagement, a cross-check of the radial engagement: per Z level, the cleared area on a bitmap of `cell`
  mm, material = the stock box's XY rectangle minus what the tool has cleared at that level (so it is exact for a
  single level cut into the stock's top layer, an approximation below it); the engagement is the share of 181 points
  on the tool's leading semicircle (radius + 0.75 cell) that lie on material, times 180 degrees, sampled every
  0.1 mm along every feed move with an XY component below the stock top (a ramp or helix counts in the level it
  descends to). `max_deg` is over all of them, `max_deg_at_level` over the constant-Z moves only (no entry ramps).
  With --part PART.stl the part is not material: a cell whose part surface (the highest triangle over its centre)
  stands above the level is left out of that level's material. Without it, a tool that runs along a wall of the
  part counts the wall within 0.75 cell of its edge as material: up to 90 degrees where it cuts nothing.
"""
import argparse
import json
import math
import re
import sys

RAPID_PLAN = 5000.0          # mm/min, rosmill plan's rapid for its estimate
MACHINE_FEED_CAP = 1828.0    # mm/min, LinuxCNC sim axes
MACHINE_ACCEL = 508.0        # mm/s^2 per axis

WORD = re.compile(r'([A-Za-z])\s*([-+]?(?:\d+\.?\d*|\.\d+))')


def parse(path):
    """Yields (kind, start, end, feed, arc) with kind 'rapid' or 'feed'; arc = (cx, cy, ccw) or None."""
    pos = [0.0, 0.0, None]
    motion = None
    feed = 0.0
    absolute = True
    with open(path) as f:
        for raw in f:
            line = re.sub(r'\([^)]*\)', '', raw.split(';')[0]).strip()
            if not line:
                continue
            words = WORD.findall(line)
            g = [float(v) for k, v in words if k.upper() == 'G']
            vals = {k.upper(): float(v) for k, v in words if k.upper() in 'XYZIJF'}
            for code in g:
                if code in (0, 1, 2, 3):
                    motion = int(code)
                elif code == 90:
                    absolute = True
                elif code == 91:
                    absolute = False
                elif code in (53, 28, 30):
                    motion = None  # machine-coordinate moves: not part of the toolpath figures
            if 'F' in vals:
                feed = vals['F']
            if not any(a in vals for a in 'XYZ') or motion is None:
                continue
            if any(code in (53, 28, 30) for code in g):
                continue
            start = list(pos)
            for i, a in enumerate('XYZ'):
                if a in vals:
                    pos[i] = vals[a] if absolute or pos[i] is None else pos[i] + vals[a]
            if start[2] is None:
                start[2] = pos[2]
            if pos[2] is None:
                continue
            arc = None
            if motion in (2, 3):
                arc = (start[0] + vals.get('I', 0.0), start[1] + vals.get('J', 0.0), motion == 3)
            yield ('rapid' if motion == 0 else 'feed', tuple(start), tuple(pos), feed, arc)


def arc_points(start, end, arc, step=0.2):
    cx, cy, ccw = arc
    r = math.hypot(start[0] - cx, start[1] - cy)
    a0 = math.atan2(start[1] - cy, start[0] - cx)
    a1 = math.atan2(end[1] - cy, end[0] - cx)
    sweep = (a1 - a0) if ccw else (a0 - a1)
    sweep %= 2 * math.pi
    if sweep < 1e-9:
        sweep = 2 * math.pi
    n = max(1, int(math.ceil(r * sweep / step)))
    pts = []
    for i in range(1, n + 1):
        t = i / n
        a = a0 + (sweep * t if ccw else -sweep * t)
        pts.append((cx + r * math.cos(a), cy + r * math.sin(a), start[2] + (end[2] - start[2]) * t))
    return pts


def segments(moves):
    """Straight pieces of every move (arcs split), as (kind, a, b, feed)."""
    for kind, a, b, feed, arc in moves:
        if arc is None:
            yield kind, a, b, feed
        else:
            prev = a
            for p in arc_points(a, b, arc):
                yield kind, prev, p, feed
                prev = p


def exact_stop_seconds(length, d, feed):
    if length <= 0 or feed <= 0:
        return 0.0
    v = min(feed, MACHINE_FEED_CAP) / 60.0
    a = math.inf
    for c in d:
        if abs(c) > 1e-12:
            a = min(a, MACHINE_ACCEL / abs(c))
    if length >= v * v / a:
        return length / v + v / a
    return 2.0 * math.sqrt(length / a)


def stats(moves, stock_top):
    out = {'motion_commands': len(moves), 'g0': 0, 'g1': 0, 'arcs': 0, 'cutting_length_mm': 0.0,
           'rapid_length_mm': 0.0, 'time_feeds_s': 0.0, 'time_exact_stop_s': 0.0}
    levels = {}
    lo = [math.inf, math.inf]
    hi = [-math.inf, -math.inf]
    feeds = set()
    for kind, a, b, feed, arc in moves:
        if kind == 'rapid':
            out['g0'] += 1
        elif arc is None:
            out['g1'] += 1
        else:
            out['arcs'] += 1
        if kind == 'feed':
            feeds.add(feed)
    for kind, a, b, feed in segments(moves):
        d = [b[i] - a[i] for i in range(3)]
        L = math.sqrt(sum(c * c for c in d))
        if L == 0:
            continue
        u = [c / L for c in d]
        if kind == 'rapid':
            out['rapid_length_mm'] += L
            out['time_feeds_s'] += L / RAPID_PLAN * 60.0
            out['time_exact_stop_s'] += exact_stop_seconds(L, u, MACHINE_FEED_CAP)
        else:
            out['cutting_length_mm'] += L
            out['time_feeds_s'] += L / feed * 60.0 if feed > 0 else math.inf
            out['time_exact_stop_s'] += exact_stop_seconds(L, u, feed)
            if abs(d[0]) + abs(d[1]) > 1e-9:
                lo = [min(lo[0], a[0], b[0]), min(lo[1], a[1], b[1])]
                hi = [max(hi[0], a[0], b[0]), max(hi[1], a[1], b[1])]
                if abs(d[2]) < 1e-9 and a[2] < stock_top:
                    z = round(a[2], 4)
                    levels[z] = levels.get(z, 0.0) + math.hypot(d[0], d[1])
    out['levels'] = [{'z': z, 'xy_feed_length_mm': l} for z, l in sorted(levels.items(), reverse=True)]
    out['feed_xy_bounds'] = [lo[0], lo[1], hi[0], hi[1]]
    out['feeds_mm_per_min'] = sorted(feeds)
    return out


def stl_triangles(path):
    """The triangles of a binary or ASCII STL as an (n, 3, 3) array."""
    import numpy as np
    data = open(path, 'rb').read()
    if len(data) >= 84:
        count = int.from_bytes(data[80:84], 'little')
        if 84 + 50 * count == len(data):
            rec = np.frombuffer(data, dtype=np.dtype([('n', '<f4', 3), ('v', '<f4', (3, 3)), ('a', '<u2')]),
                                count=count, offset=84)
            return rec['v'].astype(float)
    words = re.findall(r'vertex\s+(\S+)\s+(\S+)\s+(\S+)', data.decode('ascii', 'replace'))
    return np.array(words, dtype=float).reshape(-1, 3, 3)


def part_heights(triangles, gx0, gy0, nx, ny, cell):
    """The highest part surface over each cell centre (-inf where the part has none)."""
    import numpy as np
    top = np.full((ny, nx), -np.inf)
    for t in triangles:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
        det = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay)
        if abs(det) < 1e-12:
            continue  # a wall seen edge-on: its neighbours' tops bound it
        i0 = max(0, int(math.floor((min(ax, bx, cx) - gx0) / cell - 0.5)))
        i1 = min(nx - 1, int(math.ceil((max(ax, bx, cx) - gx0) / cell - 0.5)))
        j0 = max(0, int(math.floor((min(ay, by, cy) - gy0) / cell - 0.5)))
        j1 = min(ny - 1, int(math.ceil((max(ay, by, cy) - gy0) / cell - 0.5)))
        if i1 < i0 or j1 < j0:
            continue
        px = gx0 + (np.arange(i0, i1 + 1) + 0.5) * cell
        py = gy0 + (np.arange(j0, j1 + 1) + 0.5) * cell
        X, Y = np.meshgrid(px, py)
        u = ((X - ax) * (cy - ay) - (cx - ax) * (Y - ay)) / det
        v = ((bx - ax) * (Y - ay) - (X - ax) * (by - ay)) / det
        inside = (u >= -1e-9) & (v >= -1e-9) & (u + v <= 1 + 1e-9)
        z = az + u * (bz - az) + v * (cz - az)
        sub = top[j0:j1 + 1, i0:i1 + 1]
        np.maximum(sub, np.where(inside, z, -np.inf), out=sub)
    return top


def engagement(moves, stock, radius, cell, part=None):
    import numpy as np
    x0, y0, z0, x1, y1, z1 = stock
    pad = radius + 2.0
    gx0, gy0 = x0 - pad, y0 - pad
    nx = int(math.ceil((x1 - x0 + 2 * pad) / cell))
    ny = int(math.ceil((y1 - y0 + 2 * pad) / cell))
    xs = gx0 + (np.arange(nx) + 0.5) * cell
    ys = gy0 + (np.arange(ny) + 0.5) * cell
    stock_mask = ((ys[:, None] >= y0) & (ys[:, None] <= y1)) & ((xs[None, :] >= x0) & (xs[None, :] <= x1))
    heights = part_heights(stl_triangles(part), gx0, gy0, nx, ny, cell) if part else None
    k = int(math.ceil(radius / cell)) + 1
    oy, ox = np.mgrid[-k:k + 1, -k:k + 1].astype(float)
    r_s = radius + 0.75 * cell  # just outside the cutting circle: the material the edge touches
    angles = np.radians(np.arange(-90.0, 90.0001, 1.0))
    ca, sa = np.cos(angles), np.sin(angles)
    step = 0.1
    layers = {}

    def layer(z):
        key = round(z, 3)
        if key not in layers:
            layers[key] = stock_mask.copy() if heights is None else stock_mask & ~(heights > z + 1e-6)
        return layers[key]

    def stamp(mat, cx, cy):
        fx, fy = (cx - gx0) / cell - 0.5, (cy - gy0) / cell - 0.5
        ix, iy = int(round(fx)), int(round(fy))
        if ix - k < 0 or iy - k < 0 or ix + k + 1 > nx or iy + k + 1 > ny:
            return
        disc = ((ox - (fx - ix)) ** 2 + (oy - (fy - iy)) ** 2) * cell * cell <= radius * radius
        sub = mat[iy - k:iy + k + 1, ix - k:ix + k + 1]
        sub &= ~disc

    def sample(mat, cx, cy, ux, uy):
        px = np.clip(((cx + r_s * (ux * ca - uy * sa) - gx0) / cell).astype(int), 0, nx - 1)
        py = np.clip(((cy + r_s * (uy * ca + ux * sa) - gy0) / cell).astype(int), 0, ny - 1)
        return float(mat[py, px].mean() * 180.0)

    # Every feed piece below the stock top belongs to the level of the next level (constant-Z, XY) piece: a helix
    # or ramp cuts into the level it descends to.
    pieces = [p for p in segments(moves)]
    level_of = [None] * len(pieces)
    nxt = None
    for i in range(len(pieces) - 1, -1, -1):
        kind, a, b, feed = pieces[i]
        if kind == 'feed' and abs(a[2] - b[2]) < 1e-9 and (abs(a[0] - b[0]) + abs(a[1] - b[1])) > 1e-9:
            nxt = round(b[2], 4)
        level_of[i] = nxt if nxt is not None else round(min(a[2], b[2]), 4)
    hist = np.zeros(181)
    total = 0.0
    best = {'max_deg': 0.0, 'at': None}
    best_level = {'max_deg': 0.0, 'at': None}
    prev = None
    for (kind, a, b, feed), lev in zip(pieces, level_of):
        if kind != 'feed' or max(a[2], b[2]) >= z1 - 1e-9:
            prev = None
            continue
        ramp = abs(a[2] - b[2]) > 1e-9
        dx, dy = b[0] - a[0], b[1] - a[1]
        L = math.hypot(dx, dy)
        mat = layer(lev)
        if prev is None or math.hypot(prev[0] - a[0], prev[1] - a[1]) > 1e-6:
            stamp(mat, a[0], a[1])
        prev = b
        if L < 1e-9:
            continue
        ux, uy = dx / L, dy / L
        n = max(1, int(math.ceil(L / step)))
        for s in range(1, n + 1):
            cx, cy = a[0] + dx * s / n, a[1] + dy * s / n
            e = sample(mat, cx, cy, ux, uy)
            hist[int(round(e))] += L / n
            total += L / n
            if e > best['max_deg']:
                best = {'max_deg': e, 'at': [round(cx, 3), round(cy, 3), round(b[2], 3)]}
            if not ramp and e > best_level['max_deg']:
                best_level = {'max_deg': e, 'at': [round(cx, 3), round(cy, 3), round(b[2], 3)]}
            stamp(mat, cx, cy)
    cum = np.cumsum(hist) / max(total, 1e-12)
    share = lambda lim: float(hist[int(lim) + 1:].sum() / max(total, 1e-12))  # noqa: E731
    return {'max_deg': best['max_deg'], 'max_at': best['at'],
            'max_deg_at_level': best_level['max_deg'], 'max_at_level_at': best_level['at'],
            'p50_deg': float(np.searchsorted(cum, 0.50)), 'p95_deg': float(np.searchsorted(cum, 0.95)),
            'p99_deg': float(np.searchsorted(cum, 0.99)),
            'share_of_cut_above_90deg': share(90), 'share_of_cut_above_120deg': share(120),
            'share_of_cut_at_180deg': float(hist[180] / max(total, 1e-12)),
            'sampled_cut_mm': total, 'levels': sorted(layers, reverse=True), 'cell_mm': cell}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('program')
    ap.add_argument('--stock', required=True, help='x0,y0,z0,x1,y1,z1 (mm)')
    ap.add_argument('--tool-diameter', type=float, required=True)
    ap.add_argument('--engagement', action='store_true')
    ap.add_argument('--cell', type=float, default=0.05)
    ap.add_argument('--part', help='the part (STL, mm): not material (see --engagement)')
    args = ap.parse_args()
    stock = [float(v) for v in args.stock.split(',')]
    moves = list(parse(args.program))
    out = stats(moves, stock[5])
    if args.engagement:
        out['engagement'] = engagement(moves, stock, 0.5 * args.tool_diameter, args.cell, args.part)
    json.dump(out, sys.stdout, indent=1)
    sys.stdout.write('\n')


if __name__ == '__main__':
    main()
