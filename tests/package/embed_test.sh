#!/usr/bin/env bash
# Package.EmbedExample: installs this build into a temporary prefix, builds examples/embed
# against it with find_package, runs it under Xvfb with the validation layer, and checks its
# screenshots (embed_check.py): under an overcast deck, the deck in front of the mountain's top
# covers it, and the mountain's lower slopes hide the deck behind them.
# Arguments: the build folder, the work folder (emptied), the cmake to use, the source folder.
set -euo pipefail
build=$1 work=$2 cmake=$3 source=$4
rm -rf "$work"
mkdir -p "$work"
step() {
  local log=$1
  shift
  "$@" > "$log" 2>&1 || { tail -n 40 "$log"; echo "failed: $*"; exit 1; }
}
step "$work/install.log" "$cmake" --install "$build" --prefix "$work/prefix"
step "$work/configure.log" "$cmake" -S "$source/examples/embed" -B "$work/cmake" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix"
step "$work/build.log" "$cmake" --build "$work/cmake"
run() {
  xvfb-run -a -s "-screen 0 1024x768x24" "$work/cmake/nephele-embed" --size 320x180 --frames 3 --validation "$@"
}
run --preset overcast --screenshot "$work/with.png" --mask "$work/mask.png"
run --preset overcast --no-mountain --screenshot "$work/without.png"
/usr/bin/python3 "$source/tests/package/embed_check.py" "$work/with.png" "$work/without.png" "$work/mask.png"
