#!/usr/bin/env bash
# Regenerates every chart in docs/charts/ (CSV + PNG) from a build of the current tree:
#
#   tools/make_charts.sh            all charts
#   tools/make_charts.sh cycles_race   one chart by its step name
#
# Each chart is one step function below: it writes its CSV (and any text it prints) into
# docs/charts/ and plots the PNG with Debian's matplotlib (/usr/bin/python3). Add a chart by
# adding a step function and its name to STEPS. Uses build/ (or $BUILD_DIR), built first with the lab (lab/).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
charts=$root/docs/charts

ensure_plotting() {
  /usr/bin/python3 -c "import matplotlib" 2>/dev/null && return
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends python3-matplotlib
}

# Chart 2: whole bakes against Cycles, error against time (about 10 minutes on 2 busy cores).
step_bake_vs_cycles() {
  local work=$build/charts/bake_vs_cycles
  mkdir -p "$work"
  # A private Blender profile, so the run neither needs nor changes the user's own.
  BLENDER_USER_SCRIPTS=$work/scripts BLENDER_USER_CONFIG=$work/config \
    blender -b --factory-startup --python-exit-code 1 --python "$charts/bake_vs_cycles.py" -- \
      --addon-zip "$build/bake_radiosity.zip" --csv "$charts/bake_vs_cycles.csv" > "$work/log.txt"
  /usr/bin/python3 "$charts/plot_bake_vs_cycles.py" "$charts/bake_vs_cycles.csv" "$charts/bake_vs_cycles.png" \
    "$charts/bake_vs_cycles_ratios.txt"
}

# The race against Cycles: Cycles' sample ladder and the presets with the final gather on
# and off, against a deep Cycles truth cached outside git ($BAKE_RADIOSITY_TRUTH or build/truth; made
# when missing: 1,330 CPU s, 34 minutes on 2 busy cores), then error against element count. About
# 7 minutes on 2 busy cores once the truth is cached.
step_cycles_race() {
  local work=$build/charts/cycles_race
  mkdir -p "$work"
  BLENDER_USER_SCRIPTS=$work/scripts BLENDER_USER_CONFIG=$work/config \
    blender -b --factory-startup --python-exit-code 1 --python "$charts/cycles_race.py" -- \
      --addon-zip "$build/bake_radiosity.zip" --csv "$charts/cycles_race.csv" \
      --summary "$charts/cycles_race.txt" ${CYCLES_RACE_ARGS:-} > "$work/log.txt"
  /usr/bin/python3 "$charts/plot_cycles_race.py" "$charts/cycles_race.csv" "$charts/cycles_race.png" \
    "$charts/cycles_race_elements.png" "$charts/cycles_race_off_seams.txt"
  cat "$charts/cycles_race.txt" "$charts/cycles_race_off_seams.txt"
}

# Charts 1 and 3, the aliasing chart and the stability cases before and after (stability_before_after.png):
# native measurements (radiosity_charts, about 2 minutes).
step_native() {
  cmake --build "$build" -j "$(nproc)" --target radiosity_charts >/dev/null
  "$build/lab/radiosity_charts" "$charts"
  /usr/bin/python3 "$charts/plot_native.py" "$charts"
}

# The hierarchy (docs/hierarchy.md): accuracy per element against the uniform mesh on two scenes
# and the oracle's bound, then time and peak memory against triangle count, each bake in its own
# process, and a 1e6 triangle bake cancelled after 20 s. About 25 minutes on 2 cores (35 when they
# are busy), most of them the shadow room's uniform reference (24,580 elements at 5 cm, solved to
# 1e-6).
step_hierarchy() {
  cmake --build "$build" -j "$(nproc)" --target radiosity_hierarchy_charts >/dev/null
  "$build/lab/radiosity_hierarchy_charts" accuracy "$charts"
  "$build/lab/radiosity_hierarchy_charts" oracle "$charts"
  "$build/lab/radiosity_hierarchy_charts" scaling "$charts"
  /usr/bin/python3 "$charts/plot_hierarchy.py" "$charts"
}

STEPS=(native bake_vs_cycles cycles_race hierarchy)

RADIOSITY_BUILD_LAB=ON "$root/tools/build.sh"
ensure_plotting
steps=("$@")
[ $# -gt 0 ] || steps=("${STEPS[@]}")
for step in "${steps[@]}"; do
  echo "== chart: $step"
  "step_$step"
done
