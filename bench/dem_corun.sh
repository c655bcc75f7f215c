#!/usr/bin/env bash
# Do the two cores share what the DEM step needs? (issue 12, the 2-thread speed-up.) The
# vibrated 4000-grain bed (advancing-front bed settled 0.2 s, then 0.03 s = 10 714 driven
# steps), per round: one thread alone on CPU 0; two independent one-thread runs at once on
# CPU 0 and CPU 1; one run on 2 threads. If the co-run copies keep the speed of the lone run,
# the cores do not share what the step is limited by, and a 2-thread run could reach ~2x.
# Prints particle_steps_per_s (M/s, wall) of each run. Not part of `cargo test`.
#
# usage: bench/dem_corun.sh          env: ROUNDS (3), PDAMP (binary), WORK (scratch dir)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PDAMP=${PDAMP:-$ROOT/target/release/pdamp}
ROUNDS=${ROUNDS:-3}
WORK=${WORK:-${TMPDIR:-/tmp}/pdamp_corun}
[ -x "$PDAMP" ] || (cd "$ROOT" && cargo build --release)
ARGS=("$ROOT/bench/dem_bed.toml" --no-analysis --set damper.count=4000
    --set 'damper.box=[0.147,0.147,0.1225]' --set damper.settle_time=0.2
    --set 'damper.packing="advancing-front"' --set run.duration=0.03)
rate() { sed -n 's/.*"particle_steps_per_s": *\([0-9.eE+-]*\).*/\1/p' "$1/summary.json" | head -1 |
    awk '{printf "%.2f", $1 / 1e6}'; }
mkdir -p "$WORK"
for r in $(seq "$ROUNDS"); do
    rm -rf "${WORK:?}"/*
    RAYON_NUM_THREADS=1 taskset -c 0 "$PDAMP" simulate "${ARGS[@]}" --out "$WORK/alone" >/dev/null 2>&1
    RAYON_NUM_THREADS=1 taskset -c 0 "$PDAMP" simulate "${ARGS[@]}" --out "$WORK/co0" >/dev/null 2>&1 &
    p0=$!
    RAYON_NUM_THREADS=1 taskset -c 1 "$PDAMP" simulate "${ARGS[@]}" --out "$WORK/co1" >/dev/null 2>&1 &
    p1=$!
    # each copy's own status, so that a failed run stops the script (a bare `wait` returns 0)
    wait "$p0"
    wait "$p1"
    RAYON_NUM_THREADS=2 "$PDAMP" simulate "${ARGS[@]}" --out "$WORK/two" >/dev/null 2>&1
    echo "round $r $(date -u +%H:%M) load $(cut -d' ' -f1 /proc/loadavg): alone $(rate "$WORK/alone")" \
        " co-run CPU0 $(rate "$WORK/co0") CPU1 $(rate "$WORK/co1")  2 threads $(rate "$WORK/two")"
done
