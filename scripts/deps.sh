#!/usr/bin/env bash
# Installs the Debian packages fxraster needs, only those that are missing.
# Needs root (or sudo) when anything is missing; does nothing otherwise.
set -euo pipefail
PKGS=(cmake ninja-build g++ pkg-config verilator libsystemc-dev libglm-dev libgtest-dev libgmock-dev
      libbenchmark-dev yosys nextpnr-ice40 fpga-icestorm iverilog python3-matplotlib python3-numpy
      libstb-dev libtinyobjloader-dev nlohmann-json3-dev libcli11-dev libgmp-dev libosmesa6-dev
      glmark2-data zlib1g-dev
      clang-14 libclang-rt-14-dev)  # scripts/sanitize.sh: ASan + UBSan and libFuzzer (docs/testing.md)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#PKGS[@]} Debian packages present"
  exit 0
fi
echo "deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
