#!/usr/bin/env bash
# Builds every file an artist installs, into build/packages/:
#
#   tools/build_packages.sh [ENV...]      ENV: host (Python 3.11), trixie (3.13), sid (3.14); default all
#
#   bake_radiosity-VERSION-linux_x64.zip   the extension for Blender 4.2 and later: the add-on and
#                                          the native core as a wheel for each Python built
#   bake_radiosity-VERSION-legacy-python3.11-linux_x64.zip
#                                          the add-on zip for Blender 3.4 to 4.1 (_core inside,
#                                          for Debian 12's libraries and Python 3.11)
#
# Each wheel is built in its own environment (tools/packaging/build_core.sh: here, or in the chroot
# of tools/blender_chroot.sh), with the libraries _core needs bundled beside it under private
# sonames and symbol names (tools/packaging/privatize_libs.py, with the trixie chroot's patchelf).
# The extension is built and checked with Blender's own `--command extension build
# --split-platforms` and `extension validate`, in the trixie chroot's Blender 4.3.
# Intermediate files go to build-packages/. Needs root (chroot). JOBS=N build jobs.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
envs=("$@"); [ ${#envs[@]} -gt 0 ] || envs=(host trixie sid)
chroot_tool=tools/blender_chroot.sh
version=$(sed -n 's/^version = "\(.*\)"/\1/p' addon/bake_radiosity/blender_manifest.toml)
out=build/packages
source_dir=build-packages/extension/bake_radiosity
rm -rf "$out" "$source_dir"
mkdir -p "$out" "$source_dir/wheels"

in_env() { local env=$1; shift; if [ "$env" = host ]; then "$@"; else "$chroot_tool" "$env" run -- "$@"; fi; }
phase_start=$(date +%s)
phase() { local now; now=$(date +%s); echo "== $1: $(( now - phase_start )) s" >&2; phase_start=$now; }

# patchelf 0.18 (symbol renaming) is in trixie, not in Debian 12.
"$chroot_tool" trixie run -- sh -c 'command -v patchelf >/dev/null || { apt-get update -q && apt-get install -y -q patchelf; }' >&2

for env in "${envs[@]}"; do
  module=$(tools/packaging/build_core.sh "$env")
  bundle=build-packages/$env/bundle
  in_env "$env" python3 tools/packaging/collect_libs.py "${module#"$root"/}" "$bundle"
  "$chroot_tool" trixie run -- python3 tools/packaging/privatize_libs.py "$bundle"
  python3 tools/packaging/make_wheel.py "$bundle" "$version" "$source_dir/wheels"
  phase "wheel for $env"
done

# The add-on's sources, with the manifest naming the wheels and the platforms they are for.
mkdir -p "$source_dir/engine"
cp addon/bake_radiosity/*.py "$source_dir/"
cp addon/bake_radiosity/engine/*.py "$source_dir/engine/"
python3 tools/packaging/write_manifest.py addon/bake_radiosity/blender_manifest.toml "$source_dir"
"$chroot_tool" trixie run -- blender -b --factory-startup --command extension build \
  --source-dir "$source_dir" --output-dir "$out" --split-platforms
for package in "$out"/bake_radiosity-*.zip; do
  "$chroot_tool" trixie run -- blender -b --factory-startup --command extension validate "$package"
done
phase "extension packages"

# The legacy add-on zip, from the host build (Debian 12: Blender 3.4's Python 3.11).
if [[ " ${envs[*]} " == *" host "* ]]; then
  nice cmake --build build-packages/host -j "${JOBS:-$(nproc)}" --target addon_zip >&2
  cp build-packages/host/bake_radiosity.zip "$out/bake_radiosity-$version-legacy-python3.11-linux_x64.zip"
  phase "legacy add-on zip"
fi
ls -l "$out"
