#!/usr/bin/env bash
# tests/fuzz/run.sh - builds the libFuzzer targets in build-fuzz (clang,
# ASan+UBSan) and runs each for ${FUZZ_SECONDS:-60} seconds, one after the
# other, from seed corpora made of the test fixtures, the examples and
# ../shared/corpus when present:
#   fuzz_loader     the .rscene loader, writer and validator
#   fuzz_from_json  rscene-from-json's reader (seeds: the scenes as JSON)
#   fuzz_sim        rscene-sim's world build, 200 steps with grains, deformables
#                   and sensor readings (meshes missing)
#   fuzz_render_scene  rscene-render's scene preparation, without GL
#   fuzz_urdf       the URDF reader (seeds: tests/data/robots/urdf, examples/robots)
#   fuzz_trajectory rscene-render --trajectory's reader (seeds: a JSON Lines and a CSV trajectory)
#   fuzz_xml_world  rscene-from-xml's reading and template expansion (seeds: tests/data/xml, xml-examples)
# Exit status: 0 when nothing was found, non-zero on a crash, a leak, a
# timeout or a broken invariant (the inputs are in build-fuzz/fuzz-artifacts/).
#
# Environment: FUZZ_SECONDS (per target), FUZZ_TARGETS (default: all of
# them), FUZZ_BUILD_DIR (default build-fuzz), FUZZ_JOBS (build parallelism,
# default 2), FUZZ_ARGS (extra libFuzzer flags).
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
TARGETS=(${FUZZ_TARGETS:-fuzz_loader fuzz_from_json fuzz_sim fuzz_render_scene fuzz_urdf fuzz_trajectory fuzz_xml_world})
cmake --build "$BUILD" -j "${FUZZ_JOBS:-2}" --target "${TARGETS[@]}" make_json_seeds

# The working corpora live in the build directory: libFuzzer adds the
# inputs it finds there, and the seeds in the repository stay as they are.
ARTIFACTS=$BUILD/fuzz-artifacts
mkdir -p "$ARTIFACTS" "$BUILD/fuzz-corpus" "$BUILD/fuzz-corpus-json" "$BUILD/fuzz-corpus-sim" "$BUILD/fuzz-corpus-render"
shopt -s nullglob
# The hostile-input review's reproducers (../shared/repro) seed them too.
seeds=("$ROOT"/tests/data/*.rscene "$ROOT"/examples/*.rscene "$ROOT"/../shared/corpus/*.rscene
  "$ROOT"/../shared/repro/*/*.rscene)
for f in "${seeds[@]}"; do
  for dir in fuzz-corpus fuzz-corpus-sim fuzz-corpus-render; do
    cp -f "$f" "$BUILD/$dir/seed_$(basename "$(dirname "$f")")_$(basename "$f")"
  done
done
"$BUILD/bin/make_json_seeds" "$BUILD/fuzz-corpus-json" "${seeds[@]}"
mkdir -p "$BUILD/fuzz-corpus-urdf"
for f in "$ROOT"/tests/data/robots/urdf/*.urdf "$ROOT"/examples/robots/*/*.urdf "$ROOT"/../shared/corpus/robots/*/*.urdf \
  "$ROOT"/../shared/corpus/robots/*/urdf/*.urdf; do
  cp -f "$f" "$BUILD/fuzz-corpus-urdf/seed_$(basename "$(dirname "$f")")_$(basename "$f")"
done
mkdir -p "$BUILD/fuzz-corpus-trajectory"
printf '%s\n' '{"time":0,"path":"/box","position":[0,0,1],"quaternion":[1,0,0,0],"linearVelocity":[0,0,0],"angularVelocity":[0,0,0]}' \
  '{"time":0,"path":"/arm","position":[0,0,1],"quaternion":[1,0,0,0],"jointPositions":{"j1_qw":1,"j1_qx":0,"j1_qy":0,"j1_qz":0}}' \
  '{"time":0.5,"path":"/box","position":[0,0,0.9],"quaternion":[1,0,0,0]}' \
  '{"time":0.5,"path":"/cloth","points":[[0,0,1],[1,0,1],[0,1,1],[1,1,1]]}' \
  '{"time":0.5,"path":"/sand","points":[[0,0,0.1],[0.2,0,0.1]]}' > "$BUILD/fuzz-corpus-trajectory/seed.jsonl"
printf '%s\n' 'time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,q.j1_qw,u.j1_wx,points' '0,/box,0,0,1,1,0,0,0,0,0,0,0,0,0,,,' \
  '0,"/arm",0,0,1,1,0,0,0,0,0,0,0,0,0,1,0,' '0.5,/box,0,0,0.9,1,0,0,0,0,0,0,0,0,0,,,' \
  '0.5,/cloth,,,,,,,,,,,,,,,,0 0 1;1 0 1;0 1 1;1 1 1' '0.5,/sand,,,,,,,,,,,,,,,,0 0 0.1' > "$BUILD/fuzz-corpus-trajectory/seed.csv"
mkdir -p "$BUILD/fuzz-corpus-xml"
for f in "$ROOT"/tests/data/xml/*.xml "$ROOT"/tests/data/xml/*/*.xml "$ROOT"/../shared/spec/raisim/xml-examples/*.xml; do
  cp -f "$f" "$BUILD/fuzz-corpus-xml/seed_$(basename "$f")"
done
XML_DICT=$BUILD/fuzz-xml.dict
printf '%s\n' '"<array idx=\"@@i\" start=\"0\" end=\"@@n\" increment=\"1\">"' '"</array>"' \
  '"<params><n value=\"2\"/></params>"' '"exist=\"@@on\""' '"{1+@@i*0.5}"' '"{sin(1)}"' '"{log(0)}"' \
  '"<include file=\"x.xml\"/>"' '"<object_class><c type=\"compound\"><children><box object_param=\"1 2 3\" pos=\"0 0 0\"/></children></c></object_class>"' \
  '"<c name=\"a\"/>"' '"<dimension radius=\"1\"/>"' '"[THIS_DIR]"' '"&lol;"' '"<!DOCTYPE raisim [<!ENTITY a \"b\">]>"' \
  '"<objects>"' '"</objects>"' > "$XML_DICT"
URDF_DICT=$BUILD/fuzz-urdf.dict
printf '%s\n' '"<link name=\"a\">"' '"</link>"' '"<joint name=\"j\" type=\"spherical\">"' '"type=\"floating\""' \
  '"<parent link=\"world\"/>"' '"<child link=\"a\"/>"' '"<origin xyz=\"0 0 1\" rpy=\"0 1 0\"/>"' \
  '"<axis xyz=\"0 0 0\"/>"' '"spring_mount=\"0 0 0 0\""' '"<limit lower=\"1\" upper=\"-1\"/>"' \
  '"<mesh filename=\"package://x/y.stl\" scale=\"1 2\"/>"' '"<capsule radius=\"1\" height=\"-1\"/>"' \
  '"<material name=\"m\"><texture filename=\"t.png\"/></material>"' '"${x}"' '"@@X"' '"nan"' '"1e400"' > "$URDF_DICT"

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

# The JSON reader's dictionary: the loader's words as member names, and
# the structure of the JSON form.
JSON_DICT=$BUILD/fuzz-json.dict
{
  sed -n 's/^"\([A-Za-z_][A-Za-z0-9_]*\)=\{0,1\}"$/"\\"\1\\":"/p' "$DICT" | sort -u
  printf '%s\n' '"{\"format\":\"rscene\",\"version\":1,\"records\":["' '"\"fields\":{"' '"\"tokens\":["' \
    '"\"unknownKeys\":["' '"\"unknownTag\":true"' '"\"comments\":["' '"\"positionalCount\":"' '"{\"raw\":"' \
    '"\"trailingComments\":["' '"\\u0000"' '"\\ud800"' '"-0"' '"1e308"' '"[["' '"]]"'
} > "$JSON_DICT"

status=0
for target in "${TARGETS[@]}"; do
  case $target in
    fuzz_loader) corpus=$BUILD/fuzz-corpus dict=$DICT ;;
    fuzz_from_json) corpus=$BUILD/fuzz-corpus-json dict=$JSON_DICT ;;
    fuzz_sim) corpus=$BUILD/fuzz-corpus-sim dict=$DICT ;;
    fuzz_render_scene) corpus=$BUILD/fuzz-corpus-render dict=$DICT ;;
    fuzz_urdf) corpus=$BUILD/fuzz-corpus-urdf dict=$URDF_DICT ;;
    fuzz_trajectory) corpus=$BUILD/fuzz-corpus-trajectory dict=$JSON_DICT ;;
    fuzz_xml_world) corpus=$BUILD/fuzz-corpus-xml dict=$XML_DICT ;;
    *) echo "tests/fuzz/run.sh: error: unknown target '$target'" >&2; exit 2 ;;
  esac
  echo "$target: fuzzing for ${SECONDS_TO_RUN}s from $(find "$corpus" -type f | wc -l) inputs, $(wc -l < "$dict") dictionary entries"
  # shellcheck disable=SC2086
  "$BUILD/bin/$target" -max_total_time="$SECONDS_TO_RUN" -max_len=65536 -rss_limit_mb=2048 -timeout=10 \
    -print_final_stats=1 -artifact_prefix="$ARTIFACTS/$target-" -dict="$dict" ${FUZZ_ARGS:-} "$corpus" || {
    status=$?
    echo "tests/fuzz/run.sh: $target stopped with status $status; reproducer(s):" >&2
    ls -1 "$ARTIFACTS" >&2
  }
done
exit $status
