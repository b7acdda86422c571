#!/bin/sh
# Installs exactly the Debian 12 packages the project needs (build, tests,
# docs, fuzzing, benchmarks).  Idempotent: when every package is already
# present it only runs dpkg-query and exits, so `make test` stays fast.
set -eu

PACKAGES="
build-essential cmake pkg-config git
libcli11-dev nlohmann-json3-dev libeigen3-dev
libgtest-dev libgmock-dev bats
clang libclang-rt-14-dev libfuzzer-14-dev
mandoc jq time parallel libdtl-dev python3-yaml
chromium
slurm-wlm munge
libbullet-dev libassimp-dev libtinyxml2-dev libmujoco-dev
libpng-dev libjpeg-dev libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri
python3-dev python3-pybind11 python3-numpy python3-pytest
"

# One dpkg-query for all packages; a package it does not list as
# installed is missing.
# shellcheck disable=SC2086
installed=$(dpkg-query -W -f='${Package} ${Status}\n' $PACKAGES 2>/dev/null |
  awk '$NF == "installed" && $(NF-1) == "ok" { print $1 }' || true)
missing=""
for p in $PACKAGES; do
  case " $(echo $installed) " in
    *" $p "*) ;;
    *) missing="$missing $p" ;;
  esac
done

[ -z "$missing" ] && exit 0

if [ "$(id -u)" -ne 0 ]; then
  SUDO=sudo
else
  SUDO=
fi
echo "install-deps: installing:$missing" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
