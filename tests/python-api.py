#!/usr/bin/python3
"""The Python module against analytic curves and against the command line.

Usage: PYTHONPATH=PREFIX/lib/python3/dist-packages /usr/bin/python3 tests/python-api.py bin/tortuosity
(Debian's python3, whose numpy the test stage installs)
Prints one line per check and "python: N passed, N failed" last.
"""
import ctypes
import math
import os
import subprocess
import sys
import tempfile
import warnings

import numpy as np

import tortuosity

program = sys.argv[1]
work = tempfile.mkdtemp()
passed = failed = 0


def check(name, test):
    global passed, failed
    try:
        problem = test()
    except Exception as e:  # a check that raises has failed, and says why
        problem = "%s: %s" % (type(e).__name__, e)
    if problem:
        failed += 1
        print("FAIL %s\n     %s" % (name, problem))
    else:
        passed += 1
        print("ok   %s" % name)


def helix(n=80, a=4.0, b=2.0):
    t = np.linspace(0, 10, n)
    return np.column_stack([a * np.cos(t), a * np.sin(t), b * t])


def write_text(path, vessels):
    with open(path, "w") as f:
        f.write("\n\n".join("\n".join(" ".join("%.17g" % x for x in row) for row in v) for v in vessels) + "\n")


def cli_table(*args):
    out = subprocess.run([program, *args], check=True, capture_output=True, text=True).stdout
    lines = [line.split("\t") for line in out.splitlines()]
    return [dict(zip(lines[0], row)) for row in lines[1:]]


def field(x):  # a number as the results table prints it
    return "" if math.isnan(x) else "%.9g" % x


def test_version():
    cli = subprocess.run([program, "--version"], check=True, capture_output=True, text=True).stdout.strip()
    return None if cli == "tortuosity " + tortuosity.version() else "%r against %r" % (tortuosity.version(), cli)


def test_helix_profile():
    p = tortuosity.profile(helix(), rate=10)
    inside = p["in_window"]
    if p["status"] != "ok" or inside.sum() < 0.7 * len(inside):
        return "status %s, %d of %d samples in the window" % (p["status"], inside.sum(), len(inside))
    if p["xyz"].shape != (len(p["s"]), 3) or p["normal"].shape != p["xyz"].shape:
        return "shapes %s %s" % (p["xyz"].shape, p["normal"].shape)
    worst_kappa = np.max(np.abs(p["kappa"][inside] - 0.2))    # a / (a^2 + b^2)
    worst_tau = np.max(np.abs(p["tau"][inside] - 0.1))        # b / (a^2 + b^2)
    unit = np.max(np.abs(np.linalg.norm(p["tangent"], axis=1) - 1))
    normal_ok = np.max(np.abs(np.sum(p["tangent"][inside] * p["normal"][inside], axis=1)))
    if worst_kappa > 1e-3 or worst_tau > 1e-3 or unit > 1e-9 or normal_ok > 1e-9:
        return "kappa off by %g, tau by %g, |T| by %g, T.N %g" % (worst_kappa, worst_tau, unit, normal_ok)
    if not np.all(np.isnan(p["error"][~inside])) or np.nanmax(p["error"]) > p["metrics"]["recon_err"] + 1e-12:
        return "reconstruction error outside the window, or above the largest"
    return None


def test_semicircle_measure():
    ph = os.path.join(work, "semicircle.txt")
    subprocess.run([program, "phantom", "--shape", "semicircle", "-o", ph], check=True)
    (label, points), = tortuosity.read(ph)
    m = tortuosity.measure(points, rate=100)
    if label != "1" or points.shape[1] != 3 or m["status"] != "ok":
        return "label %s, shape %s, status %s" % (label, points.shape, m["status"])
    return None if abs(m["AC"] - 1) < 1e-3 and abs(m["TT"]) < 1e-6 else "AC %g (want 1), TT %g (want 0)" % (
        m["AC"], m["TT"])


def test_same_as_command_line():
    path = os.path.join(work, "helix.txt")
    rng = np.random.default_rng(1)
    write_text(path, [helix() + rng.normal(0, 0.01, (80, 3))])
    for options, words in (({}, []),
                           ({"lambda_": 100, "segments": 8, "degree": 4}, ["--lambda", "100", "--segments", "8",
                                                                          "--degree", "4"]),
                           ({"torsion": "significant", "integrator": "rotation"},
                            ["--torsion", "significant", "--integrator", "rotation"]),
                           ({"trim": 0.2, "planar": True}, ["--trim", "0.2", "--planar"]),
                           ({"precision": "0.05x0.05x0.1"}, ["--precision", "0.05x0.05x0.1"])):
        row, = cli_table("metrics", "--rates", "2/mm", *words, path)
        (_, points), = tortuosity.read(path)
        m = tortuosity.measure(points, rate="2/mm", **options)
        for name, _ in tortuosity.metrics():
            if field(m[name]) != row[name]:
                return "%s with %s: %s from Python, %s from the command line" % (name, words, field(m[name]),
                                                                                row[name])
        if m["status"] != row["status"] or field(m["recon_err"]) != row["recon_err"]:
            return "status or recon_err with %s" % words
    rows = cli_table("profile", "--rate", "10", path)
    p = tortuosity.profile(points, rate=10)
    for j, r in enumerate(rows):
        if field(p["kappa"][j]) != r["kappa"] or field(p["tau"][j]) != r["tau"] or field(p["error"][j]) != r["err"]:
            return "profile sample %d: kappa %s/%s tau %s/%s" % (j, field(p["kappa"][j]), r["kappa"],
                                                                 field(p["tau"][j]), r["tau"])
    return None if len(rows) == len(p["s"]) else "%d samples from Python, %d from profile" % (len(p["s"]), len(rows))


def test_read_formats():
    path = os.path.join(work, "two.txt")
    write_text(path, [helix(10), np.column_stack([helix(7), np.full(7, 0.5)])])
    vessels = tortuosity.read(path)
    if [(label, v.shape) for label, v in vessels] != [("1", (10, 3)), ("2", (7, 4))]:
        return "got %s" % [(label, v.shape) for label, v in vessels]
    if not np.allclose(vessels[1][1][:, 3], 0.5) or not np.allclose(vessels[0][1], helix(10)):
        return "values"
    csv = os.path.join(work, "um.csv")
    with open(csv, "w") as f:
        f.write("id,X,Y,Z\n" + "".join("a,%g,%g,%g\n" % (1000 * x, 1000 * y, 1000 * z) for x, y, z in helix(6)))
    (label, v), = tortuosity.read(csv, units="um", columns="X,Y,Z")
    if not np.allclose(v, helix(6)):
        return "CSV in micrometres: %s" % v[:2]
    with warnings.catch_warnings(record=True) as caught:             # the reader's warning, as Python's
        warnings.simplefilter("always")
        tortuosity.read(path, columns="x,y,z")
    return None if any("--columns" in str(w.message) for w in caught) else "no warning: %s" % caught


def test_errors():
    expected = (
        (lambda: tortuosity.read(os.path.join(work, "none.txt")), tortuosity.Error, "cannot open"),
        (lambda: tortuosity.measure(helix(), rate="fast"), tortuosity.Error, "bad rate"),
        (lambda: tortuosity.measure(helix()[:, :2]), tortuosity.Error, "n rows"),
        (lambda: tortuosity.measure(helix(), degree=9), tortuosity.Error, "degree"),
        (lambda: tortuosity.measure(helix(), colour="red"), TypeError, "colour"),
        (lambda: tortuosity.read(os.path.join(work, "two.txt"), format="nope"), tortuosity.Error, "format"),
        (lambda: tortuosity.measure(helix(), segments=2**32 + 5), tortuosity.Error, "segments"),
        (lambda: tortuosity.measure(helix(), degree=4.5), tortuosity.Error, "degree"),
        (lambda: tortuosity.read(os.path.join(work, "two.txt") + "\0junk"), ValueError, "null byte"),
        (lambda: tortuosity.measure(helix(), lambda_=1e-3, **{"lambda": 10}), TypeError, "give one"),
        (lambda: tortuosity.measure(helix(), rate=True), tortuosity.Error, "rate"),
        (lambda: tortuosity.measure(helix(), rate=None), tortuosity.Error, "rate"),
        (lambda: tortuosity.measure(helix(), trim=True), tortuosity.Error, "trim"),
        (lambda: tortuosity.measure(helix(), trim="0.1"), tortuosity.Error, "trim"),
        (lambda: tortuosity.measure(helix(), lambda_="1"), tortuosity.Error, "lambda"),
        (lambda: tortuosity.measure(helix(), filter="no"), tortuosity.Error, "filter"),
        (lambda: tortuosity.measure(helix(), planar=2), tortuosity.Error, "planar"),
        (lambda: tortuosity.measure(helix(), integrator=3), tortuosity.Error, "integrator"),
        (lambda: tortuosity.profile(helix(), torsion=True), tortuosity.Error, "torsion"),
    )
    for call, kind, words in expected:
        try:
            call()
            return "no error for %s" % words
        except kind as e:
            if words not in str(e):
                return "message %r lacks %r" % (str(e), words)
    two = tortuosity.measure(helix(2))            # a length, and no curvature
    if two["status"] != "no-curvature" or not two["L"] > 0 or not math.isnan(two["AC"]) \
            or not math.isnan(two["recon_err"]):
        return "two points: %s" % two
    return None


def test_degenerate_fits_do_not_end_the_host():
    # Fits whose factor is singular, where GSL would call its error handler: in a process of their own, so
    # that an abort shows as a signal. Each must give the command line's status.
    cases = (("3 points, penalty order 4", [[0, 0, 0], [1, 0.2, 0], [2, 0, 0.1]], "penalty_order=4"),
             ("4 points, penalty order 4", [[0, 0, 0], [1, 0.2, 0], [2, 0, 0.1], [3, 0.1, 0]], "penalty_order=4"),
             ("5 collinear points, penalty order 4, degree 3", [[i, 0, 0] for i in range(5)],
              "penalty_order=4, degree=3"),
             ("3 points, fixed lambda 0", [[0, 0, 0], [1, 1, 0], [2, 0, 0]], "lambda_=0"),
             ("6 points of a zigzag, penalty order 4, degree 3", [[i, i % 2, 0] for i in range(6)],
              "penalty_order=4, degree=3"))
    for name, points, options in cases:
        code = ("import tortuosity, numpy as np\n"
                "r = tortuosity.measure(np.array(%r, float), rate=10, %s)\n"
                "print(r['status'])" % (points, options))
        run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        if run.returncode != 0:
            return "%s: exit %d, %s" % (name, run.returncode, run.stderr.strip()[-200:])
        write_text(os.path.join(work, "degenerate.txt"), [np.array(points, float)])
        flags = options.replace("penalty_order=", "--penalty-order ").replace("degree=", "--degree ") \
                       .replace("lambda_=", "--lambda ").replace(",", "").split()
        row = cli_table("metrics", "--rates", "10", *flags, os.path.join(work, "degenerate.txt"))[0]
        if run.stdout.strip() != row["status"]:
            return "%s: status %s, the command line's %s" % (name, run.stdout.strip(), row["status"])
    return None


def test_misaligned_arrays():
    # Points in a byte buffer at an odd offset, through the module and straight into the library:
    # the same numbers as aligned points (the library copies what is not aligned for double).
    pts = helix(60)
    want = tortuosity.measure(pts)
    raw = bytearray(pts.size * 8 + 1)
    view = np.frombuffer(raw, dtype=np.float64, count=pts.size, offset=1).reshape(pts.shape)
    view[:] = pts
    if view.flags.aligned:
        return "the test's view is aligned"
    got = tortuosity.measure(view)
    result, message = tortuosity._Result(), ctypes.create_string_buffer(256)
    opt = tortuosity._options()
    address = ctypes.cast(ctypes.addressof(ctypes.c_char.from_buffer(raw, 1)), tortuosity._doubles)
    if tortuosity._lib.tort_measure(address, None, pts.shape[0], b"10", ctypes.byref(opt), ctypes.byref(result),
                                    message, 256) != 0:
        return "tort_measure: %s" % message.value
    direct = tortuosity._as_dict(result)
    for name in ("L", "AC", "AT", "TCCT"):
        if not (got[name] == want[name] == direct[name]):
            return "%s: %r, %r and %r" % (name, want[name], got[name], direct[name])
    return None


check("version: the library's is the program's", test_version)
check("profile of a helix: kappa 0.2/mm, tau 0.1/mm, a unit tangent normal to N, errors in the window",
      test_helix_profile)
check("measure a semicircle phantom of radius 1 mm: AC 1/mm, TT 0", test_semicircle_measure)
check("measure and profile give the command line's numbers, with the fit's options", test_same_as_command_line)
check("read: text with and without radii, CSV in micrometres with named columns, the reader's warning",
      test_read_formats)
check("errors are exceptions with the library's message, keywords and their types checked; a two-point vessel has a length, a status and NaN",
      test_errors)
check("degenerate fits (singular factors) give the command line's status and never end the host",
      test_degenerate_fits_do_not_end_the_host)
check("points not aligned for double (a byte buffer at an odd offset): the aligned points' numbers",
      test_misaligned_arrays)
print("python: %d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
