# shellcheck shell=bash
# A fresh build has no timings for ctest to start the longest tests first (with -j2 the
# suite would end on a 3-minute test started last): seed them from tests/ctest_costs.txt
# (seconds on 2 cores, stop 64); ctest keeps them up to date as it runs.
seed_costs() {
  local costs="$1/Testing/Temporary/CTestCostData.txt"
  [ -f "$costs" ] || { mkdir -p "$(dirname "$costs")" && cp tests/ctest_costs.txt "$costs"; }
}
