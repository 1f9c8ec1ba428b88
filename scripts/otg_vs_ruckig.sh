#!/usr/bin/env bash
# Compare shearcut's trajectory generator with ruckig 0.19.4 on random cases (not part of CI).
# Usage: scripts/otg_vs_ruckig.sh [CASES=100000] [SEED=42]
# Creates .venv-otg (gitignored), installs ruckig==0.19.4 and numpy from PyPI, builds the
# shearcut binary in release mode and runs scripts/otg_vs_ruckig.py.
set -euo pipefail
cd "$(dirname "$0")/.."
CASES="${1:-100000}"
SEED="${2:-42}"
VENV=.venv-otg
if [ ! -x "$VENV/bin/python" ]; then
    python3 -m venv "$VENV"
fi
"$VENV/bin/pip" install --quiet ruckig==0.19.4 numpy
cargo build --release --bin shearcut
BIN="${CARGO_TARGET_DIR:-target}/release/shearcut"
exec "$VENV/bin/python" scripts/otg_vs_ruckig.py --cases "$CASES" --seed "$SEED" \
    --workdir "${CARGO_TARGET_DIR:-target}/otg_vs_ruckig" ${OTG_ORACLE_ARGS:-} "$BIN"
