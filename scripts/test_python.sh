#!/usr/bin/env bash
# The Python package's tests: a fresh venv, `pip install ./python` (maturin
# and numpy from PyPI, the extension built in release), pytest.
#   scripts/test_python.sh [VENV_DIR]   (default: a new temporary directory)
# On a Debian machine whose python3 lacks the venv module it installs
# python3-venv (needs root).
set -euo pipefail
cd "$(dirname "$0")/.."
venv="${1:-$(mktemp -d)/venv}"
if ! python3 -m venv "$venv" 2>/dev/null; then
    echo "python3 has no venv module: installing python3-venv" >&2
    apt-get update -qq && apt-get install -y -qq python3-venv python3-pip
    python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet ./python pytest
# From the repository's root with the venv's pytest, so that `import
# shearcut` finds the installed package, not the source folder python/shearcut.
"$venv/bin/pytest" -q -p no:cacheprovider python/tests
