#!/usr/bin/env bash
# Runs the blob fuzzer for a bounded time: tests/fuzz/run_fuzz.sh BUILD_DIR SECONDS
# BUILD_DIR must have been configured with PRT_BUILD_FUZZERS=ON (preset "fuzz"). The corpus is
# seeded from the golden blobs into BUILD_DIR/fuzz/corpus (nothing is written into the source tree).
# Exits non-zero if the fuzzer finds a crash, an over-read, undefined behaviour or a leak.
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
corpus="$build_dir/fuzz/corpus"
artifacts="$build_dir/fuzz/artifacts/"
mkdir -p "$corpus" "$artifacts"
find "$source_dir/formats/golden" -name '*.prtk' -exec cp {} "$corpus/" \;
echo "run_fuzz: $fuzzer for ${seconds}s, corpus $corpus"
exec "$fuzzer" -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
  -dict="$here/blob.dict" -artifact_prefix="$artifacts" -print_final_stats=1 "$corpus"
