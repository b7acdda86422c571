#!/bin/sh
# Regenerates the code list of man/rscene-validate.1 (section CHECKS) from
# the registry, through `rscene-validate --list-checks`:
#   scripts/man-checks.sh build/bin/rscene-validate
# tests/scene/code_registry_test.cpp fails when the two differ.
set -eu
validate=${1:-build/bin/rscene-validate}
man=$(dirname "$0")/../man/rscene-validate.1
items=$(mktemp)
trap 'rm -f "$items" "$items.new"' EXIT
# Columns of --list-checks: code (6), severity (7), tools (19), summary.
"$validate" --list-checks | awk '{
  code = substr($0, 1, 6); sev = substr($0, 9, 7); tools = substr($0, 18, 19); summary = substr($0, 39)
  sub(/ +$/, "", sev); sub(/ +$/, "", tools)
  printf ".It Sy %s Pq %s\n%s: %s\n", code, sev, tools, summary
}' >"$items"
# Replace the list between ".Bl -tag -width RS0000" and its ".El" in CHECKS.
awk -v items="$items" '
  /^\.Sh CHECKS/ { inChecks = 1 }
  inChecks && /^\.Bl -tag -width RS0000/ { print; while ((getline line < items) > 0) print line; skipping = 1; next }
  skipping && /^\.El/ { skipping = 0; inChecks = 0 }
  !skipping { print }
' "$man" >"$items.new"
cat "$items.new" >"$man"
