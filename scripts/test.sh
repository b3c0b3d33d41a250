#!/usr/bin/env bash
# Builds (if needed) and runs the whole test suite: unit tests, device tests on the Vulkan
# device (lavapipe where there is no GPU) with validation on, CLI and golden-image tests.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -f build/build.ninja ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build >&2
cd build
ctest --output-on-failure -j2 "$@"
