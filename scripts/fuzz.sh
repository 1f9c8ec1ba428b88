#!/usr/bin/env bash
# Fuzz shearcut's input surface: each cargo-fuzz target for a fixed time,
# one target at a time (the machine's cores are shared), then minimise its
# corpus. A crash is copied to fuzz/regressions/<target>/ (replayed on
# stable by tests/reliability_fuzz_regressions.rs) and the script fails.
#
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
#   default: 600 s each for scenario_toml mesh_file surrogate_file trajectory_cases wire_messages
# Needs: rustup nightly and `cargo install cargo-fuzz`.
set -euo pipefail

cd "$(dirname "$0")/../fuzz"
seconds="${1:-600}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(scenario_toml mesh_file surrogate_file trajectory_cases wire_messages)
fi

cargo +nightly fuzz build -O

status=0
for t in "${targets[@]}"; do
    echo "== $t: ${seconds} s"
    start=$(date +%s)
    if ! cargo +nightly fuzz run -O "$t" "corpus/$t" -- \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=16384 \
        -print_final_stats=1 2>&1 | tail -n 25; then
        status=1
    fi
    echo "== $t: ran $(( $(date +%s) - start )) s"
    if compgen -G "artifacts/$t/*" > /dev/null; then
        mkdir -p "regressions/$t"
        cp artifacts/"$t"/* "regressions/$t/"
        echo "== $t: crash inputs copied to fuzz/regressions/$t/"
        status=1
    fi
    cargo +nightly fuzz cmin -O "$t" "corpus/$t" > /dev/null 2>&1 || true
done
exit $status
