#!/usr/bin/env bash
# Checks the style the repository's files set: Python by .flake8 (add-on, tests, tools, chart
# scripts), C++ by .clang-format (the core, the binding, the lab). `--fix` reformats the C++.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
flake8 && echo "Python style: flake8 clean"
mapfile -t cpp < <(git ls-files '*.h' '*.cpp')
if [[ "${1:-}" == "--fix" ]]; then
  clang-format -i "${cpp[@]}"
fi
clang-format --dry-run --Werror "${cpp[@]}" && echo "C++ style: clang-format clean (${#cpp[@]} files)"
