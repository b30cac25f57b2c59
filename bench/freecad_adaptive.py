# FreeCAD 0.20's Adaptive clearing, run headless, as the peer of rosmill's adaptive strategy (issue 29).
#
# Run by freecadcmd, which takes no script arguments of its own (further words on its command line are opened as
# documents), so the parameters come from the environment:
#   FCB_STL        the part (STL, mm)                                  default /tmp/cavity.stl
#   FCB_OUT        output prefix: writes PREFIX.ngc and PREFIX.json      default /tmp/freecad_adaptive
#   FCB_FACE       FaceN to clear; "top" (default): the highest upward horizontal planar face; "lowest-pocket":
#                  the lowest upward horizontal face that is not the part's bottom and lies inside the outline
#   FCB_STEPOVER   step-over, percent of the tool diameter              default 20 (FreeCAD's default)
#   FCB_TOLERANCE  Adaptive's Tolerance property                        default: FreeCAD's (0.1)
#   FCB_FEED       feed, mm/min, given to the tool controller           default 1000 (rosmill's flat:5)
#   FCB_PLUNGE     vertical feed, mm/min                                default 300 (rosmill's flat:5)
#   FCB_RPM        spindle speed                                         default 12000 (rosmill's flat:5)
#
# The planning time is the doc.recompute() that computes the Adaptive operation and nothing else (the job, its
# model clone and stock are recomputed before), measured here with time.perf_counter.
import json
import math
import os
import sys
import time

sys.path.append('/usr/share/freecad/Mod/Path')

import FreeCAD  # noqa: E402
import Mesh  # noqa: E402
import Part  # noqa: E402
import PathScripts.PathAdaptive as PathAdaptive  # noqa: E402
import PathScripts.PathJob as PathJob  # noqa: E402


def env(name, default):
    value = os.environ.get(name, '')
    return value if value != '' else default


STL = env('FCB_STL', '/tmp/cavity.stl')
OUT = env('FCB_OUT', '/tmp/freecad_adaptive')
FACE = env('FCB_FACE', 'top')
STEPOVER = float(env('FCB_STEPOVER', '20'))
TOLERANCE = env('FCB_TOLERANCE', '')
FEED = float(env('FCB_FEED', '1000'))
PLUNGE = float(env('FCB_PLUNGE', '300'))
RPM = float(env('FCB_RPM', '12000'))


def log(msg):
    sys.stderr.write('freecad_adaptive: %s\n' % msg)


def upward_flat(face):
    """True when the face is planar, horizontal and its material lies below it (its normal points up)."""
    if face.Surface.__class__.__name__ != 'Plane':
        return False
    bb = face.BoundBox
    if bb.ZLength > 1e-6:
        return False
    u0, u1, v0, v1 = face.ParameterRange
    n = face.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
    return n.z > 0.999


def choose_face(shape, how):
    if how.startswith('Face'):
        return how
    flats = [(f.BoundBox.ZMax, i) for i, f in enumerate(shape.Faces) if upward_flat(f)]
    if not flats:
        raise RuntimeError('no upward horizontal face in the model')
    if how == 'top':
        z, i = max(flats)
    elif how == 'lowest-pocket':
        bottom = shape.BoundBox.ZMin
        inner = [(z, i) for z, i in flats if z > bottom + 1e-6]
        z, i = min(inner)
    else:
        raise RuntimeError('FCB_FACE: top, lowest-pocket or FaceN, not ' + how)
    return 'Face%d' % (i + 1)


# ---------------------------------------------------------------------------------------------------------------
# The part, the job, the operation
t_process0 = time.perf_counter()
doc = FreeCAD.newDocument('bench')
mesh = Mesh.Mesh(STL)
shell_src = Part.Shape()
shell_src.makeShapeFromMesh(mesh.Topology, 0.05)
solid = Part.makeSolid(Part.makeShell(shell_src.Faces)).removeSplitter()
part = doc.addObject('Part::Feature', 'Part')
part.Shape = solid

job = PathJob.Create('Job', [part], None)
doc.recompute()
model = job.Model.Group[0]
face_name = choose_face(model.Shape, FACE)
face = model.Shape.getElement(face_name)

tc = job.Tools.Group[0]
tc_defaults = {
    'label': tc.Label,
    'tool': tc.Tool.Label if hasattr(tc.Tool, 'Label') else str(tc.Tool),
    'diameter_mm': float(tc.Tool.Diameter),
    'horiz_feed_mm_per_min': tc.HorizFeed.getValueAs('mm/min').Value,
    'vert_feed_mm_per_min': tc.VertFeed.getValueAs('mm/min').Value,
    'spindle_rpm': float(tc.SpindleSpeed),
}
# FreeCAD's default controller has every feed at 0 (its program would say F0, which rs274 refuses); the feeds do
# not change the path, so rosmill's for flat:5 are given to it.
tc.HorizFeed = '%g mm/min' % FEED
tc.VertFeed = '%g mm/min' % PLUNGE
tc.SpindleSpeed = RPM

op = PathAdaptive.Create('Adaptive')
op.Base = [(model, [face_name])]
op.StepOver = int(round(STEPOVER))  # a PropertyPercent: whole percent only
if TOLERANCE:
    op.Tolerance = float(TOLERANCE)

# Time Adaptive2d apart from the G-code generation of PathAdaptive (both inside the recompute).
timing = {'execute_s': 0.0, 'generate_s': 0.0}
_execute, _generate = PathAdaptive.Execute, PathAdaptive.GenerateGCode


def timed_execute(*a, **k):
    t = time.perf_counter()
    try:
        return _execute(*a, **k)
    finally:
        timing['execute_s'] += time.perf_counter() - t


def timed_generate(*a, **k):
    t = time.perf_counter()
    try:
        return _generate(*a, **k)
    finally:
        timing['generate_s'] += time.perf_counter() - t


PathAdaptive.Execute, PathAdaptive.GenerateGCode = timed_execute, timed_generate

t0 = time.perf_counter()
doc.recompute()
plan_s = time.perf_counter() - t0

commands = list(op.Path.Commands)
log('%s: %d commands in %.3f s' % (face_name, len(commands), plan_s))

# ---------------------------------------------------------------------------------------------------------------
# Walk the program: lengths, levels, bounds; write it as LinuxCNC G-code.


def fmt(v):
    s = '%.4f' % v
    s = s.rstrip('0').rstrip('.')
    return '0' if s in ('-0', '') else s


pos = {'X': 0.0, 'Y': 0.0, 'Z': None}
feed_len = rapid_len = helix_len = 0.0
n_motion = n_comment = n_g0 = n_g1 = n_arc = 0
levels = {}
xy_min = [math.inf, math.inf]
xy_max = [-math.inf, -math.inf]
feeds_used = set()
first_feed = None
in_entry = False
lines = []
clearance = op.ClearanceHeight.Value
last_f = None

for c in commands:
    name = c.Name
    if name.startswith('('):
        n_comment += 1
        in_entry = name.startswith('(Helix')
        lines.append('(' + name.strip('()').replace('(', '[').replace(')', ']') + ')')
        continue
    p = c.Parameters
    if name in ('G0', 'G00', 'G1', 'G01', 'G2', 'G02', 'G3', 'G03'):
        n_motion += 1
        start = dict(pos)
        if start['Z'] is None:
            start['Z'] = clearance
        for a in 'XYZ':
            if a in p:
                pos[a] = p[a]
        if pos['Z'] is None:
            pos['Z'] = clearance
        dx, dy, dz = pos['X'] - start['X'], pos['Y'] - start['Y'], pos['Z'] - start['Z']
        words = [name if len(name) == 2 else name[0] + name[2]]
        for a in 'XYZ':
            if a in p:
                words.append(a + fmt(p[a]))
        if name in ('G0', 'G00'):
            n_g0 += 1
            rapid_len += math.sqrt(dx * dx + dy * dy + dz * dz)
        else:
            if name in ('G1', 'G01'):
                n_g1 += 1
                length = math.sqrt(dx * dx + dy * dy + dz * dz)
                for a in 'IJ':
                    if a in p:
                        words.append(a + fmt(p[a]))
            else:
                n_arc += 1
                i, j = p.get('I', 0.0), p.get('J', 0.0)
                cx, cy = start['X'] + i, start['Y'] + j
                r = math.hypot(i, j)
                a0 = math.atan2(start['Y'] - cy, start['X'] - cx)
                a1 = math.atan2(pos['Y'] - cy, pos['X'] - cx)
                sweep = (a1 - a0) if name in ('G3', 'G03') else (a0 - a1)
                sweep %= 2 * math.pi
                if sweep < 1e-9:
                    sweep = 2 * math.pi
                length = math.hypot(r * sweep, dz)
                words += ['I' + fmt(i), 'J' + fmt(j)]
            if 'F' in p:
                # Path.Command feeds are mm/s (FreeCAD's internal unit).
                f = round(p['F'] * 60.0, 3)
                feeds_used.add(f)
                if f != last_f:
                    words.append('F' + fmt(f))
                    last_f = f
            feed_len += length
            if in_entry:
                helix_len += length
            if first_feed is None:
                first_feed = {'from': [start['X'], start['Y'], start['Z']], 'to': [pos['X'], pos['Y'], pos['Z']]}
            if abs(dx) + abs(dy) > 1e-9:
                xy_min = [min(xy_min[0], start['X'], pos['X']), min(xy_min[1], start['Y'], pos['Y'])]
                xy_max = [max(xy_max[0], start['X'], pos['X']), max(xy_max[1], start['Y'], pos['Y'])]
                if abs(dz) < 1e-9:
                    z = round(pos['Z'], 4)
                    levels[z] = levels.get(z, 0.0) + math.hypot(dx, dy)
        lines.append(' '.join(words))
    else:
        lines.append('(unhandled: %s)' % c.toGCode())

stock_bb = job.Stock.Shape.BoundBox
stock = [stock_bb.XMin, stock_bb.YMin, stock_bb.ZMin, stock_bb.XMax, stock_bb.YMax, stock_bb.ZMax]

header = [
    '(FreeCAD %s Adaptive, %s of %s, %g %% step-over, tool %g mm)' % (
        '.'.join(FreeCAD.Version()[:3]), face_name, os.path.basename(STL), STEPOVER, float(op.ToolController.Tool.Diameter)),
    '(stock %s)' % ' '.join(fmt(v) for v in stock),
    'G21 G90 G17 G40 G49 G80 G94',
    'T1 M6',
    'G43 H1',
    'S%d M3' % int(RPM),
    'G0 Z%s' % fmt(clearance),
]
footer = ['G0 Z%s' % fmt(clearance), 'M5', 'M2']
with open(OUT + '.ngc', 'w') as f:
    f.write('\n'.join(header + lines + footer) + '\n')


# ---------------------------------------------------------------------------------------------------------------
wires = []
for w in face.Wires:
    bb = w.BoundBox
    vr = [math.hypot(v.X, v.Y) for v in w.Vertexes]
    wires.append({'edges': len(w.Edges), 'bbox_xy': [bb.XMin, bb.YMin, bb.XMax, bb.YMax],
                  'vertex_radius_min': min(vr), 'vertex_radius_max': max(vr)})

result = {
    'peer': 'FreeCAD %s Adaptive (PathScripts.PathAdaptive, libarea Adaptive2d), freecadcmd' % '.'.join(
        FreeCAD.Version()[:3]),
    'stl': STL,
    'face': face_name,
    'face_z': face.BoundBox.ZMax,
    'face_area_mm2': face.Area,
    'face_wires': wires,
    'tool_diameter_mm': float(op.ToolController.Tool.Diameter),
    'stepover_percent': float(op.StepOver),
    'tolerance': float(op.Tolerance),
    'operation_type': op.OperationType,
    'side': op.Side,
    'use_outline': bool(op.UseOutline),
    'force_inside_out': bool(op.ForceInsideOut),
    'finishing_profile': bool(op.FinishingProfile),
    'stock_to_leave_mm': float(op.StockToLeave),
    'helix_angle_deg': float(op.HelixAngle),
    'helix_diameter_limit_mm': op.HelixDiameterLimit.Value,
    'lift_distance_mm': op.LiftDistance.Value,
    'keep_tool_down_ratio': float(op.KeepToolDownRatio),
    'planning_s': plan_s,
    'planning_breakdown_s': {'PathAdaptive.Execute (Adaptive2d + G-code)': timing['execute_s'],
                             'PathAdaptive.GenerateGCode': timing['generate_s']},
    'script_s': time.perf_counter() - t_process0,
    'path_commands': len(commands),
    'path_motion_commands': n_motion,
    'path_comments': n_comment,
    'g0': n_g0, 'g1': n_g1, 'arcs': n_arc,
    'cutting_length_mm': feed_len,
    'entry_helix_length_mm': helix_len,
    'rapid_length_mm': rapid_len,
    'levels': [{'z': z, 'xy_feed_length_mm': l} for z, l in sorted(levels.items(), reverse=True)],
    'feed_xy_bounds': [xy_min[0], xy_min[1], xy_max[0], xy_max[1]],
    'stock': {'type': job.Stock.Proxy.__class__.__name__,
              'extents_mm': {a: getattr(job.Stock, a).Value for a in
                             ('ExtXneg', 'ExtXpos', 'ExtYneg', 'ExtYpos', 'ExtZneg', 'ExtZpos')},
              'box': stock},
    'heights': {'clearance': op.ClearanceHeight.Value, 'safe': op.SafeHeight.Value,
                'start_depth': op.StartDepth.Value, 'final_depth': op.FinalDepth.Value,
                'step_down': op.StepDown.Value},
    'first_feed_move': first_feed,
    'entry_start_above_stock_top_mm': (first_feed['from'][2] - stock[5]) if first_feed else None,
    'feeds_mm_per_min': sorted(feeds_used),
    'tool_controller_defaults': tc_defaults,
    'tool_controller_used': {'horiz_feed_mm_per_min': FEED, 'vert_feed_mm_per_min': PLUNGE, 'spindle_rpm': RPM},
    'gcode': OUT + '.ngc',
}
with open(OUT + '.json', 'w') as f:
    json.dump(result, f, indent=1)
log('wrote %s.ngc and %s.json' % (OUT, OUT))
