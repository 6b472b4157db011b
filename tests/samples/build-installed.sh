#!/usr/bin/env bash
# Installs the ShadowPort build into a private prefix and builds samples/ against that package
# alone (find_package(ShadowPort)), as a user of the installed library would.
#   build-installed.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src="$1" build="$2"
prefix="$build/test-install"
rm -rf "$prefix"
cmake --install "$build" --prefix "$prefix" >/dev/null
# The package holds the public API only: no private header of the core or the techniques.
for private in backend.h context-internal.h validate.h cascade-fit.h csm-technique.h procedural.h; do
  if find "$prefix/include" -name "$private" | grep -q .; then
    echo "installed package contains the private header $private" >&2; exit 1
  fi
done
test -f "$prefix/lib/cmake/ShadowPort/ShadowPortConfig.cmake"
test -f "$prefix/share/shadowport/shaders-hlsl/common/depth-only.hlsl"
cmake -S "$src/samples" -B "$build/samples-installed" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$build/samples-installed" -j "$(nproc)"
