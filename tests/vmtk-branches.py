#!/usr/bin/python3
"""--vmtk-branches on files as VMTK's branch extractor leaves them, written by VTK itself.

Four tracts in one polydata, with the cell arrays vmtkbranchextractor adds: two tracts
of group 0 (two centerlines through one branch, 0.05 mm apart), a blanked tract of
group 1 (a bifurcation) and a tract of group 2; the same with a vertex cell first
(cell data run over vertices, then lines). Each as .vtp and legacy .vtk. With the
option, tortuosity must give one vessel per group that is not blanked, from the
group's first tract, with that tract's numbers; without GroupIds it must refuse.

  vmtk-branches.py path/to/tortuosity WORKDIR      (exit 1 at the first disagreement)
"""
import math
import os
import subprocess
import sys

import vtk

tortuosity, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)


def polydata(with_vertex, with_groups=True):
    pts, lines, verts = vtk.vtkPoints(), vtk.vtkCellArray(), vtk.vtkCellArray()
    arrays = {name: cls() for name, cls in (("CenterlineIds", vtk.vtkIntArray), ("TractIds", vtk.vtkIntArray),
                                            ("GroupIds", vtk.vtkIdTypeArray), ("Blanking", vtk.vtkIntArray))}
    for name, a in arrays.items():
        a.SetName(name)
    helix = [(4 * math.cos(0.1 * i), 4 * math.sin(0.1 * i), 0.2 * i) for i in range(40)]
    if with_vertex:
        verts.InsertNextCell(1)
        verts.InsertCellPoint(pts.InsertNextPoint(0, 0, 0))
        for name, value in (("CenterlineIds", 0), ("TractIds", 0), ("GroupIds", 99), ("Blanking", 0)):
            arrays[name].InsertNextValue(value)
    for group, blanked, line, shift in ((0, 0, 0, 0.0), (0, 0, 1, 0.05), (1, 1, 0, 0.0), (2, 0, 1, 0.0)):
        points = [(x + shift + 10 * group, y, z) for x, y, z in helix[:20 + 5 * group]]
        lines.InsertNextCell(len(points))
        for p in points:
            lines.InsertCellPoint(pts.InsertNextPoint(*p))
        for name, value in (("CenterlineIds", line), ("TractIds", group), ("GroupIds", group), ("Blanking", blanked)):
            arrays[name].InsertNextValue(value)
    p = vtk.vtkPolyData()
    p.SetPoints(pts)
    p.SetLines(lines)
    if with_vertex:
        p.SetVerts(verts)
    for name, a in arrays.items():
        if with_groups or name != "GroupIds":
            p.GetCellData().AddArray(a)
    return p


def write(p, path):
    w = vtk.vtkXMLPolyDataWriter() if path.endswith(".vtp") else vtk.vtkPolyDataWriter()
    w.SetFileName(path)
    w.SetInputData(p)
    if not w.Write():
        sys.exit("VTK could not write " + path)


def rows(*args):
    run = subprocess.run([tortuosity, "metrics", "-q", "--rates", "10", *args], capture_output=True, text=True)
    if run.returncode != 0:
        return run.returncode, run.stderr
    lines = [line.split("\t") for line in run.stdout.splitlines()]
    return 0, [dict(zip(lines[0], r)) for r in lines[1:]]


failed = 0
for with_vertex in (False, True):
    for ext in ("vtp", "vtk"):
        path = os.path.join(out, "branches%s.%s" % ("-vertex" if with_vertex else "", ext))
        write(polydata(with_vertex), path)
        _, grouped = rows("--vmtk-branches", path)
        _, tracts = rows(path)
        want = [("group 0", "20"), ("group 2", "30")]
        got = [(r["vessel"], r["n_data"]) for r in grouped]
        first = next(r for r in tracts if r["n_data"] == "20")   # the first tract of group 0
        same = {k: v for k, v in grouped[0].items() if k != "vessel"} == {k: v for k, v in first.items()
                                                                          if k != "vessel"}
        problem = None if got == want and same and len(tracts) == 4 else "got %s (want %s), same numbers as the " \
            "first tract: %s, %d tracts without the option" % (got, want, same, len(tracts))
        print(("ok   " if not problem else "FAIL ") + path + ("" if not problem else ": " + problem))
        failed += problem is not None
for ext in ("vtp", "vtk"):
    path = os.path.join(out, "no-groups.%s" % ext)
    write(polydata(False, with_groups=False), path)
    status, message = rows("--vmtk-branches", path)
    problem = None if status == 2 and "GroupIds" in message else "exit %s, %r" % (status, message)
    print(("ok   " if not problem else "FAIL ") + path + " refused without GroupIds" + ("" if not problem else ": " + problem))
    failed += problem is not None
sys.exit(1 if failed else 0)
