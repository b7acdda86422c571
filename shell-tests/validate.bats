#!/usr/bin/env bats
# End-to-end tests of rscene-validate: output, exit status, every flag.

load helpers
V="$BIN/rscene-validate"

setup() {
  needs_tools rscene-validate
  export NO_COLOR=1
  cd "$BATS_TEST_TMPDIR"
}

@test "a clean scene: exit 0, no output, summary on stderr" {
  run --separate-stderr "$V" "$DATA/validate_clean.rscene"
  [ "$status" -eq 0 ]
  [ -z "$output" ]
  [ "$stderr" = "no issues in 1 file" ]
}

@test "errors: file:line:col, source line, caret, hint; exit 1" {
  run --separate-stderr "$V" "$DATA/validate_errors.rscene"
  [ "$status" -eq 1 ]
  [ "${lines[0]}" = "$DATA/validate_errors.rscene:2:47: error: dynamic body '/World/a' needs a mass > 0 [RS4008]" ]
  [ "${lines[2]}" = "                                                ^" ]
  [ "${lines[3]}" = "  hint: give it a positive mass, or make it static or kinematic" ]
  [[ "$output" == *"3:27: warning: unknown key 'colour' for light [RS3002]"* ]]
  [[ "$output" == *'hint: did you mean `color`?'* ]]
  [ "$stderr" = "2 errors, 1 warning in 1 file" ]
}

@test "warnings pass unless --strict" {
  run "$V" "$DATA/validate_warnings.rscene"
  [ "$status" -eq 0 ]
  run "$V" --strict "$DATA/validate_warnings.rscene"
  [ "$status" -eq 1 ]
}

@test "syntax errors from the loader are findings" {
  run --separate-stderr "$V" "$DATA/validate_syntax.rscene"
  [ "$status" -eq 1 ]
  [[ "${lines[0]}" == *":2:10: error: time_step has 0 positional fields, expected 1 [RS1007]" ]]
}

@test "many files in one call, counted in the summary" {
  run --separate-stderr "$V" "$DATA/validate_clean.rscene" "$DATA/validate_errors.rscene" "$DATA/validate_warnings.rscene"
  [ "$status" -eq 1 ]
  [ "$stderr" = "2 errors, 2 warnings in 3 files" ]
}

@test "stdin with no operand and with -, named by --stdin-filename" {
  run --separate-stderr "$V" < "$DATA/validate_warnings.rscene"
  [ "$status" -eq 0 ]
  [[ "${lines[0]}" == "<stdin>:2:27: warning: "* ]]
  run --separate-stderr "$V" --stdin-filename scenes/w.rscene - < "$DATA/validate_warnings.rscene"
  [[ "${lines[0]}" == "scenes/w.rscene:2:27: warning: "* ]]
}

@test "--ignore and --only filter codes; unknown codes are usage errors" {
  run --separate-stderr "$V" --ignore RS4008,RS3008 "$DATA/validate_errors.rscene"
  [ "$status" -eq 0 ]
  [ "$stderr" = "1 warning in 1 file" ]
  run --separate-stderr "$V" --only RS3002 "$DATA/validate_errors.rscene"
  [ "$status" -eq 0 ]
  [ "$stderr" = "1 warning in 1 file" ]
  run --separate-stderr "$V" --only RS9999 "$DATA/validate_errors.rscene"
  [ "$status" -eq 2 ]
  [ "$stderr" = "rscene-validate: error: unknown code 'RS9999' in --only (see --list-checks)" ]
}

@test "--max-issues limits what is shown, not what is counted" {
  run --separate-stderr "$V" --max-issues 1 "$DATA/validate_errors.rscene"
  [ "$status" -eq 1 ]
  [ "$(printf '%s\n' "$output" | grep -c '^/')" -eq 1 ]
  [ "$stderr" = "2 errors, 1 warning in 1 file (2 not shown)" ]
}

@test "--list-checks prints every code any tool emits, with severity and tools" {
  run "$V" --list-checks
  [ "$status" -eq 0 ]
  [[ "${lines[0]}" == "RS1001  error    every tool           missing raisim_engine_scene header" ]]
  [[ "$output" == *"RS3002  warning  validate             unknown key (kept and ignored)"* ]]
  [[ "$output" == *"RS4008  error    validate sim render  dynamic object or compound without positive mass"* ]]
  [[ "$output" == *"RS7011  warning  validate sim render  wire to a node the simulator does not model, skipped"* ]]
  [[ "$output" == *"RS8001  error    from-json            invalid JSON"* ]]
  [[ "$output" == *"RS9001  error    render               mesh file that cannot be read"* ]]
  # Codes of other tools can be filtered on like the validator's own.
  run "$V" --only RS9001 "$DATA/validate_clean.rscene"
  [ "$status" -eq 0 ]
}

@test "what sim refuses is a validate finding with the same code and line" {
  printf 'raisim_engine_scene 2\ntime_step 0\nobject /World/a box 0 0 1 1 0 0 0 1 0 1 0.5 1 1 default engine_default false true false - dynamic true 1 1\n' >bad.rscene
  run -1 --separate-stderr "$V" bad.rscene
  [ "${lines[0]}" = "bad.rscene:2:11: error: time step must be positive [RS7008]" ]
  [[ "$output" == *"bad.rscene:3:35: error: box with a zero or negative side ('/World/a') [RS7003]"* ]]
  [ -x "$BIN/rscene-sim" ] || return 0
  run -2 --separate-stderr "$BIN/rscene-sim" --steps 1 bad.rscene
  [[ "$stderr" == *"bad.rscene:2:11: error: time step must be positive [RS7008]"* ]]
  [[ "$stderr" == *"bad.rscene:3:35: error: box with a zero or negative side ('/World/a') [RS7003]"* ]]
}

@test "a wire to an articulated system is simulated: no RS7011" {
  run -0 --separate-stderr "$V" "$BATS_TEST_DIRNAME/../examples/robot_cell.rscene"
  [[ "$output" != *"RS7011"* ]]
}

@test "--format json: one document with findings, counts and truncated" {
  command -v jq >/dev/null || skip "jq not installed"
  run --separate-stderr "$V" --format json --max-issues 2 "$DATA/validate_errors.rscene"
  [ "$status" -eq 1 ]
  [ "$(jq -r '.counts.errors, .counts.warnings, .truncated' <<<"$output" | tr '\n' ' ')" = "2 1 true " ]
  [ "$(jq -r '.files[0].findings[1] | [.code, .severity, .line, .column, .tag, .field] | join(" ")' <<<"$output")" = "RS3008 error 2 57 object material" ]
  [ "$(jq -r '.files[0].findings[0].hint' <<<"$output")" = "give it a positive mass, or make it static or kinematic" ]
}

@test "--format sarif: 2.1.0 with rules and regions" {
  command -v jq >/dev/null || skip "jq not installed"
  run --separate-stderr "$V" --format sarif "$DATA/validate_errors.rscene"
  [ "$status" -eq 1 ]
  [ "$(jq -r '.version' <<<"$output")" = "2.1.0" ]
  [ "$(jq -r '.runs[0].results[0] | [.ruleId, .level, .locations[0].physicalLocation.region.startLine, .locations[0].physicalLocation.region.startColumn] | join(" ")' <<<"$output")" = "RS4008 error 2 47" ]
  [ "$(jq -r '.runs[0].results[0] as $r | .runs[0].tool.driver.rules[$r.ruleIndex].id' <<<"$output")" = "RS4008" ]
  [ "$(jq '.runs[0].tool.driver.rules | length' <<<"$output")" -eq "$("$V" --list-checks | wc -l)" ]
}

@test "--profile raisim adds what RaiSim refuses" {
  run "$V" "$DATA/validate_raisim.rscene"
  [ "$status" -eq 0 ]
  run --separate-stderr "$V" --profile raisim "$DATA/validate_raisim.rscene"
  [ "$status" -eq 1 ]
  [[ "${lines[0]}" == *":2:1: error: RaiSim does not load point_cloud records [RS6001]" ]]
  run "$V" --profile bullet "$DATA/validate_raisim.rscene"
  [ "$status" -eq 2 ]
}

@test "--check-files resolves asset paths; --base-dir places stdin" {
  run "$V" "$DATA/validate_mesh.rscene"
  [ "$status" -eq 0 ]
  run --separate-stderr "$V" --check-files "$DATA/validate_mesh.rscene"
  [ "$status" -eq 1 ]
  [[ "${lines[0]}" == *"error: file 'validate_missing_mesh.obj' does not exist (resolved to '$DATA/./validate_missing_mesh.obj')"* || "${lines[0]}" == *"error: file 'validate_missing_mesh.obj' does not exist"* ]]
  mkdir -p here && printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > here/validate_missing_mesh.obj  # a mesh: --check-files reads it
  run "$V" --check-files --base-dir here - < "$DATA/validate_mesh.rscene"
  [ "$status" -eq 0 ]
  run "$V" --check-files --stdin-filename here/scene.rscene < "$DATA/validate_mesh.rscene"
  [ "$status" -eq 0 ]
  run "$V" --check-files < "$DATA/validate_mesh.rscene"
  [ "$status" -eq 1 ]
}

@test "--color always colors, NO_COLOR and pipes do not" {
  run "$V" --color always "$DATA/validate_warnings.rscene"
  [[ "$output" == *$'\033['* ]]
  run "$V" "$DATA/validate_warnings.rscene"
  [[ "$output" != *$'\033['* ]]
  run "$V" --color never "$DATA/validate_warnings.rscene"
  [[ "$output" != *$'\033['* ]]
}

@test "an unreadable file is trouble (exit 2), the others are still checked" {
  run --separate-stderr "$V" missing.rscene "$DATA/validate_clean.rscene"
  [ "$status" -eq 2 ]
  [[ "$stderr" == "rscene-validate: error: cannot read 'missing.rscene': "* ]]
  [[ "$stderr" == *"no issues in 1 file" ]]
}

@test "binary garbage is a finding, not a crash" {
  head -c 4096 /dev/urandom > junk.rscene
  run "$V" junk.rscene
  [ "$status" -eq 1 ]
}

@test "--help and --version" {
  run "$V" --help
  [ "$status" -eq 0 ]
  [[ "$output" == *"--format"* ]]
  run "$V" --version
  [ "$status" -eq 0 ]
  [[ "$output" == "rscene-validate "* ]]
  run "$V" --bogus
  [ "$status" -eq 2 ]
}

@test "the real corpus has no errors" {
  needs_shared corpus
  run --separate-stderr "$V" "$CORPUS"/*.rscene
  [ "$status" -eq 0 ]
  [[ "$stderr" == "no issues in "* ]]
}

@test "the man page lists every code" {
  for code in $("$V" --list-checks | cut -d' ' -f1); do
    grep -q "$code" "$BATS_TEST_DIRNAME/../man/rscene-validate.1" || { echo "missing $code"; return 1; }
  done
}

@test "a mistyped option gets a suggestion; --max-issues wants a whole number" {
  run -2 --separate-stderr "$V" --formt json x.rscene
  [ "${stderr_lines[0]}" = "rscene-validate: error: unknown option '--formt'; did you mean '--format'?" ]
  run -2 --separate-stderr "$V" --max-issues 0 x.rscene
  [ "${stderr_lines[0]}" = "rscene-validate: error: --max-issues: expected a whole number >= 1, not '0'" ]
}

@test "a byte order mark is named, and a trailing backslash gets the no-continuation hint" {
  printf '\xef\xbb\xbfraisim_engine_scene 1\n' > bom.rscene
  run -1 --separate-stderr "$V" bom.rscene
  [ "${lines[0]}" = "bom.rscene:1:1: error: file starts with a UTF-8 byte order mark (EF BB BF); remove it [RS1001]" ]
  printf 'raisim_engine_scene 1\ngravity 0 0 \\\n  -9.81\n' > cont.rscene
  run -1 --separate-stderr "$V" cont.rscene
  [ "${lines[0]}" = "cont.rscene:2:13: error: expected a number, found '\\' [RS2001]" ]
  [ "${lines[3]}" = '  hint: line 2 ends with `\`, but the format has no continuation lines: write each record on one line' ]
}

@test "references to nothing get did-you-mean: mat_bx, folder_prop" {
  {
    echo 'raisim_engine_scene 1'
    echo 'material mat_box 1 0.42 0.05 1 0 0.6 0 0 0 0 false - - - - - - id=mat_box'
    echo 'group /World/Props id=folder_props'
    echo 'object /World/Props/A box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 1 default mat_bx false true false - dynamic true 1 18446744073709551615 parentGroupId=folder_prop'
  } > refs.rscene
  run -1 --separate-stderr "$V" refs.rscene
  [ "${lines[0]}" = "refs.rscene:4:65: error: material 'mat_bx' does not exist [RS3008]" ]
  [ "${lines[3]}" = '  hint: did you mean `mat_box`?' ]
  [ "${lines[4]}" = "refs.rscene:4:141: error: parent 'folder_prop' does not exist [RS3006]" ]
  [ "${lines[7]}" = '  hint: did you mean `folder_props`?' ]
}

@test "a directory operand validates every scene under it; hidden folders are skipped" {
  mkdir -p scenes/sub scenes/.cache empty
  cp "$DATA/validate_clean.rscene" scenes/a.rscene
  cp "$DATA/validate_clean.rscene" scenes/sub/b.rscene
  cp "$DATA/validate_errors.rscene" scenes/.cache/bad.rscene
  run -0 --separate-stderr "$V" scenes/
  [ "$stderr" = "no issues in 2 files" ]
  cp "$DATA/validate_errors.rscene" scenes/sub/c.rscene
  run -1 --separate-stderr "$V" --format json scenes
  [[ "$output" == *'"scenes/sub/c.rscene"'* ]]
  run -0 --separate-stderr "$V" empty
  [ "${stderr_lines[0]}" = "rscene-validate: warning: no .rscene files under 'empty'" ]
}

@test "--check-files: a device, a FIFO or a folder is not an asset file" {
  mkfifo pipe
  mkdir folder
  for target in /dev/zero pipe folder; do
    printf 'raisim_engine_scene 1\nobject /World/M mesh 0 0 1 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false %s dynamic true 1 18446744073709551615\n' "$target" > m.rscene
    run -1 timeout 10 "$V" --check-files m.rscene
    [[ $output == *"RS5001"* ]]
  done
  run -1 "$V" --check-files m.rscene
  [ "${lines[0]}" = "m.rscene:2:90: error: file 'folder' is a directory, not a file (resolved to 'folder') [RS5001]" ]
}

# Issue 10's reproducers, scaled to run in seconds: each under a time and a
# virtual-memory bound the earlier validator broke (every finding was kept,
# ~560 B each, and each one's source line was found by scanning from the
# top).  A million findings held took ~570 MB; streamed, ~130 MB.
repeated_time_steps() {
  { printf 'raisim_engine_scene 2\n'; yes 'time_step 0.0025' | head -n "$1"; } > ts.rscene
}

@test "a million repeated time_steps with --max-issues: bounded memory, exact counts" {
  repeated_time_steps 1000000
  run -0 --separate-stderr bash -c "ulimit -v 350000; timeout 60 '$V' --max-issues 10 ts.rscene"
  [ "${#lines[@]}" -eq 40 ]
  [ "${lines[0]}" = "ts.rscene:3:1: warning: repeated time_step replaces the one on line 2 [RS3016]" ]
  [ "${lines[36]}" = "ts.rscene:12:1: warning: repeated time_step replaces the one on line 11 [RS3016]" ]
  [ "$stderr" = "999999 warnings in 1 file (999989 not shown)" ]
}

@test "a million repeated time_steps, every one shown: streamed, bounded memory, linear time" {
  repeated_time_steps 1000000
  run -0 --separate-stderr bash -c "ulimit -v 350000; timeout 60 '$V' ts.rscene | tail -n 4"
  [ "${lines[0]}" = "ts.rscene:1000001:1: warning: repeated time_step replaces the one on line 1000000 [RS3016]" ]
  [ "${lines[1]}" = "  time_step 0.0025" ]
  [ "$stderr" = "999999 warnings in 1 file" ]
  run -1 --separate-stderr bash -c "ulimit -v 350000; timeout 60 '$V' --strict --only RS3016 --max-issues 1 ts.rscene"
  [ "$stderr" = "999999 warnings in 1 file (999998 not shown)" ]
}

@test "yes x | head -100000 after a header: each line's finding printed in linear time" {
  { printf 'raisim_engine_scene 2\n'; yes x | head -n 100000; } > x.rscene
  # Quadratic line lookup took 23 s here; linear takes well under a second.
  run -0 --separate-stderr bash -c "ulimit -v 350000; timeout 10 '$V' x.rscene"
  [ "${#lines[@]}" -eq 400000 ]
  [ "${lines[0]}" = "x.rscene:2:1: warning: unknown record tag 'x' [RS3001]" ]
  [ "${lines[399996]}" = "x.rscene:100001:1: warning: unknown record tag 'x' [RS3001]" ]
  [ "${lines[399997]}" = "  x" ]
  [ "$stderr" = "100000 warnings in 1 file" ]
}

@test "JSON and SARIF with --max-issues on a million findings: valid, capped, counted" {
  repeated_time_steps 1000000
  run -0 --separate-stderr bash -c "ulimit -v 350000; timeout 60 '$V' --format json --max-issues 3 ts.rscene"
  echo "$output" > out.json
  run -0 jq -r '"\(.files[0].findings | length) \(.files[0].warnings) \(.counts.warnings) \(.truncated) \(.files[0].findings[2].line)"' out.json
  [ "$output" = "3 999999 999999 true 5" ]
  run -0 --separate-stderr bash -c "ulimit -v 350000; timeout 60 '$V' --format sarif --max-issues 3 ts.rscene"
  echo "$output" > out.sarif
  run -0 jq -r '.runs[0].results | "\(length) \(.[0].ruleId) \(.[0].locations[0].physicalLocation.region.startLine)"' out.sarif
  [ "$output" = "3 RS3016 3" ]
}

@test "JSON and SARIF stream: a million findings without --max-issues in bounded memory" {
  repeated_time_steps 1000000
  # Written as found: ~560 B per finding held would need 560 MB here.
  bash -c "ulimit -v 350000; timeout 120 '$V' --format json ts.rscene" > out.json 2> err.txt
  run -0 jq -r '"\(.files[0].findings | length) \(.files[0].warnings) \(.counts.warnings) \(.truncated) \(.files[0].findings[999998].line)"' out.json
  [ "$output" = "999999 999999 999999 false 1000001" ]
  bash -c "ulimit -v 350000; timeout 120 '$V' --format sarif ts.rscene" > out.sarif 2> err.txt
  run -0 jq -r '.runs[0].results | "\(length) \(.[999998].locations[0].physicalLocation.region.startLine)"' out.sarif
  [ "$output" = "999999 1000001" ]
}

@test "JSON and SARIF: a file without findings and several files are valid documents" {
  printf 'raisim_engine_scene 2\ntime_step 0.001\n' > clean.rscene
  printf 'raisim_engine_scene 2\nx\n' > dirty.rscene
  run -0 --separate-stderr "$V" --format json clean.rscene
  jq -e '.files == [{"file": "clean.rscene", "findings": [], "errors": 0, "warnings": 0}] and .truncated == false' <<<"$output"
  run -0 --separate-stderr "$V" --format json clean.rscene dirty.rscene clean.rscene
  jq -e '(.files | length) == 3 and .files[1].findings[0].code == "RS3001" and .counts.warnings == 1' <<<"$output"
  run -0 --separate-stderr "$V" --format sarif clean.rscene
  jq -e '.runs[0].results == [] and .version == "2.1.0"' <<<"$output"
}

# Robots (issue 11): records read against their URDF model.
ROBOTS="$DATA/robots/check"

walker_scene() {  # $1: extra records and keys, appended; URDF by absolute path
  printf '%s\n' "raisim_engine_scene 1" \
    "articulated_resource walker_res Walker $ROBOTS/walker.urdf" \
    "object /World/Box box 1 0 0.5 1 0 0 0 0.2 0.2 0.2 0.5 1 1 default - false true false - dynamic true 1 18446744073709551615 id=box" \
    "$@"
}

@test "robots: the walker fixture has no robot findings; its model is read with and without --check-files" {
  run -0 "$V" "$ROBOTS/walker.rscene"
  [[ "$output" != *RS704* ]]
  run -0 "$V" --check-files "$ROBOTS/walker.rscene"
  [[ "$output" != *RS70[34]* ]]
}

@test "robots: lengths, jointOrder, quaternions, IK frames and knobs, sensor links, wire bodies, with did-you-mean" {
  walker_scene \
    "articulated /World/W walker_res 0 0 0.5 1 0 0 0 true true id=walker jointOrder=R_HIP;R_KNEE;L_HIP;L_KNE generalizedCoordinate=0,0,0.5,2,0,0,0,0.3,-0.6,0.3,-0.6 generalizedVelocity=0,0,0" \
    "articulated_ik /World/W L_FOTO 0,0,0 maxIterations=0" \
    "sensor /World/W/Cam rgb walker 0 0 0 1 0 0 0 parentLink=L_THIG" \
    "wire /World/Leash stiff walker box 1.5 localIndexA=5" > bad.rscene
  run -1 --separate-stderr "$V" --only RS7041,RS7042,RS7043,RS7044,RS7045,RS7046,RS7048 bad.rscene
  [[ "$output" == *"bad.rscene:4:"*": error: jointOrder names 'L_KNE', which is not a joint of the model [RS7042]"* ]]
  [[ "$output" == *"hint: did you mean 'L_KNEE'?"* ]]
  [[ "$output" == *"error: jointOrder leaves out movable joints: L_KNEE [RS7042]"* ]]
  [[ "$output" == *"warning: quaternion at entries 3..6 has length 2.000000; it is normalised [RS7043]"* ]]
  [[ "$output" == *"error: generalizedVelocity has 3 numbers; the model 'walker' has 10 [RS7041]"* ]]
  [[ "$output" == *"bad.rscene:5:"*": error: maxIterations is 0; it must be 1 to 10000 [RS7048]"* ]]
  [[ "$output" == *"bad.rscene:5:25: error: frame 'L_FOTO' is no joint or link of the model 'walker' [RS7044]"* ]]
  [[ "$output" == *"hint: did you mean 'L_FOOT'?"* ]]
  [[ "$output" == *"bad.rscene:6:"*": error: parentLink 'L_THIG' is no link of the model 'walker' of '/World/W' [RS7045]"* ]]
  [[ "$output" == *"hint: did you mean 'L_THIGH'?"* ]]
  [[ "$output" == *"bad.rscene:7:"*": error: localIndexA is 5; '/World/W' has bodies 0 to 4 [RS7046]"* ]]
  [ "$stderr" = "7 errors, 1 warning in 1 file" ]
}

@test "robots: a coordinate of the wrong length is RS7040; the model's lengths make RS4007 quiet for spherical joints" {
  walker_scene "articulated /World/W walker_res 0 0 0.5 1 0 0 0 true true generalizedCoordinate=0,0,0.5,1,0,0,0,0.3,-0.6" > short.rscene
  run -1 "$V" short.rscene
  [[ "$output" == *"error: generalizedCoordinate has 9 numbers; the model 'walker' has 11 (7 for the floating base, then the joints) [RS7040]"* ]]
  # Two spherical joints, fixed base: 8 coordinates, 6 velocities.
  printf '%s\n' "raisim_engine_scene 1" "articulated_resource c C chain.urdf" \
    "articulated /World/C c 0 0 0 1 0 0 0 true true generalizedCoordinate=1,0,0,0,1,0,0,0 generalizedVelocity=0,0,0,0,0,0" > chain.rscene
  run -0 "$V" chain.rscene
  [[ "$output" != *RS4007* ]]
}

@test "robots: an unreadable model is --check-files' finding, naming the URDF and its line; text, JSON and SARIF" {
  walker_scene "articulated /World/B walker_res 0 0 0 1 0 0 0 true true sourcePath=$ROBOTS/broken.urdf generalizedCoordinate=1,2,3" > broken.rscene
  run -0 "$V" broken.rscene      # without --check-files: not a word, no model checks
  [[ "$output" != *RS70[34]* ]]
  run -1 "$V" --check-files broken.rscene
  [[ "${lines[0]}" == "$ROBOTS/broken.urdf:"[0-9]*": error: "*"[RS7030]" ]]
  run -1 "$V" --check-files --format json broken.rscene
  echo "$output" > out.json
  run -0 jq -r '.files[0].findings[] | select(.code == "RS7030") | "\(.file) \(.line > 0)"' out.json
  [ "$output" = "$ROBOTS/broken.urdf true" ]
  run -1 "$V" --check-files --format sarif broken.rscene
  echo "$output" > out.sarif
  run -0 jq -r '.runs[0].results[] | select(.ruleId == "RS7030") | .locations[0].physicalLocation.artifactLocation.uri' out.sarif
  [ "$output" = "$ROBOTS/broken.urdf" ]
}

@test "robots: --check-files names a missing collision mesh inside the URDF (RS5001) and a missing visual one (RS7031)" {
  printf '%s\n' "raisim_engine_scene 1" "articulated_resource m M $ROBOTS/missing_mesh.urdf" > mesh.rscene
  run -1 "$V" --check-files mesh.rscene
  [[ "$output" == *"$ROBOTS/missing_mesh.urdf:4:"*"error: collision mesh 'meshes/missing.stl' not found"*"[RS5001]"* ]]
  [[ "$output" == *"$ROBOTS/missing_mesh.urdf:5:"*"warning: "*"[RS7031]"* ]]
  run -0 "$V" mesh.rscene
}

@test "robots: the corpus ANYmal C in its standing pose, with its meshes, passes --check-files" {
  needs_shared corpus/robots/anymal_c
  anymal() {
    printf '%s\n' "raisim_engine_scene 1" \
      "articulated_resource anymal_res ANYmal $CORPUS/robots/anymal_c/urdf/anymal.urdf" \
      "articulated /World/Anymal anymal_res 0 0 0.54 1 0 0 0 true true generalizedCoordinate=$1" \
      "articulated_ik /World/Anymal LF_FOOT 0.3,0.2,0 enabled=false" > anymal.rscene
  }
  anymal 0,0,0.54,1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8
  run -0 "$V" --check-files --strict anymal.rscene
  anymal 0,0,0.54,1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4
  run -1 "$V" anymal.rscene
  [[ "$output" == *"generalizedCoordinate has 18 numbers; the model 'anymal' has 19"*"[RS7040]"* ]]
}

@test "robots: the corpus chain (three spherical joints): 12 coordinates and 9 velocities pass" {
  needs_shared corpus/robots/chain
  chain() {
    printf '%s\n' "raisim_engine_scene 1" "articulated_resource c C $CORPUS/robots/chain/robot.urdf" \
      "articulated /World/C c 0 0 0 1 0 0 0 true true generalizedCoordinate=1,0,0,0,1,0,0,0,1,0,0,0 generalizedVelocity=$1" > chain.rscene
  }
  chain 0,0,0,0,0,0,0,0,0
  run -0 "$V" --check-files --strict chain.rscene
  chain 0,0,0,0,0,0,0,0,0,0,0,0
  run -1 "$V" chain.rscene
  [[ "$output" == *"generalizedVelocity has 12 numbers; the model '2DrobotArm' has 9 [RS7041]"* ]]
}

@test "robots: a URDF whose <?xml?> follows a comment is read with a warning (RS7054); a mismatched end tag is named at its line" {
  { echo '<!-- exported by an old tool -->'; cat "$ROBOTS/walker.urdf"; } > commented.urdf
  grep -q '^<?xml' "$ROBOTS/walker.urdf" || sed -i '1a <?xml version="1.0" ?>' commented.urdf
  walker_scene "articulated /World/C walker_res 0 0 0 1 0 0 0 true true sourcePath=$PWD/commented.urdf" > c.rscene
  run -0 "$V" --check-files c.rscene
  [[ "$output" == *"commented.urdf:2: warning: the <?xml ...?> declaration comes after a comment"*"[RS7054]"* ]]
  [[ "$output" != *RS7030* ]]
  printf '<robot name="r">\n  <link name="a">\n\n  </lnk>\n</robot>\n' > bad.urdf
  walker_scene "articulated /World/D walker_res 0 0 0 1 0 0 0 true true sourcePath=$PWD/bad.urdf" > d.rscene
  run -1 "$V" --check-files d.rscene
  [[ "$output" == *"bad.urdf:4: error: robot file is not well-formed XML (mismatched element: </lnk> does not close <link> (opened at line 2))"*"[RS7030]"* ]]
}
