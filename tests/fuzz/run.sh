#!/usr/bin/env bash
# tests/fuzz/run.sh - builds the libFuzzer target in build-fuzz (clang,
# ASan+UBSan) and fuzzes the loader for ${FUZZ_SECONDS:-60} seconds from a
# seed corpus of the test fixtures, the examples and ../shared/corpus when
# present.  Exit status: 0 when nothing was found, non-zero on a crash, a
# leak, a timeout or a broken invariant (the input is in
# build-fuzz/fuzz-artifacts/).
#
# Environment: FUZZ_SECONDS, FUZZ_BUILD_DIR (default build-fuzz),
# FUZZ_JOBS (build parallelism, default 2), FUZZ_ARGS (extra libFuzzer flags).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${FUZZ_BUILD_DIR:-$ROOT/build-fuzz}
SECONDS_TO_RUN=${FUZZ_SECONDS:-60}

if ! command -v clang++ > /dev/null; then
  echo "tests/fuzz/run.sh: error: clang++ is missing (scripts/install-deps.sh installs it)" >&2
  exit 2
fi
CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DRSCENE_FUZZ=ON -DRSCENE_BUILD_TOOLS=OFF -DRSCENE_BUILD_TESTS=OFF > "$BUILD.configure.log" 2>&1 ||
  { cat "$BUILD.configure.log" >&2; exit 2; }
cmake --build "$BUILD" -j "${FUZZ_JOBS:-2}" --target fuzz_loader

# The working corpus lives in the build directory: libFuzzer adds the
# inputs it finds there, and the seeds in the repository stay as they are.
CORPUS=$BUILD/fuzz-corpus
ARTIFACTS=$BUILD/fuzz-artifacts
mkdir -p "$CORPUS" "$ARTIFACTS"
shopt -s nullglob
seeds=("$ROOT"/tests/data/*.rscene "$ROOT"/examples/*.rscene "$ROOT"/../shared/corpus/*.rscene)
for f in "${seeds[@]}"; do cp -f "$f" "$CORPUS/seed_$(basename "$f")"; done

# A dictionary of the tags and keys the seeds use helps the mutator build
# records that get past the first token.
DICT=$BUILD/fuzz.dict
{
  for f in "${seeds[@]}"; do
    grep -v '^#' "$f" | tr ' \t' '\n\n' | sed -n 's/^\([A-Za-z_][A-Za-z0-9_]*\)=.*/\1=/p'
    grep -v '^#' "$f" | awk '{ print $1 }'
  done
} | grep -E '^[A-Za-z_][A-Za-z0-9_]*=?$' | sort -u | sed 's/.*/"&"/' > "$DICT"
cat >> "$DICT" << 'ENTRIES'
"%"
"%20"
"%3d"
"-"
";"
","
"\x0D\x0A"
"\x09"
"18446744073709551615"
"1e-07"
"raisim_engine_scene 2\x0A"
ENTRIES

echo "fuzzing for ${SECONDS_TO_RUN}s: ${#seeds[@]} seeds, $(wc -l < "$DICT") dictionary entries"
status=0
# shellcheck disable=SC2086
"$BUILD/bin/fuzz_loader" -max_total_time="$SECONDS_TO_RUN" -max_len=65536 -rss_limit_mb=2048 -timeout=10 \
  -print_final_stats=1 -artifact_prefix="$ARTIFACTS/" -dict="$DICT" ${FUZZ_ARGS:-} "$CORPUS" || status=$?
if ((status != 0)); then
  echo "tests/fuzz/run.sh: the fuzzer stopped with status $status; reproducer(s):" >&2
  ls -1 "$ARTIFACTS" >&2
fi
exit $status
