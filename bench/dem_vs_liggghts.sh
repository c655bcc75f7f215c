#!/usr/bin/env bash
# Side-by-side DEM throughput: LIGGGHTS 3.8.0 (Debian package `liggghts`) against
# `pdamp simulate` on the same bed (issue 12). Not part of `cargo test`.
#
# Bed: R = 3 mm steel grains softened to E = 2.03e8 Pa, e = 0.9, mu = 0.3, dt = 2.8e-6 s, a closed
# box L x L x 122.5 mm moved kinematically at 15 Hz / 4.5 mm ("vibrated") or held still
# ("rest"). N = 250 is the 36.75 mm box; larger N widen the footprint with sqrt(N/250) so that
# the bed height stays the same (N = 4000: 147 mm, 16 000: 294 mm, 64 000: 588 mm).
#
# LIGGGHTS: the decks of ../shared/golden/dem/ (in.settle deposits nside x nside x 10 grains,
# in.run shakes the box; "rest" is in.run with U = 0). N = 250 starts from the shipped
# settled_L36.75.restart; other beds are settled once (NSET steps) and the restart is kept in
# $WORK. Its figure: N x NRUN / "Loop time" of the timed run (after NWARM warm-up steps).
# pdamp: bench/dem_bed.toml with the same N and box; it settles its own bed (lattice drop, at
# most PDAMP_SETTLE s, stops at a mean speed < 1 mm/s) and drives NWARM + NRUN steps; its
# figure: `particle_steps_per_s` of summary.json (grains x driven steps / wall time).
# Both on one core (taskset -c $CPU, RAYON_NUM_THREADS=1), alternating, REPEAT rounds, medians.
# With THREADS2=1 pdamp also runs on 2 threads (no taskset) for the thread speed-up column
# (from 3000 grains a run steps on its own team of 2 threads; below, the one-thread path).
# TANGENTIAL selects pdamp's tangential law: "coulomb-viscous" (the thesis's history-free law,
# default) or "mindlin" (tangential spring with per-contact history, what the LIGGGHTS deck's
# "tangential history" computes).
#
# usage: bench/dem_vs_liggghts.sh                       # N = 250 4000 16000 64000, 3 rounds
#        NS="250 4000" REPEAT=3 THREADS2=1 bench/dem_vs_liggghts.sh
# env:   NS, STATES ("vibrated rest"), REPEAT (3), PSTEPS (particle-steps per timed run, 2e7:
#        NRUN = clamp(PSTEPS/N, 400, 20000)), NWARM (max(200, NRUN/10)), NSET (LIGGGHTS
#        settling steps, 90000), PDAMP_SETTLE (0.25 s), CPU (0), WORK (scratch dir), PDAMP
#        (binary; default target/release/pdamp, built if missing), THREADS2 (0),
#        SKIP_LIGGGHTS_ABOVE (N above which LIGGGHTS is not run: its settling of 16 000 and
#        64 000 grains takes hours on one core), PDAMP_PACKING (lattice; "advancing-front"
#        packs pdamp's bed on the floor directly, so that it settles in ~0.05 s at large N),
#        TANGENTIAL (coulomb-viscous | mindlin).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
GOLDEN=${GOLDEN:-$ROOT/../shared/golden/dem}
[ -d "$GOLDEN" ] || GOLDEN=/work/shared/golden/dem
NS=${NS:-"250 4000 16000 64000"}
STATES=${STATES:-"vibrated rest"}
REPEAT=${REPEAT:-3}
PSTEPS=${PSTEPS:-20000000}
NSET=${NSET:-90000}
PDAMP_SETTLE=${PDAMP_SETTLE:-0.25}
CPU=${CPU:-0}
THREADS2=${THREADS2:-0}
SKIP_LIGGGHTS_ABOVE=${SKIP_LIGGGHTS_ABOVE:-1000000000}
PDAMP_PACKING=${PDAMP_PACKING:-lattice}
TANGENTIAL=${TANGENTIAL:-coulomb-viscous}
WORK=${WORK:-${TMPDIR:-/tmp}/pdamp_vs_liggghts}
PDAMP=${PDAMP:-$ROOT/target/release/pdamp}
DT=2.8e-6
mkdir -p "$WORK"

banner() { printf '\n!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!\n!!! %s\n!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!\n\n' "$*" >&2; }

HAVE_LIG=1
if ! command -v liggghts >/dev/null 2>&1; then
    echo "LIGGGHTS missing: apt-get install -y liggghts" >&2
    if ! { apt-get install -y liggghts >"$WORK/apt.log" 2>&1 ||
        { apt-get update >>"$WORK/apt.log" 2>&1 && apt-get install -y liggghts >>"$WORK/apt.log" 2>&1; }; }; then
        HAVE_LIG=0
        banner "LIGGGHTS COULD NOT BE INSTALLED (see $WORK/apt.log): NO RATIOS, pdamp COLUMNS ONLY"
    fi
    command -v liggghts >/dev/null 2>&1 || HAVE_LIG=0
fi
[ -x "$PDAMP" ] || (cd "$ROOT" && cargo build --release)

median() { sort -g | awk '{a[NR]=$1} END {if (NR == 0) print "nan"; else if (NR % 2) print a[(NR+1)/2]; else print (a[NR/2]+a[NR/2+1])/2}'; }

# box side (m) and lattice sites per side for N grains
side() { awk -v n="$1" 'BEGIN {printf "%.6g", 0.03675 * sqrt(n / 250)}'; }
nside() { awk -v n="$1" 'BEGIN {printf "%d", 5 * sqrt(n / 250) + 0.5}'; }
nrun() { awk -v n="$1" -v p="$PSTEPS" 'BEGIN {s = int(p / n); if (s < 400) s = 400; if (s > 20000) s = 20000; print s}'; }
nwarm() { local r; r=$(nrun "$1"); echo "${NWARM:-$(( r / 10 > 200 ? r / 10 : 200 ))}"; }

# 12-triangle closed box L x L x 0.1225 (STL, outward normals as in the golden boxes)
write_stl() {
    awk -v L="$1" 'function f(nx,ny,nz,a,b,c) {printf " facet normal %s %s %s\n  outer loop\n   vertex %s\n   vertex %s\n   vertex %s\n  endloop\n endfacet\n", nx,ny,nz,a,b,c}
    BEGIN { H = 0.1225; print "solid box"
      p0="0 0 0"; p1=L" 0 0"; p2=L" "L" 0"; p3="0 "L" 0"; q0="0 0 "H; q1=L" 0 "H; q2=L" "L" "H; q3="0 "L" "H
      f(0,0,1,p0,p1,p2); f(0,0,1,p0,p2,p3); f(0,0,-1,q0,q3,q2); f(0,0,-1,q0,q2,q1)
      f(0,1,0,p0,q0,q1); f(0,1,0,p0,q1,p1); f(0,-1,0,p3,p2,q2); f(0,-1,0,p3,q2,q3)
      f(1,0,0,p0,p3,q3); f(1,0,0,p0,q3,q0); f(-1,0,0,p1,q1,q2); f(-1,0,0,p1,q2,p2)
      print "endsolid box" }' >"$2"
}

# settled LIGGGHTS restart for N grains -> prints its path
lig_settled() {
    local n=$1 L tag ns
    L=$(side "$n"); ns=$(nside "$n"); tag="N$n"
    local dir="$WORK/lig_$tag"
    mkdir -p "$dir"
    if [ "$n" = 250 ] && [ -f "$GOLDEN/settled_L36.75.restart" ]; then
        cp -f "$GOLDEN/settled_L36.75.restart" "$dir/settled_$tag.restart"
    fi
    write_stl "$L" "$dir/box_$tag.stl"
    cp -f "$GOLDEN/in.settle" "$GOLDEN/in.run" "$dir/"
    chmod u+w "$dir"/in.*
    sed 's/^variable U .*/variable U      equal 0.0/' "$GOLDEN/in.run" >"$dir/in.rest"
    if [ ! -f "$dir/settled_$tag.restart" ]; then
        echo "LIGGGHTS: settling N = $n ($NSET steps, L = $L m) ..." >&2
        (cd "$dir" && liggghts -in in.settle -var L "$L" -var nside "$ns" -var tag "$tag" -var nset "$NSET" -log settle.log >/dev/null)
    fi
    echo "$dir"
}

# CPU seconds (user + sys) of a command, from /usr/bin/time
cpu_of() { /usr/bin/time -f "%U %S" -o "$WORK/time.txt" "$@" >/dev/null; awk '{print $1 + $2}' "$WORK/time.txt"; }

# one LIGGGHTS timed run -> "wall-based cpu-based" particle-steps/s. Wall: N x NRUN / "Loop time"
# of the timed run. CPU: N x NRUN / (CPU of the whole process - CPU of the same deck with
# NRUN = 0), i.e. the timed run's CPU time (fair on a loaded machine).
lig_run() {
    local n=$1 state=$2 dir=$3 deck=in.run
    [ "$state" = rest ] && deck=in.rest
    local r w c1 c0
    r=$(nrun "$n"); w=$(nwarm "$n")
    c1=$(cd "$dir" && cpu_of taskset -c "$CPU" liggghts -in "$deck" -var tag "N$n" -var nwarm "$w" -var nrun "$r" -log "run_$state.log")
    c0=$(cd "$dir" && cpu_of taskset -c "$CPU" liggghts -in "$deck" -var tag "N$n" -var nwarm "$w" -var nrun 0 -log "run0_$state.log")
    awk -v n="$n" -v r="$r" -v c1="$c1" -v c0="$c0" '/^Loop time of/ {t = $4} END {printf "%.6g %.6g\n", n * r / t, n * r / (c1 - c0)}' "$dir/run_$state.log"
}

# one pdamp run -> "wall-based cpu-based" particle-steps/s (threads: 1 pinned to $CPU, or 2;
# the CPU figure is the stepping thread's CPU time, particle_steps_per_cpu_s)
pdamp_run() {
    local n=$1 state=$2 threads=$3 L amp dur out
    L=$(side "$n"); amp=0.0045
    [ "$state" = rest ] && amp=0.0
    dur=$(awk -v s=$(( $(nrun "$n") + $(nwarm "$n") )) -v dt=$DT 'BEGIN {printf "%.6g", s * dt}')
    out="$WORK/pdamp_${n}_${state}_$threads"
    local pin=()
    [ "$threads" = 1 ] && pin=(taskset -c "$CPU")
    RAYON_NUM_THREADS=$threads "${pin[@]}" "$PDAMP" simulate "$ROOT/bench/dem_bed.toml" --out "$out" --no-analysis \
        --set damper.count="$n" --set "damper.box=[$L,$L,0.1225]" --set excitation.amplitude=$amp \
        --set run.duration="$dur" --set damper.settle_time="$PDAMP_SETTLE" \
        --set damper.packing="\"$PDAMP_PACKING\"" --set damper.tangential="\"$TANGENTIAL\"" >"$out.log" 2>&1
    local a b
    a=$(sed -n 's/.*"particle_steps_per_s": *\([0-9.eE+-]*\).*/\1/p' "$out/summary.json" | head -1)
    b=$(sed -n 's/.*"particle_steps_per_cpu_s": *\([0-9.eE+-]*\).*/\1/p' "$out/summary.json" | head -1)
    echo "$a ${b:-nan}"
}

echo "# pdamp vs LIGGGHTS 3.8.0, $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); REPEAT=$REPEAT, medians; M particle-steps/s; pdamp tangential law: $TANGENTIAL"
echo "# CPU: per CPU-second of the timed run (LIGGGHTS: process CPU minus a NRUN = 0 run; pdamp: stepping thread)"
echo "# wall: LIGGGHTS N x NRUN / Loop time; pdamp particle_steps_per_s (driven phase = NWARM + NRUN steps)"
printf '| bed | N | box L (mm) | timed steps | LIGGGHTS CPU | pdamp CPU | ratio CPU | LIGGGHTS wall | pdamp wall 1 thr | ratio wall |'
[ "$THREADS2" = 1 ] && printf ' pdamp wall 2 thr | speed-up 2/1 |'
printf '\n|---|---|---|---|---|---|---|---|---|---|'
[ "$THREADS2" = 1 ] && printf -- '---|---|'
printf '\n'
for n in $NS; do
    dir=""
    lig=$HAVE_LIG
    [ "$n" -gt "$SKIP_LIGGGHTS_ABOVE" ] && lig=0
    [ "$lig" = 1 ] && dir=$(lig_settled "$n")
    for state in $STATES; do
        : >"$WORK/l.txt"; : >"$WORK/p1.txt"; : >"$WORK/p2.txt"
        for _ in $(seq "$REPEAT"); do
            [ "$lig" = 1 ] && lig_run "$n" "$state" "$dir" >>"$WORK/l.txt"
            pdamp_run "$n" "$state" 1 >>"$WORK/p1.txt"
            [ "$THREADS2" = 1 ] && pdamp_run "$n" "$state" 2 >>"$WORK/p2.txt"
        done
        lw=$(cut -d' ' -f1 "$WORK/l.txt" | median); lc=$(cut -d' ' -f2 "$WORK/l.txt" | median)
        pw=$(cut -d' ' -f1 "$WORK/p1.txt" | median); pc=$(cut -d' ' -f2 "$WORK/p1.txt" | median)
        p2=$(cut -d' ' -f1 "$WORK/p2.txt" | median)
        echo "# N=$n $state (wall cpu): LIGGGHTS $(tr '\n' ',' <"$WORK/l.txt")| pdamp $(tr '\n' ',' <"$WORK/p1.txt")| pdamp-2 $(tr '\n' ',' <"$WORK/p2.txt")" >&2
        awk -v n="$n" -v st="$state" -v L="$(side "$n")" -v r="$(nrun "$n")" -v lw="$lw" -v lc="$lc" -v pw="$pw" -v pc="$pc" -v q="$p2" -v t2="$THREADS2" '
            function m(x) { return (x == "nan" || x == "") ? "n/a" : sprintf("%.2f", x / 1e6) }
            function ra(a, b) { return (a == "nan" || b == "nan" || a == "" || b == "") ? "n/a" : sprintf("%.2fx", a / b) }
            BEGIN {
            printf "| %s | %d | %.2f | %d | %s | %s | %s | %s | %s | %s |", st, n, L * 1000, r, m(lc), m(pc), ra(pc, lc), m(lw), m(pw), ra(pw, lw)
            if (t2 == 1) printf " %s | %s |", m(q), ra(q, pw)
            printf "\n" }'
    done
done
[ "$HAVE_LIG" = 1 ] || banner "LIGGGHTS WAS NOT AVAILABLE: the LIGGGHTS column is empty"
