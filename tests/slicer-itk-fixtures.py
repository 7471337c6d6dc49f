#!/usr/bin/env python3
"""Three analytic vessels written as 3D Slicer and ITK/TubeTK write centerlines, for the
readers of .mrk.json and .tre files to be tested against a plain-text reference.

  slicer-itk-fixtures.py OUTDIR

The reference (vessels.txt, 'x y z r' lines, a blank line between vessels) is in LPS
millimetres, the frame of ITK physical space and of Slicer's default markups files:
  - vessels-lps.mrk.json holds the same numbers; vessels-ras.mrk.json has x and y negated.
    Layout of Slicer 5.0 to 5.12 (vtkMRMLMarkupsJsonStorageNode, rapidjson PrettyWriter):
    Slicer writes one markup per file but reads every item of "markups"; the radius is the
    "Radius" measurement's controlPointValues, as SlicerVMTK's Extract Centerline adds it.
    Numbers are rapidjson's shortest round-trip form ("1.0", "-0.0", "1e-7").
  - the .tre files are ITK 5.4 SpatialObjectWriter output of a GroupSpatialObject (ID 0)
    holding TubeSpatialObjects: a Scene, the Group, then the Tubes (ParentID links them).
    Numbers have 6 significant digits (MetaSceneConverter sets precision 6) and points are
    float32, so the tubes give the reference back to ~1e-5 mm, not exactly.
    A point's world position is, from the tube up to the root, p <- M p + Offset per
    object, with p first scaled by ElementSpacing; M is TransformMatrix read row by row;
    CenterOfRotation plays no part (Offset is the whole translation).  Radius: r times
    ElementSpacing[0]; rotations leave it as stored.
  - vessels-itk4.tre is the ITK 4 / old TubeTK layout (other PointDim, no Artery line,
    points in index units with ElementSpacing 0.5)."""
import decimal
import json
import math
import os
import sys

import numpy as np

out = sys.argv[1]
os.makedirs(out, exist_ok=True)


def vessels():
    t = np.linspace(0.0, 10.0, 60)
    helix = np.column_stack([4 * np.cos(t), 4 * np.sin(t), 2 * t, np.full(60, 0.5)])
    s = np.linspace(0.0, 2.0, 30)                       # 5 mm arc over 2 rad, in z = 0
    arc = np.column_stack([5 * np.cos(s), 5 * np.sin(s), np.zeros(30), np.full(30, 0.3)])
    i = np.arange(7.0)                                  # x and z cross 0: signed zeros
    line = np.column_stack([-3 + i, 1 + 0.5 * i, 2 - i, np.full(7, 0.4)])
    return [("helix", helix), ("arc", arc), ("line", line)]


VESSELS = vessels()


def emit(name, data, what):
    path = os.path.join(out, name)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())
    print(f"{path}: {what}")


emit("vessels.txt", "\n".join("".join(" ".join(repr(float(v)) for v in p) + "\n" for p in pts)
                              for _, pts in VESSELS),
     "reference, LPS, " + ", ".join(f"{n} {len(p)} points" for n, p in VESSELS))

# ---- Slicer markups JSON -------------------------------------------------------------
class Line(list):
    """An array rapidjson writes on one line (vtkMRMLJsonWriter's WriteVector)."""


def rj_double(v):
    """rapidjson Writer::Double: Grisu2 digits, then Prettify's layout."""
    v = float(v)
    if v == 0.0:
        return "-0.0" if math.copysign(1.0, v) < 0 else "0.0"
    _, digits, k = decimal.Decimal(repr(abs(v))).normalize().as_tuple()
    ds, sign = "".join(map(str, digits)), "-" if v < 0 else ""
    n = len(ds)
    kk = n + k                                          # 10^(kk-1) <= |v| < 10^kk
    if 0 <= k and kk <= 21:
        s = ds + "0" * k + ".0"
    elif 0 < kk <= 21:
        s = ds[:kk] + "." + ds[kk:]
    elif -6 < kk <= 0:
        s = "0." + "0" * -kk + ds
    else:
        s = (ds if n == 1 else ds[0] + "." + ds[1:]) + "e" + str(kk - 1)
    return sign + s


def rj(v, level=0):
    """rapidjson PrettyWriter: 4-space indent, ": " after keys, no final newline."""
    pad, inner = "    " * level, "    " * (level + 1)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return rj_double(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, Line):
        return "[" + ", ".join(rj(x) for x in v) + "]"
    if isinstance(v, list):
        return "[]" if not v else \
            "[\n" + ",\n".join(inner + rj(x, level + 1) for x in v) + "\n" + pad + "]"
    return "{\n" + ",\n".join(inner + json.dumps(k) + ": " + rj(x, level + 1)
                             for k, x in v.items()) + "\n" + pad + "}"


def markup(name, pts, lps):
    # Slicer holds RAS; the reference is LPS, so RAS = (-x, -y, z) and the LPS writer
    # negates x and y back (and the first six entries of each orientation matrix).
    ident = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    orient = Line([-a for a in ident[:6]] + ident[6:]) if lps else Line(ident)
    cps = [{"id": str(i + 1), "label": f"{name}-{i + 1}", "description": "",
            "associatedNodeID": "",
            "position": Line([float(p[0]), float(p[1]), float(p[2])] if lps else
                             [float(-p[0]), float(-p[1]), float(p[2])]),
            "orientation": orient, "selected": True, "locked": False, "visibility": True,
            "positionStatus": "defined"} for i, p in enumerate(pts)]
    off = {"enabled": False, "printFormat": "%5.3f %s"}    # curve measurements, disabled
    meas = [{"name": "length", "enabled": False, "units": "mm", "printFormat": "%-#4.4g%s"}] + \
        [{"name": n, **off} for n in ("curvature mean", "curvature max", "torsion mean",
                                      "torsion max")] + \
        [{"name": "Radius", "enabled": True, "units": "mm",
          "controlPointValues": [float(p[3]) for p in pts]}]
    display = {                                 # vtkMRMLMarkupsDisplayNode's defaults
        "visibility": True, "opacity": 1.0, "color": Line([0.4, 1.0, 1.0]),
        "selectedColor": Line([1.0, 0.5, 0.5]), "activeColor": Line([0.4, 1.0, 0.0]),
        "propertiesLabelVisibility": True, "pointLabelsVisibility": False, "textScale": 3.0,
        "glyphType": "Sphere3D", "glyphScale": 3.0, "glyphSize": 5.0, "useGlyphScale": True,
        "sliceProjection": False, "sliceProjectionUseFiducialColor": True,
        "sliceProjectionOutlinedBehindSlicePlane": False,
        "sliceProjectionColor": Line([1.0, 1.0, 1.0]), "sliceProjectionOpacity": 0.6,
        "lineThickness": 0.2, "lineColorFadingStart": 1.0, "lineColorFadingEnd": 10.0,
        "lineColorFadingSaturation": 1.0, "lineColorFadingHueOffset": 0.0,
        "handlesInteractive": False, "translationHandleVisibility": True,
        "rotationHandleVisibility": True, "scaleHandleVisibility": False,
        "interactionHandleScale": 3.0, "snapMode": "toVisibleSurface"}
    return {"type": "Curve", "coordinateSystem": "LPS" if lps else "RAS",
            "coordinateUnits": "mm", "locked": False, "fixedNumberOfControlPoints": False,
            "labelFormat": "%N-%d", "lastUsedControlPointNumber": len(pts),
            "controlPoints": cps, "measurements": meas, "display": display}


SCHEMA = ("https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/"
          "Markups/Resources/Schema/markups-schema-v1.0.3.json#")
for frame, lps in (("lps", True), ("ras", False)):
    doc = {"@schema": SCHEMA, "markups": [markup(n, p, lps) for n, p in VESSELS]}
    emit(f"vessels-{frame}.mrk.json", rj(doc),
         f"3 Curve markups, coordinateSystem {frame.upper()}, radius as 'Radius' measurement")

# ---- ITK MetaIO scenes ---------------------------------------------------------------
I3 = np.eye(3)
POINTDIM5 = ("id x y z red green blue alpha mark r rn mn bn cv lv ro in "
             "tx ty tz v1x v1y v1z v2x v2y v2z a1 a2 a3")
POINTDIM4 = "x y z r v1x v1y v1z v2x v2y v2z tx ty tz red green blue alpha id"
COLORS = {"helix": (1, 0, 0, 1), "arc": (0, 1, 0, 1), "line": (0, 0, 1, 1)}


def g6(v):
    return "%.6g" % float(v)                  # std::ostream, precision 6, general format


def obj(otype, oid, parent=-1, name="", M=I3, off=(0, 0, 0), cen=(0, 0, 0), spacing=1.0,
        pts=None, itk4=False, color=(1, 1, 1, 1)):
    return dict(otype=otype, oid=oid, parent=parent, name=name, M=np.asarray(M, float),
                off=off, cen=cen, spacing=spacing, pts=pts, itk4=itk4, color=color)


def meta_object(o, binary):
    h = [f"ObjectType = {o['otype']}", "NDims = 3"]   # MetaObject::M_SetupWriteFields order
    h += [f"Name = {o['name']}"] * bool(o["name"]) + [f"ID = {o['oid']}"] * (o["oid"] >= 0)
    h += [f"ParentID = {o['parent']}"] * (o["parent"] >= 0)
    if any(c != 1 for c in o["color"]):                # Color only when not white
        h.append("Color = " + " ".join(g6(c) for c in o["color"]))
    h += ["BinaryData = True", "BinaryDataByteOrderMSB = False", "CompressedData = False"] \
        if binary else ["BinaryData = False"]
    h.append("TransformMatrix = " + " ".join(g6(m) for m in o["M"].reshape(-1)))  # row-major
    h.append("Offset = " + " ".join(g6(v) for v in o["off"]))
    h.append("CenterOfRotation = " + " ".join(g6(v) for v in o["cen"]))
    h.append("ElementSpacing = " + " ".join([g6(o["spacing"])] * 3))
    if o["otype"] == "Group":
        return ("\n".join(h) + "\nEndGroup = \n").encode()
    pts = np.asarray(o["pts"], float) / o["spacing"]   # index units when spacing != 1
    z = np.zeros(len(pts))
    ids, ones = np.arange(len(pts), dtype=float), np.ones(len(pts))  # point colour 1 0 0 1
    if o["itk4"]:                                      # ITK 4: no Artery, fixed order
        h += ["Root = False", f"PointDim = {POINTDIM4}"]
        cols = [pts[:, 0], pts[:, 1], pts[:, 2], pts[:, 3]] + [z] * 9 + [ones, z, z, ones, ids]
    else:
        h += ["Root = False", "Artery = True", f"PointDim = {POINTDIM5}"]
        cols = [ids, pts[:, 0], pts[:, 1], pts[:, 2], ones, z, z, ones, z, pts[:, 3]] + [z] * 19
    h += [f"NPoints = {len(pts)}", "Points = "]
    rows = np.column_stack(cols).astype("<f4")        # TubePnt fields are float
    if binary:                                         # little-endian float32, then "\n"
        body = rows.tobytes() + b"\n"
    else:                                  # each value and a space (ints print the same)
        body = "".join("".join(g6(v) + " " for v in r) + "\n" for r in rows).encode()
    return ("\n".join(h) + "\n").encode() + body


def write_tre(name, objects, what, binary=False):
    scene = f"ObjectType = Scene\nNDims = 3\nNObjects = {len(objects)}\n".encode()
    emit(name, scene + b"".join(meta_object(o, binary) for o in objects), what)


def inverse(pts, M, off):
    """The points that M p + off maps onto pts (radius unchanged)."""
    q = pts.copy()
    q[:, :3] = (pts[:, :3] - np.asarray(off, float)) @ np.asarray(M, float)  # M^T (p - off)
    return q


def tubes(transform=None, **kw):
    M, off, cen = transform or (I3, (0, 0, 0), (0, 0, 0))
    return [obj("Tube", k + 1, 0, n, M, off, cen, pts=inverse(p, M, off), color=COLORS[n], **kw)
            for k, (n, p) in enumerate(VESSELS)]


RZ = np.array([[0.6, -0.8, 0], [0.8, 0.6, 0], [0, 0, 1]])  # exact in 6 digits; not symmetric
RX = np.array([[1, 0, 0], [0, 0.6, -0.8], [0, 0.8, 0.6]])
RY = np.array([[0.8, 0, 0.6], [0, 1, 0], [-0.6, 0, 0.8]])
GROUP = obj("Group", 0)

write_tre("vessels.tre", [GROUP] + tubes(), "ITK 5.4 scene, Group + 3 Tubes, ASCII, identity")
write_tre("vessels-transformed.tre", [GROUP] + tubes((RZ, (10, -20, 5), (1, 2, 3))),
          "ITK 5.4, each Tube rotated about z, Offset 10 -20 5, CenterOfRotation 1 2 3")
write_tre("vessels-binary.tre", [GROUP] + tubes(), "ITK 5.4, BinaryData: little-endian float32 points",
          binary=True)

# Child chain: Group (G) -> helix (T1) -> arc (T2), Group -> line; world = G T1 T2 p.
G, T1, T2 = (RZ, (10, -20, 5)), (RX, (0, 3, -4)), (RY, (-2, 0, 1))
(_, helix), (_, arc), (_, line) = VESSELS


def up_g(p):                                           # world -> the Group's frame
    return inverse(p, *G)


def up_g1(p):                                          # world -> helix's frame
    return inverse(up_g(p), *T1)


write_tre("vessels-child.tre",
          [obj("Group", 0, -1, "", *G),
           obj("Tube", 1, 0, "helix", *T1, pts=up_g1(helix), color=COLORS["helix"]),
           obj("Tube", 2, 1, "arc", *T2, pts=inverse(up_g1(arc), *T2), color=COLORS["arc"]),
           obj("Tube", 3, 0, "line", pts=up_g(line), color=COLORS["line"])],
          "ITK 5.4, arc's parent is helix, helix's and line's the Group; 3 transforms compose")
write_tre("vessels-itk4.tre", [GROUP] + tubes(spacing=0.5, itk4=True),
          "ITK 4.13 / old TubeTK layout, ElementSpacing 0.5 (points and r in index units)")
