#!/usr/bin/env bash
# Builds (if needed) and runs the default test suite: unit tests, device tests on the Vulkan
# device (lavapipe where there is no GPU) with validation on, CLI and golden-image tests.
# --slow runs the tests labelled slow instead (those of `nephele bench` and `gallery --classic`,
# which run the benchmarks they check), --all both. Other arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ctest_costs.sh
labels=(-LE slow)
case "${1:-}" in
  --slow) labels=(-L slow); shift ;;
  --all) labels=(); shift ;;
esac
[ -f build/build.ninja ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build >&2
seed_costs build
cd build
ctest --output-on-failure -j2 "${labels[@]}" "$@"
