#!/usr/bin/env bash
# pdamp against TISEAN 3.0.1, same machine, same run, same options: `lyap_k` vs
# `pdamp lyap-k --tisean` and `false_nearest` vs `pdamp fnn --tisean` on Lorenz x (dt = 0.01,
# the project's generator) of 50 000 and 200 000 points. Checks that the outputs are equal to
# TISEAN's print precision, then prints wall and CPU (user+sys) seconds and the ratios.
#
# TISEAN is not part of pdamp (GPL-2) and is never stored here: give a copy of the public
# snapshot esandford/TISEAN at commit 4e51806 ("TISEAN 3.0.1 ... with no changes"), either
#   TISEAN_SRC=/path/to/TISEAN        a checkout/unpacked tree (with source_c/), or
#   TISEAN_GIT_DIR=/path/to/repo.git  a git directory holding commit 4e51806.
# Its three C programs are built outside the repository, in $WORK/tisean-build, as
# tests/golden/README.md says: gcc -O3 -c routines/*.c; ar rcs libddtsa.a *.o;
# gcc -O3 -o lyap_k lyap_k.c libddtsa.a -lm (same for false_nearest, mutual).
#
# Usage: TISEAN_SRC=... bench/vs_tisean.sh
# Environment: LENGTHS (default "50000 200000"), PROGRAMS (default "lyap_k false_nearest"),
#   WORK (scratch directory, default /tmp/pdamp-vs-tisean), SKIP_TISEAN_ABOVE (skip TISEAN's
#   lyap_k above this N, e.g. when its ~N² run time is too long; its ratio is then not printed),
#   REPEAT (runs of each command, default 1; the table then shows medians).
# Order per (program, N), repeated REPEAT times (alternating): TISEAN, pdamp on 2 threads, pdamp
# on 1 thread (RAYON_NUM_THREADS=1, taskset -c 0 if available). Load (uptime) is printed before
# each round: on a shared machine compare CPU seconds (user+sys), which the load disturbs much
# less than wall time.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORK=${WORK:-/tmp/pdamp-vs-tisean}
LENGTHS=${LENGTHS:-"50000 200000"}
PROGRAMS=${PROGRAMS:-"lyap_k false_nearest"}
SKIP_TISEAN_ABOVE=${SKIP_TISEAN_ABOVE:-0}
REPEAT=${REPEAT:-1}
COMMIT=4e51806
mkdir -p "$WORK"

# exact options (identical for both programs)
LYAP_OPTS="-m2 -M6 -d17 -r0.0755099 -R0.755099 -#4 -s600 -t100"
FNN_OPTS="-m1 -M1,8 -d17 -f10 -t100"

# --- TISEAN ---------------------------------------------------------------------------------
SRC="$WORK/tisean-src"
if [[ -n "${TISEAN_SRC:-}" ]]; then
  SRC="$TISEAN_SRC"
elif [[ -n "${TISEAN_GIT_DIR:-}" ]]; then
  rm -rf "$SRC" && mkdir -p "$SRC"
  git --git-dir="$TISEAN_GIT_DIR" archive "$COMMIT" | tar -x -C "$SRC"
else
  echo "give TISEAN_SRC=<esandford/TISEAN tree> or TISEAN_GIT_DIR=<its git dir> (commit $COMMIT)" >&2
  exit 2
fi
[[ -f "$SRC/source_c/lyap_k.c" ]] || { echo "$SRC/source_c/lyap_k.c not found" >&2; exit 2; }
TB="$WORK/tisean-build"
rm -rf "$TB" && mkdir -p "$TB"
cp -r "$SRC/source_c/routines" "$TB/"
cp "$SRC"/source_c/{lyap_k,false_nearest,mutual}.c "$TB/"
(
  cd "$TB"
  rm -f routines/*.o routines/*.a
  gcc -O3 -c routines/*.c 2>/dev/null
  ar rcs libddtsa.a ./*.o
  for p in lyap_k false_nearest mutual; do gcc -O3 -o "$p" "$p.c" libddtsa.a -lm 2>/dev/null; done
)
echo "TISEAN built in $TB from $SRC"

# --- pdamp and the series -------------------------------------------------------------------
(cd "$ROOT" && cargo build --release --quiet --bin pdamp --example gen_series)
PDAMP="$ROOT/target/release/pdamp"
GEN="$ROOT/target/release/examples/gen_series"
for n in $LENGTHS; do
  if [[ ! -s "$WORK/lorenz_x_n$n.dat" ]]; then
    "$GEN" "$n" "$WORK/lorenz_x_n$n.txt" 2>/dev/null
    grep -v '^#' "$WORK/lorenz_x_n$n.txt" >"$WORK/lorenz_x_n$n.dat"
  fi
done
ONE_CORE=""
command -v taskset >/dev/null && ONE_CORE="taskset -c 0"

# timed CMD... : prints "wall cpu" (seconds, cpu = user + sys, to the millisecond) of the
# command (bash's `time`); its stdout goes to $OUT
timed() {
  local tf
  tf=$(mktemp)
  { TIMEFORMAT="%3R %3U %3S"; time "$@" >"$OUT" 2>/dev/null; } 2>"$tf"
  awk '{ printf "%.3f %.3f\n", $1, $2 + $3 }' "$tf"
  rm -f "$tf"
}

# median WALL_CPU... : "wall cpu", the medians of the "wall cpu" pairs given
median() {
  printf '%s\n' "$@" | awk '{ w[NR] = $1; c[NR] = $2 }
    function med(a, n,   i, j, t) { for (i = 2; i <= n; i++) for (j = i; j > 1 && a[j - 1] > a[j]; j--) { t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
                                   return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2 }
    END { printf "%.3f %.3f\n", med(w, NR), med(c, NR) }'
}

# compare_lyap TISEAN_FILE PDAMP_CSV: every row equal to TISEAN's print precision
compare_lyap() {
  awk 'FNR == NR {
         if ($1 == "#epsilon=") { eps = $2; m = $4; next }
         if (NF == 3) { n++; te[n] = eps; tm[n] = m; td[n] = $1; ts[n] = $2; tc[n] = $3 }
         next }
       FNR == 1 { next }
       { split($0, f, ","); k++
         if (f[2] != tm[k] || f[3] != td[k] || f[5] != tc[k] || !near(f[4], ts[k]) || !near(f[1], te[k])) bad++ }
       function near(p, g,   e, h) { e = g; sub(/.*[eE]/, "", e); h = 0.5 * 10 ^ (e - 6)
         return (p - g <= h + 1e-12 * (g < 0 ? -g : g)) && (g - p <= h + 1e-12 * (g < 0 ? -g : g)) }
       END { if (k != n) { print "rows " k " vs " n; exit 1 } ; if (bad) { print bad " rows differ"; exit 1 }
             print "equal (" n " rows)" }' "$1" "$2"
}

# compare_fnn TISEAN_FILE PDAMP_CSV
compare_fnn() {
  awk 'FNR == NR { n++; tm[n] = $1; tf[n] = $2; ta[n] = $3; tr[n] = $4; next }
       FNR == 1 { next }
       { split($0, f, ","); k++
         if (f[1] != tm[k] || !near(f[2], tf[k]) || !near(f[5], ta[k]) || !near(f[6], tr[k])) bad++ }
       function near(p, g,   e, h) { e = g; sub(/.*[eE]/, "", e); h = 0.5 * 10 ^ (e - 6)
         return (p - g <= h + 1e-12 * g) && (g - p <= h + 1e-12 * g) }
       END { if (k != n) { print "rows " k " vs " n; exit 1 } ; if (bad) { print bad " rows differ"; exit 1 }
             print "equal (" n " rows)" }' "$1" "$2"
}

echo
echo "machine: $(nproc) cores, $(uname -m); $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
RESULTS=()
for prog in $PROGRAMS; do
  for n in $LENGTHS; do
    dat="$WORK/lorenz_x_n$n.dat"
    case $prog in
      lyap_k) opts=$LYAP_OPTS; verb="lyap-k"; ext=lyap ;;
      false_nearest) opts=$FNN_OPTS; verb="fnn"; ext=fnn ;;
      *) echo "unknown program $prog" >&2; exit 2 ;;
    esac
    tfile="$WORK/tisean_n$n.$ext"
    pfile="$WORK/pdamp_n$n.$ext.csv"
    echo "== $prog, N = $n: $prog $(basename "$dat") $opts -V0   |   pdamp $verb $(basename "$dat") --tisean $opts"
    run_tisean=0
    [[ $SKIP_TISEAN_ABOVE -eq 0 || $n -le $SKIP_TISEAN_ABOVE || $prog != lyap_k ]] && run_tisean=1
    tt=(); tp2=(); tp1=()
    for ((rep = 1; rep <= REPEAT; rep++)); do
      echo "   load: $(uptime | sed 's/.*load/load/')"
      if [[ $run_tisean -eq 1 ]]; then
        # shellcheck disable=SC2086
        if [[ $prog == lyap_k ]]; then
          OUT=/dev/null; t=$(timed "$TB/lyap_k" "$dat" $opts -V0 -o "$tfile")
        else
          OUT=$tfile; t=$(timed "$TB/false_nearest" "$dat" $opts -V0)
        fi
        tt+=("$t")
      fi
      # shellcheck disable=SC2086
      OUT=$pfile; t=$(timed "$PDAMP" "$verb" "$dat" --tisean $opts); tp2+=("$t")
      # shellcheck disable=SC2086
      OUT=$pfile.1; t=$(RAYON_NUM_THREADS=1 timed $ONE_CORE "$PDAMP" "$verb" "$dat" --tisean $opts); tp1+=("$t")
      last_t="- -"
      [[ ${#tt[@]} -gt 0 ]] && last_t=${tt[-1]}
      echo "   run $rep wall/cpu s: TISEAN $last_t | pdamp 2 thr ${tp2[-1]} | pdamp 1 thr ${tp1[-1]}"
    done
    t_t="- -"
    [[ $run_tisean -eq 1 ]] && t_t=$(median "${tt[@]}")
    t_p2=$(median "${tp2[@]}")
    t_p1=$(median "${tp1[@]}")
    [[ $REPEAT -gt 1 ]] && echo "   medians of $REPEAT: TISEAN $t_t | pdamp 2 thr $t_p2 | pdamp 1 thr $t_p1"
    cmp -s "$pfile" "$pfile.1" || { echo "   pdamp output depends on the thread count!"; exit 1; }
    if [[ -s $tfile && $t_t != "- -" ]]; then
      if [[ $prog == lyap_k ]]; then eq=$(compare_lyap "$tfile" "$pfile"); else eq=$(compare_fnn "$tfile" "$pfile"); fi
      echo "   outputs: $eq"
    fi
    RESULTS+=("$prog $n $t_t $t_p2 $t_p1")
  done
done

echo
[[ $REPEAT -gt 1 ]] && echo "(medians of $REPEAT runs each)"
echo "| program | N | TISEAN wall (cpu) s | pdamp 2 thr wall (cpu) s | pdamp 1 thr wall (cpu) s | ratio wall 2 thr | ratio wall 1 thr | ratio cpu 1 thr |"
echo "|---|---|---|---|---|---|---|---|"
for r in "${RESULTS[@]}"; do
  awk '{ tw = $3; tc = $4
         r2 = (tw == "-") ? "-" : sprintf("%.1f×", tw / $5)
         r1 = (tw == "-") ? "-" : sprintf("%.1f×", tw / $7)
         rc = (tw == "-") ? "-" : sprintf("%.1f×", tc / $8)
         printf "| %s | %s | %s (%s) | %s (%s) | %s (%s) | %s | %s | %s |\n", $1, $2, tw, tc, $5, $6, $7, $8, r2, r1, rc }' <<<"$r"
done
