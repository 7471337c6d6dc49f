#!/usr/bin/env python3
"""Write one polydata (three polylines of 5, 7 and 4 points on a helix, a vertex and a
triangle that must be ignored, a radius and other point arrays) in every encoding VTK's
own writers produce, read each file with tortuosity, and compare with what VTK reads:
the number of points of each vessel, its length and chord ratio (from every coordinate),
its minimum and mean radius.

  vtk-fixtures.py path/to/tortuosity WORKDIR

Prints one line per file and exits 1 at the first disagreement."""
import math
import os
import subprocess
import sys

import vtk

tortuosity, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
written = []


def make(point_type=vtk.VTK_DOUBLE, radius_as_scalars=False):
    pts = vtk.vtkPoints()
    pts.SetDataType(point_type)
    radius = vtk.vtkDoubleArray(); radius.SetName("MaximumInscribedSphereRadius")
    other = vtk.vtkFloatArray(); other.SetName("Other"); other.SetNumberOfComponents(2)
    typed = {}   # one point array per integer type, the radius scaled to fit
    for name, cls in [("r_Int8", vtk.vtkSignedCharArray), ("r_UInt8", vtk.vtkUnsignedCharArray),
                      ("r_Int16", vtk.vtkShortArray), ("r_UInt16", vtk.vtkUnsignedShortArray),
                      ("r_Int32", vtk.vtkIntArray), ("r_UInt32", vtk.vtkUnsignedIntArray),
                      ("r_Int64", vtk.vtkTypeInt64Array), ("r_UInt64", vtk.vtkTypeUInt64Array),
                      ("r_Float32", vtk.vtkFloatArray)]:
        a = cls(); a.SetName(name); typed[name] = a
    lines = vtk.vtkCellArray()
    k = 0
    for cell, n in enumerate([5, 7, 4]):
        lines.InsertNextCell(n)
        for i in range(n):
            t = 0.37 * k + cell
            x, y, z = 10.0 * math.cos(t) + cell / 3.0, 10.0 * math.sin(t) - 1 / 7.0, 1.1 * t
            if point_type in (vtk.VTK_SHORT, vtk.VTK_INT):
                x, y, z = round(x * 100), round(y * 100), round(z * 100)
            pts.InsertNextPoint(x, y, z)
            r = 1.0 + 0.1 * math.sin(3.1 * t) + k / 31.0
            radius.InsertNextValue(r)
            other.InsertNextTuple2(k * 0.5, -k)
            for name, a in typed.items():
                a.InsertNextValue(r if name == "r_Float32" else int(r * 40))
            lines.InsertCellPoint(k)
            k += 1
    verts = vtk.vtkCellArray(); verts.InsertNextCell(1); verts.InsertCellPoint(2)
    polys = vtk.vtkCellArray(); polys.InsertNextCell(3)
    for i in (0, 6, 13): polys.InsertCellPoint(i)
    pd = vtk.vtkPolyData()
    pd.SetPoints(pts); pd.SetLines(lines); pd.SetVerts(verts); pd.SetPolys(polys)
    pd.GetPointData().AddArray(other)
    for a in typed.values(): pd.GetPointData().AddArray(a)
    if radius_as_scalars:
        pd.GetPointData().SetScalars(radius)
    else:
        pd.GetPointData().AddArray(radius)
    return pd

def xml(name, pd, mode, compress=False, header64=False, big=False, encode=True, idtype32=False, pieces=1):
    w = vtk.vtkXMLPolyDataWriter()
    w.SetFileName(os.path.join(out, name))
    if pieces > 1:   # split the cells so that the pieces differ (and renumber their points)
        split = vtk.vtkExtractPolyDataPiece(); split.SetInputData(pd); split.CreateGhostCellsOff()
        w.SetInputConnection(split.GetOutputPort())
    else:
        w.SetInputData(pd)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary,
     "appended": w.SetDataModeToAppended}[mode]()
    if compress:   # True: zlib; or "lz4", "lzma"
        {True: w.SetCompressorTypeToZLib, "lz4": w.SetCompressorTypeToLZ4,
         "lzma": w.SetCompressorTypeToLZMA}[compress]()
        w.SetBlockSize(64)
    else:
        w.SetCompressorTypeToNone()
    w.SetHeaderTypeToUInt64() if header64 else w.SetHeaderTypeToUInt32()
    w.SetByteOrderToBigEndian() if big else w.SetByteOrderToLittleEndian()
    w.SetEncodeAppendedData(1 if encode else 0)
    if idtype32: w.SetIdTypeToInt32()
    w.SetNumberOfPieces(pieces)
    if not w.Write(): raise SystemExit("write failed: " + name)
    written.append(name)

def legacy(name, pd, binary, version=None):
    w = vtk.vtkPolyDataWriter()
    w.SetFileName(os.path.join(out, name))
    w.SetInputData(pd)
    w.SetFileTypeToBinary() if binary else w.SetFileTypeToASCII()
    if version: w.SetFileVersion(version)
    if not w.Write(): raise SystemExit("write failed: " + name)
    written.append(name)

def with_attributes(pd, color=False):
    """Every legacy attribute kind, in point and cell data, for the reader to skip;
    color: the cell scalars are RGBA bytes (COLOR_SCALARS) instead of a float with a lookup table."""
    n, nc = pd.GetNumberOfPoints(), pd.GetNumberOfCells()
    def arr(cls, name, comps, count, f):
        a = cls(); a.SetName(name); a.SetNumberOfComponents(comps)
        for i in range(count): a.InsertNextTuple([f(i, c) for c in range(comps)])
        return a
    pt, cd = pd.GetPointData(), pd.GetCellData()
    pt.SetVectors(arr(vtk.vtkDoubleArray, "vec", 3, n, lambda i, c: i + c / 10))
    pt.SetNormals(arr(vtk.vtkFloatArray, "nrm", 3, n, lambda i, c: c == 2))
    pt.SetTCoords(arr(vtk.vtkFloatArray, "tc", 2, n, lambda i, c: i / 16))
    pt.SetTensors(arr(vtk.vtkDoubleArray, "ten", 9, n, lambda i, c: c))
    pt.SetGlobalIds(arr(vtk.vtkIdTypeArray, "gid", 1, n, lambda i, c: 100 + i))
    s = arr(vtk.vtkFloatArray, "cs", 1, nc, lambda i, c: i)
    lut = vtk.vtkLookupTable(); lut.SetNumberOfTableValues(3); lut.Build()
    s.SetLookupTable(lut)
    rgba = arr(vtk.vtkUnsignedCharArray, "rgba", 4, nc, lambda i, c: 10 * i + c)
    if color:
        cd.SetScalars(rgba); cd.AddArray(s)
    else:
        cd.SetScalars(s); cd.AddArray(rgba)
    cd.SetNormals(arr(vtk.vtkFloatArray, "cn", 3, nc, lambda i, c: c == 0))
    return pd

pd = make()
pd32 = make(vtk.VTK_FLOAT)
pdi = make(vtk.VTK_SHORT)
pds = make(radius_as_scalars=True)
xml("ascii.vtp", pd, "ascii")
xml("ascii-f32.vtp", pd32, "ascii")
xml("bin32.vtp", pd, "binary")
xml("bin64.vtp", pd, "binary", header64=True)
xml("binz32.vtp", pd, "binary", compress=True)
xml("binz64.vtp", pd, "binary", compress=True, header64=True)
xml("binbe.vtp", pd, "binary", big=True)
xml("binzbe64.vtp", pd32, "binary", compress=True, header64=True, big=True)
xml("appraw.vtp", pd, "appended", encode=False)
xml("apprawz.vtp", pd, "appended", encode=False, compress=True)
xml("apprawbe.vtp", pd, "appended", encode=False, big=True, header64=True)
xml("apprawzbe.vtp", pd32, "appended", encode=False, compress=True, big=True)
xml("appb64.vtp", pd, "appended")
xml("appb64z.vtp", pd, "appended", compress=True)
xml("appb64z64.vtp", pd32, "appended", compress=True, header64=True)
xml("f32-bin.vtp", pd32, "binary")
xml("int16-points.vtp", pdi, "binary", compress=True, idtype32=True)
xml("int16-points-ascii.vtp", pdi, "ascii", idtype32=True)
xml("id32.vtp", pd, "appended", encode=False, idtype32=True)
xml("pieces2.vtp", pd, "appended", compress=True, pieces=2)
for codec in ("lz4", "lzma"):   # VTK's other compressors, in each mode and header
    xml("bin-%s.vtp" % codec, pd, "binary", compress=codec)
    xml("app-%s-64be.vtp" % codec, pd32, "appended", encode=False, compress=codec, header64=True, big=True)
    xml("appb64-%s.vtp" % codec, pd, "appended", compress=codec)
xml("pieces2-ascii.vtp", pd32, "ascii", pieces=2)
legacy("legacy-ascii.vtk", pd, False)
legacy("legacy-binary.vtk", pd, True)
legacy("legacy-ascii-42.vtk", pd, False, 42)
legacy("legacy-binary-42.vtk", pd, True, 42)
legacy("legacy-scalars-ascii.vtk", pds, False)
legacy("legacy-scalars-binary.vtk", pds, True)
legacy("legacy-scalars-binary-42.vtk", pds, True, 42)
legacy("legacy-f32-binary.vtk", pd32, True)
legacy("legacy-int16-ascii.vtk", pdi, False)
pda = with_attributes(make(radius_as_scalars=True))
legacy("legacy-attrs-ascii.vtk", pda, False)
legacy("legacy-attrs-binary.vtk", pda, True)
legacy("legacy-attrs-binary-42.vtk", pda, True, 42)
xml("attrs.vtp", pda, "appended", compress=True)
pdc = with_attributes(make(), color=True)
legacy("legacy-color-ascii.vtk", pdc, False)
legacy("legacy-color-binary.vtk", pdc, True)


def vtk_vessels(path):
    """Per polyline cell with points: n, L, D, r_min, r_mean, as VTK reads the file."""
    if path.endswith(".vtk"):
        r = vtk.vtkPolyDataReader()
        r.ReadAllScalarsOn(); r.ReadAllFieldsOn()
    else:
        r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    pd = r.GetOutput()
    rad = pd.GetPointData().GetArray("MaximumInscribedSphereRadius")
    ids, rows = vtk.vtkIdList(), []
    lines = pd.GetLines()
    lines.InitTraversal()
    while lines.GetNextCell(ids):
        p = [pd.GetPoint(ids.GetId(j)) for j in range(ids.GetNumberOfIds())]
        r = [rad.GetTuple1(ids.GetId(j)) for j in range(ids.GetNumberOfIds())]
        length = sum(math.dist(p[j - 1], p[j]) for j in range(1, len(p)))
        rows.append((len(p), length, length / math.dist(p[0], p[-1]), min(r), sum(r) / len(r)))
    return rows


def ours(path):
    text = subprocess.run([tortuosity, "metrics", "-q", "--rates", "raw", "--trim", "0", path],
                          capture_output=True, text=True, check=True).stdout.splitlines()
    head = text[0].split("\t")
    col = {name: head.index(name) for name in ("n_data", "L", "D", "r_min", "r_mean")}
    return [tuple(float(f[col[c]]) for c in ("n_data", "L", "D", "r_min", "r_mean"))
            for f in (line.split("\t") for line in text[1:])]


for name in written:
    path = os.path.join(out, name)
    want, got = vtk_vessels(path), ours(path)
    ok = len(want) == len(got) == 3 and all(
        w[0] == g[0] and all(abs(a - b) <= 1e-8 * abs(a) for a, b in zip(w[1:], g[1:])) for w, g in zip(want, got))
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {len(got)} vessels, points {[int(g[0]) for g in got]}")
    if not ok:
        print(f"  VTK:        {want}\n  tortuosity: {got}")
        sys.exit(1)
print(f"vtk-fixtures: {len(written)} files read as VTK reads them")
