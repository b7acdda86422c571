#!/usr/bin/env bats
# scripts/rscene-review-range.sh (issue 27): one rscene-diff --review
# folder per scene a git range changes, and index.md over them, in a real
# temporary repository with several commits.

load helpers
SCRIPT="$ROOT/scripts/rscene-review-range.sh"
export LP_NUM_THREADS=1

setup() {
  needs_tools rscene-diff
  "$BIN/rscene-diff" --help | grep -q -- --review || skip "rscene-diff built without lib/render"
  command -v git >/dev/null || skip "no git"
  export RSCENE_DIFF="$BIN/rscene-diff"
  in_workdir
  git init -q repo
  cd repo
  git config user.email t@example.com
  git config user.name T
  mkdir -p scenes/yard
  scene() {  # $1: the crate's x
    printf '%s\n' 'raisim_engine_scene 2' 'light /World/Sun 0.3 0.2 -1 3 type=directional shadows=true' \
      'object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615' \
      "object /World/Crates/Box box $1 0 0.5 1 0 0 0 1 1 1 1 1 1 default - false true false - static true 1 18446744073709551615"
  }
  scene 0 > scenes/a.rscene
  scene 1 > scenes/yard/b.rscene
  echo readme > README
  git add -A && git commit -qm one
  scene 1.5 > scenes/a.rscene          # a crate moved
  git rm -q scenes/yard/b.rscene       # a scene deleted
  scene 2 > scenes/c.rscene            # a scene added
  git add -A && git commit -qm two
  sed -i 's/ 1.5 0 0.5 / 1.50 0 0.50 /' scenes/a.rscene   # respelled only
  echo more >> README
  git add -A && git commit -qm three
}

@test "review range: a folder per changed scene and index.md; exit 1 when scenes changed" {
  run "$SCRIPT" -o ../review -W 64 -H 40 HEAD~2 HEAD~1
  [ "$status" -eq 1 ]
  cd ../review
  run ls
  [ "$output" = "$(printf '%s\n' index.md scenes__a scenes__c scenes__yard__b)" ]
  for d in scenes__a scenes__c scenes__yard__b; do
    [ -s $d/review.md ] && [ -s $d/index.html ] && [ -s $d/before.png ] && [ -s $d/after.png ] && [ -s $d/changes.png ]
  done
  cat index.md
  grep -qxF '# Scene review: HEAD~2..HEAD~1' index.md
  grep -qxF '| [`scenes/a.rscene`](<scenes__a/review.md>) | modified | changed |' index.md
  grep -qxF '| [`scenes/c.rscene`](<scenes__c/review.md>) | added | changed |' index.md
  grep -qxF '| [`scenes/yard/b.rscene`](<scenes__yard__b/review.md>) | deleted | changed |' index.md
  # The scenes' sections, their images under their folders.
  grep -qF '![changes](<scenes__a/changes.png>)' index.md
  grep -qF '| object /World/Crates/Box | changed | position | 0,0,0.5 | 1.5,0,0.5 |' index.md
  grep -qF '(/dev/null &rarr; scenes/c.rscene)' index.md
  grep -qF '(scenes/yard/b.rscene &rarr; /dev/null)' index.md
}

@test "review range: a respelled scene is no change (exit 0); a range without scenes says so" {
  run "$SCRIPT" -o ../r1 -W 64 -H 40 HEAD~1 HEAD
  [ "$status" -eq 0 ]
  grep -qxF '| [`scenes/a.rscene`](<scenes__a/review.md>) | modified | no change |' ../r1/index.md
  git commit -q --allow-empty -m four
  run "$SCRIPT" -o ../r2 HEAD~1
  [ "$status" -eq 0 ]
  grep -qx 'No scene changed.' ../r2/index.md
}

@test "review range: a scene that does not parse is an error in its line; the others are still reviewed" {
  printf 'raisim_engine_scene 2\nobject /World/X box 0 0\n' > scenes/a.rscene
  scene 3 > scenes/c.rscene
  git add -A && git commit -qm broken
  run "$SCRIPT" -o ../r -W 64 -H 40 HEAD~1
  [ "$status" -eq 2 ]
  grep -qxF '| [`scenes/a.rscene`](<scenes__a/review.md>) | modified | error (see the job'"'"'s log) |' ../r/index.md
  grep -qxF '| [`scenes/c.rscene`](<scenes__c/review.md>) | modified | changed |' ../r/index.md
  grep -q '^```diff$' ../r/scenes__a/review.md
  run "$SCRIPT" -o ../r nosuchrev
  [ "$status" -eq 2 ]
  [[ "$output" == *"'nosuchrev' is no commit"* ]]
}

@test "review range: a pull request's range starts at its merge base: a change the base made since is not shown" {
  git checkout -q -b pr
  scene 4 > scenes/c.rscene
  git commit -qam "pr: the crate of c moved"
  git checkout -q -
  mkdir -p scenes/yard && scene 7 > "scenes/yard/with space.rscene"
  sed -i 's/type=directional/type=directional intensity=0.5/' scenes/a.rscene
  git add -A && git commit -qm "base: a changed since the branch left"
  git checkout -q pr
  run "$SCRIPT" -o ../r -W 64 -H 40 "$(git rev-parse --abbrev-ref @{-1})" HEAD
  [ "$status" -eq 1 ]
  cat ../r/index.md
  [ "$(grep -c '^| \[' ../r/index.md)" -eq 1 ]
  grep -qxF '| [`scenes/c.rscene`](<scenes__c/review.md>) | modified | changed |' ../r/index.md
  # A path with a space: the link's destination in <...> resolves.
  git checkout -q -
  run "$SCRIPT" -o ../r2 -W 64 -H 40 HEAD~1 HEAD
  [ "$status" -eq 1 ]
  grep -qF '| [`scenes/yard/with space.rscene`](<scenes__yard__with space/review.md>) | added | changed |' ../r2/index.md
  grep -qF '![changes](<scenes__yard__with space/changes.png>)' ../r2/index.md
}

@test "review range: an output it cannot write, or one git tracks, is an error (2), never 'changed' (1)" {
  echo file > ../afile
  run "$SCRIPT" -o ../afile HEAD~2 HEAD~1
  [ "$status" -eq 2 ]
  mkdir review && echo x > review/after.png && git add review && git commit -qm "a committed review folder"
  run "$SCRIPT" -o review HEAD~3 HEAD~2
  [ "$status" -eq 2 ]
  [[ "$output" == *"'review' holds files tracked by git; write the review elsewhere (-o)"* ]]
  [ "$(cat review/after.png)" = x ]
}

@test "review range: the GitHub Actions and GitLab CI jobs of examples/ci are YAML and run the script" {
  python3 -c 'import yaml' 2>/dev/null || skip "no python3-yaml"
  for f in "$ROOT"/examples/ci/github-scene-review.yml "$ROOT"/examples/ci/gitlab-scene-review.yml; do
    python3 -c 'import sys, yaml; yaml.safe_load(open(sys.argv[1]))' "$f"
    grep -q 'scripts/rscene-review-range.sh -o scene-review' "$f"
    grep -q 'scene-review/index.md' "$f"
  done
}
