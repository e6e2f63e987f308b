"""Rewrites a 2D Kacanov snapshot file of format 8 as format 7 (each snapshot's K a dense R x n_c
dataset `K` instead of K_indptr, K_indices, K_data), 6 (also no /settings attribute `solver`)
or 5 (also no root attribute `dimension`), the layout those writers produced,
with the checksum recomputed here (docs/file-formats.md,
"Integrity": FNV-1a over (path, digest) in path order, each field's digest FNV-1a over its kind,
shape and bytes). The file is left unsealed: the caller seals it (contactrb::seal_file).

The checksum of the file as given is recomputed first and must equal the stored one, so a
rewrite never rests on a checksum this script gets wrong.

Usage: /usr/bin/python3 snapshot_as_older_format.py FILE.h5 VERSION   (VERSION: 5, 6 or 7)
Exit codes: 0 rewritten, 1 the recomputed checksum differs (or the file is not a 2D Kacanov
file of format 8, or VERSION is not 5, 6 or 7),
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


def dense_contact_rows(f):
    """Each snapshot's compressed rows (format 8) as the dense R x n_c dataset K of format 7."""
    n_c = f["discretization/contact_dofs"].shape[0]
    for key in f["snapshots"]:
        s = f["snapshots"][key]
        if not isinstance(s, h5py.Group) or "K_indptr" not in s:
            continue
        indptr, indices, data = s["K_indptr"][()], s["K_indices"][()], s["K_data"][()]
        K = np.zeros((indptr.size - 1, n_c))
        for r in range(indptr.size - 1):
            K[r, indices[indptr[r]:indptr[r + 1]]] = data[indptr[r]:indptr[r + 1]]
        for name in ("K_indptr", "K_indices", "K_data"):
            del s[name]
        s.create_dataset("K", data=K.astype("<f8"))
        s["K"].attrs["shape_meaning"] = np.bytes_(
            "R x n_c: the contact rows K(w) on the contact DOFs (/discretization/contact_dofs)")
        s["K"].attrs["units"] = np.bytes_("1")


def main():
    version = int(sys.argv[2]) if len(sys.argv) > 2 else 0
    if version not in (5, 6, 7):
        print("the target version must be 5, 6 or 7")
        return 1
    with h5py.File(sys.argv[1], "r+") as f:
        if (int(f.attrs["format_version"]) != 8 or int(f.attrs["dimension"]) != 2
                or f["settings"].attrs["solver"] != b"kacanov"):
            print("not a 2D Kacanov snapshot file of format 8")
            return 1
        table = fields(f)
        if checksum(table) != int(f.attrs["checksum"]):
            print(f"recomputed checksum {checksum(table)} differs from the stored {int(f.attrs['checksum'])}")
            return 1
        dense_contact_rows(f)
        if version <= 6:
            del f["settings"].attrs["solver"]
        if version == 5:
            del f.attrs["dimension"]
        f.attrs.modify("format_version", np.int32(version))
        f.attrs.modify("checksum", np.uint64(checksum(fields(f))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
