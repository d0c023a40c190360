#!/usr/bin/env bash
# Builds gmsh's hxt (contrib/hxt/tetMesh, standalone CMake) and the driver
# hxt_dwpt.c, then times hxt, CGAL and dewall's incremental engine on one point
# file, alternated, each pinned to one CPU. See README.md.
#
#   bench/hxt/run.sh GMSH_SOURCE_DIR POINTS.dwpt
#
# Environment: HXT_BUILD (default /tmp/hxt), DEWALL_BUILD (default the repo's
# build/, must hold bench/bench_scale_cgal and cli/dewall), ROUNDS (3), CPU (1),
# THREADS (1; 2 = also CGAL --parallel, dewall --threads 2, hxt on 2 threads,
# pinned to CPUS, default 0,1), CERTIFY (1: certify hxt's output once with
# `dewall certify --canonical`, untimed).
set -euo pipefail

if [ $# -ne 2 ]; then
  echo "usage: $0 GMSH_SOURCE_DIR POINTS.dwpt" >&2
  exit 2
fi
GMSH=$(cd "$1" && pwd)
POINTS=$2
HERE=$(cd "$(dirname "$0")" && pwd)
HXT_BUILD=${HXT_BUILD:-/tmp/hxt}
DEWALL_BUILD=${DEWALL_BUILD:-$HERE/../../build}
ROUNDS=${ROUNDS:-3}
CPU=${CPU:-1}
THREADS=${THREADS:-1}
CPUS=${CPUS:-0,1}
CERTIFY=${CERTIFY:-1}
H=$GMSH/contrib/hxt
[ -f "$H/tetMesh/CMakeLists.txt" ] || { echo "no $H/tetMesh/CMakeLists.txt" >&2; exit 1; }

# hxt's own recipe (contrib/hxt/README.md): Release (-O3 -DNDEBUG), -march=native,
# real archives instead of CMake object libraries; OpenMP on (found by CMake).
cmake -S "$H/tetMesh" -B "$HXT_BUILD" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_C_FLAGS=-march=native -DCMAKE_CXX_FLAGS=-march=native \
  -DHXT_TETMESH_OBJECT_ONLY=OFF -DHXT_CORE_OBJECT_ONLY=OFF \
  -DHXT_PREDICATES_OBJECT_ONLY=OFF -DHXT_TETBR_OBJECT_ONLY=OFF >/dev/null
nice make -C "$HXT_BUILD" -j"$(nproc)" hxt_tetMesh Delaunay_CLI >/dev/null
nice gcc -O3 -march=native -fopenmp -std=c99 -Wall -I"$H/core/include" -I"$H/tetMesh/include" \
  -o "$HXT_BUILD/hxt_dwpt" "$HERE/hxt_dwpt.c" \
  -L"$HXT_BUILD" -L"$HXT_BUILD/tetBR" -L"$HXT_BUILD/predicates" -L"$HXT_BUILD/core" \
  -lhxt_tetMesh -lhxt_tetBR -lhxt_predicates -lhxt_core -lstdc++ -lm
HXT=$HXT_BUILD/hxt_dwpt
CGAL=$DEWALL_BUILD/bench/bench_scale_cgal
DEWALL=$DEWALL_BUILD/cli/dewall
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

if [ "$CERTIFY" = 1 ]; then
  OMP_NUM_THREADS=1 "$HXT" "$POINTS" -o "$OUT/hxt.dwsx" >/dev/null
  "$DEWALL" certify "$POINTS" "$OUT/hxt.dwsx" --canonical
  rm -f "$OUT/hxt.dwsx"
fi

# dewall --stats prints key=value words on standard error; keep simplices, engine, build_s
dewall_stats() { tr ' ' '\n' | grep -E '^(simplices|engine|build_s)=' | tr '\n' ' '; }

one_thread() {
  local pin="taskset -c $CPU"
  # hxt with glibc's default heap, then with transparent huge pages as CGAL and dewall use
  echo "hxt     $(GLIBC_TUNABLES=glibc.malloc.hugetlb=0 OMP_NUM_THREADS=1 $pin "$HXT" "$POINTS")"
  echo "hxt-thp $(GLIBC_TUNABLES=glibc.malloc.hugetlb=1 OMP_NUM_THREADS=1 $pin "$HXT" "$POINTS")"
  echo "cgal    $($pin "$CGAL" "$POINTS")"
  echo "dewall  $($pin "$DEWALL" triangulate "$POINTS" -o "$OUT/x.dwsx" --engine incremental --threads 1 --stats 2>&1 | dewall_stats)"
}

two_threads() {
  local pin="taskset -c $CPUS"
  echo "hxt-2     $(GLIBC_TUNABLES=glibc.malloc.hugetlb=0 OMP_NUM_THREADS=2 $pin "$HXT" "$POINTS")"
  echo "cgal-2    $($pin "$CGAL" "$POINTS" --parallel)"
  echo "dewall-2  $($pin "$DEWALL" triangulate "$POINTS" -o "$OUT/x.dwsx" --engine incremental --threads 2 --stats 2>&1 | dewall_stats)"
}

for r in $(seq 1 "$ROUNDS"); do
  echo "== round $r $(date -Is)"
  one_thread
  if [ "$THREADS" = 2 ]; then two_threads; fi
done
