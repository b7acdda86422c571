#!/usr/bin/env bats
# Documentation checks for every tool built in $BIN: man pages lint clean,
# and each long option `--help` prints is documented in the man page, the
# three shell completions and the tool's shell test.  A new tool is checked
# as soon as its binary exists in $BIN; nothing here names a tool.

load helpers

setup() {
  command -v mandoc >/dev/null || skip "mandoc not installed"
}

# The user-facing tools: built executables with a cmd/<tool>/ folder (so
# helpers such as bench's scene generator are not taken for tools).
tools() {
  local t
  for t in "$BIN"/rscene-*; do
    [ -x "$t" ] && [ -f "$t" ] && [ -d "$ROOT/cmd/$(basename "$t")" ] && basename "$t"
  done
  return 0
}

require_tools() {
  [ -n "$(tools)" ] || skip "no rscene-* tool built in $BIN"
}

# The shell test of a tool: rscene-fmt -> fmt.bats; to-json and from-json
# share json.bats; other two-word names take an underscore (to_xml.bats).
bats_file() {
  local short=${1#rscene-}
  case $short in
    to-json | from-json) short=json ;;
    *-*) short=${short//-/_} ;;  # to-xml -> to_xml.bats
  esac
  echo "$ROOT/shell-tests/$short.bats"
}

long_options() {
  "$BIN/$1" --help | grep -oE -- '(^|[ ,])--[a-z][a-z0-9-]*' | sed 's/^[ ,]*//' | sort -u
}

rendered_man() {
  mandoc -Tascii "$1" | col -b
}

# Prints "tool: what is missing" for each gap and fails if there is any.
report() {
  if [ -n "$1" ]; then
    printf '%s' "$1"
    return 1
  fi
}

@test "man/rscene.5 passes mandoc -Tlint -W warning" {
  run mandoc -Tlint -W warning "$ROOT/man/rscene.5"
  [ "$status" -eq 0 ]
  [ -z "$output" ]
}

@test "man/rscene.5 documents every record kind of the schema table" {
  page=$(rendered_man "$ROOT/man/rscene.5")
  tags=$(grep -oE '^\{"[a-z_0-9]+", [0-9]+, Role::' "$ROOT/lib/core/schema_table.cpp" | cut -d'"' -f2)
  [ "$(echo "$tags" | wc -l)" -ge 39 ]
  missing=""
  for t in $tags; do
    grep -qE "^     $t( |$)" <<<"$page" || missing+="rscene.5: record kind $t is not listed"$'\n'
  done
  report "$missing"
}

@test "every tool's man page passes mandoc -Tlint -W warning" {
  require_tools
  missing=""
  for t in $(tools); do
    page="$ROOT/man/$t.1"
    if [ ! -f "$page" ]; then
      missing+="$t: no man/$t.1"$'\n'
      continue
    fi
    out=$(mandoc -Tlint -W warning "$page" 2>&1) || true
    [ -z "$out" ] || missing+="$t: $out"$'\n'
  done
  report "$missing"
}

@test "every tool's man page has EXIT STATUS (0, 1, 2, 130) and EXAMPLES" {
  require_tools
  missing=""
  for t in $(tools); do
    page="$ROOT/man/$t.1"
    [ -f "$page" ] || { missing+="$t: no man/$t.1"$'\n'; continue; }
    text=$(rendered_man "$page")
    for s in "EXIT STATUS" "EXAMPLES"; do
      grep -qx "$s" <<<"$text" || missing+="$t: no $s section"$'\n'
    done
    status_section=$(sed -n '/^EXIT STATUS$/,/^[A-Z]/p' <<<"$text")
    for code in 0 1 2 130; do
      grep -qE "^ +$code([[:space:]]|$)" <<<"$status_section" || missing+="$t: EXIT STATUS lacks $code"$'\n'
    done
  done
  report "$missing"
}

@test "every long option in --help is in the tool's man page" {
  require_tools
  missing=""
  for t in $(tools); do
    [ -f "$ROOT/man/$t.1" ] || { missing+="$t: no man/$t.1"$'\n'; continue; }
    text=$(rendered_man "$ROOT/man/$t.1")
    for o in $(long_options "$t"); do
      grep -qE -- "(^|[^a-z-])$o([^a-z-]|$)" <<<"$text" || missing+="$t: $o not in man/$t.1"$'\n'
    done
  done
  report "$missing"
}

@test "--help names each option's value in words, never CLI11's validator text (INT:INT in [1 - 16384])" {
  require_tools
  found=""
  for t in $(tools); do
    found+=$("$BIN/$t" --help | grep -E -- "^ +-.*:(U?INT|FLOAT|TEXT)( in |\b)" | sed "s|^|$t: |")
  done
  report "$found"
}

@test "every long option in --help is in the bash completion" {
  require_tools
  missing=""
  for t in $(tools); do
    f="$ROOT/completions/bash/$t"
    [ -f "$f" ] || { missing+="$t: no completions/bash/$t"$'\n'; continue; }
    for o in $(long_options "$t"); do
      grep -qE -- "(^|[^a-z-])$o([^a-z-]|$)" "$f" || missing+="$t: $o not in completions/bash/$t"$'\n'
    done
  done
  report "$missing"
}

@test "every long option in --help is in the zsh completion" {
  require_tools
  missing=""
  for t in $(tools); do
    f="$ROOT/completions/zsh/_$t"
    [ -f "$f" ] || { missing+="$t: no completions/zsh/_$t"$'\n'; continue; }
    head -n 1 "$f" | grep -qx "#compdef $t" || missing+="$t: completions/zsh/_$t does not start with #compdef $t"$'\n'
    for o in $(long_options "$t"); do
      grep -qE -- "(^|[^a-z-])$o([^a-z-]|$)" "$f" || missing+="$t: $o not in completions/zsh/_$t"$'\n'
    done
  done
  report "$missing"
}

@test "every long option in --help is in the fish completion" {
  require_tools
  missing=""
  for t in $(tools); do
    f="$ROOT/completions/fish/$t.fish"
    [ -f "$f" ] || { missing+="$t: no completions/fish/$t.fish"$'\n'; continue; }
    for o in $(long_options "$t"); do
      grep -qE -- "^complete -c $t .*-l ${o#--}( |$)" "$f" || missing+="$t: -l ${o#--} not in completions/fish/$t.fish"$'\n'
    done
  done
  report "$missing"
}

@test "every long option in --help is exercised by the tool's shell test" {
  require_tools
  missing=""
  for t in $(tools); do
    f=$(bats_file "$t")
    [ -f "$f" ] || { missing+="$t: no shell-tests/$(basename "$f")"$'\n'; continue; }
    for o in $(long_options "$t"); do
      grep -qE -- "(^|[^a-z-])$o([^a-z-]|$)" "$f" || missing+="$t: $o not in shell-tests/$(basename "$f")"$'\n'
    done
  done
  report "$missing"
}

@test "bash completion files load without errors" {
  require_tools
  missing=""
  for t in $(tools); do
    f="$ROOT/completions/bash/$t"
    [ -f "$f" ] || continue
    out=$(bash -c "source '$f' && complete -p $t" 2>&1) || missing+="$t: $out"$'\n'
  done
  report "$missing"
}
