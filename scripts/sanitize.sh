#!/usr/bin/env bash
# Builds nephele with AddressSanitizer + UndefinedBehaviorSanitizer (NEPHELE_SANITIZE=ON) in
# build-sanitize/ and runs the unit tests, the CLI tests (which run the instrumented `nephele`
# binary) and the fuzz tests under them. Any sanitizer report fails its test, and the script
# exits non-zero. Extra arguments go to ctest (e.g. -R CliTest to narrow the run further).
# Runtime settings and the reasons for them: scripts/sanitizers/env.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

# -O1 -g: quick enough to build and run, frames still line up; NDEBUG stays off.
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DNEPHELE_SANITIZE=ON >/dev/null
# Only what the run below uses: the instrumented CLI and the unit/CLI/fuzz test binary.
cmake --build build-sanitize -j2 --target nephele_cli nephele_tests >&2

# The unit tests' suites (every suite in tests/unit/), the CLI tests and the fuzz tests.
# Parametrised tests are named Prefix/Suite.Test/N, hence (^|/).
unit_suites=$(grep -ho 'TEST\(_F\|_P\)\?( *[A-Za-z0-9_]*' tests/unit/*.cpp | sed 's/.*( *//' |
  sort -u | paste -sd'|')
regex="(^|/)(Fuzz[A-Za-z0-9_]*|CliTest|CliInputs|InputLimitsCli|${unit_suites})\\."

source scripts/sanitizers/env.sh
source scripts/ctest_costs.sh
seed_costs build-sanitize
cd build-sanitize
ctest --output-on-failure --no-tests=error -j2 -LE slow -R "$regex" "$@"
