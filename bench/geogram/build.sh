#!/usr/bin/env bash
# Builds geogram's Delaunay module (its tools/extract_psm.sh: one .h/.cpp
# pair) and the driver geogram_dwpt.cpp from a geogram checkout. See README.md.
#
#   bench/geogram/build.sh GEOGRAM_SOURCE_DIR
#
# Environment: GEOGRAM_BUILD (default /tmp/geogram), CXXFLAGS_GEOGRAM (default
# geogram's own Release flags for gcc, cmake/platforms/Linux-gcc.cmake:
# -O3 -DNDEBUG -frounding-math -ffp-contract=off -fopenmp). Prints the
# driver's path.
set -euo pipefail
if [ $# -ne 1 ]; then
  echo "usage: $0 GEOGRAM_SOURCE_DIR" >&2
  exit 2
fi
SRC=$(cd "$1" && pwd)
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${GEOGRAM_BUILD:-/tmp/geogram}
FLAGS=${CXXFLAGS_GEOGRAM:--O3 -DNDEBUG -frounding-math -ffp-contract=off -fopenmp}
PSM=$SRC/src/lib/geogram/delaunay/Delaunay.psm
[ -f "$PSM" ] || { echo "no $PSM" >&2; exit 1; }
mkdir -p "$OUT"
# extract_psm.sh writes into the current directory; its example is not needed
# (its path does not exist in every checkout: the "cat" error is harmless).
(cd "$OUT" && bash "$SRC/tools/extract_psm.sh" "$PSM" >/dev/null 2>&1 || true)
[ -s "$OUT/Delaunay_psm.cpp" ] || { echo "extract_psm.sh made no Delaunay_psm.cpp" >&2; exit 1; }
# With gcc, GEO_FP_CONTRACT_OFF expands to a static struct definition; the PSM
# puts two of them (multi_precision.cpp's and predicates.cpp's) into one
# translation unit, a redefinition: keep the first.
awk '/^GEO_FP_CONTRACT_OFF$/ { if (seen++) next } { print }' "$OUT/Delaunay_psm.cpp" >"$OUT/Delaunay_psm_one.cpp"
nice g++ -std=c++20 $FLAGS -w -c -o "$OUT/Delaunay_psm.o" "$OUT/Delaunay_psm_one.cpp" -I"$OUT"
nice g++ -std=c++20 $FLAGS -Wall -c -o "$OUT/geogram_dwpt.o" "$HERE/geogram_dwpt.cpp" -I"$OUT"
g++ $FLAGS -o "$OUT/geogram_dwpt" "$OUT/geogram_dwpt.o" "$OUT/Delaunay_psm.o" -ldl -lm -lpthread
echo "$OUT/geogram_dwpt"
