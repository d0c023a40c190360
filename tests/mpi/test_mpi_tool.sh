#!/usr/bin/env bash
# The dewall-mpi tool through mpiexec (ctest: mpi_tool, tests/CMakeLists.txt):
#   * the output, certified canonical (CGAL's simplices) by `dewall certify`
#     for 1, 2, 3 and 4 ranks (3D; 1 and 3 in 2D), has the same bytes on a
#     second run; with --sorted the same bytes for every number of ranks;
#   * .ele and the plain list (MPI-IO), standard output, --per-rank files;
#   * a NaN in one rank's share: exit 1 on every rank, one message naming the point;
#   * a truncated file, a missing file: exit 2, one message;
#   * no -o: exit 2, the usage once;
#   * a rank that exits early: mpiexec ends the job (no hang: ctest's timeout);
#   * after every failure an old output file is untouched.
# usage: test_mpi_tool.sh MPIEXEC NUMPROC_FLAG DEWALL_MPI DEWALL
set -uo pipefail
mpiexec=$1 np=$2 tool=$3 dewall=$4
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir" || exit 2
failures=0
fail() { echo "FAILED: $*" >&2; failures=$((failures + 1)); }
run() {  # run R ARGS…: the tool on R ranks; stdout+stderr in run.log, status in $status
  local ranks=$1; shift
  "$mpiexec" "$np" "$ranks" "$tool" "$@" >run.log 2>&1
  status=$?
}

"$dewall" generate uniform 4000 --dim 3 --seed 5 -o u3.dwpt --quiet || exit 2
"$dewall" generate bubbles 3000 --dim 2 --seed 6 -o b2.dwpt --quiet || exit 2

for input in u3 b2; do
  all_ranks="1 2 3 4"; [ "$input" = b2 ] && all_ranks="1 3"
  for ranks in $all_ranks; do
    run "$ranks" triangulate "$input.dwpt" -o "$input.$ranks.dwsx"
    [ "$status" -eq 0 ] || { fail "$input on $ranks ranks: exit $status"; cat run.log >&2; continue; }
    "$dewall" certify "$input.dwpt" "$input.$ranks.dwsx" --canonical >certify.log 2>&1 ||
      { fail "$input on $ranks ranks: not CGAL's triangulation"; cat certify.log >&2; }
    run "$ranks" triangulate "$input.dwpt" -o "$input.$ranks.sorted.dwsx" --sorted
    [ "$status" -eq 0 ] || { fail "$input on $ranks ranks, --sorted: exit $status"; cat run.log >&2; continue; }
    cmp -s "$input.1.sorted.dwsx" "$input.$ranks.sorted.dwsx" ||
      fail "$input --sorted: the bytes differ between 1 and $ranks ranks"
  done
done
"$dewall" certify u3.dwpt u3.1.sorted.dwsx --canonical >certify.log 2>&1 ||
  { fail "u3 --sorted: not CGAL's triangulation"; cat certify.log >&2; }
run 3 triangulate u3.dwpt -o u3.again.dwsx
cmp -s u3.3.dwsx u3.again.dwsx || fail "u3: two runs on 3 ranks differ"
echo "outputs: canonical, the same bytes on a second run, --sorted the same bytes for 1-4 ranks"

# The text formats written through MPI-IO, standard output (rank 0 alone) and per-rank files.
run 3 triangulate u3.dwpt -o u3.3.ele
[ "$status" -eq 0 ] && "$dewall" certify u3.dwpt u3.3.ele --canonical >certify.log 2>&1 ||
  { fail "u3 on 3 ranks as .ele"; cat run.log certify.log >&2; }
"$mpiexec" "$np" 2 "$tool" triangulate u3.dwpt -o - >u3.stdout.txt 2>run.log &&
  "$dewall" certify u3.dwpt u3.stdout.txt --canonical >certify.log 2>&1 ||
  { fail "u3 on 2 ranks to standard output"; cat run.log certify.log >&2; }
run 3 triangulate u3.dwpt -o u3.parts.txt --per-rank
cat u3.parts.r0.txt u3.parts.r1.txt u3.parts.r2.txt >u3.parts.txt 2>/dev/null
[ "$status" -eq 0 ] && "$dewall" certify u3.dwpt u3.parts.txt --canonical >certify.log 2>&1 ||
  { fail "u3 on 3 ranks, --per-rank"; cat run.log certify.log >&2; }
run 3 triangulate u3.dwpt -o u3.3.txt
cmp -s u3.3.txt u3.parts.txt || fail "u3: --per-rank's files differ from the parts of the one file"
echo "text formats, standard output, per-rank files: canonical"

# The errors. old.txt must survive each of them.
echo "old contents" >old.txt
expect_error() {  # expect_error STATUS PATTERN DESCRIPTION
  if [ "$status" -ne "$1" ]; then fail "$3: exit $status, expected $1"; cat run.log >&2; fi
  local lines
  lines=$(grep -c -- "$2" run.log)
  [ "$lines" -eq 1 ] || { fail "$3: the message \"$2\" appears $lines times, expected once"; cat run.log >&2; }
  [ "$(cat old.txt)" = "old contents" ] || fail "$3: the old output was replaced"
  [ -z "$(ls -A | grep -v -E '^(u3|b2|nan|cut)\.|^(old\.txt|run\.log|certify\.log)$')" ] ||
    fail "$3: files left behind: $(ls -A)"
  echo "$3: exit $status, one message"
}

cp u3.dwpt nan.dwpt
# point 3900 (in the last rank's share), its y coordinate: a quiet NaN, little-endian
printf '\x00\x00\x00\x00\x00\x00\xf8\x7f' | dd of=nan.dwpt bs=1 seek=$((24 + 8 * (3900 * 3 + 1))) conv=notrunc status=none
run 3 triangulate nan.dwpt -o old.txt
expect_error 1 "dewall-mpi: nan.dwpt: point 3900 has a non-finite coordinate (NaN or infinity)" "a NaN on rank 2 of 3"

cp u3.dwpt cut.dwpt
truncate -s -5 cut.dwpt
run 4 triangulate cut.dwpt -o old.txt
expect_error 2 "dewall-mpi: cut.dwpt: truncated: 4000 points of dimension 3 need 96024 bytes, the file has 96019" \
  "a truncated file"

run 2 triangulate missing.dwpt -o old.txt
expect_error 2 "dewall-mpi: missing.dwpt: cannot open file" "a missing file"

run 3 triangulate u3.dwpt
expect_error 2 "^usage: mpirun -n R dewall-mpi triangulate" "no output file"

# A rank that exits early (the third process of the job is `false`: it ends
# before MPI_Init): mpiexec ends the job, no rank hangs, old.txt survives.
"$mpiexec" "$np" 2 "$tool" triangulate u3.dwpt -o old.txt : "$np" 1 false >run.log 2>&1
status=$?
[ "$status" -ne 0 ] || fail "a rank exiting early: exit 0"
[ "$(cat old.txt)" = "old contents" ] || fail "a rank exiting early: the old output was replaced"
[ -z "$(ls -A | grep -v -E '^(u3|b2|nan|cut)\.|^(old\.txt|run\.log|certify\.log)$')" ] ||
  fail "a rank exiting early: files left behind: $(ls -A)"
echo "a rank exiting early: exit $status, the old output untouched"

[ "$failures" -eq 0 ] && echo "passed" || echo "$failures failure(s)"
exit $((failures > 0))
