"""Sets one entry of an integer or double dataset of a snapshot file and recomputes the file's
checksum (snapshot_as_older_format.py's independent implementation of docs/file-formats.md,
"Integrity"): a crafted file, which reaches the reader's checks behind the checksum. The file is
left unsealed: the caller seals it (contactrb::seal_file).

Usage: /usr/bin/python3 snapshot_crafted.py FILE.h5 DATASET INDEX VALUE
Exit codes: 0 rewritten, 1 the recomputed checksum of the file as given differs from the stored
one, 77 h5py or numpy missing.
"""
import os
import sys

try:
    import h5py
    import numpy as np
except ImportError:
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from snapshot_as_older_format import checksum, fields  # noqa: E402 (after the skip)


def main():
    path, dataset, index, value = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    with h5py.File(path, "r+") as f:
        if checksum(fields(f)) != int(f.attrs["checksum"]):
            print("the recomputed checksum differs from the stored one")
            return 1
        d = f[dataset]
        a = d[()]
        a[index] = float(value) if a.dtype.kind == "f" else int(value)
        d[...] = a
        f.attrs.modify("checksum", np.uint64(checksum(fields(f))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
