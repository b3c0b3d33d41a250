#!/usr/bin/env bash
# Package.DebianPackage: cpack makes nephele's .deb from this build; it holds the tools, both
# libraries, the headers, the CMake package and the pkg-config file under /usr, and depends on
# the Debian packages of the libraries its binaries use and on a Vulkan driver. (Installing it
# with apt needs root and changes the machine: done by hand, docs/embedding.md.)
# Arguments: the build folder, the work folder (emptied).
set -euo pipefail
build=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
(cd "$build" && cpack -G DEB -B "$work" > "$work/cpack.log" 2>&1) || { tail -n 40 "$work/cpack.log"; exit 1; }
deb=$(ls "$work"/nephele_*_amd64.deb)
dpkg-deb -c "$deb" | awk '{print $6}' > "$work/contents.txt"
for path in ./usr/bin/nephele ./usr/lib/libnephele.a ./usr/lib/libnephele.so.0.1 \
            ./usr/include/nephele/renderer.h ./usr/lib/cmake/nephele/nepheleConfig.cmake \
            ./usr/lib/cmake/nephele/nepheleTargets.cmake ./usr/lib/pkgconfig/nephele.pc; do
  grep -qx "$path" "$work/contents.txt" || { echo "the package lacks $path"; exit 1; }
done
grep -q '^./usr/lib/python3/dist-packages/nephele\..*\.so$' "$work/contents.txt" ||
  { echo "the package lacks the Python module"; exit 1; }
depends=$(dpkg-deb -f "$deb" Depends)
for package in libvulkan1 libgdal32 libopenvdb10.0 libopenexr-3-1-30 mesa-vulkan-drivers; do
  grep -q "$package" <<< "$depends" || { echo "the package does not depend on $package: $depends"; exit 1; }
done
echo "$deb: $(wc -l < "$work/contents.txt") paths; Depends: $depends"
