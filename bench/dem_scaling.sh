#!/usr/bin/env bash
# Cost per grain against N for the DEM bed at rest (issue 12, "cost flat in N"): pdamp alone,
# one thread pinned to $CPU, bench/dem_bed.toml with the box footprint widened as sqrt(N/250)
# (bed height kept), the bed packed by the advancing front and settled for at most
# SETTLE s (0.05), then NWARM + NRUN driven steps at amplitude 0 (NRUN = clamp(2e7/N, 400,
# 20 000), NWARM = max(200, NRUN/10), as bench/dem_vs_liggghts.sh). Prints
# particle_steps_per_cpu_s (stepping thread) and particle_steps_per_s per N, medians of REPEAT,
# and the contacts per grain of the last run (grain-grain pairs in contact, wall contacts;
# summary.json's mean over the steady window's samples, here the last step only): a step's
# cost grows with them, so they say how much of the cost in N is the
# bed's physics (see bench/README.md, "What the step's cost in N is made of").
#
# usage: nice -n 5 bench/dem_scaling.sh            # N = 250 4000 16000 64000, REPEAT=1
# env:   NS, REPEAT (1), SETTLE (0.05), CPU (0), PDAMP (binary), WORK, EXTRA (more --set args)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
NS=${NS:-"250 4000 16000 64000"}
REPEAT=${REPEAT:-1}
SETTLE=${SETTLE:-0.05}
CPU=${CPU:-0}
PDAMP=${PDAMP:-$ROOT/target/release/pdamp}
WORK=${WORK:-${TMPDIR:-/tmp}/pdamp_scaling}
EXTRA=${EXTRA:-}
DT=2.8e-6
mkdir -p "$WORK"
median() { sort -g | awk '{a[NR]=$1} END {if (NR == 0) print "nan"; else if (NR % 2) print a[(NR+1)/2]; else print (a[NR/2]+a[NR/2+1])/2}'; }
echo "# pdamp DEM bed at rest, 1 thread, $(date -u '+%Y-%m-%d %H:%M UTC'), load $(cut -d' ' -f1-3 /proc/loadavg), $PDAMP"
echo "| N | box L (mm) | driven steps | M particle-steps / CPU s | M particle-steps / s (wall) | pair contacts / grain | wall contacts / grain | ns / grain-step (CPU) | load before |"
echo "|---|---|---|---|---|---|---|---|---|"
for n in $NS; do
    L=$(awk -v n="$n" 'BEGIN {printf "%.6g", 0.03675 * sqrt(n / 250)}')
    r=$(awk -v n="$n" 'BEGIN {s = int(2e7 / n); if (s < 400) s = 400; if (s > 20000) s = 20000; print s}')
    w=$(( r / 10 > 200 ? r / 10 : 200 ))
    dur=$(awk -v s=$((r + w)) -v dt=$DT 'BEGIN {printf "%.6g", s * dt}')
    : >"$WORK/c.txt"; : >"$WORK/w.txt"
    load=$(cut -d' ' -f1 /proc/loadavg)
    for k in $(seq "$REPEAT"); do
        out="$WORK/N${n}_$k"
        # shellcheck disable=SC2086
        RAYON_NUM_THREADS=1 taskset -c "$CPU" "$PDAMP" simulate "$ROOT/bench/dem_bed.toml" --out "$out" --no-analysis \
            --set damper.count="$n" --set "damper.box=[$L,$L,0.1225]" --set excitation.amplitude=0.0 \
            --set run.duration="$dur" --set damper.settle_time="$SETTLE" \
            --set 'damper.packing="advancing-front"' $EXTRA >"$out.log" 2>&1
        sed -n 's/.*"particle_steps_per_cpu_s": *\([0-9.eE+-]*\).*/\1/p' "$out/summary.json" | head -1 >>"$WORK/c.txt"
        sed -n 's/.*"particle_steps_per_s": *\([0-9.eE+-]*\).*/\1/p' "$out/summary.json" | head -1 >>"$WORK/w.txt"
    done
    c=$(median <"$WORK/c.txt"); wl=$(median <"$WORK/w.txt")
    pc=$(sed -n 's/.*"pair_contacts_per_grain": *\([0-9.eE+-]*\).*/\1/p' "$out/summary.json" | head -1)
    wc=$(sed -n 's/.*"wall_contacts_per_grain": *\([0-9.eE+-]*\).*/\1/p' "$out/summary.json" | head -1)
    awk -v n="$n" -v L="$L" -v s=$((r + w)) -v c="$c" -v wl="$wl" -v ld="$load" -v pc="${pc:-nan}" -v wc="${wc:-nan}" \
        'BEGIN {printf "| %d | %.2f | %d | %.2f | %.2f | %.3f | %.3f | %.1f | %s |\n", n, L * 1000, s, c / 1e6, wl / 1e6, pc, wc, 1e9 / c, ld}'
done
