#!/bin/sh
# The library example as a user builds it: installs this build into a fresh prefix, configures
# examples/library against the installed package (find_package(afemp CONFIG)), builds it and
# runs it. The example checks its physics itself (momentum to 1e-10, the residual velocity's
# band) and exits non-zero when a check fails.
# usage: install_and_run.sh CMAKE BUILD_DIR EXAMPLE_DIR
set -eu
cmake=$1 build=$2 example=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$cmake" --install "$build" --prefix "$work/prefix" > "$work/install.log"
test -f "$work/prefix/include/afemp/afemp.hpp"
test -f "$work/prefix/lib/cmake/afemp/afempConfig.cmake" || test -f "$work/prefix/lib64/cmake/afemp/afempConfig.cmake"
"$cmake" -S "$example" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log" ||
  { cat "$work/configure.log"; exit 1; }
"$cmake" --build "$work/build" > "$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }
OMP_NUM_THREADS=1 "$work/build/plate_impact"
