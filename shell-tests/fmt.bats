#!/usr/bin/env bats
# End-to-end tests of rscene-fmt: every flag and exit status, exact
# messages for bad input, and the formatter's invariants on real files.

load helpers
FMT="$BIN/rscene-fmt"

setup() {
  needs_tools rscene-fmt
  in_workdir
}

# The canonical text of tests/data/fmt_messy.rscene.  The compound_child
# before any compound is an orphan: it sorts with the compound kinds, in
# file order.
messy_formatted() {
  cat <<'EOF'
# A hand-edited scene: everything rscene-fmt normalises, in one file.
raisim_engine_scene 1
time_step 0.0025
gravity 0 0 -9.81
future_record alpha beta=1
# the only material
material mat_crate 1 0.42 0.05 1 0 0.6 0 0 0 0 false - - - - - - id=mat_crate
group /World id=folder_world parentId=- visible=true
# objects before their materials
object /World/Crate box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 2.5 default mat_crate false true false - dynamic true 1 18446744073709551615 id=object_crate futureKey=Keep%20Me
compound_child /World/Cart box 0 0 0 1 0 0 0 1 1 1 size=1,1,1
compound /World/Cart 0 0 1 1 0 0 0 1 1 1 10 dynamic true true id=compound_cart
compound_child /World/Cart sphere 0 0 0.5 1 0 0 0 1 1 1 radius=0.25
EOF
}

# --- standard input and output ---------------------------------------------

@test "stdin to stdout when there are no operands" {
  run --separate-stderr "$FMT" < "$DATA/fmt_messy.rscene"
  [ "$status" -eq 0 ]
  [ "$output" = "$(messy_formatted)" ]
  [ -z "$stderr" ]
}

@test "- operand reads standard input" {
  run --separate-stderr "$FMT" - < "$DATA/fmt_messy.rscene"
  [ "$status" -eq 0 ]
  [ "$output" = "$(messy_formatted)" ]
}

@test "file operand to stdout ends in exactly one newline" {
  "$FMT" "$DATA/fmt_messy.rscene" > out.rscene
  [ "$(tail -c 1 out.rscene | od -An -c | tr -d ' ')" = '\n' ]
  [ "$(tail -c 2 out.rscene | head -c 1)" != "" ]
  ! grep -q '[[:space:]]$' out.rscene
  ! grep -q '^$' out.rscene
}

@test "a canonical file is a fixed point" {
  run --separate-stderr "$FMT" "$DATA/fmt_canonical.rscene"
  [ "$status" -eq 0 ]
  [ "$output" = "$(cat "$DATA/fmt_canonical.rscene")" ]
  "$FMT" "$DATA/fmt_canonical.rscene" | cmp - "$DATA/fmt_canonical.rscene"
}

# --- -o / --output -----------------------------------------------------------

@test "-o writes the canonical text to a file and nothing to stdout" {
  run --separate-stderr "$FMT" -o out.rscene "$DATA/fmt_messy.rscene"
  [ "$status" -eq 0 ]
  [ -z "$output" ]
  [ "$(cat out.rscene)" = "$(messy_formatted)" ]
}

@test "--output= long form" {
  run "$FMT" --output=out.rscene "$DATA/fmt_canonical.rscene"
  [ "$status" -eq 0 ]
  cmp out.rscene "$DATA/fmt_canonical.rscene"
}

@test "-o does not create the output file on a parse error" {
  printf 'time_step 1\n' > bad.rscene
  run --separate-stderr "$FMT" -o out.rscene bad.rscene
  [ "$status" -eq 2 ]
  [ ! -e out.rscene ]
  [ -z "$(ls -A | grep -v '^bad.rscene$')" ]  # no temporary file left behind
}

@test "-o leaves an existing output file alone on a parse error" {
  printf 'keep me\n' > out.rscene
  printf 'raisim_engine_scene 9\n' > bad.rscene
  run "$FMT" -o out.rscene bad.rscene
  [ "$status" -eq 2 ]
  [ "$(cat out.rscene)" = "keep me" ]
}

@test "-o with two inputs is a usage error" {
  run --separate-stderr "$FMT" -o out.rscene "$DATA/fmt_messy.rscene" "$DATA/fmt_canonical.rscene"
  [ "$status" -eq 2 ]
  [ "$stderr" = "rscene-fmt: error: --output takes a single input" ]
  [ ! -e out.rscene ]
}

# --- -i / --in-place ---------------------------------------------------------

@test "-i rewrites a non-canonical file and keeps its permissions" {
  cp "$DATA/fmt_messy.rscene" s.rscene
  chmod 640 s.rscene
  run --separate-stderr "$FMT" -i s.rscene
  [ "$status" -eq 0 ]
  [ -z "$output" ]
  [ -z "$stderr" ]
  [ "$(cat s.rscene)" = "$(messy_formatted)" ]
  [ "$(stat -c %a s.rscene)" = "640" ]
}

@test "--in-place leaves a canonical file untouched (mtime kept)" {
  cp "$DATA/fmt_canonical.rscene" c.rscene
  touch -d '2001-02-03 04:05:06' c.rscene
  before=$(stat -c %Y c.rscene)
  run "$FMT" --in-place c.rscene
  [ "$status" -eq 0 ]
  [ "$(stat -c %Y c.rscene)" = "$before" ]
  cmp c.rscene "$DATA/fmt_canonical.rscene"
}

@test "-i on a file that changes updates its mtime" {
  cp "$DATA/fmt_messy.rscene" s.rscene
  touch -d '2001-02-03 04:05:06' s.rscene
  before=$(stat -c %Y s.rscene)
  "$FMT" -i s.rscene
  [ "$(stat -c %Y s.rscene)" != "$before" ]
}

@test "-i on a parse error leaves the file byte-identical and exits 2" {
  printf 'raisim_engine_scene 1\ntime_step 0.50\nmaterial a%%G1 1 1 1 1 0 0.5 0 0 0 0 false - - - - - -\n' > bad.rscene
  cp bad.rscene orig.rscene
  run --separate-stderr "$FMT" -i bad.rscene
  [ "$status" -eq 2 ]
  cmp bad.rscene orig.rscene
  [ "$(ls -A | sort | tr '\n' ' ')" = "bad.rscene orig.rscene " ]
}

@test "-i formats the good files even when another one fails" {
  cp "$DATA/fmt_messy.rscene" good.rscene
  printf 'time_step 1\n' > bad.rscene
  run "$FMT" -i bad.rscene good.rscene
  [ "$status" -eq 2 ]
  [ "$(cat good.rscene)" = "$(messy_formatted)" ]
  [ "$(cat bad.rscene)" = "time_step 1" ]
}

@test "-i refuses standard input" {
  run --separate-stderr "$FMT" -i - < "$DATA/fmt_messy.rscene"
  [ "$status" -eq 2 ]
  [ "$stderr" = "rscene-fmt: error: --in-place needs file operands, not standard input" ]
  [ -z "$output" ]
}

@test "-i cannot be combined with --check" {
  cp "$DATA/fmt_messy.rscene" s.rscene
  run --separate-stderr "$FMT" -i --check s.rscene
  [ "$status" -eq 2 ]
  [ "$stderr" = "rscene-fmt: error: --in-place cannot be combined with --check, --diff or --output" ]
  cmp s.rscene "$DATA/fmt_messy.rscene"
}

# --- --check -----------------------------------------------------------------

@test "--check lists exactly the non-canonical files and exits 1" {
  cp "$DATA/fmt_messy.rscene" a.rscene
  cp "$DATA/fmt_canonical.rscene" b.rscene
  cp "$DATA/fmt_crlf.rscene" c.rscene
  run --separate-stderr "$FMT" --check a.rscene b.rscene c.rscene
  [ "$status" -eq 1 ]
  [ "$output" = "$(printf 'a.rscene\nc.rscene')" ]
  [ -z "$stderr" ]
  cmp a.rscene "$DATA/fmt_messy.rscene"  # nothing written
}

@test "--check exits 0 and prints nothing when all files are canonical" {
  cp "$DATA/fmt_canonical.rscene" b.rscene
  "$FMT" "$DATA/fmt_messy.rscene" > a.rscene
  run --separate-stderr "$FMT" --check a.rscene b.rscene
  [ "$status" -eq 0 ]
  [ -z "$output" ]
  [ -z "$stderr" ]
}

@test "--check on standard input names it <stdin>" {
  run --separate-stderr "$FMT" --check < "$DATA/fmt_messy.rscene"
  [ "$status" -eq 1 ]
  [ "$output" = "<stdin>" ]
}

@test "--check with a parse error exits 2" {
  printf 'time_step 1\n' > bad.rscene
  cp "$DATA/fmt_messy.rscene" a.rscene
  run --separate-stderr "$FMT" --check a.rscene bad.rscene
  [ "$status" -eq 2 ]
  [ "$output" = "a.rscene" ]
  [ "${stderr%%$'\n'*}" = "bad.rscene:1:1: error: missing raisim_engine_scene header [RS1001]" ]
}

# --- --diff ------------------------------------------------------------------

@test "--diff prints a unified diff and exits 0" {
  printf 'raisim_engine_scene 1\ngravity 0 0 -9.81\ntime_step 0.50\n' > s.rscene
  run --separate-stderr "$FMT" --diff s.rscene
  [ "$status" -eq 0 ]
  [ "${lines[0]}" = "--- s.rscene" ]
  [ "${lines[1]}" = "+++ s.rscene (formatted)" ]
  [[ "${lines[2]}" == "@@ -1,3 +1,3 @@" ]]
  [[ "$output" == *$'\n-time_step 0.50'* ]]
  [[ "$output" == *$'\n+time_step 0.5'* ]]
  [[ "$output" == *$'\n gravity 0 0 -9.81'* || "$output" == *$'\n-gravity 0 0 -9.81'* ]]
  [ -z "$stderr" ]
  [ "$(cat s.rscene)" = "$(printf 'raisim_engine_scene 1\ngravity 0 0 -9.81\ntime_step 0.50')" ]
}

@test "--diff prints nothing for a canonical file" {
  run --separate-stderr "$FMT" --diff "$DATA/fmt_canonical.rscene"
  [ "$status" -eq 0 ]
  [ -z "$output" ]
}

@test "--diff applied with patch gives the formatted file" {
  command -v patch >/dev/null || skip "patch not installed"
  cp "$DATA/fmt_messy.rscene" s.rscene
  "$FMT" --diff s.rscene > d.patch
  patch -s s.rscene < d.patch
  [ "$(cat s.rscene)" = "$(messy_formatted)" ]
}

@test "--check --diff prints the diff and exits 1" {
  run --separate-stderr "$FMT" --check --diff "$DATA/fmt_crlf.rscene"
  [ "$status" -eq 1 ]
  [[ "${lines[0]}" == "--- "*"fmt_crlf.rscene" ]]
}

# --- --stdin-filename and messages -------------------------------------------

@test "--textconv: canonical text, or a scene that does not parse as written with one warning, exit 0" {
  run -0 --separate-stderr "$FMT" --textconv "$DATA/fmt_messy.rscene"
  [ "$output" = "$(messy_formatted)" ]
  [ -z "$stderr" ]
  printf 'raisim_engine_scene 1\r\nobject /World/Box box 0 0\r\n' >broken.rscene
  "$FMT" --textconv broken.rscene >out 2>err
  cmp broken.rscene out  # byte for byte, CRLF kept
  [ "$(cat err)" = "broken.rscene:2:26: warning: object has 4 positional fields, expected 25, 19 or 17; shown as written [RS1007]" ] || { cat err; false; }
  printf 'junk\0\001\n' >junk.rscene
  run -0 "$FMT" --textconv junk.rscene
  "$FMT" --textconv junk.rscene 2>/dev/null | cmp - junk.rscene
  # Without --textconv a parse error stays exit 2 (pre-commit hooks rely on it).
  run -2 "$FMT" broken.rscene
  run -2 "$FMT" --textconv --check broken.rscene
}

@test "--textconv: git's temporary copy of a committed version is named by its file name, and said so (issue 27)" {
  printf 'raisim_engine_scene 1\nobject /World/Box box 0 0\n' >broken.rscene
  mkdir -p tmp/git-blob-Ab12Cd tmp/git-blob-long-name
  cp broken.rscene tmp/git-blob-Ab12Cd/s.rscene       # git since 2.2x
  cp broken.rscene tmp/Xy34Zw_s.rscene                # older git: $TMPDIR/XXXXXX_NAME
  cp broken.rscene tmp/git-blob-long-name/s.rscene    # not git's: named as given
  local said="object has 4 positional fields, expected 25, 19 or 17; shown as written"
  local copy=" (a committed version: git gives textconv no folder or commit) [RS1007]"
  run -0 --separate-stderr "$FMT" --textconv "$PWD/tmp/git-blob-Ab12Cd/s.rscene"
  [ "$stderr" = ".../s.rscene:2:26: warning: $said$copy" ]
  TMPDIR=$PWD/tmp/ run -0 --separate-stderr "$FMT" --textconv "$PWD/tmp/Xy34Zw_s.rscene"
  [ "$stderr" = ".../s.rscene:2:26: warning: $said$copy" ]
  TMPDIR=/elsewhere run -0 --separate-stderr "$FMT" --textconv "$PWD/tmp/Xy34Zw_s.rscene"
  [ "$stderr" = "$PWD/tmp/Xy34Zw_s.rscene:2:26: warning: $said [RS1007]" ]
  run -0 --separate-stderr "$FMT" --textconv tmp/git-blob-long-name/s.rscene
  [ "$stderr" = "tmp/git-blob-long-name/s.rscene:2:26: warning: $said [RS1007]" ]
  # A working-copy file: git passes its repository path, used as is.
  run -0 --separate-stderr "$FMT" --textconv broken.rscene
  [ "$stderr" = "broken.rscene:2:26: warning: $said [RS1007]" ]
}

@test "--stdin-filename names standard input in messages" {
  run --separate-stderr "$FMT" --stdin-filename scenes/a.rscene < <(printf 'raisim_engine_scene 1\ntime_step 1\nobject /World/A box 0 0\n')
  [ "$status" -eq 2 ]
  [ -z "$output" ]
  [[ "${stderr%%$'\n'*}" == "scenes/a.rscene:3:"*": error: object has 4 positional fields, expected 25, 19 or 17 [RS1007]" ]]
}

@test "--stdin-filename=PATH form with --check" {
  run --separate-stderr "$FMT" --check --stdin-filename=named.rscene < "$DATA/fmt_messy.rscene"
  [ "$status" -eq 1 ]
  [ "$output" = "named.rscene" ]
}

@test "missing header: exact stderr" {
  printf 'time_step 1\n' > nohdr.rscene
  run --separate-stderr "$FMT" nohdr.rscene
  [ "$status" -eq 2 ]
  [ -z "$output" ]
  expected='nohdr.rscene:1:1: error: missing raisim_engine_scene header [RS1001]
  time_step 1
  ^
  hint: the first record must be `raisim_engine_scene 1` or `raisim_engine_scene 2`'
  [ "$stderr" = "$expected" ]
}

@test "missing header after comments and blank lines is reported on its line" {
  printf '# c\n\ngravity 0 0 -9.81\n' > nohdr.rscene
  run --separate-stderr "$FMT" nohdr.rscene
  [ "$status" -eq 2 ]
  [ "${stderr%%$'\n'*}" = "nohdr.rscene:3:1: error: missing raisim_engine_scene header [RS1001]" ]
}

@test "empty input: missing header" {
  run --separate-stderr "$FMT" --stdin-filename empty.rscene < /dev/null
  [ "$status" -eq 2 ]
  [ "${stderr%%$'\n'*}" = "empty.rscene:1:1: error: missing raisim_engine_scene header [RS1001]" ]
}

@test "unsupported version" {
  printf 'raisim_engine_scene 3\n' > v3.rscene
  run --separate-stderr "$FMT" v3.rscene
  [ "$status" -eq 2 ]
  [ -z "$output" ]
  [ "${stderr%%$'\n'*}" = "v3.rscene:1:21: error: unsupported rscene version '3' [RS1002]" ]
}

@test "invalid percent escape %G1" {
  printf 'raisim_engine_scene 1\nmaterial a%%G1 1 1 1 1 0 0.5 0 0 0 0 false - - - - - -\n' > pct.rscene
  run --separate-stderr "$FMT" pct.rscene
  [ "$status" -eq 2 ]
  [ -z "$output" ]
  [ "${stderr%%$'\n'*}" = "pct.rscene:2:11: error: invalid percent escape '%G1' [RS1003]" ]
}

@test "NUL byte" {
  printf 'raisim_engine_scene 1\ntime_step 0\0001\n' > nul.rscene
  run --separate-stderr "$FMT" nul.rscene
  [ "$status" -eq 2 ]
  [ -z "$output" ]
  [ "${stderr%%$'\n'*}" = "nul.rscene:2:12: error: NUL byte in scene text [RS1004]" ]
}

@test "invalid UTF-8" {
  printf 'raisim_engine_scene 1\ngroup /World/\377\n' > utf.rscene
  run --separate-stderr "$FMT" utf.rscene
  [ "$status" -eq 2 ]
  [ -z "$output" ]
  [ "${stderr%%$'\n'*}" = "utf.rscene:2:14: error: invalid UTF-8 byte 0xFF [RS1005]" ]
}

@test "truncated object line" {
  printf 'raisim_engine_scene 1\nobject /World/A box 0 0 0 1 0' > trunc.rscene
  run --separate-stderr "$FMT" trunc.rscene
  [ "$status" -eq 2 ]
  [ -z "$output" ]
  [ "${stderr%%$'\n'*}" = "trunc.rscene:2:30: error: object has 7 positional fields, expected 25, 19 or 17 [RS1007]" ]
  [[ "$stderr" == *"hint: the line may be truncated"* ]]
}

@test "a file cut in the middle of the last record is an error, not a crash" {
  size=$(wc -c < "$DATA/fmt_canonical.rscene")
  head -c $((size - 110)) "$DATA/fmt_canonical.rscene" > cut.rscene
  run --separate-stderr "$FMT" cut.rscene
  [ "$status" -eq 2 ]
  [[ "${stderr%%$'\n'*}" == "cut.rscene:11:"*": error: "*"[RS1007]" ]]
}

@test "an unreadable file: tool error and exit 2" {
  run --separate-stderr "$FMT" does-not-exist.rscene
  [ "$status" -eq 2 ]
  [ -z "$output" ]
  [ "$stderr" = "rscene-fmt: error: cannot read 'does-not-exist.rscene': No such file or directory" ]
}

@test "no color codes in messages when NO_COLOR is set or stderr is not a terminal" {
  printf 'time_step 1\n' > nohdr.rscene
  NO_COLOR=1 run --separate-stderr "$FMT" nohdr.rscene
  [ "$status" -eq 2 ]
  [[ "$stderr" != *$'\e['* ]]
}

# --- content kept --------------------------------------------------------------

@test "CRLF input becomes LF with the same records" {
  run --separate-stderr "$FMT" "$DATA/fmt_crlf.rscene"
  [ "$status" -eq 0 ]
  [ "$output" = "$(tr -d '\r' < "$DATA/fmt_crlf.rscene")" ]
  "$FMT" "$DATA/fmt_crlf.rscene" > out.rscene
  ! grep -q $'\r' out.rscene
}

@test "version 2 stays version 2 with %3B and %2D kept" {
  run --separate-stderr "$FMT" "$DATA/fmt_v2_escapes.rscene"
  [ "$status" -eq 0 ]
  [ "${lines[0]}" = "raisim_engine_scene 2" ]
  [[ "$output" == *" semanticClass=a%3Bb "* ]]
  [[ "$output" == *" instanceLabel=%2D "* ]]
  [[ "$output" == *" emptyText=-" ]]
  [[ "$output" == *"/World/A%20Box "* ]]
}

@test "18446744073709551615 survives digit for digit" {
  run "$FMT" "$DATA/fmt_messy.rscene"
  [ "$status" -eq 0 ]
  [[ "$output" == *" 1 18446744073709551615 id=object_crate "* ]]
  printf 'raisim_engine_scene 1\nobject /W/A box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default m false true false - dynamic true 18446744073709551614 18446744073709551615\n' > g.rscene
  run "$FMT" g.rscene
  [ "$status" -eq 0 ]
  [[ "$output" == *" true 18446744073709551614 18446744073709551615" ]]
}

@test "comments, unknown records and unknown keys are kept" {
  run "$FMT" "$DATA/fmt_messy.rscene"
  [ "$status" -eq 0 ]
  [[ "$output" == *$'\n# the only material\nmaterial mat_crate '* ]]
  [[ "$output" == *$'\n# objects before their materials\nobject /World/Crate '* ]]
  [[ "$output" == *$'\nfuture_record alpha beta=1\n'* ]]
  [[ "$output" == *" futureKey=Keep%20Me"* ]]
}

@test "the Engine 2 corpus file is a fixed point" {
  needs_shared corpus/rayrai_forest_head.rscene
  f="$CORPUS/rayrai_forest_head.rscene"
  "$FMT" "$f" | cmp - "$f"
  run "$FMT" --check "$f"
  [ "$status" -eq 0 ]
  [ -z "$output" ]
}

@test "idempotence: fmt(fmt(x)) = fmt(x) on every fixture and example" {
  n=0
  for f in "$DATA"/*.rscene "$ROOT"/examples/*.rscene "$SHARED"/corpus/*.rscene; do
    [ -f "$f" ] || continue
    rc=0
    "$FMT" "$f" > once.rscene 2>/dev/null || rc=$?
    case "$(basename "$f")" in
      fmt_*) [ "$rc" -eq 0 ] ;;   # our own fixtures all parse
    esac
    [[ "$f" == "$ROOT/examples/"* ]] && [ "$rc" -eq 0 ]
    [ "$rc" -eq 0 ] || continue   # other areas' fixtures may be invalid on purpose
    "$FMT" once.rscene > twice.rscene || { echo "fmt output does not parse again: $f"; return 1; }
    cmp once.rscene twice.rscene || { echo "not idempotent: $f"; return 1; }
    "$FMT" --check once.rscene
    n=$((n + 1))
  done
  [ "$n" -ge 8 ]
}

# --- the command line --------------------------------------------------------

@test "--help exits 0 and lists every option" {
  run --separate-stderr "$FMT" --help
  [ "$status" -eq 0 ]
  for o in --output --in-place --check --diff --stdin-filename --help --version; do
    [[ "$output" == *"$o"* ]]
  done
  [[ "$output" == *"Usage: rscene-fmt"* ]]
}

@test "-h is --help" {
  run "$FMT" -h
  [ "$status" -eq 0 ]
  [[ "$output" == *"--in-place"* ]]
}

@test "--version exits 0 and prints the name and version" {
  run --separate-stderr "$FMT" --version
  [ "$status" -eq 0 ]
  [[ "$output" =~ ^rscene-fmt\ [0-9]+\.[0-9]+\.[0-9]+$ ]]
}

@test "an unknown flag is a usage error (exit 2)" {
  run --separate-stderr "$FMT" --no-such-flag "$DATA/fmt_canonical.rscene"
  [ "$status" -eq 2 ]
  [ -z "$output" ]
  [[ "$stderr" == "rscene-fmt: error: "*"--no-such-flag"* ]]
}

@test "-o without its argument is a usage error (exit 2)" {
  run --separate-stderr "$FMT" -o
  [ "$status" -eq 2 ]
  [[ "$stderr" == "rscene-fmt: error: "* ]]
}

@test "bash completion offers the long options and .rscene files" {
  cp "$DATA/fmt_canonical.rscene" scene.rscene
  touch notes.txt
  run bash -c "source '$ROOT/completions/bash/rscene-fmt'
    COMP_WORDS=(rscene-fmt --); COMP_CWORD=1; _rscene_fmt; echo \"\${COMPREPLY[*]}\"
    COMP_WORDS=(rscene-fmt ''); COMP_CWORD=1; _rscene_fmt; echo \"\${COMPREPLY[*]}\""
  [ "$status" -eq 0 ]
  for o in --help --version --output --in-place --check --diff --stdin-filename; do
    [[ "${lines[0]}" == *"$o"* ]]
  done
  [ "${lines[1]}" = "scene.rscene" ]
}

@test "a mistyped option gets the closest long option as a suggestion" {
  run -2 --separate-stderr "$FMT" --chek x.rscene
  [ "${stderr_lines[0]}" = "rscene-fmt: error: unknown option '--chek'; did you mean '--check'?" ]
  [ "${stderr_lines[1]}" = "Try 'rscene-fmt --help' for more information." ]
  # one dash short of a long option, and a value after `=`
  run -2 --separate-stderr "$FMT" -check x.rscene
  [ "${stderr_lines[0]}" = "rscene-fmt: error: unknown option '-check'; did you mean '--check'?" ]
  run -2 --separate-stderr "$FMT" --stdin-filenme=a.rscene
  [ "${stderr_lines[0]}" = "rscene-fmt: error: unknown option '--stdin-filenme'; did you mean '--stdin-filename'?" ]
  # nothing close: no guess
  run -2 --separate-stderr "$FMT" --banana
  [ "${stderr_lines[0]}" = "rscene-fmt: error: unknown option '--banana'" ]
}

# A tree with scenes to format, a canonical one, hidden ones and a link loop.
make_tree() {
  mkdir -p tree/b/deep tree/.git tree/a tree/empty
  cp "$DATA/fmt_messy.rscene" tree/top.rscene
  cp "$DATA/fmt_messy.rscene" tree/b/z.rscene
  cp "$DATA/fmt_messy.rscene" tree/b/deep/m.rscene
  cp "$DATA/fmt_canonical.rscene" tree/a/x.rscene
  cp "$DATA/fmt_messy.rscene" tree/.git/h.rscene
  cp "$DATA/fmt_messy.rscene" tree/.hidden.rscene
  echo 'not a scene' > tree/readme.txt
  ln -s .. tree/b/loop
}

@test "--check DIR walks it for *.rscene in sorted order, skipping hidden entries and folder links" {
  make_tree
  run -1 --separate-stderr "$FMT" --check tree
  [ "$output" = $'tree/b/deep/m.rscene\ntree/b/z.rscene\ntree/top.rscene' ]
  [ -z "$stderr" ]  # tree/empty is part of the tree, not an operand of its own
  cd tree
  run -1 "$FMT" --check .
  [ "$output" = $'b/deep/m.rscene\nb/z.rscene\ntop.rscene' ]
}

@test "-i DIR formats every scene under it and leaves hidden ones alone; --diff DIR diffs them" {
  make_tree
  run -0 "$FMT" --diff tree/b
  [ "$(grep -c '^--- ' <<<"$output")" -eq 2 ]
  run -0 "$FMT" -i tree
  run -0 "$FMT" --check tree
  messy_formatted | cmp - tree/b/deep/m.rscene
  cmp "$DATA/fmt_messy.rscene" tree/.git/h.rscene
  cmp "$DATA/fmt_messy.rscene" tree/.hidden.rscene
}

@test "a folder without scenes is a warning, not an error; DIR alone is a usage error" {
  mkdir empty
  run -0 --separate-stderr "$FMT" --check empty
  [ -z "$output" ]
  [ "$stderr" = "rscene-fmt: warning: no .rscene files under 'empty'" ]
  run -2 --separate-stderr "$FMT" empty
  [ "$stderr" = "rscene-fmt: error: a directory or project operand needs --check, --diff or --in-place" ]
  run -2 --separate-stderr "$FMT" -o out.rscene empty
  [ ! -e out.rscene ]
}

@test "an unreadable folder is an error (exit 2) and the other operands are still checked" {
  [ "$(id -u)" != 0 ] || skip "root reads every folder"
  make_tree
  chmod 000 tree/b
  run -2 --separate-stderr "$FMT" --check tree
  chmod 755 tree/b
  [ "$output" = "tree/top.rscene" ]
  [ "${stderr_lines[0]}" = "rscene-fmt: error: cannot read directory 'tree/b': Permission denied" ]
}

# Runs the hooks of a pre-commit YAML file ($1: a .pre-commit-hooks.yaml
# list, or a config whose first `local` repository holds them) the way
# pre-commit does: entry, then the names of the files matching `files`.
# Prints "id status" per hook.
run_hooks() {
  python3 - "$1" "${@:2}" <<'PY'
import re, shlex, subprocess, sys, yaml
doc = yaml.safe_load(open(sys.argv[1]))
hooks = doc if isinstance(doc, list) else next(r["hooks"] for r in doc["repos"] if r["repo"] == "local")
for h in hooks:
    assert h["language"] == "system", h
    files = [f for f in sys.argv[2:] if re.search(h["files"], f)]
    rc = subprocess.call(shlex.split(h["entry"]) + files, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    print(h["id"], rc)
PY
}

@test "the hooks of .pre-commit-hooks.yaml and the README's local pre-commit config work as pre-commit runs them" {
  python3 -c 'import yaml' 2>/dev/null || skip "python3-yaml not installed"
  export PATH="$BIN:$PATH"
  cp "$DATA/fmt_messy.rscene" messy.rscene
  cp "$DATA/fmt_canonical.rscene" clean.rscene
  cp "$DATA/fmt_messy.rscene" messy.rscene.bak
  run -0 run_hooks "$ROOT/.pre-commit-hooks.yaml" messy.rscene.bak clean.rscene
  [ "$output" = $'rscene-fmt 0\nrscene-fmt-check 0\nrscene-validate 0' ]
  # The hooks run in order: rscene-fmt rewrites messy.rscene (pre-commit
  # then fails the commit because a file changed), so the check after it
  # passes; the orphan compound_child stays a lint error.
  run -0 run_hooks "$ROOT/.pre-commit-hooks.yaml" messy.rscene clean.rscene
  [ "$output" = $'rscene-fmt 0\nrscene-fmt-check 0\nrscene-validate 1' ]
  messy_formatted | cmp - messy.rscene
  cmp "$DATA/fmt_messy.rscene" messy.rscene.bak  # not a scene name: untouched
  # The README's `repo: local` block, exactly as printed there.
  awk '/^```yaml$/ { y = 1; b = ""; next } /^```$/ { if (y && b ~ /repo: local/) printf "%s", b; y = 0; next } y { b = b $0 "\n" }' \
    "$ROOT/README.md" > local.yaml
  grep -q 'repo: local' local.yaml
  cp "$DATA/fmt_messy.rscene" messy.rscene
  run -0 run_hooks local.yaml messy.rscene clean.rscene
  [ "$output" = $'rscene-fmt 0\nrscene-validate 1' ]
  messy_formatted | cmp - messy.rscene
}
