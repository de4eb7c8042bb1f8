#!/usr/bin/env bash
# Builds the Debian package with CPack from the build tree and inspects it with dpkg-deb: it must
# hold the binary, the shared library, the header, the CMake package, the pkg-config file, the
# man page and the bash completion, and depend (dpkg-shlibdeps) on the libraries the binaries
# link, each of them a package installed here.
#
#   deb_package.sh BUILD_DIR
set -euo pipefail
build="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# cpack's Depends come from dpkg-shlibdeps (dpkg-dev) and file(1); without them: skipped (77).
for tool in dpkg-deb dpkg-shlibdeps file; do
  command -v "$tool" > /dev/null || { echo "SKIPPED: $tool is not installed (dpkg-dev, file)"; exit 77; }
done

cpack --config "$build/CPackConfig.cmake" -G DEB -B "$work" > "$work/cpack.log" 2>&1 ||
  { cat "$work/cpack.log"; exit 1; }
deb="$(ls "$work"/quadrix_*.deb)"
echo "built $(basename "$deb") ($(stat -c %s "$deb") bytes)"
dpkg-deb -c "$deb" > "$work/contents"
lib=' \./usr/lib/([^ ]+/)?'
for pattern in ' \./usr/bin/quadrix$' "${lib}libquadrix\.so\.0\.[0-9.]+$" "${lib}libquadrix\.so\.0 -> " \
               "${lib}libquadrix\.so -> " ' \./usr/include/quadrix/quadrix\.h$' \
               "${lib}cmake/Quadrix/QuadrixConfig\.cmake$" \
               "${lib}cmake/Quadrix/QuadrixConfigVersion\.cmake$" \
               "${lib}cmake/Quadrix/QuadrixTargets\.cmake$" "${lib}pkgconfig/quadrix\.pc$" \
               ' \./usr/share/man/man1/quadrix\.1(\.gz)?$' \
               ' \./usr/share/bash-completion/completions/quadrix$' \
               ' \./usr/share/doc/quadrix/api\.md$' "${lib}quadrix/quadrix-cairo\.so$"; do
  grep -Eq -- "$pattern" "$work/contents" || { echo "missing in the package: $pattern"; exit 1; }
done
# The modules the build made (src/quadrix/util/module_loader.h) are all in the package.
for module in "$build"/quadrix-*.so; do
  grep -Eq -- "${lib}quadrix/$(basename "$module")$" "$work/contents" ||
    { echo "module missing in the package: $(basename "$module")"; exit 1; }
done
if grep -E -- '/usr/include/quadrix/.+/' "$work/contents"; then
  echo "internal headers are in the package"; exit 1
fi

dpkg-deb -I "$deb" > "$work/info"
cat "$work/info"
grep -q '^ Package: quadrix$' "$work/info"
grep -q '^ Architecture: ' "$work/info"
depends="$(sed -n 's/^ Depends: //p' "$work/info")"
[[ -n "$depends" ]] || { echo "no Depends"; exit 1; }
# The libraries the binaries need must be among the dependencies.
for lib in libc6 libstdc++6 libtbb zlib1g libfmt libcairo2; do
  grep -q "$lib" <<< "$depends" || { echo "Depends lacks $lib: $depends"; exit 1; }
done
# Every dependency is a package installed here, so `apt-get install ./quadrix_*.deb` has them.
IFS=',' read -ra deps <<< "$depends"
for d in "${deps[@]}"; do
  name="$(sed -E 's/^ *([^ (|]+).*/\1/' <<< "$d")"
  dpkg-query -W -f='${Status}\n' "$name" 2> /dev/null | grep -q 'install ok installed' ||
    { echo "dependency $name is not an installed package"; exit 1; }
done
echo "deb package: ok"
