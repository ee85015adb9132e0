#!/bin/sh
# The `viewer` test: runs a scene with the afemp command, then has ParaView render its
# fields.xmf (tests/viewer/render_fields.py), which fails on an empty block or a blank picture.
# Usage: render_run.sh AFEMP XVFB_RUN PVPYTHON SCENE OUT_DIR; the picture is OUT_DIR/fields.png.
set -eu
afemp=$1 xvfb_run=$2 pvpython=$3 scene=$4 out=$5
rm -rf "$out"
"$afemp" run "$scene" -o "$out/run"
"$xvfb_run" -a -s "-screen 0 1024x768x24" "$pvpython" "$(dirname "$0")/render_fields.py" \
  "$out/run/fields.xmf" "$out/fields.png"
