#!/bin/bash
# Agreement runner (issue 23, item 7): runs every scene of a catalogue that
# gen-catalogue.py wrote through
#   rscene-validate --check-files SCENE
#   rscene-sim --steps 2 -o /dev/null SCENE
#   rscene-render --width 32 --height 24 SCENE   (no -o: the camera's outputPath,
#                                               inside the scratch folder)
# (each from a scratch folder, so nothing is written into OUTDIR) and prints
# one line a scene:
#   NAME  V=<exit> <code>@<loc>  S=<exit> <code>@<loc>  R=<exit> <code>@<loc>  STATUS  [why]
# <code>@<loc> is the first error each tool prints (file:line:col, the scene's
# own file name left out; '-' when none).  STATUS:
#   AGREE      a control (NAME_ok) all three accept (exit 0); or a defect all
#              three refuse (validate 1, sim 2, render 2) with the same first
#              code at the same place
#   AGREE-REG  validate's first error is a code the registry
#              (rscene-validate --list-checks) gives to validate alone, or to
#              validate and one of sim/render: the tools it names refuse with
#              it at the same place, the others accept.  STRICT=1 counts this
#              as a disagreement.
#   DISAGREE   anything else (also a "defect" no tool refuses)
#   KNOWN      a disagreement listed, with its reason, in
#              known-disagreements.txt (open work, named in the README); a
#              listed scene that agrees is a DISAGREE ("fixed: remove it")
# Disagreements are printed first.  Exit 1 when any scene disagrees.
#
#   RSCENE_BIN=build/bin bash tests/agreement/run.sh OUTDIR
# Environment: RSCENE_BIN (default: build/bin beside this folder), JOBS
# (parallel scenes, default 2), STRICT, TOOL_TIMEOUT (s a tool, default 60).
set -u
here=$(cd "$(dirname "$0")" && pwd)
BIN=${RSCENE_BIN:-$here/../../build/bin}
out=${1:?usage: run.sh OUTDIR (written by gen-catalogue.py)}
out=$(cd "$out" && pwd) || exit 2
[ -f "$out/manifest.tsv" ] || { echo "run.sh: $out/manifest.tsv not found" >&2; exit 2; }
for t in rscene-validate rscene-sim rscene-render; do
  [ -x "$BIN/$t" ] || { echo "run.sh: $BIN/$t not found (set RSCENE_BIN)" >&2; exit 2; }
done
BIN=$(cd "$BIN" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/rscene-agree.XXXXXX") || exit 2
trap 'rm -rf "$work"' EXIT
export here BIN out work TOOL_TIMEOUT=${TOOL_TIMEOUT:-60} NO_COLOR=1

# code -> tools that report it ("validate sim render"), from the registry.
"$BIN/rscene-validate" --list-checks |
  awk '/^RS[0-9]+ /{t=""; for(i=3;i<=NF;i++){ if($i=="validate"||$i=="sim"||$i=="render"||$i=="every"){t=t" "$i} else break } print $1 t}' \
  > "$work/registry"
export REGISTRY="$work/registry"

one() { # scene name: run the three tools from a scratch folder
  local n=$1 d="$work/$1" v s r
  mkdir -p "$d/cwd" && cd "$d/cwd" || return
  timeout "$TOOL_TIMEOUT" "$BIN/rscene-validate" --check-files "$out/$n.rscene" >"$d/v" 2>/dev/null; v=$?
  timeout "$TOOL_TIMEOUT" "$BIN/rscene-sim" --steps 2 -o /dev/null "$out/$n.rscene" >/dev/null 2>"$d/s"; s=$?
  timeout "$TOOL_TIMEOUT" "$BIN/rscene-render" --width 32 --height 24 "$out/$n.rscene" >/dev/null 2>"$d/r"; r=$?
  echo "$v $s $r" > "$d/rc"
  cd "$work" && rm -rf "$d/cwd"
}
export -f one

grep -v '^#' "$out/manifest.tsv" | cut -f1 | xargs -P "${JOBS:-2}" -I{} bash -c 'one "$1"' _ {}

# Judge every scene and print the table, disagreements first.
/usr/bin/python3 - "$out" "$work" "${STRICT:-0}" <<'PY'
import os, re, sys
out, work, strict = sys.argv[1], sys.argv[2], sys.argv[3] == "1"
reg = {}
for l in open(os.path.join(work, "registry")):
    f = l.split()
    if f:
        reg[f[0]] = set(f[1:])
ERR = re.compile(r"^(.*?): error: .*?(?:\[(RS\d+)\])?\s*$")

def first_error(path, name):
    try:
        data = open(path, "rb").read().decode("utf-8", "replace")
    except OSError:
        return "-"
    for line in data.splitlines():
        if ": error: " not in line:
            continue
        m = ERR.match(line)
        loc, code = (m.group(1), m.group(2)) if m else (line.split(": error: ")[0], None)
        loc = loc.replace(out + "/", "")
        if loc.startswith(name + ".rscene:"):
            loc = loc[len(name) + 8:]
        return f"{code or 'nocode'}@{loc}"
    return "-"

def judge(v, ve, s, se, r, re_, line):
    why = []
    for t, x in (("validate", v), ("sim", s), ("render", r)):
        if x == "124":
            why.append(f"{t} timed out")
        elif x not in ("0", "1", "2"):
            why.append(f"{t} exit {x}")
    if line == "0":
        if (v, s, r) == ("0", "0", "0"):
            return "AGREE"
        return "DISAGREE control refused" + (": " + "; ".join(why) if why else "")
    if (v, s, r) == ("1", "2", "2") and ve == se == re_ and ve != "-":
        return "AGREE"
    code = ve.split("@")[0]
    tools = reg.get(code, set())
    if v == "1" and ve != "-":
        ok = True
        for t, x, e in (("sim", s, se), ("render", r, re_)):
            if t in tools or "every" in tools:
                ok &= x == "2" and e == ve
            else:
                ok &= x == "0"
        if ok:
            tag = f"registry:{code}=[{' '.join(sorted(tools))}]"
            return f"DISAGREE {tag} (STRICT)" if strict else f"AGREE-REG {tag}"
    if (v, s, r) == ("0", "0", "0"):
        why.append("no tool refuses")
    if v == "0" and s == "2":
        why.append(f"validate clean, sim {se}")
    if v == "0" and r == "2":
        why.append(f"validate clean, render {re_}")
    if v == "1" and s == "0":
        why.append(f"sim accepts {ve}")
    if v == "1" and r == "0":
        why.append(f"render accepts {ve}")
    if v == "1" and s == "2" and se != ve:
        why.append(f"sim {se} vs validate {ve}")
    if v == "1" and r == "2" and re_ != ve:
        why.append(f"render {re_} vs validate {ve}")
    if v == "0" and s == "2" and r == "2" and se != re_:
        why.append(f"sim {se} vs render {re_}")
    return "DISAGREE " + "; ".join(why)

known = {}
for l in open(os.path.join(os.environ["here"], "known-disagreements.txt")):
    if l.strip() and not l.startswith("#"):
        k, _, why = l.strip().partition(" ")
        known[k] = why.strip()

rows = []
for l in open(os.path.join(out, "manifest.tsv")):
    if l.startswith("#") or not l.strip():
        continue
    name, line = l.split("\t")[:2]
    d = os.path.join(work, name)
    try:
        v, s, r = open(os.path.join(d, "rc")).read().split()
    except (OSError, ValueError):
        v = s = r = "x"
    ve, se, re_ = (first_error(os.path.join(d, t), name) for t in "vsr")
    st = judge(v, ve, s, se, r, re_, line)
    if name in known:
        st = ("KNOWN " + known[name]) if st.startswith("DISAGREE") else "DISAGREE fixed: remove it from known-disagreements.txt"
    rows.append((not st.startswith("DISAGREE"), name,
                 f"{name:<34} V={v} {ve:<30} S={s} {se:<30} R={r} {re_:<30} {st}"))
rows.sort(key=lambda x: (x[0], x[1]))
for _, _, text in rows:
    print(text)
bad = sum(1 for ok, _, _ in rows if not ok)
reg_n = sum(1 for ok, _, t in rows if ok and "AGREE-REG" in t)
known_n = sum(1 for ok, _, t in rows if ok and " KNOWN " in t)
print(f"# {len(rows)} scenes: {len(rows) - bad - known_n} agree ({reg_n} of them AGREE-REG), {known_n} known "
      f"disagreements, {bad} disagree", file=sys.stderr)
sys.exit(1 if bad else 0)
PY
