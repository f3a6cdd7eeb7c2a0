#!/usr/bin/env bash
# Checks the install story end to end: `make install` into a fresh prefix, then the versioned soname, no libvulkan
# dependency, a C program built with exactly `pkg-config --cflags --libs dnsr`, a CMake consumer of
# find_package(dnsr) -> dnsr::dnsr (through Vulkan-Headers' package and through FindVulkan), and
# `make uninstall` leaving nothing behind. Run from anywhere: bash capi-tests/install/check.sh
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here=$root/capi-tests/install
cd "$root"

tmp=$(mktemp -d)
work=$(mktemp -d)
trap 'rm -rf "$tmp" "$work"' EXIT
fail() { echo "install check: FAILED: $*" >&2; exit 1; }

echo "== make install PREFIX=$tmp"
make --no-print-directory install PREFIX="$tmp"

version=$(sed -n '/^\[package\]/,/^\[/s/^version *= *"\([^"]*\)".*/\1/p' Cargo.toml)
major=${version%%.*}
minor=${version#*.}; minor=${minor%%.*}
if [[ $major == 0 ]]; then abi=0.$minor; else abi=$major; fi
soname=libdnsr.so.$abi

echo "== soname and dependencies"
[[ -f $tmp/lib/libdnsr.so.$version && ! -L $tmp/lib/libdnsr.so.$version ]] || fail "no libdnsr.so.$version"
[[ $(readlink "$tmp/lib/$soname") == "libdnsr.so.$version" ]] || fail "$soname does not link to libdnsr.so.$version"
[[ $(readlink "$tmp/lib/libdnsr.so") == "$soname" ]] || fail "libdnsr.so does not link to $soname"
[[ -f $tmp/lib/libdnsr.a ]] || fail "no libdnsr.a"
dynamic=$(readelf -d "$tmp/lib/libdnsr.so.$version")
echo "$dynamic" | grep -E 'SONAME|NEEDED'
grep SONAME <<<"$dynamic" | grep -qF "[$soname]" || fail "SONAME is not $soname"
if grep NEEDED <<<"$dynamic" | grep -q libvulkan; then fail "libdnsr.so has a NEEDED entry for libvulkan"; fi

echo "== pkg-config"
flags=$(PKG_CONFIG_PATH=$tmp/lib/pkgconfig pkg-config --cflags --libs dnsr)
echo "pkg-config --cflags --libs dnsr: $flags"
[[ $(PKG_CONFIG_PATH=$tmp/lib/pkgconfig pkg-config --modversion dnsr) == "$version" ]] || fail "dnsr.pc version"
[[ " $flags " != *" -lvulkan "* ]] || fail "pkg-config --libs pulls in the Vulkan loader"
# shellcheck disable=SC2086 # the flags are words
cc -std=c11 -Wall -Wextra -Werror -o "$work/consumer-pc" "$here/consumer/main.c" $flags
needed=$(readelf -d "$work/consumer-pc" | grep NEEDED)
grep -qF "[$soname]" <<<"$needed" || fail "consumer does not record $soname"
LD_LIBRARY_PATH=$tmp/lib "$work/consumer-pc"

echo "== FidelityFX integration: the installed include/dnsr-ffx headers and libdnsr alone"
ffx_flags=$(PKG_CONFIG_PATH=$tmp/lib/pkgconfig pkg-config --cflags --libs dnsr-ffx)
echo "pkg-config --cflags --libs dnsr-ffx: $ffx_flags"
[[ $ffx_flags == *"$tmp/include/dnsr-ffx"* ]] || fail "dnsr-ffx.pc does not add include/dnsr-ffx"
# shellcheck disable=SC2086 # the flags are words
cc -std=c11 -Wall -Wextra -Werror -o "$work/consumer-ffx" "$root/capi-tests/ffx_header_c11.c" $ffx_flags
LD_LIBRARY_PATH=$tmp/lib "$work/consumer-ffx"

echo "== shader sources: an installed entry file compiles as dnsr's own variant does"
glslc --target-env=vulkan1.1 -I"$tmp/share/dnsr/shaders" -DDNSR_OUTPUT_FORMAT=r16f \
    "$tmp/share/dnsr/shaders/tile_classification.comp" -o "$work/tile_classification_r16f.spv"
cmp "$work/tile_classification_r16f.spv" "$root/shaders/spv/tile_classification_r16f.spv" \
    || fail "the installed sources do not compile to the embedded tile_classification_r16f"

echo "== custom G-buffer example: the passes compiled from the installed sources with the engine's callbacks"
bash "$root/examples-c/custom_gbuffer/build_shaders.sh" "$tmp/share/dnsr/shaders" "$work/custom-spv"
# shellcheck disable=SC2086 # the flags are words
cc -std=c11 -Wall -Wextra -Werror -I"$root/capi-tests" -o "$work/custom_gbuffer" \
    "$root/examples-c/custom_gbuffer/custom_gbuffer.c" "$root/capi-tests/host.c" $flags -lvulkan -lm
LD_LIBRARY_PATH=$tmp/lib "$work/custom_gbuffer" "$work/custom-spv"

echo "== CMake (Vulkan::Headers from Vulkan-Headers' package)"
cmake -S "$here/consumer" -B "$work/cmake" -DCMAKE_PREFIX_PATH="$tmp" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_C_FLAGS="-Wall -Wextra -Werror" >"$work/cmake.log" || { cat "$work/cmake.log"; fail "cmake configure"; }
cmake --build "$work/cmake" >"$work/build.log" || { cat "$work/build.log"; fail "cmake build"; }
LD_LIBRARY_PATH=$tmp/lib "$work/cmake/consumer"
LD_LIBRARY_PATH=$tmp/lib "$work/cmake/consumer_ffx"

echo "== CMake (Vulkan headers from FindVulkan)"
cmake -S "$here/consumer" -B "$work/cmake-findvulkan" -DCMAKE_PREFIX_PATH="$tmp" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_DISABLE_FIND_PACKAGE_VulkanHeaders=TRUE >"$work/cmake.log" || { cat "$work/cmake.log"; fail "cmake configure (FindVulkan)"; }
cmake --build "$work/cmake-findvulkan" >"$work/build.log" || { cat "$work/build.log"; fail "cmake build (FindVulkan)"; }
LD_LIBRARY_PATH=$tmp/lib "$work/cmake-findvulkan/consumer"

for exe in "$work/cmake/consumer" "$work/cmake-findvulkan/consumer"; do
    needed=$(readelf -d "$exe" | grep NEEDED)
    grep -qF "[$soname]" <<<"$needed" || fail "$exe does not record $soname"
    if grep -q libvulkan <<<"$needed"; then fail "$exe links libvulkan"; fi
done

echo "== CMake version compatibility"
mkdir "$work/probe"
cat >"$work/probe/CMakeLists.txt" <<'CM'
cmake_minimum_required(VERSION 3.16)
project(probe C)
find_package(dnsr ${want} QUIET)
message(STATUS "found=${dnsr_FOUND}")
CM
probe() { # probe <requested version>: succeeds when find_package(dnsr <version>) finds the installed package
    rm -rf "$work/probe/build"
    local out
    out=$(cmake -S "$work/probe" -B "$work/probe/build" -DCMAKE_PREFIX_PATH="$tmp" -Dwant="$1")
    grep -qx -- '-- found=1' <<<"$out"
}
probe "$abi" || fail "find_package(dnsr $abi) failed"
probe "$version" || fail "find_package(dnsr $version) failed"
probe "$abi...$major.$((minor + 5))" || fail "find_package(dnsr $abi...$major.$((minor + 5))) failed"
if [[ $major == 0 ]]; then next=0.$((minor + 1)); else next=$((major + 1)); fi
! probe "$next" || fail "find_package(dnsr $next) accepted $version"
echo "find_package(dnsr $abi), ($version), ($abi...$major.$((minor + 5))) found; ($next) rejected"

echo "== relocated prefix (CMake package paths are relative to it)"
cp -a "$tmp" "$work/moved"
cmake -S "$here/consumer" -B "$work/cmake-moved" -DCMAKE_PREFIX_PATH="$work/moved" >"$work/cmake.log" \
    || { cat "$work/cmake.log"; fail "cmake configure (moved prefix)"; }
cmake --build "$work/cmake-moved" >"$work/build.log" || { cat "$work/build.log"; fail "cmake build (moved prefix)"; }
LD_LIBRARY_PATH=$work/moved/lib "$work/cmake-moved/consumer" >/dev/null
rm -rf "$work/moved"

echo "== make uninstall PREFIX=$tmp"
make --no-print-directory uninstall PREFIX="$tmp"
left=$(find "$tmp" -iname '*dnsr*')
[[ -z $left ]] || fail "left after uninstall: $left"

echo "install check: ok (pkg-config, CMake, soname $soname)"
