#!/usr/bin/env bash
# Step cost of two pdamp binaries on the vibrated bed of bench/dem_vs_liggghts.sh (scene B's
# softened grains, N grains in an L × L × 0.1225 m box, L = 36.75 mm × sqrt(N/250), U = 4.5 mm
# at 15 Hz, dt = 2.8e-6 s, 1.1 × 20e6/N driven steps), one thread pinned to CPU $CPU, the two
# binaries alternated REPEAT times. Prints the median particle-steps per CPU-second of each
# and their ratio (B/A): issue 41's "the new walls and body forces cost no more than ~10 % of
# a step when unused" is B = the build with them, A = the build before.
#
#   bench/step_cost_ab.sh OLD_PDAMP NEW_PDAMP            # N=4000, REPEAT=5
#   N=250 REPEAT=9 bench/step_cost_ab.sh old new
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
A=$1; B=$2
N=${N:-4000}; REPEAT=${REPEAT:-5}; CPU=${CPU:-0}
WORK=${WORK:-${TMPDIR:-/tmp}/pdamp_step_ab}
mkdir -p "$WORK"
L=$(awk -v n="$N" 'BEGIN {printf "%.6g", 0.03675 * sqrt(n / 250)}')
S=$(awk -v n="$N" 'BEGIN {s = int(20000000 / n); if (s < 400) s = 400; if (s > 20000) s = 20000; print s}')
DUR=$(awk -v s="$S" 'BEGIN {printf "%.6g", (s + (s / 10 > 200 ? s / 10 : 200)) * 2.8e-6}')
run() {
    local bin=$1 out=$WORK/run
    RAYON_NUM_THREADS=1 taskset -c "$CPU" "$bin" simulate "$ROOT/bench/dem_bed.toml" --out "$out" \
        --no-analysis -q --set damper.count="$N" --set "damper.box=[$L,$L,0.1225]" \
        --set run.duration="$DUR" --set damper.settle_time=0.25 >/dev/null
    sed -n 's/.*"particle_steps_per_cpu_s": *\([0-9.eE+-]*\).*/\1/p' "$out/summary.json" | head -1
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
: >"$WORK/a"; : >"$WORK/b"
for _ in $(seq "$REPEAT"); do
    run "$A" >>"$WORK/a"
    run "$B" >>"$WORK/b"
done
ma=$(median <"$WORK/a"); mb=$(median <"$WORK/b")
echo "# N=$N, L=$L m, $DUR s driven, $REPEAT runs each, CPU $CPU, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "A $A: $(tr '\n' ' ' <"$WORK/a")-> median $ma particle-steps/CPU-s"
echo "B $B: $(tr '\n' ' ' <"$WORK/b")-> median $mb particle-steps/CPU-s"
awk -v a="$ma" -v b="$mb" 'BEGIN {printf "B/A = %.3f (cost per step B/A = %.3f)\n", b / a, a / b}'
