#!/usr/bin/env bash
# Installs the Debian packages adjoin needs to build, test and benchmark, if they are missing.
# Idempotent: packages already present are left alone, and the script says what it installs.
# Usage: scripts/setup.sh [--with-mpi]
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libfftw3-dev libgsl-dev
  catch2 libtomlplusplus-dev libcli11-dev nlohmann-json3-dev
  libnlopt-cxx-dev   # NLopt: the optimisers of `adjoin optimize`
  libbenchmark-dev gnuplot-nox python3
  # The Python package (python/, `import adjoin`) and its tests; matplotlib for adjoin.plot.
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib
)
for arg in "$@"; do
  case "$arg" in
    --with-mpi) packages+=(libopenmpi-dev openmpi-bin) ;;
    --with-fuzz) packages+=(clang libclang-rt-14-dev) ;;
    *) echo "error: scripts/setup.sh: unknown option '$arg' (expected --with-mpi or --with-fuzz)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
