#!/usr/bin/env bats
# End-to-end tests of rscene-to-json and rscene-from-json: the lossless
# round trip through `jq .` on every scene we have, every flag, exit
# statuses, and exact messages for bad input.

load helpers
TO="$BIN/rscene-to-json"
FROM="$BIN/rscene-from-json"

setup() {
  needs_tools rscene-to-json rscene-from-json
  in_workdir
}

header_json='{"tag":"raisim_engine_scene","fields":{"version":1}}'

@test "to-json | jq . | from-json equals rscene-fmt on every fixture, example and corpus file" {
  command -v jq >/dev/null || skip "jq not installed"
  [ -x "$BIN/rscene-fmt" ] || skip "rscene-fmt not built"
  n=0
  for f in "$DATA"/*.rscene "$ROOT"/examples/*.rscene "$SHARED"/corpus/*.rscene; do
    [ -f "$f" ] || continue
    "$BIN/rscene-fmt" "$f" >expected 2>/dev/null || continue
    "$TO" "$f" | jq . | "$FROM" >actual
    cmp expected actual || { echo "round trip differs: $f"; return 1; }
    n=$((n + 1))
  done
  [ "$n" -ge 4 ]
}

@test "jq sees typed fields: numbers, booleans, arrays and uint64 masks as strings" {
  command -v jq >/dev/null || skip "jq not installed"
  run -0 bash -c "'$TO' '$DATA/json_tricky.rscene' | jq -c '.records[] | select(.tag == \"object\") | .fields | [.position, .mass, .visible, .collisionMask, .meshPath]'"
  [ "${lines[0]}" = '[[0,0,"-0"],2.5,true,"18446744073709551615","-"]' ]
  run -0 bash -c "'$TO' '$DATA/json_tricky.rscene' | jq -c '.records[3].unknownKeys, .records[7].unknownTag, .trailingComments'"
  [ "${lines[0]}" = '["futureShader","blank"]' ]
  [ "${lines[1]}" = 'true' ]
  [ "${lines[2]}" = '["# trailing comment"]' ]
}

@test "output is compact when not a terminal; --pretty indents; --compact is one line" {
  run -0 "$TO" "$DATA/json_tricky.rscene"
  [ "${#lines[@]}" -eq 1 ]
  run -0 "$TO" --compact "$DATA/json_tricky.rscene"
  [ "${#lines[@]}" -eq 1 ]
  run -0 "$TO" -p "$DATA/json_tricky.rscene"
  [ "${lines[0]}" = "{" ]
  [ "${lines[1]}" = '  "format": "rscene",' ]
  [ "${lines[2]}" = '  "version": 2,' ]
  run -2 "$TO" --compact --pretty "$DATA/json_tricky.rscene"
}

@test "--schema prints a 2020-12 JSON Schema naming every record kind" {
  command -v jq >/dev/null || skip "jq not installed"
  run -0 bash -c "'$TO' --schema | jq -r '.\"\$schema\", (.\"\$defs\" | keys | map(select(startswith(\"fields_\"))) | length)'"
  [ "${lines[0]}" = "https://json-schema.org/draft/2020-12/schema" ]
  [ "${lines[1]}" -ge 39 ]
}

@test "-o writes the file; --output for from-json too" {
  run -0 "$TO" -o out.json "$DATA/json_tricky.rscene"
  [ -z "$output" ]
  run -0 "$FROM" --output out.rscene out.json
  [ -z "$output" ]
  run -0 cmp out.rscene <("$BIN/rscene-fmt" "$DATA/json_tricky.rscene")
  run -0 "$TO" --schema --output schema.json
  grep -q '"\$schema"' schema.json
}

@test "standard input and --stdin-filename" {
  run -0 bash -c "'$TO' < '$DATA/json_tricky.rscene' | '$FROM' - > back.rscene"
  run -0 cmp back.rscene <("$BIN/rscene-fmt" "$DATA/json_tricky.rscene")
  run -2 --separate-stderr "$TO" --stdin-filename scene.rscene <<<"time_step 1"
  [ -z "$output" ]
  [ "${stderr_lines[0]}" = "scene.rscene:1:1: error: missing raisim_engine_scene header [RS1001]" ]
  run -2 --separate-stderr "$FROM" --stdin-filename scene.json <<<"[]"
  [ "${stderr_lines[0]}" = "scene.json:1:1: error: /: expected a JSON object at the top level [RS8002]" ]
}

@test "from-json: invalid JSON is exit 2 with line and column" {
  printf '{"format": "rscene",\n "version": 1,, }\n' >bad.json
  run -2 --separate-stderr "$FROM" bad.json
  [ -z "$output" ]
  [[ ${stderr_lines[0]} == "bad.json:2:15: error: invalid JSON: syntax error while parsing object key"*"[RS8001]" ]]
}

@test "from-json: a schema mismatch names the JSON pointer" {
  printf '{"format":"rscene","version":1,"records":[%s,\n{"tag":"time_step","fields":{"dt":true}}]}\n' "$header_json" >bad.json
  run -2 --separate-stderr "$FROM" bad.json
  [ "${stderr_lines[0]}" = "bad.json:2:30: error: /records/1/fields/dt: expected number, got a boolean [RS8002]" ]
  printf '{"format":"rscene","version":1,"records":[%s,{"tag":"material","fields":{"name":"m","colr":1}}]}\n' "$header_json" >bad.json
  run -2 --separate-stderr "$FROM" bad.json
  [[ ${stderr_lines[0]} == *"/records/1/fields: missing positional field 'color' [RS8002]" ]]
}

@test "from-json: a failed conversion leaves an existing output file alone" {
  echo "keep me" >out.rscene
  echo '{"format":"rscene"' >bad.json
  run -2 "$FROM" -o out.rscene bad.json
  [ "$(cat out.rscene)" = "keep me" ]
}

@test "to-json: an unreadable file is exit 2" {
  run -2 --separate-stderr "$TO" missing.rscene
  [ "${stderr_lines[0]}" = "rscene-to-json: error: cannot read 'missing.rscene': No such file or directory" ]
}

@test "--help and --version" {
  run -0 "$TO" --help
  [[ $output == *"--compact"* && $output == *"--schema"* ]]
  run -0 "$FROM" --help
  [[ $output == *"--output"* ]]
  run -0 "$TO" --version
  [[ $output == "rscene-to-json "* ]]
  run -0 "$FROM" --version
  [[ $output == "rscene-from-json "* ]]
  run -2 "$TO" --no-such-flag
}

@test "from-json: 100 k nested objects fail at once, in bounded memory" {
  awk 'BEGIN { printf "{\"zz\":"; for (i = 0; i < 100000; i++) printf "{\"a\":"; printf "1";
               for (i = 0; i < 100000; i++) printf "}"; print "}" }' > deep.json
  run -2 --separate-stderr bash -c "ulimit -v 400000; ulimit -t 10; '$FROM' deep.json"
  [[ ${stderr_lines[0]} == "deep.json:1:"*": error: /zz/a/"*"nesting deeper than 32 levels (a scene nests at most 6) [RS8002]" ]]
}

@test "rscene-from-json(1)'s rename example, run as printed, gives a scene rscene-validate accepts" {
  command -v jq >/dev/null || skip "jq not installed"
  [ -x "$BIN/rscene-validate" ] || skip "rscene-validate not built"
  export PATH="$BIN:$PATH"
  # The example's lines: the literal display after "Rename a material", with
  # mdoc's \e turned back into a backslash.
  awk '/^Rename a material/ { want = 1 } want && /^\.Bd -literal/ { on = 1; next } on && /^\.Ed/ { exit }
       on { gsub(/\\e/, "\\"); print }' "$ROOT/man/rscene-from-json.1" > rename.sh
  grep -q '^  | rscene-from-json -o scene.rscene$' rename.sh
  sed 's/mat_safety/mat_old/g' "$ROOT/examples/warehouse_crates.rscene" > scene.rscene
  [ "$(grep -c 'mat_old' scene.rscene)" -ge 4 ]
  run -0 "$BIN/rscene-validate" scene.rscene
  run -0 bash -e -o pipefail rename.sh
  run -0 --separate-stderr "$BIN/rscene-validate" scene.rscene
  ! grep -q mat_old scene.rscene
  # the material record, its id and every reference
  grep -q '^material mat_new .* id=mat_new' scene.rscene
  [ "$(grep -c ' mat_new ' scene.rscene)" -eq "$(sed 's/mat_safety/mat_old/g' "$ROOT/examples/warehouse_crates.rscene" | grep -c ' mat_old ')" ]
}
