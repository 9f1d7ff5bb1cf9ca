# Run by FreeCAD's command line (freecadcmd export_outline.py OUT.dxf): a slot outline of
# lines and arcs and three drill circles, exported by FreeCAD's own DXF writer. FreeCAD names
# each layer after the object's name and gives every layer the line type CONTINUOUS.
import sys

import FreeCAD
import Import
import Part
from FreeCAD import Vector as V

out = [a for a in sys.argv if a.endswith(".dxf")][-1]
doc = FreeCAD.newDocument("millpath")
quarter = 1.5707963267948966
edges = [
    Part.LineSegment(V(0, 0, 0), V(40, 0, 0)).toShape(),
    Part.ArcOfCircle(Part.Circle(V(40, 10, 0), V(0, 0, 1), 10), -quarter, 0.0).toShape(),
    Part.LineSegment(V(50, 10, 0), V(50, 30, 0)).toShape(),
    Part.ArcOfCircle(Part.Circle(V(40, 30, 0), V(0, 0, 1), 10), 0.0, quarter).toShape(),
    Part.LineSegment(V(40, 40, 0), V(0, 40, 0)).toShape(),
    Part.LineSegment(V(0, 40, 0), V(0, 0, 0)).toShape(),
]
circles = [Part.Circle(V(x, 10, 0), V(0, 0, 1), 1).toShape() for x in (10, 20, 30)]
# one object, so one layer: FreeCAD names the layer after the object
part = doc.addObject("Part::Feature", "P7001_1P")
part.Shape = Part.Compound([Part.Wire(edges)] + circles)
doc.recompute()
Import.writeDXFObject([part], out, 14, True)
print("exported", out)
