# Sanitizer runtime settings for scripts/sanitize.sh (sourced by it). Source it to reproduce
# a finding by hand:
#   source scripts/sanitizers/env.sh
#   build-sanitize/nephele render --preset default -o /tmp/x.png
#   build-sanitize/tests/nephele_tests --gtest_filter='CliTest.*'
_nephele_san_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

# Lavapipe is the one Vulkan driver: otherwise the loader also dlopens (and dlcloses) every
# other installed ICD (Intel, Radeon: no device here), which the preload below does not cover.
_nephele_icd=/usr/share/vulkan/icd.d/lvp_icd.$(uname -m).json
_nephele_lvp=$(sed -n 's/.*"library_path" *: *"\([^"]*\)".*/\1/p' "$_nephele_icd" 2>/dev/null || true)
if [ -z "$_nephele_lvp" ] || [ ! -f "$_nephele_lvp" ]; then
  echo "sanitize: lavapipe not found ($_nephele_icd; Debian: mesa-vulkan-drivers)" >&2
  return 1
fi
export VK_DRIVER_FILES="$_nephele_icd"
export VK_ICD_FILENAMES="$_nephele_icd"  # loaders before 1.3.207

# The loader dlclose()s lavapipe at vkDestroyInstance. What lavapipe keeps in its own globals
# (allocated once per process, never freed: two 56-byte callocs per process here) then has no
# pointer left to it, and LeakSanitizer reports it at exit as "Indirect leak ...
# (<unknown module>)": the module is unmapped, so no suppression can name it. Preloading
# lavapipe keeps it mapped for the process's life (the loader's dlopen/dlclose then only count
# references), so LSan finds those globals and reports nothing; a leak that lavapipe really
# makes would show with its frames, to be named in lsan.supp. The preload needs ASan's check
# that its runtime comes first in the initial library list off (verify_asan_link_order=0):
# lavapipe defines no malloc, so ASan's interceptors still win. Uninstrumented processes
# started from here (ctest, the shells popen runs) load lavapipe too, which only costs time.
export LD_PRELOAD="$_nephele_lvp${LD_PRELOAD:+:$LD_PRELOAD}"

# Any report ends the process with a non-zero status, so its test fails: in-process for the
# unit and fuzz tests, and through `nephele`'s exit status and output for the CLI tests.
# quarantine_size_mb=16: lavapipe allocates and frees large blocks with every dispatch, and the
# diffusion light's build (about 300 dispatches) held 13 GB in the default quarantine (a render
# at 32x32; two such CLI tests at once were killed for memory), 1.35 GB with 16 MB (3.7 GB with
# 64). Freed memory is still poisoned while it waits there.
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:verify_asan_link_order=0:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:strict_string_checks=1:quarantine_size_mb=16"
export LSAN_OPTIONS="suppressions=$_nephele_san_dir/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:report_error_type=1"
unset _nephele_san_dir _nephele_icd _nephele_lvp
