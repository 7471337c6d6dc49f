#!/usr/bin/env python3
"""Read a .vtp written by tortuosity with VTK's own reader (vtkXMLPolyDataReader) and
compare every array with the table the same command writes.

  vtk-roundtrip.py profile FILE.vtp FILE.tsv   point arrays against 'profile' columns
  vtk-roundtrip.py metrics FILE.vtp FILE.tsv   cell arrays against 'metrics' rows
  vtk-roundtrip.py vmtk FILE.vtp FILE.tsv      the default names (VMTK's), Radius, a threshold on rate

The tables print 9 significant digits, the .vtp keeps doubles: numbers must agree to
1e-8 relative, an empty field must be NaN, strings must be equal. Exit status 0 when
everything agrees; otherwise the first difference is printed."""
import csv
import math
import sys

import vtk

# Statuses whose rows have samples (pipeline.h); the others' cells are their data polylines.
WITH_SAMPLES = {"ok", "endpoints-coincide", "all-filtered"}
TEXT_COLUMNS = {"file", "vessel", "status"}


def read_vtp(path):
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        sys.exit(f"{path}: VTK cannot read it")
    return reader.GetOutput()


def read_tsv(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f, delimiter="\t", quoting=csv.QUOTE_NONE)]
    header = rows[0]
    return [dict(zip(header, r)) for r in rows[1:] if r]


def same(text, value, where):
    if text == "":
        ok = math.isnan(value)
    else:
        x = float(text)
        ok = not math.isnan(value) and abs(value - x) <= 1e-8 * max(1.0, abs(x))
    if not ok:
        sys.exit(f"{where}: table {text!r}, VTK {value!r}")


def check_profile(poly, rows):
    n = poly.GetNumberOfPoints()
    if n != len(rows):
        sys.exit(f"{n} points in the .vtp, {len(rows)} rows in the table")
    if poly.GetNumberOfCells() != 1 or poly.GetCell(0).GetNumberOfPoints() != n:
        sys.exit("expected one polyline through every point")
    pd = poly.GetPointData()
    arrays = {  # VTK array -> table columns, one per component
        "arc_length": ["s"], "curvature": ["kappa"], "torsion": ["tau"], "speed": ["speed"],
        "tangent": ["Tx", "Ty", "Tz"], "normal": ["Nx", "Ny", "Nz"], "binormal": ["Bx", "By", "Bz"],
        "in_window": ["in_range"], "reconstruction": ["X", "Y", "Z"], "reconstruction_error": ["err"],
    }
    checked = 0
    for name, columns in arrays.items():
        a = pd.GetArray(name)
        if a is None or a.GetNumberOfTuples() != n or a.GetNumberOfComponents() != len(columns):
            sys.exit(f"point array {name}: missing or of the wrong shape")
        for j, row in enumerate(rows):
            for c, col in enumerate(columns):
                same(row[col], a.GetComponent(j, c), f"point {j} {name}[{c}]")
                checked += 1
    pts = poly.GetPoints()
    for j, row in enumerate(rows):
        p = pts.GetPoint(j)
        for c, col in enumerate("xyz"):
            same(row[col], p[c], f"point {j} coordinate {col}")
            checked += 1
    frame = pd.GetArray("frame_defined")
    for j, row in enumerate(rows):
        if frame.GetValue(j) != (row["tau"] != ""):
            sys.exit(f"point {j}: frame_defined {frame.GetValue(j)} but tau {row['tau']!r}")
    return checked


def check_metrics(poly, rows):
    # Every row is a cell: the samples where it has them, else its data polyline (n_data points).
    if poly.GetNumberOfCells() != len(rows):
        sys.exit(f"{poly.GetNumberOfCells()} cells in the .vtp, {len(rows)} rows in the table")
    cd = poly.GetCellData()
    checked = 0
    for i, row in enumerate(rows):
        want = int(row["n"]) if row["status"] in WITH_SAMPLES else int(row["n_data"])
        if poly.GetCell(i).GetNumberOfPoints() != want:
            sys.exit(f"cell {i} ({row['status']}): {poly.GetCell(i).GetNumberOfPoints()} points, expected {want}")
        for col, text in row.items():
            if col == "rate":       # a number to threshold (factor, points per mm, 0 for raw) and its text
                label = cd.GetAbstractArray("rate_label")
                if label is None or label.GetValue(i) != text:
                    sys.exit(f"cell {i} rate_label: table {text!r}")
                number = 0.0 if text == "raw" else float(text.replace("/mm", ""))
                same(repr(number), cd.GetArray("rate").GetValue(i), f"cell {i} rate")
                checked += 1
                continue
            a = cd.GetAbstractArray(col)
            if a is None:
                sys.exit(f"no cell array {col}")
            if col in TEXT_COLUMNS:
                if a.GetValue(i) != text:
                    sys.exit(f"cell {i} {col}: table {text!r}, VTK {a.GetValue(i)!r}")
            else:
                same(text, a.GetValue(i), f"cell {i} {col}")
            checked += 1
    return checked


def check_vmtk(poly, rows):
    """The default names on vessels with radii: VMTK's array names, a Radius array, and
    vtkThreshold on the numeric rate keeps exactly the cells of one rate."""
    pd = poly.GetPointData()
    for name in ("Abscissas", "Curvature", "Torsion", "FrenetTangent", "FrenetNormal", "FrenetBinormal",
                 "Radius"):
        if pd.GetArray(name) is None:
            sys.exit(f"no point array {name}")
    for name in ("curvature", "torsion", "tangent", "normal", "binormal", "arc_length"):
        if pd.GetArray(name) is not None:
            sys.exit(f"point array {name} under its own name too")
    r_min = min(float(r["r_min"]) for r in rows)
    lo, hi = pd.GetArray("Radius").GetRange()
    if lo < r_min - 1e-12:
        sys.exit(f"Radius {lo} below the data's r_min {r_min}")
    want = sum(1 for r in rows if r["rate"] == "10" and r["status"] in WITH_SAMPLES)
    th = vtk.vtkThreshold()
    th.SetInputData(poly)
    th.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_CELLS, "rate")
    th.SetLowerThreshold(10)
    th.SetUpperThreshold(10)
    th.SetThresholdFunction(vtk.vtkThreshold.THRESHOLD_BETWEEN)
    th.Update()
    got = th.GetOutput().GetNumberOfCells()
    labels = th.GetOutput().GetCellData().GetAbstractArray("rate_label")
    if got != want or any(labels.GetValue(i) != "10" for i in range(got)):
        sys.exit(f"threshold rate = 10: {got} cells, the table has {want} rows at 10X")
    return got


def main():
    mode, vtp, tsv = sys.argv[1:4]
    if mode == "vmtk":
        poly, rows = read_vtp(vtp), read_tsv(tsv)
        print(f"{vtp}: {check_vmtk(poly, rows)} cells at 10X by threshold, VMTK's names, Radius")
        return
    poly, rows = read_vtp(vtp), read_tsv(tsv)
    checked = check_profile(poly, rows) if mode == "profile" else check_metrics(poly, rows)
    print(f"{vtp}: {poly.GetNumberOfPoints()} points, {poly.GetNumberOfCells()} cells, {checked} values agree")


if __name__ == "__main__":
    main()
