#!/usr/bin/env bash
# Runs the tests inside Blender (blender_tests/test_*.py, or those named) against an installed
# package, each with its own user config, scripts and extensions folders under WORK:
#
#   tools/packaging/run_package_tests.sh BLENDER PACKAGE.zip WORK [test_x.py ...]
#
# PACKAGE is an extension package (build/packages/bake_radiosity-*-PLATFORM.zip: installed as an
# extension, module bl_ext.user_default.bake_radiosity) or the legacy add-on zip. Prints PASS or
# FAIL and the time of each; exits 1 if any failed. Used here inside the chroots
# (tools/blender_chroot.sh SUITE run -- tools/packaging/run_package_tests.sh blender ...) and by
# .github/workflows/release.yml on each platform.
set -uo pipefail
[ $# -ge 3 ] || { sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
blender=$1 package=$2 work=$(realpath -m "$3"); shift 3
root=$(cd "$(dirname "$0")/../.." && pwd)
tests=("$@")
if [ ${#tests[@]} -eq 0 ]; then
  for test in "$root"/blender_tests/test_*.py; do tests+=("$(basename "$test")"); done
fi
failed=()
for test in "${tests[@]}"; do
  home=$work/${test%.py}
  rm -rf "$home"; mkdir -p "$home"
  start=$(date +%s)
  if BLENDER_USER_CONFIG=$home/config BLENDER_USER_SCRIPTS=$home/scripts BLENDER_USER_EXTENSIONS=$home/extensions \
     PYTHONPATH=$root/blender_tests "$blender" -b --factory-startup --python-exit-code 1 \
     --python "$root/blender_tests/$test" -- --addon-zip "$package" --work "$home/work" >"$home/log.txt" 2>&1; then
    echo "PASS $test ($(( $(date +%s) - start )) s)"
  else
    echo "FAIL $test ($(( $(date +%s) - start )) s): $home/log.txt"; tail -n 30 "$home/log.txt"; failed+=("$test")
  fi
done
[ ${#failed[@]} -eq 0 ] || { echo "failed: ${failed[*]}"; exit 1; }
