# The STL files of the adaptive benchmark beside FreeCAD, written by FreeCAD's Part (run by freecadcmd).
#   FCB_DIR  folder to write to (default /tmp)
# - groove.stl: FreeCAD's Adaptive region on the cavity's top face as a design of its own. It is FreeCAD's default
#   stock box for the cavity (the part's bounds grown 1 mm every way: x -61..61, y -60.6713..60.6713, z -1..61)
#   with a 1 mm deep ring groove from z 60 to 61 between the cavity's 30-gons of r 50 and r 60 (vertices at
#   angles 12k degrees, as rosmill's primitive). Roughing it from its bounds box clears exactly what FreeCAD's
#   Adaptive clears, walls on both sides: the stock section at z 60 minus the part's section grown by the tool
#   radius is the annulus shrunk by 2.5 mm, FreeCAD's tool-centre region.
# - pocket.stl: the second region: a 80 x 60 x 20 block with a 40 x 30 x 10 mm rectangular pocket in its top,
#   centred (pocket floor at z 10).
import math
import os
import sys

import FreeCAD
import Mesh
import MeshPart
import Part

V = FreeCAD.Vector
out = os.environ.get('FCB_DIR', '') or '/tmp'


def ngon(r, z, n=30):
    pts = [V(r * math.cos(2 * math.pi * k / n), r * math.sin(2 * math.pi * k / n), z) for k in range(n)]
    return Part.Face(Part.makePolygon(pts + [pts[0]]))


def write(shape, name):
    mesh = MeshPart.meshFromShape(Shape=shape, LinearDeflection=0.01, AngularDeflection=0.1, Relative=False)
    path = os.path.join(out, name)
    mesh.write(path)
    sys.stderr.write('freecad_shapes: %s: %d triangles, volume %.1f mm3, bounds %s\n' % (
        path, mesh.CountFacets, shape.Volume, shape.BoundBox))


ya = 60.0 * math.cos(math.pi / 30)  # the 30-gon's apothem: its y extent
ring = ngon(60, 60).extrude(V(0, 0, 1)).cut(ngon(50, 60).extrude(V(0, 0, 1)))
box = Part.makeBox(122, 2 * ya + 2, 62, V(-61, -ya - 1, -1))
write(box.cut(ring).removeSplitter(), 'groove.stl')

pocket = Part.makeBox(80, 60, 20).cut(Part.makeBox(40, 30, 10, V(20, 15, 10)))
write(pocket.removeSplitter(), 'pocket.stl')
