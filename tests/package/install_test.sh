#!/usr/bin/env bash
# Package.InstalledPackageBuildsAHost: installs this build into a temporary prefix, then builds
# the host in tests/package/consumer against it with find_package (the static library and the
# shared one) and with pkg-config (the shared one), and runs each (each renders a small image on the
# Vulkan device).
# Arguments: the build folder, the work folder (emptied), the cmake to use.
set -euo pipefail
build=$1 work=$2 cmake=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work"
# Each step's log is shown when it fails.
step() {
  local log=$1
  shift
  "$@" > "$log" 2>&1 || { tail -n 40 "$log"; echo "failed: $*"; exit 1; }
}
step "$work/install.log" "$cmake" --install "$build" --prefix "$work/prefix"
test -f "$work/prefix/include/nephele/renderer.h"
test -f "$work/prefix/lib/cmake/nephele/nepheleConfig.cmake"
step "$work/configure.log" "$cmake" -S "$here/consumer" -B "$work/cmake" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix"
step "$work/build.log" "$cmake" --build "$work/cmake"
"$work/cmake/consumer"
"$work/cmake/consumer_shared"
# (grep reads all of ldd's output: with -q it could stop early, ldd die of SIGPIPE and pipefail
# fail the test.)
ldd "$work/cmake/consumer_shared" | grep "$work/prefix/lib/libnephele.so" > /dev/null ||
  { echo "consumer_shared does not load the prefix's libnephele.so"; exit 1; }
export PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig"
flags=$(pkg-config --cflags --libs nephele)  # the shared library, as -lnephele finds it first
# shellcheck disable=SC2086
# The .pc file's rpath variable: the program finds the prefix's library with no LD_LIBRARY_PATH.
step "$work/pkgconfig.log" g++ -std=c++20 -O1 "$here/consumer/main.cpp" -o "$work/pkgconfig-consumer" $flags \
  "$(pkg-config --variable=rpath nephele)"
ldd "$work/pkgconfig-consumer" | grep "libnephele.so[^ ]* => $work/prefix/" > /dev/null ||
  { echo "pkgconfig-consumer does not load the prefix's libnephele.so"; exit 1; }
"$work/pkgconfig-consumer"
# The Python module, where it was built, from the prefix.
if compgen -G "$work/prefix/lib/python3/dist-packages/nephele.*.so" > /dev/null; then
  PYTHONPATH="$work/prefix/lib/python3/dist-packages" /usr/bin/python3 -c \
    'import nephele; a = nephele.render(width=8, height=6); assert a.shape == (6, 8, 4); print("python: rendered", a.shape)'
fi
