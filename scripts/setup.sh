#!/usr/bin/env bash
# Installs nephele's dependencies (Debian 12 packages), builds it, and renders the default
# scene. Prints the path of the rendered image. Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  cmake ninja-build g++ pkg-config dpkg-dev
  libvulkan-dev mesa-vulkan-drivers glslc vulkan-validationlayers
  libspirv-cross-c-shared-dev libglm-dev libstb-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libopenexr-dev
  libgtest-dev libnova-dev libgdal-dev
  libopenvdb-dev libnanovdb-dev libtinyobjloader-dev libboost-iostreams-dev
  libglfw3-dev libimgui-dev xvfb xauth python3-matplotlib
  pybind11-dev python3-dev python3-numpy python3-pytest libeccodes-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "nephele: installing ${missing[*]}" >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build >&2

mkdir -p out
./build/nephele render --preset default --output out/default.png --stats-json out/default.json
