#!/bin/sh
# Runs paraview_check.py with pvpython (Debian python3-paraview) under a virtual X server
# (xvfb-run, Debian xvfb): ParaView's Python cannot render without a display here.
# Usage: run_paraview_check.sh CONTACTRB WORK_DIR. Exit 77 (ctest: skipped) when a tool is missing.
set -eu
for tool in pvpython xvfb-run; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "$tool missing (scripts/install-deps.sh installs python3-paraview and xvfb): skipped"
    exit 77
  fi
done
rm -rf "$2"
exec xvfb-run -a -s "-screen 0 1280x1024x24" pvpython "$(dirname "$0")/paraview_check.py" "$1" "$2"
