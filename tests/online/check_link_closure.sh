#!/bin/sh
# The light executables load no mesh generation, FE or sparse-solver library at run time
# (docs/rb.md, "Layout"): fails when `ldd` lists one of them for any executable given.
#   check_link_closure.sh <executable>...
status=0
for exe in "$@"; do
  libs=$(ldd "$exe") || { echo "ldd failed on $exe"; exit 1; }
  count=$(printf '%s\n' "$libs" | grep -c '=>')
  heavy=$(printf '%s\n' "$libs" | grep -E -i 'libgmsh|libTK|libfltk|libX11|libcholmod|libumfpack|libsuitesparse|libtoml' || true)
  echo "$exe: $count shared libraries"
  if [ -n "$heavy" ]; then
    echo "$exe loads libraries the online stage must not need:"
    printf '%s\n' "$heavy"
    status=1
  fi
done
exit $status
