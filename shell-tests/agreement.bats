#!/usr/bin/env bats
# Agreement catalogue (issue 23, item 7): tests/agreement/gen-catalogue.py
# writes a valid base scene for every family of records (world, obj, gran,
# def, sens, vis, wire, terrain, cam, urdf, mjcf) and one-defect variants of
# it, with the tiny meshes and robot files they name; tests/agreement/run.sh
# runs each through rscene-validate --check-files, rscene-sim --steps 2 and
# rscene-render 32x24 and compares exit statuses and the first error's code
# and file:line:col.  A base scene must pass all three; a defect must be
# refused by all three with the same first error (or, for a code the
# registry gives to fewer tools, by exactly those tools).  One test a
# family; a failure lists the disagreeing scenes.  The catalogue is
# generated and run once, in setup_file (about two minutes on two cores).

load helpers
AGREE="$ROOT/tests/agreement"

setup_file() {
  export CAT="$BATS_FILE_TMPDIR/catalogue" TABLE="$BATS_FILE_TMPDIR/table.txt"
  for t in rscene-validate rscene-sim rscene-render; do
    [ -x "$BIN/$t" ] || { echo "agreement.bats: $BIN/$t is not built" > "$BATS_FILE_TMPDIR/setup-error"; return 0; }
  done
  /usr/bin/python3 "$AGREE/gen-catalogue.py" "$CAT" > /dev/null 2> "$BATS_FILE_TMPDIR/setup-error" || return 0
  (cd "$CAT" && find . | LC_ALL=C sort) > "$BATS_FILE_TMPDIR/before.lst"
  local rc=0
  RSCENE_BIN="$BIN" JOBS="${JOBS:-2}" bash "$AGREE/run.sh" "$CAT" > "$TABLE" 2> "$BATS_FILE_TMPDIR/run.err" || rc=$?
  echo "$rc" > "$BATS_FILE_TMPDIR/run.rc"
  (cd "$CAT" && find . | LC_ALL=C sort) > "$BATS_FILE_TMPDIR/after.lst"
  rm -f "$BATS_FILE_TMPDIR/setup-error"
}

setup() {
  if [ -s "$BATS_FILE_TMPDIR/setup-error" ]; then
    cat "$BATS_FILE_TMPDIR/setup-error" >&2
    return 1
  fi
  CAT="$BATS_FILE_TMPDIR/catalogue" TABLE="$BATS_FILE_TMPDIR/table.txt"
}

# Every scene of family $1 is listed, and none disagrees.
family_agrees() {
  local n bad
  n=$(grep -c "^$1_" "$CAT/manifest.tsv")
  [ "$n" -ge 2 ] || { echo "family $1 has $n scenes" >&2; return 1; }
  [ "$(grep -c "^$1_" "$TABLE")" -eq "$n" ] || { echo "family $1: $n scenes in the manifest, $(grep -c "^$1_" "$TABLE") in the table" >&2; return 1; }
  grep -q "^$1_ok .* AGREE$" "$TABLE" || { echo "family $1: the base scene is refused:" >&2; grep "^$1_ok " "$TABLE" >&2; return 1; }
  bad=$(grep "^$1_" "$TABLE" | grep ' DISAGREE' || true)
  if [ -n "$bad" ]; then
    echo "family $1: $(wc -l <<< "$bad") of $n scenes disagree:" >&2
    echo "$bad" >&2
    return 1
  fi
}

@test "catalogue: at least 150 one-defect scenes, every family with its control, each scene judged" {
  [ "$(grep -v '^#' "$CAT/manifest.tsv" | awk -F'\t' '$2 != 0' | wc -l)" -ge 150 ]
  for f in world obj gran def sens vis wire terrain cam urdf mjcf; do
    [ -f "$CAT/${f}_ok.rscene" ]
    grep -q "^${f}_ok	0	" "$CAT/manifest.tsv"
  done
  # Every scene has a line in the table, and run.sh's exit status says
  # whether any disagrees.
  [ "$(grep -vc '^#' "$CAT/manifest.tsv")" -eq "$(wc -l < "$TABLE")" ]
  if grep -q ' DISAGREE' "$TABLE"; then [ "$(cat "$BATS_FILE_TMPDIR/run.rc")" = 1 ]
  else [ "$(cat "$BATS_FILE_TMPDIR/run.rc")" = 0 ]; fi
}

@test "catalogue: the runner writes nothing into the catalogue folder" {
  run diff "$BATS_FILE_TMPDIR/before.lst" "$BATS_FILE_TMPDIR/after.lst"
  [ "$status" -eq 0 ] || { echo "$output" >&2; false; }
}

@test "agreement: world (header, time_step, gravity, solver, lexical errors)" { family_agrees world; }
@test "agreement: obj (objects, meshes, compounds and their children)" { family_agrees obj; }
@test "agreement: gran (granular)" { family_agrees gran; }
@test "agreement: def (deformable, with their OBJ meshes)" { family_agrees def; }
@test "agreement: sens (rgb, depth, lidar and imu sensors)" { family_agrees sens; }
@test "agreement: vis (light, projected_decal, local_fog, reflection_probe, irradiance_volume, point_cloud, instanced_visual)" { family_agrees vis; }
@test "agreement: wire" { family_agrees wire; }
@test "agreement: terrain (terrain_region, splat and foliage layers)" { family_agrees terrain; }
@test "agreement: cam (camera records and outputPath)" { family_agrees cam; }
@test "agreement: urdf (articulated robots from a URDF, IK targets)" { family_agrees urdf; }
@test "agreement: mjcf (articulated robots from an MJCF file)" { family_agrees mjcf; }
