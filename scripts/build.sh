#!/usr/bin/env bash
# scripts/build.sh [TARGET...]: configures (once) and builds the project into
# build/ (Release, ccache when present): the given targets, or everything.
# ./run builds only the command-line tool (most of a fresh build is tests and
# benchmarks); ./test builds everything.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="$here/build"
if [ ! -f "$build/CMakeCache.txt" ]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
fi

targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$build" -j "$(nproc)" "${targets[@]}"
