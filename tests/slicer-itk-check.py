#!/usr/bin/python3
"""3D Slicer markups and ITK/TubeTK tube files read as the same vessels as plain text.

Writes the fixtures of slicer-itk-fixtures.py (three analytic vessels as Slicer and ITK
write them), reads each with tortuosity, and compares with the plain-text reference:
the raw points (profile --rate raw) and the metrics at 10X. Markups files hold the
reference's numbers exactly, in LPS or RAS, so everything must agree to the byte; tube
files hold 6 significant digits, so points agree within 1e-4 mm, lengths within 1e-4 and
curvature within 1e-3 relative (rounded points bend a 5 mm arc by that much). Then malformed files must be refused with exit status 2 and a message.

  slicer-itk-check.py path/to/tortuosity WORKDIR      (one line per check; exit 1 on failure)
"""
import os
import subprocess
import sys

tortuosity, out = sys.argv[1], sys.argv[2]
here = os.path.dirname(os.path.abspath(__file__))
subprocess.run([sys.executable, os.path.join(here, "slicer-itk-fixtures.py"), out], check=True,
               capture_output=True)
failed = 0


def table(*args):
    run = subprocess.run([tortuosity, *args], capture_output=True, text=True)
    if run.returncode != 0:
        return run.returncode, run.stderr
    lines = [line.split("\t") for line in run.stdout.splitlines() if line]      # profile: blank lines between vessels
    return 0, [dict(zip(lines[0], r)) for r in lines[1:]]


def report(name, problem):
    global failed
    print(("ok   " if not problem else "FAIL ") + name + ("" if not problem else ": " + problem))
    failed += problem is not None


def compare(path, labels, exact):
    _, ref_points = table("profile", "-q", "--rate", "raw", "--vessel", "all", os.path.join(out, "vessels.txt"))
    _, ref_metrics = table("metrics", "-q", "--rates", "10", os.path.join(out, "vessels.txt"))
    status, points = table("profile", "-q", "--rate", "raw", "--vessel", "all", path)
    if status:
        return "exit %d: %s" % (status, points.strip())
    _, metrics = table("metrics", "-q", "--rates", "10", path)
    if [m["vessel"] for m in metrics] != labels:
        return "vessels %s, want %s" % ([m["vessel"] for m in metrics], labels)
    if len(points) != len(ref_points):
        return "%d points, want %d" % (len(points), len(ref_points))
    worst = max(abs(float(p[k]) - float(q[k])) for p, q in zip(points, ref_points) for k in ("x", "y", "z"))
    if worst > (0 if exact else 1e-4):
        return "points differ by up to %g mm" % worst
    for m, r in zip(metrics, ref_metrics):
        for k in ("n_data", "L", "D", "AC", "TC", "r_min", "r_mean", "status"):
            tol = 1e-3 if k in ("AC", "TC") else 1e-4
            same = m[k] == r[k] if exact or k in ("n_data", "status") else \
                abs(float(m[k]) - float(r[k])) <= tol * max(abs(float(r[k])), 1e-3)
            if not same:
                return "vessel %s: %s %s, want %s" % (m["vessel"], k, m[k], r[k])
    return None


for name in ("vessels-lps.mrk.json", "vessels-ras.mrk.json"):
    report(name + ": the reference's points and metrics, to the byte", compare(os.path.join(out, name),
                                                                                ["1", "2", "3"], True))
for name in ("vessels.tre", "vessels-transformed.tre", "vessels-binary.tre", "vessels-child.tre",
             "vessels-itk4.tre"):
    report(name + ": the reference's points within 1e-4 mm, its metrics", compare(os.path.join(out, name), ["helix", "arc", "line"], False))

bad = {
    "broken.mrk.json": ('{"markups": [\n  {"type": "Curve",\n   "controlPoints": [}\n]}', "broken.mrk.json:3:"),
    "fiducials.mrk.json": ('{"markups": [{"type": "Fiducial", "controlPoints": []}]}', "no Curve markup"),
    "frame.mrk.json": ('{"markups": [{"type": "Curve", "coordinateSystem": "XYZ", "controlPoints": []}]}',
                       "coordinateSystem"),
    "position.mrk.json": ('{"markups": [{"type": "Curve", "controlPoints": [{"position": [1, 2]}]}]}',
                          "position is not 3 numbers"),
    "loop.tre": ("ObjectType = Tube\nNDims = 3\nID = 1\nParentID = 2\nPointDim = x y z r\nNPoints = 2\nPoints = \n"
                 "0 0 0 1\n1 0 0 1\nObjectType = Group\nNDims = 3\nID = 2\nParentID = 1\n", "loop"),
    "short.tre": ("ObjectType = Tube\nNDims = 3\nPointDim = x y z r\nNPoints = 2\nPoints = \n0 0 0 1\n1 0 0\n"
                  "2 0 0 1\n3 0 0 1\n", "short.tre:7: expected 4 values"),
    "few.tre": ("ObjectType = Tube\nNDims = 3\nPointDim = x y z r\nNPoints = 100\nPoints = \n0 0 0 1\n",
                "the file ends before"),
    "twice.tre": ("ObjectType = Tube\nNDims = 3\nPointDim = x y z r\nNPoints = 1\nPoints = \n0 0 0 1\n"
                  "Points = \n0 0 0 1\n", "a second Points block"),
    "msb.tre": ("ObjectType = Tube\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = True\n", "big-endian"),
    "extra.tre": ("ObjectType = Tube\nNDims = 3\nPointDim = x y z r\nNPoints = 1\nPoints = \n0 0 0 1\n"
                  "1 0 0 1\n", "extra.tre:7: a point after the NPoints points"),
    "noxyz.tre": ("ObjectType = Tube\nNDims = 3\nPointDim = a b c\nNPoints = 1\nPoints = \n0 0 0\n", "no x, y and z"),
}
for name, (text, words) in bad.items():
    path = os.path.join(out, name)
    with open(path, "w") as f:
        f.write(text)
    status, message = table("metrics", "-q", path)
    report(name + " refused: " + words, None if status == 2 and words in message else "exit %s, %r" % (status,
                                                                                                        message))
print("slicer-itk: %d failed" % failed)
sys.exit(1 if failed else 0)
