#!/usr/bin/env bats
# Writing outputs never destroys anything (README "Outputs"): every tool and
# every output it writes (-o, -i, --trajectory, --diff-output, a missing
# --reference baseline) goes through one routine.  Each test runs each way
# of writing against one kind of target: a new file, a regular file, a
# symlink, /dev/null, a FIFO, a read-only or hard-linked file, /dev/full,
# and an interrupted write.

load helpers
FMT="$BIN/rscene-fmt"

setup() {
  needs_tools rscene-fmt
  in_workdir
}

teardown() {
  [ -z "${NOBODY_DIR:-}" ] || rm -rf "$NOBODY_DIR"
  # A regression here would have replaced the machine's /dev/null or
  # /dev/full with a regular file (the bug this file tests for): put the
  # device back, and fail.
  local restored=""
  for dev in null:3 full:7; do
    if [ ! -c "/dev/${dev%:*}" ] && [ "$(id -u)" = 0 ]; then
      rm -f "/dev/${dev%:*}" && mknod -m 666 "/dev/${dev%:*}" c 1 "${dev#*:}"
      restored+=" /dev/${dev%:*}"
    fi
  done
  [ -z "$restored" ] || { echo "replaced and restored:$restored" >&2; return 1; }
}

# Every way a tool writes a file; those of tools that are not built are
# left out.  render-reference writes only a missing baseline.
WAYS="fmt-o to-json from-json to-xml sim-o sim-trajectory render-o render-diff"

tool_of() {
  case $1 in
    fmt-*) echo rscene-fmt ;;
    to-json) echo rscene-to-json ;;
    from-json) echo rscene-from-json ;;
    to-xml) echo rscene-to-xml ;;
    sim-*) echo rscene-sim ;;
    render-*) echo rscene-render ;;
  esac
}

built() { [ -x "$BIN/$(tool_of "$1")" ]; }

# Writes with way $1 to target $2 (exit status and stderr are the tool's).
write_to() {
  local target=$2
  case $1 in
    fmt-o) "$BIN/rscene-fmt" -o "$target" "$DATA/fmt_messy.rscene" ;;
    to-json) "$BIN/rscene-to-json" -o "$target" "$DATA/fmt_messy.rscene" ;;
    from-json)
      "$BIN/rscene-to-json" "$DATA/fmt_messy.rscene" > "$BATS_TEST_TMPDIR/in.json"
      "$BIN/rscene-from-json" -o "$target" "$BATS_TEST_TMPDIR/in.json"
      ;;
    to-xml) "$BIN/rscene-to-xml" -q -o "$target" "$DATA/sim_drop.rscene" ;;
    sim-o) "$BIN/rscene-sim" --steps 20 -o "$target" "$DATA/sim_drop.rscene" ;;
    sim-trajectory) "$BIN/rscene-sim" --steps 20 --trajectory "$target" "$DATA/sim_drop.rscene" > /dev/null ;;
    render-o) "$BIN/rscene-render" --width 32 --height 24 -o "$target" "$DATA/render_minimal.rscene" ;;
    render-diff)
      # The same render as its reference: exit 0, and the diff image is written.
      "$BIN/rscene-render" --width 32 --height 24 -o "$BATS_TEST_TMPDIR/ref.png" "$DATA/render_minimal.rscene"
      "$BIN/rscene-render" --width 32 --height 24 --reference "$BATS_TEST_TMPDIR/ref.png" \
        --diff-output "$target" "$DATA/render_minimal.rscene" > /dev/null
      ;;
    render-reference)
      "$BIN/rscene-render" --width 32 --height 24 --reference "$target" "$DATA/render_minimal.rscene" > /dev/null
      ;;
  esac
}

# What way $1 writes, in $BATS_TEST_TMPDIR/expected.$1.
expected() {
  rm -f "$BATS_TEST_TMPDIR/expected.$1"
  write_to "$1" "$BATS_TEST_TMPDIR/expected.$1" 2> /dev/null || [ "$1" = render-reference ]
  echo "$BATS_TEST_TMPDIR/expected.$1"
}

# Temporary files left in folder $1 (default: here).
leftovers() { find "${1:-.}" -maxdepth 1 -name '.*.tmp*' | sort; }

# --- regular files ------------------------------------------------------------

@test "a new file is created with the umask applied, for every way of writing" {
  umask 027
  for way in $WAYS render-reference; do
    built "$way" || continue
    run --separate-stderr write_to "$way" "new.$way"
    # A missing baseline is written and reported as a finding (exit 1).
    [ "$status" -eq "$([ "$way" = render-reference ] && echo 1 || echo 0)" ] || { echo "$way: $status $stderr"; false; }
    [ -s "new.$way" ] || { echo "$way: nothing written"; false; }
    [ "$(stat -c %a "new.$way")" = 640 ] || { echo "$way: mode $(stat -c %a "new.$way")"; false; }
  done
  [ -z "$(leftovers)" ]
}

@test "a regular file is replaced atomically: new inode, mode kept" {
  for way in $WAYS; do
    built "$way" || continue
    echo old > "out.$way"
    chmod 604 "out.$way"
    before=$(stat -c %i "out.$way")
    run -0 write_to "$way" "out.$way"
    cmp "out.$way" "$(expected "$way")"
    [ "$(stat -c %a "out.$way")" = 604 ] || { echo "$way: mode $(stat -c %a "out.$way")"; false; }
    [ "$(stat -c %i "out.$way")" != "$before" ]
  done
  [ -z "$(leftovers)" ]
}

@test "owner and group are kept (as root), for -o and -i" {
  [ "$(id -u)" = 0 ] || skip "needs root to give files away"
  for way in $WAYS; do
    built "$way" || continue
    echo old > "out.$way"
    chown nobody:nogroup "out.$way"
    run -0 write_to "$way" "out.$way"
    [ "$(stat -c %U:%G "out.$way")" = nobody:nogroup ] || { echo "$way: $(stat -c %U:%G "out.$way")"; false; }
  done
  cp "$DATA/fmt_messy.rscene" s.rscene
  chown nobody:nogroup s.rscene
  chmod 2640 s.rscene
  run -0 "$FMT" -i s.rscene
  [ "$(stat -c %U:%G:%a s.rscene)" = nobody:nogroup:2640 ]
  cmp s.rscene <("$FMT" "$DATA/fmt_messy.rscene")
}

@test "-o to a folder is refused" {
  mkdir d
  run -2 --separate-stderr "$FMT" -o d "$DATA/fmt_messy.rscene"
  [ "$stderr" = "rscene-fmt: error: d: is a directory" ]
}

@test "-o into a missing folder is a clear error" {
  run -2 --separate-stderr "$FMT" -o no/such/out.rscene "$DATA/fmt_messy.rscene"
  [ "$stderr" = "rscene-fmt: error: no/such/out.rscene: cannot create a file in 'no/such': no such file or directory" ]
}

# --- symbolic links -----------------------------------------------------------

@test "a symlink stays a link and its target in another folder is rewritten" {
  mkdir real
  for way in $WAYS; do
    built "$way" || continue
    echo old > "real/t.$way"
    ln -s "real/t.$way" "link.$way"
    run -0 write_to "$way" "link.$way"
    [ -L "link.$way" ] || { echo "$way: the link was replaced"; false; }
    [ "$(readlink "link.$way")" = "real/t.$way" ]
    cmp "real/t.$way" "$(expected "$way")"
  done
  [ -z "$(leftovers)" ] && [ -z "$(leftovers real)" ]
}

@test "-i through a symlink formats its target and keeps the link" {
  mkdir real
  cp "$DATA/fmt_messy.rscene" real/s.rscene
  ln -s ../w/real/s.rscene link.rscene
  run -0 "$FMT" -i link.rscene
  [ -L link.rscene ]
  [ "$(readlink link.rscene)" = ../w/real/s.rscene ]
  cmp real/s.rscene <("$FMT" "$DATA/fmt_messy.rscene")
}

@test "a dangling symlink is refused and nothing is created" {
  for way in $WAYS render-reference; do
    built "$way" || continue
    ln -s "missing.$way" "link.$way"
    run -2 --separate-stderr write_to "$way" "link.$way"
    [ "$stderr" = "$(tool_of "$way"): error: link.$way: is a dangling symbolic link to 'missing.$way'; create the target or remove the link" ] ||
      { echo "$way: $stderr"; false; }
    [ ! -e "missing.$way" ] && [ -L "link.$way" ]
  done
}

# --- devices, FIFOs, descriptors ----------------------------------------------

@test "/dev/null stays a character device" {
  for way in $WAYS; do
    built "$way" || continue
    run -0 write_to "$way" /dev/null
    [ -c /dev/null ] || { echo "$way replaced /dev/null"; false; }
  done
}

@test "a FIFO stays a FIFO and its reader gets exactly the output" {
  for way in $WAYS; do
    built "$way" || continue
    mkfifo "pipe.$way"
    cat "pipe.$way" > "got.$way" &
    reader=$!
    run -0 write_to "$way" "pipe.$way"
    wait "$reader"
    [ -p "pipe.$way" ] || { echo "$way replaced the FIFO"; false; }
    cmp "got.$way" "$(expected "$way")"
  done
}

@test "a FIFO with no reader yet: the tool waits for one" {
  mkfifo pipe
  { sleep 0.3; cat pipe > got; } &
  run -0 "$FMT" -o pipe "$DATA/fmt_messy.rscene"
  wait
  cmp got <("$FMT" "$DATA/fmt_messy.rscene")
  [ -p pipe ]
}

@test "a terminal is written through" {
  command -v script > /dev/null || skip "script(1) not installed"
  run -0 script -qec "'$FMT' -o \$(tty) '$DATA/fmt_canonical.rscene'; test -c \$(tty)" typescript
  grep -q '^raisim_engine_scene' typescript
}

@test "-o /dev/stdout writes to the open descriptor (appending stays appending)" {
  echo first > log
  "$FMT" -o /dev/stdout "$DATA/fmt_messy.rscene" >> log
  cmp log <(echo first; "$FMT" "$DATA/fmt_messy.rscene")
}

@test "/dev/full: exit 2 with the reason" {
  [ -c /dev/full ] || skip "no /dev/full"
  for way in $WAYS; do
    built "$way" || continue
    run -2 --separate-stderr write_to "$way" /dev/full
    [ "$stderr" = "$(tool_of "$way"): error: /dev/full: no space left on device" ] || { echo "$way: $stderr"; false; }
  done
}

# --- refusals -----------------------------------------------------------------

@test "a read-only file is refused, root included, and left unchanged" {
  for way in $WAYS; do
    built "$way" || continue
    echo keep > "ro.$way"
    chmod 444 "ro.$way"
    run -2 --separate-stderr write_to "$way" "ro.$way"
    [ "$stderr" = "$(tool_of "$way"): error: ro.$way: permission denied" ] || { echo "$way: $stderr"; false; }
    [ "$(cat "ro.$way")" = keep ]
  done
  [ -z "$(leftovers)" ]
}

@test "-i refuses a read-only file that needs formatting, root included" {
  cp "$DATA/fmt_messy.rscene" ro.rscene
  chmod 444 ro.rscene
  run -2 --separate-stderr "$FMT" -i ro.rscene
  [ "$stderr" = "rscene-fmt: error: ro.rscene: permission denied" ]
  cmp ro.rscene "$DATA/fmt_messy.rscene"
  [ "$(stat -c %a ro.rscene)" = 444 ]
  # Already canonical: nothing to write, so nothing to refuse.
  cp "$DATA/fmt_canonical.rscene" ok.rscene
  chmod 444 ok.rscene
  run -0 "$FMT" -i ok.rscene
}

# Runs the rest as user nobody in a folder nobody may write.
as_nobody() { setpriv --reuid=nobody --regid=nogroup --clear-groups "$@"; }

# Sets NOBODY_DIR to a fresh folder anyone may write (teardown removes it)
# holding m.rscene, a copy of tests/data/fmt_messy.rscene.
nobody_folder() {
  [ "$(id -u)" = 0 ] || skip "needs root to switch to user nobody"
  command -v setpriv > /dev/null || skip "setpriv not installed"
  as_nobody "$FMT" --version > /dev/null || skip "user nobody cannot run $FMT"
  NOBODY_DIR=$(mktemp -d /tmp/rscene-output-XXXXXX)
  chmod 777 "$NOBODY_DIR"
  cp "$DATA/fmt_messy.rscene" "$NOBODY_DIR/m.rscene"
}

@test "unprivileged: -i refuses a 0444 file of one's own in a writable folder" {
  nobody_folder
  dir=$NOBODY_DIR
  chown nobody "$dir/m.rscene"
  chmod 444 "$dir/m.rscene"
  run -2 --separate-stderr as_nobody "$FMT" -i "$dir/m.rscene"
  [ "$stderr" = "rscene-fmt: error: $dir/m.rscene: permission denied" ]
  cmp "$dir/m.rscene" "$DATA/fmt_messy.rscene"
  [ -z "$(leftovers "$dir")" ]
}

@test "unprivileged: -o refuses another user's file and a folder one may not write" {
  nobody_folder
  dir=$NOBODY_DIR
  chmod 644 "$dir/m.rscene"
  run -2 --separate-stderr as_nobody "$FMT" -o "$dir/m.rscene" "$DATA/fmt_messy.rscene"
  [ "$stderr" = "rscene-fmt: error: $dir/m.rscene: permission denied" ]
  mkdir "$dir/locked"
  run -2 --separate-stderr as_nobody "$FMT" -o "$dir/locked/new.rscene" "$DATA/fmt_messy.rscene"
  [ "$stderr" = "rscene-fmt: error: $dir/locked/new.rscene: cannot create a file in '$dir/locked': permission denied" ]
  [ ! -e "$dir/locked/new.rscene" ]
}

@test "a hard-linked file is refused with the count and the way out; no link is split" {
  for way in $WAYS; do
    built "$way" || continue
    echo keep > "a.$way"
    ln "a.$way" "b.$way"
    run -2 --separate-stderr write_to "$way" "a.$way"
    [ "$stderr" = "$(tool_of "$way"): error: a.$way: has 2 hard links; refusing to split them (to write it, make it a file of its own first: cp a.$way tmp && mv tmp a.$way)" ] ||
      { echo "$way: $stderr"; false; }
    [ "$(stat -c %h "a.$way")" = 2 ] && [ "$(cat "b.$way")" = keep ]
  done
  cp "$DATA/fmt_messy.rscene" s.rscene
  ln s.rscene t.rscene
  run -2 "$FMT" -i s.rscene
  cmp s.rscene "$DATA/fmt_messy.rscene"
  [ "$(stat -c %h s.rscene)" = 2 ]
}

# --- failures and interruptions mid-write -------------------------------------

# A scene big enough that writing it takes a while (bench's generator).
big_scene() {
  [ -x "$BIN/rscene-bench-gen" ] || skip "rscene-bench-gen not built in $BIN"
  "$BIN/rscene-bench-gen" --size 64M > big.rscene
  cp big.rscene big.orig
}

@test "a write that fails midway (file size limit) leaves the original and no temporary file" {
  big_scene
  run -2 --separate-stderr bash -c "ulimit -f 1024; exec '$FMT' -i big.rscene"
  [ "$stderr" = "rscene-fmt: error: big.rscene: file too large" ]
  cmp big.rscene big.orig
  [ -z "$(leftovers)" ]
}

# Starts "$@" in the background with SIGINT at its default (a shell without
# job control makes background jobs ignore it), waits until the temporary
# file `.big.rscene.tmp*` appears, sends signal $sig and sets `status`.
interrupt_mid_write() {
  env --default-signal=INT "$@" &
  local pid=$! seen=""
  SECONDS=0
  # Polls every few milliseconds: the temporary file lives for the whole
  # write (at least a few hundred of them for 64 MB), and the signal goes
  # at first sight, far from the rename at its end.
  while [ -z "$seen" ] && [ "$SECONDS" -lt 120 ] && kill -0 "$pid" 2> /dev/null; do
    for t in .big.rscene.tmp*; do [ -e "$t" ] && seen=$t; done
    [ -n "$seen" ] || sleep 0.005
  done
  [ -n "$seen" ] && kill -s "$sig" "$pid"
  status=0
  wait "$pid" || status=$?
  [ -n "$seen" ] || { echo "never saw a temporary file (exit $status)"; false; }
}

@test "SIGINT during -i: exit 130, the original byte for byte, no temporary file" {
  command -v env > /dev/null && env --default-signal=INT true || skip "env --default-signal unsupported"
  big_scene
  sig=INT
  interrupt_mid_write "$FMT" -i big.rscene
  [ "$status" -eq 130 ]
  cmp big.rscene big.orig
  [ -z "$(leftovers)" ]
}

@test "SIGTERM during -o over an existing file: exit 143, the old file kept, no temporary file" {
  command -v env > /dev/null && env --default-signal=INT true || skip "env --default-signal unsupported"
  big_scene
  sig=TERM
  interrupt_mid_write "$FMT" -o big.rscene big.orig
  [ "$status" -eq 143 ]
  cmp big.rscene big.orig
  [ -z "$(leftovers)" ]
}

@test "SIGINT while rscene-sim steps: exit 130 and no output written" {
  [ -x "$BIN/rscene-sim" ] || skip "rscene-sim not built in $BIN"
  command -v env > /dev/null && env --default-signal=INT true || skip "env --default-signal unsupported"
  echo keep > out.rscene
  env --default-signal=INT "$BIN/rscene-sim" --steps 100000000 --max-steps 100000000 -o out.rscene "$DATA/sim_drop.rscene" &
  pid=$!
  sleep 0.5
  kill -INT "$pid"
  status=0
  wait "$pid" || status=$?
  [ "$status" -eq 130 ]
  [ "$(cat out.rscene)" = keep ]
  [ -z "$(leftovers)" ]
}

@test "two outputs that are one file, or both standard output, are refused before anything is written" {
  [ -x "$BIN/rscene-sim" ] && [ -x "$BIN/rscene-render" ] || skip "rscene-sim/rscene-render not built"
  scene="$DATA/render_minimal.rscene"
  run -2 --separate-stderr "$BIN/rscene-sim" --steps 2 -o same.txt --trajectory ./same.txt "$scene"
  [ "${stderr_lines[0]}" = "rscene-sim: error: -o 'same.txt' and --trajectory './same.txt' are the same file; one would overwrite the other" ]
  [ ! -e same.txt ]
  run -2 --separate-stderr "$BIN/rscene-sim" --steps 2 --trajectory - "$scene"
  [ "${stderr_lines[0]}" = "rscene-sim: error: -o and --trajectory would both write standard output; send one to a file" ]
  # A refused --trajectory leaves -o untouched (it is checked first).
  echo keep > ok.rscene
  : > ro.csv && chmod 444 ro.csv
  run -2 --separate-stderr "$BIN/rscene-sim" --steps 2 -o ok.rscene --trajectory ro.csv "$scene"
  [ "${stderr_lines[0]}" = "rscene-sim: error: ro.csv: permission denied" ]
  [ "$(cat ok.rscene)" = keep ]
  run -2 --separate-stderr "$BIN/rscene-sim" -o "" "$scene"
  [ "${stderr_lines[0]}" = "rscene-sim: error: --output: an empty path names no file" ]

  "$BIN/rscene-render" --width 32 --height 24 -o base.png "$scene"
  sum=$(cksum < base.png)
  ln -s base.png link.png
  run -2 --separate-stderr "$BIN/rscene-render" --width 32 --height 24 -o link.png --reference base.png "$scene"
  [ "${stderr_lines[0]}" = "rscene-render: error: -o 'link.png' and --reference 'base.png' are the same file; one would overwrite the other" ]
  run -2 --separate-stderr "$BIN/rscene-render" --width 32 --height 24 -o o.png --reference base.png --diff-output ./base.png "$scene"
  [ "${stderr_lines[0]}" = "rscene-render: error: --diff-output './base.png' and --reference 'base.png' are the same file; one would overwrite the other" ]
  [ "$(cksum < base.png)" = "$sum" ]
  [ ! -e o.png ]
  run -2 --separate-stderr "$BIN/rscene-render" --width 32 --height 24 -o o.png --reference base.png --diff-output ro.csv "$scene"
  [ "${stderr_lines[0]}" = "rscene-render: error: ro.csv: permission denied" ]
  [ ! -e o.png ]
}

@test "fmt -i on a FIFO or a device is refused at once instead of blocking on the read" {
  mkfifo pipe
  run -2 --separate-stderr timeout 10 "$FMT" -i pipe
  [ "${stderr_lines[0]}" = "rscene-fmt: error: pipe: --in-place needs a regular file; it is a FIFO, not a regular file" ]
  run -2 --separate-stderr "$FMT" -i /dev/null
  [ "${stderr_lines[0]}" = "rscene-fmt: error: /dev/null: --in-place needs a regular file; it is a device, not a regular file" ]
  [ -c /dev/null ]
}
