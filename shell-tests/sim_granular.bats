#!/usr/bin/env bats
# End-to-end tests of granular records in rscene-sim: the solver's
# warnings and refusals at the record's key (RS7082, RS7086-RS7089), the
# written-back explicit positions that reload as they were left, the
# trajectory's points, --report's granular figures, determinism.

load helpers
SIM="$BIN/rscene-sim"

# A 3 x 3 x 2 box fill of RaiSim's example material over the ground;
# EXTRA appends keys (tests change a written key with sed).
bed() {
  cat <<EOF2
raisim_engine_scene 1
time_step 0.001
object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
granular /World/Sand sand 0 0 0.1 1 0 0 0 1 1 1 boxMin=0,0,0 boxMax=0.13,0.13,0.09 radius=0.02 spacing=0.043 density=1600 normalStiffness=5e4 normalDamping=25 tangentialStiffness=2.5e4 tangentialDamping=6 friction=0.8 rollingFriction=0.02 normalContactModel=linear substeps=2${EXTRA:-}
EOF2
}

setup() {
  needs_tools rscene-sim
  cd "$BATS_TEST_TMPDIR"
}

@test "RaiSim's example material runs in its own substeps, with no warning" {
  bed > bed.rscene
  run -0 --separate-stderr "$SIM" --steps 20 -o out.rscene bed.rscene
  [ "$stderr" = "" ]
}

@test "the schema's stiff defaults raise the substeps with a warning at substeps (RS7086)" {
  printf 'raisim_engine_scene 1\ngranular /World/Sand sand 0 0 0 1 0 0 0 1 1 1 boxMin=0,0,0 boxMax=0.05,0.05,0.05\n' > stiff.rscene
  run -0 --separate-stderr "$SIM" --steps 2 -o /dev/null stiff.rscene
  [[ $stderr =~ ^stiff\.rscene:2:[0-9]+:\ warning:\ granular\ /World/Sand:\ substeps\ raised\ from\ 2\ to\ [0-9]+\ for\ stability ]]
  [[ $stderr == *"[RS7086]"* ]]
  # Writing the substeps it asked for silences it.
  n=$(sed -n 's/.*raised from 2 to \([0-9]*\) .*/\1/p' <<< "$stderr" | head -1)
  printf 'raisim_engine_scene 1\ngranular /World/Sand sand 0 0 0 1 0 0 0 1 1 1 boxMin=0,0,0 boxMax=0.05,0.05,0.05 substeps=%s\n' "$n" > ok.rscene
  run -0 --separate-stderr "$SIM" --steps 2 -o /dev/null ok.rscene
  [ "$stderr" = "" ]
}

@test "hostile values are refused at their key with exit 2 (RS7088, RS7087, RS7089, RS7082)" {
  bed | sed 's/density=1600/density=-1600/' > neg.rscene
  run -2 --separate-stderr "$SIM" --steps 1 neg.rscene
  [[ ${stderr_lines[0]} =~ ^neg\.rscene:4:[0-9]+:\ error:\ granular\ /World/Sand:\ density\ must\ be\ positive.*\[RS7088\]$ ]]
  bed | sed 's/=linear/=mindlin/' > model.rscene
  run -2 --separate-stderr "$SIM" --steps 1 model.rscene
  [[ $stderr == *"error: unknown contact_model 'mindlin' [RS2006]"* ]]  # validate's words
  bed | sed 's/normalStiffness=5e4/normalStiffness=1e12/' > stiff.rscene
  run -2 --separate-stderr "$SIM" --steps 1 stiff.rscene
  [[ $stderr == *"stability needs more than 1000 substeps per world step"*"[RS7087]"* ]]
  EXTRA=" positions=0,0,0;0,0,0 radii=0.02" bed > one.rscene
  run -2 --separate-stderr "$SIM" --steps 1 one.rscene
  [[ $stderr == *"particles 0 and 1 overlap by more than half their radii"*"[RS7089]"* ]]
  EXTRA=" maxParticles=5" bed > many.rscene
  run -2 --separate-stderr "$SIM" --steps 1 many.rscene
  [[ $stderr == *"has 18 particles, more than its maxParticles 5 [RS7082]"* ]]
}

@test "the written-back bed has explicit positions and radii that reload as they were left" {
  bed > bed.rscene
  run -0 "$SIM" --steps 200 -o out.rscene bed.rscene
  grep -q '^granular /World/Sand .* positions=[^ ]*;.* radii=0.02,0.02,' out.rscene
  # Zero steps from the written-back bed write the same positions back.
  run -0 "$SIM" --steps 0 -o again.rscene out.rscene
  cmp out.rscene again.rscene
}

@test "runs are byte-identical, trajectory included" {
  EXTRA=" cohesionStiffness=20 cohesionMaxDistance=0.002 velocity=0.3,0,0" bed | sed 's/=linear/=hertz/' > bed.rscene
  for k in 1 2; do
    run -0 "$SIM" --steps 300 --trajectory "t$k.jsonl" --every 100 -o "out$k.rscene" bed.rscene
  done
  cmp out1.rscene out2.rscene
  cmp t1.jsonl t2.jsonl
  # One line per sample for the bed, with its 18 grains.
  [ "$(grep -c '"path":"/World/Sand"' t1.jsonl)" -eq 4 ]
  [ "$(grep '"path":"/World/Sand"' t1.jsonl | tail -1 | jq '.points | length')" -eq 18 ]
}

@test "--report has the granular solver's figures" {
  bed > bed.rscene
  run -0 --separate-stderr "$SIM" --steps 10 --report -o /dev/null bed.rscene
  # 18 grains x 2 substeps x 10 steps.
  [ "$(jq '.granular.particleSubsteps' <<< "$stderr")" -eq 360 ]
  [ "$(jq '.granular.substepsPerStep' <<< "$stderr")" -eq 2 ]
  jq -e '.granular | (.neighbourTime >= 0 and .contactTime >= 0 and .surfaceTime >= 0 and .integrationTime >= 0 and .neighbourBuilds >= 1)' <<< "$stderr"
}
