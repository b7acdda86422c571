#!/usr/bin/env bats
# End-to-end tests of rscene-diff: output blocks, every flag, exit
# statuses like diff(1), and git's external diff driver in a real
# temporary repository (`git diff` and `git log -p --ext-diff`).

BIN="${RSCENE_BIN:-$BATS_TEST_DIRNAME/../build/bin}"
ROOT="$BATS_TEST_DIRNAME/.."
DATA="$ROOT/tests/data"
DIFF="$BIN/rscene-diff"
OLD="$DATA/diff_old.rscene"
NEW="$DATA/diff_new.rscene"

bats_require_minimum_version 1.5.0

setup() {
  [ -x "$DIFF" ] || skip "rscene-diff not built in $BIN"
  mkdir "$BATS_TEST_TMPDIR/w"
  cd "$BATS_TEST_TMPDIR/w"
}

expected_blocks() {
  cat <<'EOF2'
~ editor_ux
    multiSelect: true -> false
~ group /World
    locked: false -> true
~ terrain_region /World/T
    heights: 25 values, 2 changed, max |delta| 0.03
+ light /World/Sun
- light /World/Fill
~ object /World/Props/Box (moved from /World/Box)
~ object /World/Crate
    position: 1,0,0.5 -> 1,0,0.5000000001
    mass: 1 -> 3
EOF2
}

@test "blocks of +, - and ~ with name: old -> new; exit 1 when different" {
  run -1 --separate-stderr "$DIFF" "$OLD" "$NEW"
  [ "$output" = "$(expected_blocks)" ]
  [ -z "$stderr" ]
}

@test "the same scene reordered and respelt is no change: exit 0, no output" {
  [ -x "$BIN/rscene-fmt" ] || skip "rscene-fmt not built"
  "$BIN/rscene-fmt" "$ROOT/tests/data/fmt_messy.rscene" >canonical.rscene
  run -0 "$DIFF" "$ROOT/tests/data/fmt_messy.rscene" canonical.rscene
  [ -z "$output" ]
}

@test "--stat prints counts per kind" {
  run -1 "$DIFF" --stat "$OLD" "$NEW"
  [ "${lines[0]}" = " editor_ux       1 changed" ]
  [ "${lines[2]}" = " light           1 added, 1 removed" ]
  [ "${lines[3]}" = " object          2 changed" ]
  [ "${lines[5]}" = " 7 records: 5 changed, 1 added, 1 removed" ]
}

@test "--format json for machines, also when the scenes are the same" {
  command -v jq >/dev/null || skip "jq not installed"
  run -0 bash -c "'$DIFF' --format json '$OLD' '$NEW' | jq -c '.same, .stat, [.records[] | select(.tag == \"object\") | .oldPath // .fields[1].new]'"
  [ "${lines[0]}" = "false" ]
  [ "${lines[1]}" = '{"added":1,"removed":1,"changed":5,"fieldsChanged":5}' ]
  [ "${lines[2]}" = '["/World/Box","3"]' ]
  run -0 bash -c "'$DIFF' --format=json '$OLD' '$OLD' | jq -c .same"
  [ "$output" = "true" ]
  run -2 "$DIFF" --format yaml "$OLD" "$NEW"
}

@test "--tolerance and --rel-tolerance hide float noise" {
  run -1 "$DIFF" --tolerance 1e-6 "$OLD" "$NEW"
  [[ $output != *"position:"* ]]
  [[ $output == *"mass: 1 -> 3"* ]]
  run -1 "$DIFF" --rel-tolerance 1e-6 "$OLD" "$NEW"
  [[ $output != *"position:"* ]]
  run -2 "$DIFF" --tolerance -1 "$OLD" "$NEW"
}

@test "--ignore-editor-state and --ignore KEY,..." {
  run -1 "$DIFF" --ignore-editor-state "$OLD" "$NEW"
  [[ $output != *"editor_ux"* && $output != *"locked"* ]]
  run -1 "$DIFF" --ignore heights,object.mass,position "$OLD" "$NEW"
  [[ $output != *"heights"* && $output != *"mass"* && $output != *"position"* ]]
  [[ $output == *"multiSelect"* ]]
}

@test "-q and --quiet print nothing; the exit status tells" {
  run -1 "$DIFF" -q "$OLD" "$NEW"
  [ -z "$output" ]
  run -0 "$DIFF" --quiet "$OLD" "$OLD"
  [ -z "$output" ]
}

@test "standard input on one side, named by --stdin-filename" {
  run -1 bash -c "'$DIFF' - '$NEW' < '$OLD'"
  [[ $output == *"mass: 1 -> 3"* ]]
  run -2 --separate-stderr "$DIFF" --stdin-filename old.rscene - "$NEW" <<<"time_step 1"
  [ "${stderr_lines[0]}" = "old.rscene:1:1: error: missing raisim_engine_scene header [RS1001]" ]
  run -2 "$DIFF" - - </dev/null
}

@test "trouble is exit 2: unreadable file, wrong operand count" {
  run -2 --separate-stderr "$DIFF" "$OLD" missing.rscene
  [ "${stderr_lines[0]}" = "rscene-diff: error: cannot read 'missing.rscene': No such file or directory" ]
  run -2 "$DIFF" "$OLD"
  run -2 "$DIFF" a b c
}

@test "seven arguments: git's external diff form exits 0" {
  run -0 "$DIFF" scene.rscene "$OLD" 1111111 100644 "$NEW" 2222222 100644
  [ "${lines[0]}" = "rscene-diff a/scene.rscene b/scene.rscene" ]
  [ "${lines[1]}" = "~ editor_ux" ]
  run -0 "$DIFF" new.rscene /dev/null . . "$NEW" 2222222 100644
  [ "${lines[1]}" = "+ raisim_engine_scene" ]
  [ "${lines[2]}" = "+ time_step" ]
  run -0 "$DIFF" old.rscene "$OLD" 1111111 100644 /dev/null . .
  [ "${lines[2]}" = "- time_step" ]
}

@test "git diff and git log -p --ext-diff use it through .gitattributes" {
  command -v git >/dev/null || skip "git not installed"
  git init -q repo
  cd repo
  git config user.email t@example.com
  git config user.name t
  git config diff.rscene.command "$DIFF"
  echo '*.rscene diff=rscene' >.gitattributes
  cp "$OLD" scene.rscene
  git add .gitattributes scene.rscene
  git commit -q -m one
  cp "$NEW" scene.rscene
  run -0 git diff
  [ "${lines[0]}" = "rscene-diff a/scene.rscene b/scene.rscene" ]
  [[ $output == *"~ object /World/Props/Box (moved from /World/Box)"* ]]
  [[ $output != *"@@"* ]]
  git commit -q -am two
  run -0 git log -p --ext-diff --format=%s
  [[ $output == *"mass: 1 -> 3"* ]]
  [[ $output == *"+ time_step"* ]]  # the first commit adds the file
  run -0 git log -p --format=%s
  [[ $output == *"@@"* ]]  # without --ext-diff, log keeps line diffs
}

@test "--help and --version" {
  run -0 "$DIFF" --help
  [[ $output == *"--ignore-editor-state"* && $output == *"--rel-tolerance"* ]]
  run -0 "$DIFF" --version
  [[ $output == "rscene-diff "* ]]
  run -2 "$DIFF" --no-such-flag "$OLD" "$NEW"
}
