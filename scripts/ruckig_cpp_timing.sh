#!/usr/bin/env bash
# Times ruckig's own C++ (no Python binding) on the cases that
# `OTG_ORACLE_ARGS="--timing-only" scripts/otg_vs_ruckig.sh CASES SEED` times through the binding
# (20 000 per DoF count for 1, 3, 6 and 7 DoFs, same seed, same order).
#
# An oracle measurement only: outside shearcut's crates and CI. ruckig is never part of our code;
# its 0.19.4 sources are downloaded from PyPI (pip download, the sdist) into a temporary
# directory, compiled there with g++ -O3 -march=native together with
# scripts/ruckig_cpp_timing.cpp (no cmake needed: the library is a handful of .cpp files), run,
# and deleted.
# Usage: scripts/ruckig_cpp_timing.sh [SEED=42]   (needs g++ with C++20, python3, network)
set -euo pipefail
cd "$(dirname "$0")/.."
SEED="${1:-42}"
VENV=.venv-otg
if [ ! -x "$VENV/bin/python" ]; then
    python3 -m venv "$VENV"
fi
"$VENV/bin/pip" install --quiet ruckig==0.19.4 numpy
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
"$VENV/bin/python" scripts/otg_vs_ruckig.py --seed "$SEED" --dump-timing-cases "$TMP/cases.txt" none
(cd "$TMP" && "$OLDPWD/$VENV/bin/pip" download --quiet --no-binary ruckig --no-deps ruckig==0.19.4 -d . \
    && tar xzf ruckig-0.19.4.tar.gz)
SRC="$TMP/ruckig-0.19.4"
g++ -std=c++20 -O3 -march=native -DNDEBUG -I"$SRC/include" \
    "$SRC"/src/ruckig/brake.cpp "$SRC"/src/ruckig/position_*.cpp "$SRC"/src/ruckig/velocity_*.cpp \
    scripts/ruckig_cpp_timing.cpp -o "$TMP/ruckig_cpp_timing"
"$TMP/ruckig_cpp_timing" "$TMP/cases.txt"
