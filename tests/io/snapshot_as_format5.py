"""Rewrites a 2D snapshot file of format 6 as format 5 (no root attribute `dimension`), the
layout the format 5 writer produced, with the checksum recomputed here (docs/file-formats.md,
"Integrity": FNV-1a over (path, digest) in path order, each field's digest FNV-1a over its kind,
shape and bytes). The file is left unsealed: the caller seals it (contactrb::seal_file).

The checksum of the file as given is recomputed first and must equal the stored one, so a
rewrite never rests on a checksum this script gets wrong.

Usage: /usr/bin/python3 snapshot_as_format5.py FILE.h5
Exit codes: 0 rewritten, 1 the recomputed checksum differs (or the file is not 2D format 6),
77 h5py or numpy missing.
"""
import sys

try:
    import h5py
    import numpy as np
except ImportError:
    sys.exit(77)

OFFSET = 14695981039346656037
PRIME = 1099511628211
MASK = (1 << 64) - 1
# Attributes outside the checksum (docs/file-formats.md, "Integrity"): a group's description,
# a dataset's shape_meaning and units, the root's checksum and complete mark. (A parameter
# group's `units` is data.)
DESCRIPTIVE_GROUP = {"description", "checksum", "complete"}
DESCRIPTIVE_DATASET = {"shape_meaning", "units"}


def fnv(h, data):
    for b in data:
        h = ((h ^ b) * PRIME) & MASK
    return h


def digest(kind, dims, data):
    h = fnv(OFFSET, kind.encode())
    for d in dims:
        h = fnv(h, int(d).to_bytes(8, "little"))
    return fnv(h, data)


def value_digest(value):
    """(kind, dims, bytes) of an attribute or dataset value as the C++ visitor adds it."""
    if isinstance(value, (bytes, np.bytes_)):
        return digest("s", [len(value)], bytes(value))
    a = np.asarray(value)
    if a.dtype.kind == "f":
        dims = [1] if a.ndim == 0 else list(a.shape)
        return digest("d", dims, a.astype("<f8").tobytes())
    if a.dtype.kind in "iu":
        dims = [1] if a.ndim == 0 else list(a.shape)
        return digest("i", dims, a.astype("<i4").tobytes())
    raise SystemExit(f"unexpected value type {a.dtype}")


def fields(f):
    out = {}

    def attributes(path, obj):
        descriptive = DESCRIPTIVE_DATASET if isinstance(obj, h5py.Dataset) else DESCRIPTIVE_GROUP
        for key in obj.attrs:
            if key not in descriptive:
                out[(path if path != "/" else "") + "/" + key] = value_digest(obj.attrs[key])

    attributes("/", f)

    def visit(name, obj):
        attributes("/" + name, obj)
        if isinstance(obj, h5py.Dataset):
            out["/" + name] = value_digest(obj[()])

    f.visititems(visit)
    return out


def checksum(table):
    h = OFFSET
    for name in sorted(table, key=lambda s: s.encode()):
        h = fnv(h, name.encode() + b"\0")
        h = fnv(h, table[name].to_bytes(8, "little"))
    return h


def main():
    with h5py.File(sys.argv[1], "r+") as f:
        if int(f.attrs["format_version"]) != 6 or int(f.attrs["dimension"]) != 2:
            print("not a 2D snapshot file of format 6")
            return 1
        table = fields(f)
        if checksum(table) != int(f.attrs["checksum"]):
            print(f"recomputed checksum {checksum(table)} differs from the stored {int(f.attrs['checksum'])}")
            return 1
        del f.attrs["dimension"]
        f.attrs.modify("format_version", np.int32(5))
        f.attrs.modify("checksum", np.uint64(checksum(fields(f))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
