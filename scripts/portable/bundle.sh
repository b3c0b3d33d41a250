#!/usr/bin/env bash
# Packs build/nephele with every shared library it needs (but the C library's own) into one
# archive that runs on another x86-64 Linux with a Vulkan driver and no nephele dependencies:
# a GPU machine to trace references or time the bench on (docs/validation.md). Usage:
#   scripts/portable/bundle.sh OUT_DIR      -> OUT_DIR/nephele-portable.tar.xz (about 49 MB)
# There, scripts/portable/nephele.sh runs it. ICU's 30 MB data library is replaced by a stub
# (nephele converts no text through ICU; GDAL links it), the C++ runtime kept apart (used only
# where the machine's is older), and the C library kept for a machine whose is older.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:?usage: bundle.sh OUT_DIR}
[ -x build/nephele ] || { echo "bundle.sh: build/nephele is missing: build it first" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
b=$work/nephele-portable
mkdir -p "$b/lib" "$b/cxx" "$b/glibc"
cp build/nephele "$b/" && strip "$b/nephele"
ldd build/nephele | awk '$3 ~ /^\// {print $3}' | while read -r lib; do
  case $(basename "$lib") in
    libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|libresolv.so.*) ;;
    libstdc++.so.*|libgcc_s.so.*) cp -L "$lib" "$b/cxx/" ;;
    *) cp -L "$lib" "$b/lib/" ;;
  esac
done
strip --strip-unneeded "$b"/lib/*.so* "$b"/cxx/*.so* 2>/dev/null || true
for lib in libc.so.6 libm.so.6 libresolv.so.2 ld-linux-x86-64.so.2; do
  cp -L "/lib/x86_64-linux-gnu/$lib" "$b/glibc/"
done
if [ -f "$b/lib/libicudata.so.72" ]; then
  printf 'const unsigned char icudt72_dat[64] = {0};\n' > "$work/icu.c"
  cc -shared -fPIC -Wl,-soname,libicudata.so.72 -o "$b/lib/libicudata.so.72" "$work/icu.c"
fi
mkdir -p "$out"
tar -C "$work" -cf - nephele-portable | xz -9 -T0 > "$out/nephele-portable.tar.xz"
ls -l "$out/nephele-portable.tar.xz"
