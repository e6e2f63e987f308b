"""What the independent-reader scripts (test_model_h5py.py, test_snapshots_3d_h5py.py) share: the
check log, running the CLI, and the Float64 arrays of a VTU file with raw appended data (parsed
here, not by contactrb or meshio). Needs numpy (the scripts skip with 77 without it).
"""
import re
import struct
import subprocess
import sys

import numpy as np

FAILURES = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        FAILURES.append(what)


def run(cli, args, cwd):
    p = subprocess.run([cli] + args, cwd=cwd, capture_output=True, text=True, timeout=600)
    if p.returncode != 0:
        print(p.stdout)
        print(p.stderr, file=sys.stderr)
        raise SystemExit(f"contactrb {' '.join(args)} exited with {p.returncode}")
    return p.stdout


def vtu_arrays(path):
    """The Float64 DataArrays of a VTU file written with raw appended data (UInt64 headers)."""
    data = open(path, "rb").read()
    start = data.index(b"<AppendedData")
    xml = data[:start].decode("utf-8")
    base = data.index(b"_", start) + 1
    arrays = {}
    for m in re.finditer(r"<DataArray ([^>]*)/>", xml):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        if attrs.get("type") != "Float64":
            continue
        offset = base + int(attrs["offset"])
        (nbytes,) = struct.unpack_from("<Q", data, offset)
        values = np.frombuffer(data, dtype="<f8", count=nbytes // 8, offset=offset + 8)
        arrays[attrs["Name"]] = values.reshape(-1, int(attrs.get("NumberOfComponents", "1")))
    return arrays
