#!/usr/bin/env bash
# The native core's libraries for a wheel build outside Debian (cibuildwheel's CIBW_BEFORE_ALL in
# .github/workflows/release.yml): vcpkg into $VCPKG_ROOT (default /opt/vcpkg, or ./vcpkg on
# Windows and macOS), shared libraries, the release configuration only.
#
#   tools/packaging/ci/install_deps_vcpkg.sh TRIPLET      x64-linux-dynamic, x64-windows,
#                                                         arm64-osx-dynamic, x64-osx-dynamic
# Binary caching: VCPKG_BINARY_SOURCES (the workflow points it at a cached folder).
set -euo pipefail
triplet=$1
root=${VCPKG_ROOT:-/opt/vcpkg}
if command -v dnf >/dev/null; then  # the manylinux_2_28 image (AlmaLinux 8)
  dnf install -y -q git curl zip unzip tar pkgconfig perl-IPC-Cmd ninja-build
fi
[ -x "$root/vcpkg" ] || [ -x "$root/vcpkg.exe" ] || {
  git clone --depth 1 https://github.com/microsoft/vcpkg "$root"
  "$root/bootstrap-vcpkg.sh" -disableMetrics 2>/dev/null || "$root/bootstrap-vcpkg.bat" -disableMetrics
}
cat > "$root/triplets/community/$triplet-release.cmake" <<EOF
include("\${CMAKE_CURRENT_LIST_DIR}/../$triplet.cmake" OPTIONAL)
include("\${CMAKE_CURRENT_LIST_DIR}/$triplet.cmake" OPTIONAL)
set(VCPKG_BUILD_TYPE release)
EOF
"$root/vcpkg" install --triplet "$triplet-release" glm tbb embree "openvdb" pybind11
