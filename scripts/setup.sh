#!/usr/bin/env bash
# Installs what is missing (Debian 12 packages), then configures and builds
# dotvision into ./build. Safe to run again: it only installs absent packages
# and rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config git
  libopencv-dev libeigen3-dev libceres-dev
  libprotobuf-dev protobuf-compiler
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libspdlog-dev
  libnanoflann-dev libcpp-httplib-dev zlib1g-dev
  ocl-icd-opencl-dev opencl-headers pocl-opencl-icd clinfo
  libgtest-dev libgmock-dev libbenchmark-dev
  libaravis-dev libusb-1.0-0-dev aravis-tools ffmpeg  # aravis-0.8.pc requires libusb-1.0.pc
  chromium chromium-driver  # the console's browser tests (headless)
  clang-14 libclang-rt-14-dev  # the fuzz targets and the sanitizer build (scripts/fuzz.sh, sanitize.sh)
  jq curl  # scripts/soak.sh
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs=$(nproc)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"
