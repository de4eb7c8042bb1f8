#!/usr/bin/env bash
# Installs the build tree into a temporary prefix and builds a separate project against it, twice:
# with find_package(Quadrix REQUIRED) (CMake) and with pkg-config, then runs both consumers
# (tests/package/consumer/main.cpp renders a sphere and checks it analytically).
#
#   install_consumer.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build="$1"
src="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

cmake --install "$build" --prefix "$prefix" > "$work/install.log"
for f in bin/quadrix include/quadrix/quadrix.h share/man/man1/quadrix.1 \
         share/bash-completion/completions/quadrix; do
  [[ -f "$prefix/$f" ]] || { echo "not installed: $f"; exit 1; }
done
config="$(find "$prefix" -name QuadrixConfig.cmake)"
pc="$(find "$prefix" -name quadrix.pc)"
[[ -n "$config" && -n "$pc" ]] || { echo "no QuadrixConfig.cmake or quadrix.pc"; exit 1; }
# No internal header is installed: the API is the one header.
if find "$prefix/include" -name '*.h' | grep -v 'include/quadrix/quadrix.h$'; then
  echo "internal headers were installed"; exit 1
fi
"$prefix/bin/quadrix" --version
# The installed program loads its modules (Cairo, OpenEXR, MPI: src/quadrix/util/module_loader.h)
# from the prefix's <libdir>/quadrix, not from the build tree.
LD_DEBUG=files "$prefix/bin/quadrix" draw "$src/examples/tube.uq" -o "$work/tube.pdf" 2> "$work/ld.log"
grep -Eq "file=$prefix/[^ ]+/quadrix/quadrix-cairo\.so" "$work/ld.log" ||
  { grep -E 'file=.*quadrix-' "$work/ld.log"; echo "the installed quadrix did not load its own Cairo module"; exit 1; }
[[ "$(head -c 5 "$work/tube.pdf")" == "%PDF-" ]] || { echo "no PDF from the installed quadrix"; exit 1; }

# 1. CMake: find_package(Quadrix REQUIRED). The project's own flags must not reach the consumer.
cmake -S "$src/tests/package/consumer" -B "$work/cmake-build" -G Ninja \
      -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/cmake-build" -v > "$work/build.log"
if grep -E -- '-Wpedantic|-ffp-contract' "$work/build.log"; then
  echo "the consumer inherited the project's warning flags"; exit 1
fi
"$work/cmake-build/consumer" "$work/cmake.png"

# 2. pkg-config.
export PKG_CONFIG_PATH="$(dirname "$pc")"
pkg-config --exists quadrix
echo "pkg-config quadrix $(pkg-config --modversion quadrix): $(pkg-config --cflags --libs quadrix)"
# shellcheck disable=SC2046
c++ -std=c++20 "$src/tests/package/consumer/main.cpp" -o "$work/consumer-pc" \
    $(pkg-config --cflags --libs quadrix)
LD_LIBRARY_PATH="$(pkg-config --variable=libdir quadrix)" "$work/consumer-pc" "$work/pc.png"

for png in "$work/cmake.png" "$work/pc.png"; do
  [[ "$(head -c 4 "$png" | tail -c 3)" == "PNG" ]] || { echo "$png is not a PNG"; exit 1; }
done
cmp "$work/cmake.png" "$work/pc.png"
echo "install + find_package + pkg-config consumers: ok"
