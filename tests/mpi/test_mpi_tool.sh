#!/usr/bin/env bash
# The dewall-mpi tool through mpiexec (ctest: mpi_tool, tests/CMakeLists.txt):
#   * the output, certified canonical (CGAL's simplices) by `dewall certify`
#     for 1, 2, 3 and 4 ranks (3D; 1 and 3 in 2D), has the same bytes on a
#     second run; with --sorted the same bytes for every number of ranks;
#   * .ele and the plain list (MPI-IO), standard output, --per-rank files;
#   * regions (--region-points, --stream): canonical, the same bytes on a
#     second run, .ele, per-rank files, --sorted the same bytes as without;
#   * 8-byte .dwsx indices (--index-bytes 8): canonical;
#   * certify on 1, 2 and 3 ranks: the words and exit status of `dewall certify`
#     on a canonical output and on mutants of it (with and without --all, with
#     --canonical; --json, --stream, --memory), and on --per-rank files;
#   * a NaN in one rank's share: exit 1 on every rank, one message naming the point;
#   * a truncated file, a missing file: exit 2, one message;
#   * no -o: exit 2, one line and a pointer to the help; help, help triangulate;
#   * --per-rank to '-', names that say a point format, -o the input: refused;
#   * an empty input: dewall's message and status;
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

# Regions (--region-points, as --stream with small regions): canonical, the
# same bytes on a second run, the same simplices as without regions; .ele and
# per-rank files; --sorted the same bytes as without regions.
count_of() { od -An -t u8 -j 16 -N 8 "$1" | tr -d ' '; }  # a .dwsx header's count
for ranks in 1 2 3; do
  run "$ranks" triangulate u3.dwpt -o "u3.$ranks.regions.dwsx" --region-points 300 --stats
  [ "$status" -eq 0 ] || { fail "u3 on $ranks ranks with regions: exit $status"; cat run.log >&2; continue; }
  awk '$1 == "0" && $6 > 1 { ok = 1 } END { exit !ok }' run.log || { fail "u3 with regions: not in regions"; cat run.log >&2; }
  "$dewall" certify u3.dwpt "u3.$ranks.regions.dwsx" --canonical >certify.log 2>&1 ||
    { fail "u3 on $ranks ranks with regions: not CGAL's triangulation"; cat certify.log >&2; }
done
run 3 triangulate u3.dwpt -o u3.again.regions.dwsx --region-points 300
cmp -s u3.3.regions.dwsx u3.again.regions.dwsx || fail "u3 with regions: two runs on 3 ranks differ"
run 2 triangulate u3.dwpt -o u3.2.regions.sorted.dwsx --region-points 300 --sorted
cmp -s u3.1.sorted.dwsx u3.2.regions.sorted.dwsx || fail "u3 with regions, --sorted: the bytes differ from 1 rank's"
run 3 triangulate b2.dwpt -o b2.3.regions.ele --stream
[ "$status" -eq 0 ] && "$dewall" certify b2.dwpt b2.3.regions.ele --canonical >certify.log 2>&1 ||
  { fail "b2 on 3 ranks with --stream as .ele"; cat run.log certify.log >&2; }
run 3 triangulate u3.dwpt -o u3.3.regions.ele --region-points 250
[ "$status" -eq 0 ] && "$dewall" certify u3.dwpt u3.3.regions.ele --canonical >certify.log 2>&1 ||
  { fail "u3 on 3 ranks with regions as .ele"; cat run.log certify.log >&2; }
run 3 triangulate u3.dwpt -o u3.3.regions.txt --region-points 250
run 3 triangulate u3.dwpt -o u3.rparts.txt --region-points 250 --per-rank
cat u3.rparts.r0.txt u3.rparts.r1.txt u3.rparts.r2.txt | sort >u3.rparts.sorted.txt
sort u3.3.regions.txt | cmp -s - u3.rparts.sorted.txt ||
  fail "u3 with regions: --per-rank's files differ from the one file"
run 3 triangulate u3.dwpt -o u3.rparts.dwsx --region-points 250 --per-rank
counted=0
for r in 0 1 2; do
  c=$(count_of "u3.rparts.r$r.dwsx")
  [ "$(stat -c %s "u3.rparts.r$r.dwsx")" -eq $((24 + 16 * c)) ] || fail "u3 with regions: u3.rparts.r$r.dwsx's size"
  counted=$((counted + c))
done
[ "$counted" -eq "$(count_of u3.3.regions.dwsx)" ] || fail "u3 with regions: the per-rank .dwsx counts"
echo "regions: canonical, the same bytes on a second run, .ele, per-rank files"

# 8-byte indices (what more than 2^32 - 2 points get), forced on a small set.
run 2 triangulate u3.dwpt -o u3.wide.dwsx --index-bytes 8
[ "$status" -eq 0 ] && "$dewall" certify u3.dwpt u3.wide.dwsx --canonical >certify.log 2>&1 ||
  { fail "u3 with 8-byte indices"; cat run.log certify.log >&2; }
[ "$(od -An -t u4 -j 12 -N 4 u3.wide.dwsx | tr -d ' ')" = 8 ] || fail "u3.wide.dwsx: the header's index width is not 8"
[ "$(stat -c %s u3.wide.dwsx)" -eq $((24 + 32 * $(count_of u3.wide.dwsx))) ] || fail "u3.wide.dwsx: its size"
run 2 triangulate u3.dwpt -o u3.wide.sorted.dwsx --index-bytes 8 --sorted
"$dewall" certify u3.dwpt u3.wide.sorted.dwsx --canonical >certify.log 2>&1 ||
  { fail "u3 with 8-byte indices, --sorted"; cat run.log certify.log >&2; }
run 3 triangulate u3.dwpt -o u3.wide.regions.dwsx --index-bytes 8 --region-points 300
"$dewall" certify u3.dwpt u3.wide.regions.dwsx --canonical >certify.log 2>&1 ||
  { fail "u3 with 8-byte indices and regions"; cat run.log certify.log >&2; }
run 2 triangulate u3.dwpt -o u3.bad.dwsx --index-bytes 6
[ "$status" -eq 2 ] || fail "--index-bytes 6: exit $status, expected 2"
echo "8-byte indices: canonical"

# certify: what `dewall certify` prints (standard output; --json's but its
# seconds) and its exit status.
certify_same() {  # certify_same RANKS FILE ARGS…
  local ranks=$1 file=$2; shift 2
  "$dewall" certify u3.dwpt "$file" "$@" >want.out 2>/dev/null
  local want=$?
  "$mpiexec" "$np" "$ranks" "$tool" certify u3.dwpt "$file" "$@" >got.out 2>/dev/null
  local got=$?
  sed -i 's/,"seconds":[0-9.e+-]*//' want.out got.out
  if [ "$got" -ne "$want" ] || ! cmp -s want.out got.out; then
    fail "certify $file $* on $ranks ranks: exit $got, dewall certify's $want"; diff want.out got.out >&2
  fi
}
awk 'NR == 100 { $2 = 17 } { print }' u3.3.txt >u3.m1.txt            # a vertex replaced
awk 'NR != 5000' u3.3.txt >u3.m2.txt                                 # a row dropped
awk '{ print } NR == 7000 { print $4, $3, $2, $1 }' u3.3.txt >u3.m3.txt  # a row repeated, reversed
awk 'NR == 12000 { $1 = 4002 } { print }' u3.3.txt >u3.m4.txt        # an index out of range
awk 'NR == 3 { $1 = $2 } NR == 20000 { $3 = 11 } { print }' u3.3.txt >u3.m5.txt  # a repeated vertex, a vertex replaced
for ranks in 1 2 3; do
  certify_same "$ranks" u3.3.dwsx --canonical
  for m in 1 2 3 4 5; do
    certify_same "$ranks" "u3.m$m.txt"
    certify_same "$ranks" "u3.m$m.txt" --all --canonical
  done
done
grep -q "^not delaunay" got.out || fail "certify: the last mutant not rejected"
for ranks in 2 3; do  # --json, --stream, --memory
  certify_same "$ranks" u3.3.dwsx --json --canonical
  certify_same "$ranks" u3.m1.txt --json --all
  certify_same "$ranks" u3.m4.txt --stream --memory 1K
  certify_same "$ranks" u3.m2.txt --json --stream --memory 64K --all --canonical
done
grep -q '^{"delaunay":false,.*"violations":\[{"rule":' got.out || { fail "certify --json: no violations listed"; cat got.out >&2; }
"$mpiexec" "$np" 2 "$tool" certify u3.dwpt u3.3.dwsx --memory 12Q >got.out 2>&1
[ $? -eq 2 ] && grep -q -- "--memory must be a positive size" got.out || { fail "certify --memory 12Q"; cat got.out >&2; }
"$mpiexec" "$np" 2 "$tool" certify u3.dwpt u3.parts.txt --per-rank --canonical >got.out 2>&1 &&
  grep -q "^delaunay canonical: u3.parts.r\*.txt is the canonical" got.out || { fail "certify --per-rank"; cat got.out >&2; }
# A mutant of the whole set (every file but one vertex of one row as written).
cp u3.parts.r0.txt u3.mparts.r0.txt
cp u3.parts.r2.txt u3.mparts.r2.txt
awk 'NR == 100 { $2 = 17 } { print }' u3.parts.r1.txt >u3.mparts.r1.txt
cmp -s u3.parts.r1.txt u3.mparts.r1.txt && fail "certify --per-rank: the mutant is the original"
"$mpiexec" "$np" 2 "$tool" certify u3.dwpt u3.mparts.txt --per-rank >got.out 2>/dev/null
[ $? -eq 1 ] && grep -q "^not delaunay: u3.mparts.r\*.txt" got.out || { fail "certify --per-rank, a mutant"; cat got.out >&2; }
# Fewer ranks to the same OUT: the earlier run's last file is removed, and the set is this run's.
cp u3.parts.r0.txt u3.stale.r0.txt
cp u3.parts.r1.txt u3.stale.r1.txt
cp u3.parts.r2.txt u3.stale.r2.txt
run 2 triangulate u3.dwpt -o u3.stale.txt --per-rank
[ "$status" -eq 0 ] || { fail "triangulate --per-rank on 2 ranks over an earlier run on 3"; cat run.log >&2; }
[ -e u3.stale.r2.txt ] && fail "triangulate --per-rank on 2 ranks left the third file of an earlier run"
"$mpiexec" "$np" 2 "$tool" certify u3.dwpt u3.stale.txt --per-rank --canonical >got.out 2>&1 ||
  { fail "certify --per-rank after a run on fewer ranks"; cat got.out >&2; }
rm -f want.out got.out
echo "certify: dewall certify's words and status on 1-3 ranks, canonical and mutants; --json, --stream; --per-rank"

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
run 3 certify u3.dwpt missing.txt
expect_error 2 "dewall-mpi: missing.txt: cannot open file" "certify, a missing file"

run 3 triangulate u3.dwpt
expect_error 2 "^dewall-mpi: missing -o OUT$" "no output file"
grep -q "run 'dewall-mpi help'" run.log || fail "no output file: no pointer to the help"
grep -q "^usage:" run.log && fail "no output file: the whole usage printed, not one line and a pointer"

run 2 triangulate u3.dwpt --per-rank -o -
expect_error 2 "^dewall-mpi: --per-rank writes one file per rank" "--per-rank to standard output"

: >empty.dwpt
run 2 triangulate empty.dwpt -o old.txt
mpi_message=$(grep "^dewall-mpi:" run.log | sed 's/^dewall-mpi: //')
"$dewall" triangulate empty.dwpt >/dev/null 2>dewall.log
dewall_status=$?
[ "$status" -eq 2 ] && [ "$dewall_status" -eq 2 ] || fail "an empty input: exit $status, dewall's $dewall_status"
[ "$mpi_message" = "$(sed 's/^dewall: //' dewall.log)" ] || fail "an empty input: '$mpi_message', dewall says '$(cat dewall.log)'"
rm -f empty.dwpt dewall.log

for name in old.dwpt old.NODE; do
  run 2 triangulate u3.dwpt -o "$name"
  [ "$status" -eq 2 ] && grep -q "the name says" run.log || { fail "-o $name: not refused"; cat run.log >&2; }
  [ ! -e "$name" ] || fail "-o $name: created"
done
cp u3.dwpt u3.bin
run 2 triangulate u3.bin -o u3.bin
[ "$status" -eq 2 ] && grep -q "the output is the input" run.log || { fail "-o the input: not refused"; cat run.log >&2; }
cmp -s u3.dwpt u3.bin || fail "-o the input: the input was replaced"
rm -f u3.bin

for args in "help" "help triangulate" "help certify" "--help"; do
  "$mpiexec" "$np" 1 "$tool" $args >help.log 2>&1
  [ $? -eq 0 ] && grep -q "^usage: mpirun -n R dewall-mpi triangulate" help.log || fail "dewall-mpi $args: no usage"
done
rm -f help.log

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
