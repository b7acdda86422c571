#!/usr/bin/env bats
# git integration never makes git fail (issue 9): the documented textconv
# (`rscene-fmt --textconv`) and external diff driver (`rscene-diff`) in a
# real temporary repository whose history holds a scene that does not
# parse, binary junk, a rename with a change, and a deletion.  Before the
# fix, git stopped at the broken commit with exit 128.

load helpers
FMT="$BIN/rscene-fmt"
DIFF="$BIN/rscene-diff"

SUBJECTS="good one
good two
broken
fixed
renamed and changed
binary junk
deleted"

commit() {
  git add -A
  git commit -q -m "$1"
  git tag "$2"
}

setup() {
  command -v git >/dev/null || skip "git not installed"
  needs_tools rscene-fmt rscene-diff
  cd "$BATS_TEST_TMPDIR"
  git init -q repo
  cd repo
  git config user.email t@example.com
  git config user.name t
  git config diff.rscene.textconv "$FMT --textconv"
  git config diff.rscene.command "$DIFF"
  echo '*.rscene diff=rscene' >.gitattributes
  cp "$DATA/diff_old.rscene" scene.rscene
  commit "good one" one
  cp "$DATA/diff_new.rscene" scene.rscene
  commit "good two" two
  printf 'raisim_engine_scene 1\nobject /World/Box box 0 0\n' >scene.rscene  # a truncated record
  commit "broken" broken
  cp "$DATA/diff_new.rscene" scene.rscene
  commit "fixed" fixed
  git mv scene.rscene moved.rscene
  sed 's/^time_step 0.0025$/time_step 0.002/' "$DATA/diff_new.rscene" >moved.rscene
  commit "renamed and changed" renamed
  printf 'junk\0\001\002\n' >junk.rscene
  commit "binary junk" junk
  git rm -q moved.rscene
  commit "deleted" deleted
}

@test "textconv: git log -p shows every commit and exits 0" {
  run -0 --separate-stderr git log -p --format=%s
  while read -r subject; do
    grep -qx "$subject" <<<"$output" || { echo "missing commit: $subject"; false; }
  done <<<"$SUBJECTS"
  # The broken scene as written; canonical text around it.
  [[ $output == *"+object /World/Box box 0 0"* ]]
  [[ $output == *"-mass"* || $output == *"-object /World/Crate box 1 0 0.5000000001"* ]]
  # A committed version reaches textconv as git's temporary copy, with no
  # repository path: named by its file name, and said so (issue 27).
  [[ $stderr == *".../scene.rscene:2:26: warning: "*"shown as written (a committed version: git gives textconv no folder or commit) [RS"* ]]
  [[ $stderr != *git-blob* && $stderr != *"${TMPDIR:-/tmp}/"* ]]
}

@test "textconv: git diff from a good to a broken scene and back exits 0" {
  # diff.rscene.command is configured too: plain `git diff` would run it.
  run -0 --separate-stderr git diff --no-ext-diff two broken
  [[ $output == *"+object /World/Box box 0 0"* ]]
  [[ $output == *"-time_step 0.0025"* ]]
  [ "$(grep -c 'shown as written' <<<"$stderr")" -eq 1 ]
  run -0 git diff --no-ext-diff broken fixed
  [[ $output == *"-object /World/Box box 0 0"* ]]
}

@test "textconv: git diff of a broken working copy exits 0" {
  git checkout -q fixed
  echo 'object /World/Half' >>scene.rscene
  run -0 --separate-stderr git diff --no-ext-diff
  [[ $output == *"+object /World/Half"* ]]
  [[ $stderr == *"shown as written"* ]]
  run -0 git diff --no-ext-diff --stat
  run -0 --separate-stderr git diff  # the external diff: a line diff
  [[ $output == *"+object /World/Half"* ]]
  [[ $stderr == *"showing a line diff"* ]]
}

@test "external diff: git log -p --ext-diff shows every commit and exits 0" {
  run -0 --separate-stderr git log -p --ext-diff --format=%s
  while read -r subject; do
    grep -qx "$subject" <<<"$output" || { echo "missing commit: $subject"; false; }
  done <<<"$SUBJECTS"
  # Scenes that parse: a semantic diff.
  [[ $output == *"rscene-diff a/scene.rscene b/scene.rscene"$'\n'"~ editor_ux"* ]]
  [[ $output == *"mass: 1 -> 3"* ]]
  # A side that does not parse: a header and a plain line diff.
  [[ $output == *$'rscene-diff a/scene.rscene b/scene.rscene\n--- a/scene.rscene\n+++ b/scene.rscene\n@@'* ]]
  [[ $output == *"+object /World/Box box 0 0"* ]]
  # A rename (git's nine arguments) names both paths.
  [[ $output == *$'rscene-diff a/scene.rscene b/moved.rscene\n~ time_step\n    dt: 0.0025 -> 0.002'* ]]
  # Binary junk, added; a deleted scene.
  [[ $output == *"Binary files /dev/null and b/junk.rscene differ"* ]]
  [[ $output == *$'rscene-diff a/moved.rscene /dev/null\n- raisim_engine_scene\n    version: 1\n- time_step\n    dt: 0.002\n'* ]]
  [[ $stderr == *"showing a line diff"* ]]
}

@test "external diff: git diff between any two commits exits 0" {
  for range in "one two" "two broken" "broken fixed" "fixed renamed" "renamed junk" "junk deleted" "broken deleted"; do
    run -0 git diff --ext-diff $range
  done
  run -0 --separate-stderr git diff --ext-diff broken junk -- junk.rscene
  [ "${lines[1]}" = "Binary files /dev/null and b/junk.rscene differ" ]
}

@test "a scene named like an option (-dash.rscene) at the top of the repository" {
  cp "$DATA/diff_old.rscene" ./-dash.rscene
  git add -- -dash.rscene
  git commit -q -m dash
  cp "$DATA/diff_new.rscene" ./-dash.rscene
  run -0 git diff --no-ext-diff -- -dash.rscene  # textconv gets the worktree file: -dash.rscene
  [[ $output == *"-time_step 0.0025"* || $output == *"+editor_ux multiSelect=false"* ]]
  run -0 git diff -- -dash.rscene
  [ "${lines[0]}" = "rscene-diff a/-dash.rscene b/-dash.rscene" ]
  [ "${lines[1]}" = "~ editor_ux" ]
  git commit -q -am "dash two"
  run -0 git log -p --ext-diff --format=%s -2
  [[ $output == *"mass: 1 -> 3"* ]]
}

# Issue 27: what each git mode shows, as the README's table says; each row
# checked in a real repository with both configured.
modes_repo() {
  cd "$BATS_TEST_TMPDIR"
  git init -q modes
  cd modes
  git config user.email t@example.com
  git config user.name t
  git config diff.rscene.textconv "$FMT --textconv"
  git config diff.rscene.command "$DIFF"
  echo '*.rscene diff=rscene' >.gitattributes
  scene >scene.rscene
  git add -A
  git commit -q -m base
}

# The base scene; $1..: sed expressions applied to it (one sed run).
scene() {
  local text e args=(-e "")
  for e in "$@"; do args+=(-e "$e"); done
  text='raisim_engine_scene 1
time_step 0.0025
material mat_a 0.5 0.5 0.5 1 0 0.5 0 0 0 0 false - - - - - - id=mat_a
object /World/A box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 2.5 default mat_a false true false - dynamic true 1 18446744073709551615 id=a semanticClass=crate parentGroupId=-
object /World/B box 1 0 0.5 1 0 0 0 1 1 1 0.5 1 2.5 default mat_a false true false - dynamic true 1 18446744073709551615 id=b'
  sed "${args[@]}" <<<"$text"
}

@test "git modes: records of one section reordered show in textconv, not in the external driver" {
  modes_repo
  scene '4{h;d}' '5G' >scene.rscene  # B before A
  [[ $(sed -n 4p scene.rscene) == "object /World/B "* ]]
  run -0 git diff --no-ext-diff
  [[ $output == *$'\n-object /World/A '* && $output == *$'\n+object /World/A '* ]]
  run -0 git diff --ext-diff
  [ -z "$output" ]
}

@test "git modes: sections reordered, numbers and flags respelt, spaces: hidden in both" {
  modes_repo
  # The material after the objects, time_step last, 0.50 and no/yes, two spaces.
  scene '2{h;d}' '3{H;d}' '$G' 's/^object \/World\/B box 1 0 0.5 /object \/World\/B  box 1 0 0.50 /' \
    '/World\/B/s/false true false/no yes no/' >scene.rscene
  [ "$(sed -n 2p scene.rscene)" = "object /World/A box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 2.5 default mat_a false true false - dynamic true 1 18446744073709551615 id=a semanticClass=crate parentGroupId=-" ]
  [ "$(tail -n 1 scene.rscene)" = "material mat_a 0.5 0.5 0.5 1 0 0.5 0 0 0 0 false - - - - - - id=mat_a" ]
  ! git diff --quiet --no-textconv  # the bytes did change
  run -0 git diff --no-ext-diff
  [ -z "$output" ]
  run -0 git diff --ext-diff
  [ -z "$output" ]
}

@test "git modes: keys reordered and comments show in textconv, not in the external driver" {
  modes_repo
  scene 's/semanticClass=crate parentGroupId=-/parentGroupId=- semanticClass=crate/' '4i # the first crate' >scene.rscene
  run -0 git diff --no-ext-diff
  [[ $output == *$'\n+# the first crate'* ]]
  [[ $output == *$'\n+object /World/A '*"parentGroupId=- semanticClass=crate"* ]]
  run -0 git diff --ext-diff
  [ -z "$output" ]
}

@test "git modes: a changed value, a whole line in textconv, a word with --word-diff, a field in the driver" {
  modes_repo
  scene '/World\/B/s/ 2.5 default/ 3 default/' >scene.rscene
  run -0 git diff --no-ext-diff
  [[ $output == *$'\n-object /World/B box 1 0 0.5 1 0 0 0 1 1 1 0.5 1 2.5 default'* ]]
  [[ $output == *$'\n+object /World/B box 1 0 0.5 1 0 0 0 1 1 1 0.5 1 3 default'* ]]
  run -0 git diff --no-ext-diff --word-diff
  [[ $output == *$'\nobject /World/B box 1 0 0.5 1 0 0 0 1 1 1 0.5 1 [-2.5-]{+3+} default'* ]]
  run -0 git diff --ext-diff
  [ "$output" = $'rscene-diff a/scene.rscene b/scene.rscene\n~ object /World/B\n    mass: 2.5 -> 3' ]
}

@test "git modes: an added scene in the driver reads /dev/null and lists its records' values" {
  modes_repo
  mkdir -p sub
  scene >sub/new.rscene
  git add sub/new.rscene
  run -0 git diff --cached --ext-diff -- sub/new.rscene
  [ "${lines[0]}" = "rscene-diff /dev/null b/sub/new.rscene" ]
  [[ $output == *$'\n+ object /World/B\n    primitive: box\n    position: 1,0,0.5\n'* ]]
  git commit -q -m added
  git rm -q sub/new.rscene
  run -0 git diff --cached --ext-diff -- sub/new.rscene
  [ "${lines[0]}" = "rscene-diff a/sub/new.rscene /dev/null" ]
  [[ $output == *$'\n- object /World/A\n    primitive: box\n'* ]]
}

@test "git modes: warnings name the repository path where git gives it" {
  modes_repo
  mkdir -p sub
  printf 'raisim_engine_scene 1\nobject /World/Box box 0 0\n' >sub/s.rscene  # does not parse
  git add sub/s.rscene
  git commit -q -m broken
  scene >sub/s.rscene
  # textconv: the working copy by its repository path (git passes it), also
  # from a folder below the top; the committed version by its name only.
  cd sub
  run -0 --separate-stderr git diff --no-ext-diff
  [ "$stderr" = ".../s.rscene:2:26: warning: object has 4 positional fields, expected 25, 19 or 17; shown as written (a committed version: git gives textconv no folder or commit) [RS1007]" ]
  cd ..
  git commit -q -am fixed
  printf 'raisim_engine_scene 1\nobject /World/Box box 0 0\n' >sub/s.rscene
  run -0 --separate-stderr git diff --no-ext-diff
  [ "$stderr" = "sub/s.rscene:2:26: warning: object has 4 positional fields, expected 25, 19 or 17; shown as written [RS1007]" ]
  # The external driver: git passes the path, both sides are named by it.
  run -0 --separate-stderr git diff --ext-diff HEAD~1 HEAD
  [ "$stderr" = "a/sub/s.rscene:2:26: warning: object has 4 positional fields, expected 25, 19 or 17; showing a line diff [RS1007]" ]
}
