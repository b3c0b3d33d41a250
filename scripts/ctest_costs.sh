# shellcheck shell=bash
# A fresh build has no timings for ctest to start the longest tests first (with -j2 the
# suite would end on a 3-minute test started last): seed them from the chunks' estimates
# (written with the test binary from tests/ctest_costs.txt, cmake/gtest_chunks.cmake) and the
# other tests' costs; ctest keeps them up to date as it runs.
seed_costs() {
  local costs="$1/Testing/Temporary/CTestCostData.txt"
  [ -f "$costs" ] && return
  mkdir -p "$(dirname "$costs")"
  { grep -hv '^---$' "$1/tests/nephele_tests_chunk_costs.txt" tests/ctest_costs.txt 2>/dev/null
    echo '---'; } > "$costs"
}
