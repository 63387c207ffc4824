#!/usr/bin/env bash
# Checks the Python style the repository's .flake8 sets (add-on, tests, tools, chart scripts).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
flake8 && echo "Python style: flake8 clean"
