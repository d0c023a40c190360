#!/usr/bin/env bash
# Installs the Debian packages the project needs, only those that are missing.
set -euo pipefail
packages=(cmake g++ make ninja-build ccache libcgal-dev libgmp-dev libmpfr-dev libboost-dev
          catch2 libtbb-dev libbenchmark-dev qhull-bin libeigen3-dev
          clang libclang-rt-14-dev
          pybind11-dev python3-dev python3-numpy python3-scipy python3-pytest python3-mypy
          python3-setuptools python3-wheel python3-pip python3-venv
          libopenmpi-dev openmpi-bin)  # Open MPI: the optional dewall-mpi build (mpi/)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=""; [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}" >/dev/null
fi
