#!/usr/bin/env bash
# rscene-review-range.sh: a review folder (rscene-diff --review) for every
# .rscene file a git revision range changes, and an index.md over them for
# a pull-request comment (README, "Reviewing scene changes in CI").
#
# usage: scripts/rscene-review-range.sh [-o DIR] [-W WIDTH -H HEIGHT] BASE [HEAD]
#   BASE, HEAD  commits (HEAD: HEAD); the range is what HEAD has that BASE
#               has not, file by file, as a pull request shows it: from
#               their merge base to HEAD (git diff BASE...HEAD), so a
#               change made on BASE after the branch left it is not shown
#   -o DIR      where the folders go (default: scene-review); DIR/<scene
#               path with / as __, less .rscene>/ per scene, DIR/index.md
#   -W, -H      image size (rscene-diff --width/--height)
# Run inside the repository.  rscene-diff is taken from $RSCENE_DIFF, else
# from PATH.  The old side of each scene is read from git on standard input
# named by its path (rscene-diff --stdin-filename), so its meshes and
# robots resolve in the checkout; the new side is the checked-out file
# when HEAD is the checkout's and the file is unmodified, else a copy.
# Exit: 0 no scene changed, 1 some changed, 2 a scene failed (its folder
# and index line say so; the others are still written) or the script
# could not do its work (an output folder it cannot make, a git error).
set -euo pipefail
# Whatever fails unguarded is an error (2), never "some changed" (1),
# which CI jobs accept.
trap 'exit 2' ERR

out=scene-review
size=()
while getopts 'o:W:H:' opt; do
  case $opt in
    o) out=$OPTARG ;;
    W) size+=(--width "$OPTARG") ;;
    H) size+=(--height "$OPTARG") ;;
    *) echo "usage: $0 [-o DIR] [-W WIDTH -H HEIGHT] BASE [HEAD]" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: $0 [-o DIR] [-W WIDTH -H HEIGHT] BASE [HEAD]" >&2
  exit 2
fi
base=$1
head=${2:-HEAD}
diff=${RSCENE_DIFF:-rscene-diff}
command -v "$diff" >/dev/null || { echo "$0: rscene-diff not found (set RSCENE_DIFF)" >&2; exit 2; }
case $diff in */*) diff=$(cd "$(dirname "$diff")" && pwd)/$(basename "$diff") ;; esac  # it runs from other folders
for rev in "$base" "$head"; do
  git rev-parse --verify --quiet "$rev^{commit}" >/dev/null || { echo "$0: '$rev' is no commit" >&2; exit 2; }
done
since=$(git merge-base "$base" "$head") || { echo "$0: '$base' and '$head' have no common history" >&2; exit 2; }
# The folder is written into: in the repository it could hold links a pull
# request placed there, which every write would follow.
if [ -n "$(git ls-files -- "$out" 2>/dev/null | head -n 1)" ]; then
  echo "$0: '$out' holds files tracked by git; write the review elsewhere (-o)" >&2
  exit 2
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)
top=$(git rev-parse --show-toplevel)
cd "$top"
headIsCheckout=false
[ "$(git rev-parse "$head^{commit}")" = "$(git rev-parse HEAD)" ] && headIsCheckout=true
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

status=0
rows=()
sections=()
while IFS= read -r -d '' change && IFS= read -r -d '' path; do
  name=${path%.rscene}
  name=${name//\//__}
  dir="$out/$name"
  case $change in
    A) what=added ;;
    D) what=deleted ;;
    *) what=modified ;;
  esac
  # The old side: git's blob on standard input, named by its path.
  if [ "$change" = A ]; then
    oldArgs=(/dev/null)
  else
    git show "$since:$path" > "$tmp/old.rscene"
    oldArgs=(--stdin-filename "$path" -)
  fi
  if [ "$change" = D ]; then
    new=/dev/null
  else
    new=$path
  fi
  # The new side from the checkout when it is HEAD's; else from a copy
  # under $tmp/new, run from there so that it keeps its name.
  from=$top
  if [ "$change" != D ] && ! { $headIsCheckout && git diff --quiet HEAD -- "$path"; }; then
    mkdir -p "$tmp/new/$(dirname "$path")"
    git show "$head:$path" > "$tmp/new/$path"
    from=$tmp/new
  fi
  rc=0
  if [ "$change" = A ]; then
    (cd "$from" && "$diff" -q --review "$dir" "${size[@]}" /dev/null "$new" </dev/null) || rc=$?
  else
    (cd "$from" && "$diff" -q --review "$dir" "${size[@]}" "${oldArgs[@]}" "$new" < "$tmp/old.rscene") || rc=$?
  fi
  case $rc in
    0) result="no change" ;;
    1) result=changed; [ $status -eq 0 ] && status=1 ;;
    *) result="error (see the job's log)"; status=2 ;;
  esac
  # <...>: a link destination that may hold spaces.
  rows+=("| [\`$path\`](<$name/review.md>) | $what | $result |")
  if [ -f "$dir/review.md" ]; then
    # The scene's review, its images and headings under this index.
    sections+=("$(sed -e "s#](\(before\|after\|changes\)\.png)#](<$name/\1.png>)#g" -e 's/^###/##/' "$dir/review.md")")
  fi
done < <(git diff --name-status --no-renames -z "$since" "$head" -- '*.rscene')

{
  echo "# Scene review: $base..$head"
  echo
  if [ ${#rows[@]} -eq 0 ]; then
    echo "No scene changed."
  else
    echo "| scene | file | result |"
    echo "|---|---|---|"
    printf '%s\n' "${rows[@]}"
    for s in "${sections[@]}"; do
      echo
      echo "$s"
    done
  fi
} > "$out/index.md.tmp"
mv "$out/index.md.tmp" "$out/index.md"
exit $status
