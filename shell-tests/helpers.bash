# What the shell tests share, loaded by each with `load helpers` (after
# its header comment).  A .bash file, not .bats: `bats shell-tests` runs
# only *.bats, and docs.bats reads a tool's own FILE.bats for its flags,
# so every flag a test exercises is still written in that file.

# shellcheck disable=SC2034  # the variables set here are read by the files that load it

bats_require_minimum_version 1.5.0

# The tools under test: `make shell-test` sets RSCENE_BIN to its build.
BIN="${RSCENE_BIN:-$BATS_TEST_DIRNAME/../build/bin}"
ROOT="$BATS_TEST_DIRNAME/.."
DATA="$ROOT/tests/data"
# The corpus and RaiSim's spec live beside the repository, not in it:
# `make test` on a fresh clone runs without them, so tests that read
# them skip through needs_shared.
SHARED="$ROOT/../shared"
CORPUS="$SHARED/corpus"

# needs_tools TOOL...: skips the test unless every $BIN/TOOL is built (a
# partial build, e.g. without the renderer, still runs the rest).
needs_tools() {
  local t
  for t in "$@"; do
    [ -x "$BIN/$t" ] || skip "$t not built in $BIN"
  done
}

# needs_shared PATH: skips the test unless ../shared/PATH exists.
needs_shared() {
  [ -e "$SHARED/$1" ] || skip "no ../shared/$1"
}

# in_workdir: makes the current directory an empty folder of this test's
# own.  Not BATS_TEST_TMPDIR itself, where bats keeps files of its own, so
# that a test can assert on everything a tool left in its folder.
in_workdir() {
  mkdir "$BATS_TEST_TMPDIR/w"
  cd "$BATS_TEST_TMPDIR/w" || return
}

# bounded KB SECONDS CMD...: runs CMD with at most KB of address space and
# SECONDS of wall time, so that a regression fails the test (timeout's 124,
# or an allocation failure's abort) instead of hanging or swapping the
# machine.  The limits are guards, not measurements: bench/ measures.
bounded() {
  local kb=$1 secs=$2
  shift 2
  ( ulimit -v "$kb" && exec timeout "$secs" "$@" )
}

# refused WHERE CMD...: asserts that CMD refuses its input cleanly:
#   - exit status 2 (usage, I/O or parse error), within 10 s and 1 GiB of
#     address space (bounded): a hang, a crash or a runaway allocation
#     exits otherwise and fails;
#   - nothing on standard output;
#   - the first line of standard error is one diagnostic,
#     "FILE[:LINE:COL]: error: MESSAGE [RSnnnn]", and starts with WHERE
#     (a literal prefix: "bad.xml:3:", or the whole line);
#   - no file appears or disappears anywhere under the current folder (no
#     output and no temporary file left behind, no input removed);
#   - every output CMD names (the operand of -o, --output or --trajectory)
#     is also left as it was when it exists already: CMD runs a second
#     time with each one holding a line of its own, which must keep its
#     bytes.
# It leaves $status, $output, $stderr, $lines and $stderr_lines of the
# first run for further assertions.  CMD is run as given: name its inputs
# with paths relative to the current folder so WHERE can name them.
refused() {
  local where=$1
  shift
  local outs=() prev="" arg out
  for arg in "$@"; do
    case $prev in -o | --output | --trajectory) outs+=("$arg") ;; esac
    prev=$arg
  done
  for out in "${outs[@]}"; do
    [ ! -e "$out" ] || { echo "refused: output $out exists before the run: the test cannot tell"; return 1; }
  done
  local before after
  before=$(find . | LC_ALL=C sort)
  run -2 --separate-stderr bounded 1048576 10 "$@"
  [ -z "$output" ] || { echo "refused: standard output is not empty:"; echo "$output"; return 1; }
  local first=${stderr_lines[0]-}
  [[ $first =~ ^[^\ ]+(:[0-9]+:[0-9]+)?:\ error:\ .+\ \[RS[0-9]{4}\]$ ]] ||
    { echo "refused: the first line of standard error is no error diagnostic:"; echo "$stderr"; return 1; }
  [[ $first == "$where"* ]] || { echo "refused: expected a first line starting with: $where"; echo "$stderr"; return 1; }
  after=$(find . | LC_ALL=C sort)
  [ "$before" = "$after" ] ||
    { echo "refused: the folder changed:"; diff <(echo "$before") <(echo "$after"); return 1; }
  ((${#outs[@]})) || return 0
  local saved_output=$output saved_stderr=$stderr saved_lines=("${lines[@]}") saved_stderr_lines=("${stderr_lines[@]}")
  for out in "${outs[@]}"; do echo "kept by refused: $out" >"$out"; done
  run -2 --separate-stderr bounded 1048576 10 "$@"
  for out in "${outs[@]}"; do
    [ "$(cat "$out")" = "kept by refused: $out" ] || { echo "refused: existing output $out was changed"; return 1; }
    rm -f "$out"
  done
  after=$(find . | LC_ALL=C sort)
  [ "$before" = "$after" ] ||
    { echo "refused: the folder changed on the run with existing outputs:"; diff <(echo "$before") <(echo "$after"); return 1; }
  status=2 output=$saved_output stderr=$saved_stderr
  lines=("${saved_lines[@]}") stderr_lines=("${saved_stderr_lines[@]}")
}

# Width and height ("WxH") of a PNG, from its IHDR.
png_size() {
  od -An -tu1 -j16 -N8 "$1" | awk '{ printf "%dx%d\n", $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8 }'
}

# Whether file $1 starts with the PNG signature.
is_png() {
  [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]
}

# The z of object PATH in the scene text on stdin.
zof() { awk -v p="$1" '$1 == "object" && $2 == p { print $6 }'; }
