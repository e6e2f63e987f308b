"""Independent reader for the VTU tests: reads a .vtu (binary appended or ASCII) with meshio and
prints it as JSON: points, cells, point_data, cell_data, field_data.

Usage: /usr/bin/python3 read_vtu.py FILE.vtu
Exit codes: 0 ok, 3 meshio (or numpy) missing, 4 meshio could not read the file.
"""
import json
import sys

try:
    import meshio
except ImportError:
    sys.exit(3)


def main() -> int:
    try:
        mesh = meshio.read(sys.argv[1])
    except Exception as e:  # noqa: BLE001 - any reader failure is a test failure
        print(f"meshio could not read {sys.argv[1]}: {e}", file=sys.stderr)
        return 4
    out = {
        "points": mesh.points.tolist(),
        "cells": [{"type": block.type, "data": block.data.tolist()} for block in mesh.cells],
        "point_data": {name: values.tolist() for name, values in mesh.point_data.items()},
        "cell_data": {name: [block.tolist() for block in blocks] for name, blocks in mesh.cell_data.items()},
        "field_data": {name: values.tolist() for name, values in mesh.field_data.items()},
    }
    json.dump(out, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
