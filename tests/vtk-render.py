#!/usr/bin/env python3
"""A .vtp of 'metrics' as a ParaView or Slicer user first sees it: the active point scalar is the
curvature of the metrics' window, so that the default colour range is the window's, at every rate;
and the file renders, offscreen, in colour (under xvfb-run: VTK's X window needs a server).

  vtk-render.py FILE.vtp FILE.tsv    the .vtp and the table of the same 'metrics' command

Exit status 0 when all holds; otherwise what does not is printed."""
import csv
import math
import sys

import vtk
from vtk.util import numpy_support

import numpy as np


def main(vtp, tsv):
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(vtp)
    reader.Update()
    data = reader.GetOutput()
    with open(tsv, newline="") as f:
        rows = [r for r in csv.reader(f, delimiter="\t", quoting=csv.QUOTE_NONE) if r][1:]
    if data.GetNumberOfCells() != len(rows):
        return "%d cells for %d rows of the table" % (data.GetNumberOfCells(), len(rows))
    scalars = data.GetPointData().GetScalars()
    if scalars is None or scalars.GetName() != "curvature_in_window":
        return "the active point scalar is %s, not curvature_in_window" % (scalars and scalars.GetName())
    active = numpy_support.vtk_to_numpy(scalars)
    kappa = numpy_support.vtk_to_numpy(data.GetPointData().GetArray("Curvature"))
    window = numpy_support.vtk_to_numpy(data.GetPointData().GetArray("in_window")) == 1
    rate = numpy_support.vtk_to_numpy(data.GetCellData().GetArray("rate"))
    points_of = {}                                   # rate -> the point ids of its cells
    ids = vtk.vtkIdList()
    for c in range(data.GetNumberOfCells()):
        data.GetCellPoints(c, ids)
        points_of.setdefault(float(rate[c]), []).extend(ids.GetId(i) for i in range(ids.GetNumberOfIds()))
    for r, pts in sorted(points_of.items()):
        pts = np.array(pts)
        a, inside = active[pts], window[pts]
        if np.any(np.isfinite(a) != inside) or np.any(a[inside] != kappa[pts][inside]):
            return "rate %g: the active scalar is not the curvature in the window and NaN outside" % r
        if inside.any():
            lo, hi = np.nanmin(a), np.nanmax(a)
            whole = (np.nanmin(kappa[pts]), np.nanmax(kappa[pts]))
            print("rate %g: colour range %.4g..%.4g /mm (the window's), all samples %.4g..%.4g" % (r, lo, hi, *whole))
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(data)
    mapper.SetScalarModeToUsePointData()
    mapper.SetScalarRange(scalars.GetRange())                  # what ParaView's colour map takes
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    renderer.ResetCamera()
    window_ = vtk.vtkRenderWindow()
    window_.SetOffScreenRendering(1)
    window_.AddRenderer(renderer)
    window_.SetSize(400, 400)
    window_.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window_)
    grab.Update()
    pixels = numpy_support.vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars())
    drawn = pixels[pixels.sum(axis=1) > 0]
    colours = len({tuple(p) for p in drawn})
    print("rendered: %d pixels drawn in %d colours" % (len(drawn), colours))
    if len(drawn) < 100 or colours < 10:
        return "the rendering is empty or of one colour"
    return None


if __name__ == "__main__":
    problem = main(sys.argv[1], sys.argv[2])
    if problem:
        sys.exit(problem)
