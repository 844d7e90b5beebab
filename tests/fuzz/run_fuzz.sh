#!/usr/bin/env bash
# Runs the blob fuzzer for a bounded time: tests/fuzz/run_fuzz.sh BUILD_DIR SECONDS
# BUILD_DIR must have been configured with PRT_BUILD_FUZZERS=ON (preset "fuzz"). First the smoke
# test (fuzz.blob_smoke: a short fixed-seed run from the golden blobs), then the timed run. The
# corpus is seeded from every golden blob into BUILD_DIR/fuzz/corpus (nothing is written into the
# source tree). At the end it prints the edge coverage of the technique section checkers
# (formats/src/<technique>/, per function) and of the runtime's technique files (per file), from
# libFuzzer's -print_coverage=1; the full coverage listing is kept in BUILD_DIR/fuzz/coverage.txt.
# Exits non-zero if the fuzzer finds a crash, an over-read, undefined behaviour or a leak, or if
# a technique's checker (formats/src/<t>/ for each t of PRT_TECHNIQUES) has no covered edge after
# the run: its golden blobs are missing from the seeds or never reach it.
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 BUILD_DIR SECONDS" >&2
  exit 2
fi
build_dir=$1
seconds=$2
here=$(cd "$(dirname "$0")" && pwd)
source_dir=$(cd "$here/../.." && pwd)
fuzzer="$build_dir/tests/fuzz/prt_fuzz_blob"
if [ ! -x "$fuzzer" ]; then
  echo "run_fuzz: $fuzzer not found; configure with --preset fuzz and build prt_fuzz_blob" >&2
  exit 2
fi

echo "run_fuzz: smoke test"
ctest --test-dir "$build_dir" -R '^fuzz\.blob_smoke$' --output-on-failure --no-tests=error

corpus="$build_dir/fuzz/corpus"
seeds="$build_dir/fuzz/seeds"
artifacts="$build_dir/fuzz/artifacts/"
log="$build_dir/fuzz/coverage.txt"
seeds_log="$build_dir/fuzz/coverage_seeds.txt"
rm -rf "$seeds"
mkdir -p "$corpus" "$seeds" "$artifacts"
find "$source_dir/formats/golden" \( -name '*.prtk' -o -name '*.prts' \) -exec cp {} "$corpus/" \; -exec cp {} "$seeds/" \;
# What the golden blobs alone reach, for comparison with the run.
"$fuzzer" -runs=0 -print_coverage=1 "$seeds" >"$seeds_log" 2>&1
echo "run_fuzz: $fuzzer for ${seconds}s, corpus $corpus"
set +e
"$fuzzer" -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
  -dict="$here/blob.dict" -artifact_prefix="$artifacts" -print_final_stats=1 -print_coverage=1 \
  "$corpus" 2>&1 | tee "$log" | grep --line-buffered -v -E '^(COVERAGE:|COVERED_FUNC:|UNCOVERED_FUNC:|  UNCOVERED_PC:)'
status=${PIPESTATUS[0]}
set -e

# COVERED_FUNC: hits: N edges: covered/total NAME FILE:LINE (UNCOVERED_FUNC alike, 0 covered).
# Static helpers inlined into a function count as its edges. The totals include the blocks of
# the sanitizers' checks, which a run without undefined behaviour never enters.
# The techniques of PRT_TECHNIQUES (written at configure time); staged ones have no golden blobs.
techniques=$(cat "$build_dir/tests/fuzz/checked_techniques.txt")
echo "run_fuzz: edges covered by the golden blobs alone, and after the run"
awk -v techniques="$techniques" '
  /^(COVERED|UNCOVERED)_FUNC:/ {
    split($5, e, "/")
    file = $7
    sub(/:[0-9]+$/, "", file)
    if (!match(file, /(formats|runtime)\/src\/[a-z0-9_]+\/[^\/]+$/)) next
    file = substr(file, RSTART)
    if (file ~ /^formats\/src\/mesh\//) next
    n = 0
    if (file ~ /^formats\//) keys[++n] = file " " $6  # checkers: per function and per file
    keys[++n] = file " (file)"
    for (i = 1; i <= n; ++i) {
      k = keys[i]
      if (FILENAME == ARGV[1]) {
        seeds[k] += e[1]
      } else {
        if (!(k in total)) order[++count] = k
        covered[k] += e[1]
        total[k] += e[2]
      }
    }
    if (FILENAME != ARGV[1] && file ~ /^formats\//) {
      split(file, dirs, "/")
      checker_edges[dirs[3]] += e[1]
    }
  }
  END {
    for (pass = 0; pass < 2; ++pass)
      for (i = 1; i <= count; ++i) {
        k = order[i]
        if ((k ~ /^formats\//) != (pass == 0)) continue
        split(k, part, " ")
        printf "  %-40s %-20s seeds %4d, run %4d / %-4d edges (%5.1f %%)\n", part[1], part[2],
               seeds[k], covered[k], total[k], total[k] ? 100 * covered[k] / total[k] : 0
      }
    n = split(techniques, names, " ")
    for (i = 1; i <= n; ++i)
      if (!checker_edges[names[i]]) {
        print "run_fuzz: no covered edge of formats/src/" names[i] "/ in the report" > "/dev/stderr"
        missing = 1
      }
    if (missing) exit 1
  }' "$seeds_log" "$log" || status=${status/#0/1}
exit "$status"
