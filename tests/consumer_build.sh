#!/usr/bin/env bash
# find_package(slipgraph) from another project: installs this build tree into a scratch prefix,
# configures and builds examples/filter_and_smooth against it, and runs it on the bundled sample.
# Usage: consumer_build.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build="$1"; source="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
# The example is compiled and linked as the tree was (a sanitizer build's libraries need the
# sanitizers' runtime in the program that links them).
cache() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
cmake -S "$source/examples/filter_and_smooth" -B "$work/example" \
  -DCMAKE_BUILD_TYPE="$(cache CMAKE_BUILD_TYPE)" \
  -DCMAKE_CXX_COMPILER="$(cache CMAKE_CXX_COMPILER)" \
  -DCMAKE_CXX_FLAGS="$(cache CMAKE_CXX_FLAGS)" \
  -DCMAKE_EXE_LINKER_FLAGS="$(cache CMAKE_EXE_LINKER_FLAGS)" \
  -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/configure.log" ||
  { cat "$work/configure.log"; exit 1; }
cmake --build "$work/example" -j2 >"$work/build.log" || { cat "$work/build.log"; exit 1; }
"$work/example/filter_and_smooth" "$source/data/sample"
