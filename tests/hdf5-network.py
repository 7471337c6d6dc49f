#!/usr/bin/env python3
"""A Blue Brain vascular graph with every kind of joint, written with h5py, read by
tortuosity: a chain of single-child links becomes one vessel, a branch and a merge
(a section with two parents) end vessels, a pure cycle is one vessel started at its
lowest section; the child's first point, a repeat of its parent's last, is kept once; the same
network compressed by HDF5's filters (and h5py's LZF) reads the same.

  hdf5-network.py path/to/tortuosity WORKDIR

Exit status 0 when the vessels, their labels and point counts are the expected ones."""
import os
import subprocess
import sys

import h5py
import numpy as np

tortuosity, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)

# Section s: three points; a child starts where its parent ends (the Blue Brain layout).
links = [(0, 1), (1, 2),            # chain 0 -> 1 -> 2: one vessel "0-2"
         (3, 4), (3, 5),            # branch: 3, 4, 5 apart
         (6, 8), (7, 8),            # merge: 8 has two parents; 6, 7, 8 apart
         (9, 10), (10, 9)]          # pure cycle: one vessel "9-10"
nsec = 11
parent = {c: p for p, c in links if sum(1 for q, d in links if d == c) == 1}
rows, start = [], []
for s in range(nsec):
    start.append(len(rows))
    if s in parent and parent[s] < s:
        first = list(rows[start[parent[s]] + 2])          # the parent's last row, diameter too
    else:
        first = [100.0 * s, s, 0.0, 2.0]
    for k in range(3):
        rows.append([first[0] + 10 * k, first[1] + 3 * k * k, first[2] + k, first[3] + 0.5 * k])
path = os.path.join(out, "network.h5")
with h5py.File(path, "w") as f:
    f["points"] = np.array(rows, dtype="<f8")
    f["structure"] = np.array([[s0, 0] for s0 in start], dtype="<f8")
    f["connectivity"] = np.array(links, dtype="<i8")

text = subprocess.run([tortuosity, "metrics", "-q", "--rates", "raw", "--trim", "0", path],
                      capture_output=True, text=True, check=True).stdout.splitlines()
got = [(f.split("\t")[1], int(f.split("\t")[3])) for f in text[1:]]
want = [("0-2", 7), ("3", 3), ("4", 3), ("5", 3), ("6", 3), ("7", 3), ("8", 3), ("9-10", 5)]
if got != want:
    sys.exit(f"vessels {got}, expected {want}")

# The same network in chunked datasets, compressed and checked by HDF5's own filters (deflate,
# shuffle, Fletcher-32, scale-offset, and h5py's LZF), is read as the plain one.
filters = {"chunked": dict(chunks=True), "gzip": dict(compression="gzip", compression_opts=9),
           "shuffle+gzip": dict(compression="gzip", shuffle=True), "fletcher32": dict(fletcher32=True),
           "scaleoffset": dict(scaleoffset=0), "lzf": dict(compression="lzf"),
           "gzip+fletcher32": dict(compression="gzip", fletcher32=True)}
for label, options in filters.items():
    packed = os.path.join(out, "network-%s.h5" % label)
    with h5py.File(packed, "w") as f:
        f.create_dataset("points", data=np.array(rows, dtype="<f8"), **options)
        f.create_dataset("structure", data=np.array([[s0, 0] for s0 in start], dtype="<f8"), **options)
        f.create_dataset("connectivity", data=np.array(links, dtype="<i8"), **options)
    run = subprocess.run([tortuosity, "metrics", "-q", "--rates", "raw", "--trim", "0", packed],
                         capture_output=True, text=True)
    same = [(f.split("\t")[1], int(f.split("\t")[3])) for f in run.stdout.splitlines()[1:]]
    if run.returncode != 0 or same != want:
        sys.exit(f"{label}: status {run.returncode}, {run.stderr.strip()!r}, vessels {same}")

# A link to a section that does not exist is refused with the file's name, status 2.
bad = os.path.join(out, "bad.h5")
with h5py.File(bad, "w") as f:
    f["points"] = np.array(rows, dtype="<f8")
    f["structure"] = np.array([[s0, 0] for s0 in start], dtype="<f8")
    f["connectivity"] = np.array(links + [(3, 11)], dtype="<i8")
run = subprocess.run([tortuosity, "metrics", bad], capture_output=True, text=True)
if run.returncode != 2 or not run.stderr.startswith(bad + ": ") or run.stdout:
    sys.exit(f"bad link: status {run.returncode}, message {run.stderr!r}")
print(f"hdf5-network: {len(got)} vessels as expected, and with {len(filters)} filters; a bad link refused: "
      f"{run.stderr.strip()}")
