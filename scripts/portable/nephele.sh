#!/usr/bin/env bash
# Runs the archive of bundle.sh on a machine without nephele's libraries: nephele.sh ARGS...
# (as `nephele ARGS...`). The archive is read from beside this script, or from
# $NEPHELE_PORTABLE (a path), and unpacked once into /tmp/nephele-portable. NVIDIA's driver is
# found under /usr/local/nvidia as well as where the system keeps it; Debian packages of the
# Vulkan loader and glvnd (libvulkan1, libegl1, libglvnd0, libgl1, libglx0) in a folder
# $NEPHELE_PORTABLE_DEBS are unpacked into / first, for a machine that has the driver but
# no loader. VK_LOADER_DEBUG=error,driver says why a driver is not found.
set -eu
PATH=$PATH:/sbin:/usr/sbin
here=$(cd "$(dirname "$0")" && pwd)
archive=${NEPHELE_PORTABLE:-$here/nephele-portable.tar.xz}
b=/tmp/nephele-portable
if [ ! -x "$b/nephele" ]; then
  [ -f "$archive" ] || { echo "nephele.sh: no archive at $archive (bundle.sh makes it)" >&2; exit 2; }
  tar -xJf "$archive" -C /tmp
fi
if [ -n "${NEPHELE_PORTABLE_DEBS:-}" ]; then
  for deb in "$NEPHELE_PORTABLE_DEBS"/*.deb; do dpkg -x "$deb" /; done
  ldconfig
fi
path=$b/lib
for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do [ -d "$d" ] && path=$path:$d; done
for icd in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json; do
  [ -f "$icd" ] && export VK_DRIVER_FILES=${VK_DRIVER_FILES:-$icd}
done
egl=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f "$egl" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-$egl}
# The bundled C++ runtime only where the machine's is older than the one nephele was built with.
need=$(strings "$b/cxx/libstdc++.so.6" | grep -o '^GLIBCXX_3\.4\.[0-9]*$' | sort -t. -k3 -n | tail -1)
have=$(ldconfig -p | awk '/libstdc\+\+\.so\.6 .*x86-64/ {print $NF; exit}')
if [ -z "$have" ] || ! grep -qa "$need" "$have"; then path=$path:$b/cxx; fi
export LD_LIBRARY_PATH=$path${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
if "$b/nephele" --version > /dev/null 2>&1; then exec "$b/nephele" "$@"; fi
# An older C library than the build machine's: the bundled one, through its own loader.
exec "$b/glibc/ld-linux-x86-64.so.2" --library-path "$b/glibc:$path:$b/cxx" "$b/nephele" "$@"
