#!/usr/bin/env bash
# pdamp against TISEAN 3.0.1, same machine, same run, same options, every verb: `mutual`,
# `false_nearest` (pdamp fnn --tisean), `lyap_k` (lyap-k --tisean), `d2`, `lyap_r`, `nrlazy`
# (nrlazy --tisean) and the Fortran `surrogates` on Lorenz x (dt = 0.01, the project's
# generator) of 50 000 and 200 000 points. Checks that the outputs are equal to TISEAN's print
# precision (surrogates, which are random: both outputs a permutation of the data), then prints
# wall and CPU (user+sys) seconds and the ratios.
#
# TISEAN is not part of pdamp (GPL-2) and is never stored here: give a copy of the public
# snapshot esandford/TISEAN at commit 4e51806 ("TISEAN 3.0.1 ... with no changes"), either
#   TISEAN_SRC=/path/to/TISEAN        a checkout/unpacked tree (with source_c/), or
#   TISEAN_GIT_DIR=/path/to/repo.git  a git directory holding commit 4e51806.
# Its C programs are built outside the repository, in $WORK/tisean-build, as
# tests/golden/README.md says: gcc -O3 -c routines/*.c; ar rcs libddtsa.a *.o;
# gcc -O3 -o lyap_k lyap_k.c libddtsa.a -lm (same for the others); `surrogates` (Fortran) with
# gfortran -O3 from source_f/ (its libtsa.a and slatec's libsla.a), if gfortran is installed.
#
# Usage: TISEAN_SRC=... bench/vs_tisean.sh
# Environment: LENGTHS (default "50000 200000"), PROGRAMS (default: all seven, "mutual
#   false_nearest lyap_k d2 lyap_r nrlazy surrogates"), WORK (scratch directory, default
#   /tmp/pdamp-vs-tisean), SKIP_TISEAN_ABOVE (skip TISEAN's lyap_k and d2 above this N, when
#   their ~N² run time is too long; their ratio is then not printed; TISEAN's surrogates is
#   always skipped above 100 000, the most its Fortran arrays hold),
#   REPEAT (runs of each command, default 1; the table then shows medians), PDAMP (a pdamp
#   binary to time instead of building target/release/pdamp), PDAMP_BASE (a second pdamp
#   binary, e.g. the main branch's, timed in the same rounds right after PDAMP, its output
#   checked equal to PDAMP's; its rows are marked "(base)").
# Order per (program, N), repeated REPEAT times (alternating): TISEAN, pdamp on 2 threads, pdamp
# on 1 thread (RAYON_NUM_THREADS=1, taskset -c 0 if available). Load (uptime) is printed before
# each round: on a shared machine compare CPU seconds (user+sys), which the load disturbs much
# less than wall time.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORK=${WORK:-/tmp/pdamp-vs-tisean}
LENGTHS=${LENGTHS:-"50000 200000"}
PROGRAMS=${PROGRAMS:-"mutual false_nearest lyap_k d2 lyap_r nrlazy surrogates"}
SKIP_TISEAN_ABOVE=${SKIP_TISEAN_ABOVE:-0}
REPEAT=${REPEAT:-1}
COMMIT=4e51806
mkdir -p "$WORK"

# exact options (identical for both programs)
LYAP_OPTS="-m2 -M6 -d17 -r0.0755099 -R0.755099 -#4 -s600 -t100"
FNN_OPTS="-m1 -M1,8 -d17 -f10 -t100"
MUT_OPTS="-D100"
D2_OPTS="-M1,6 -d10 -t100 -r0.05 -R8 -#50"            # TISEAN adds -N0 (pdamp's only mode)
LYAPR_OPTS="-m5 -d10 -t100 -s150"
NRLAZY_TOPTS="-m1,7 -v0.2 -i1"                         # TISEAN's spelling
NRLAZY_POPTS="-m1,7 --radius-sd 0.2 -i1"               # pdamp's: -v is --verbose there
SURR_TOPTS="-n1 -I1"
SURR_POPTS="-n 1 -I 1"

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
cp "$SRC"/source_c/{lyap_k,false_nearest,mutual,d2,lyap_r,nrlazy}.c "$TB/"
(
  cd "$TB"
  rm -f routines/*.o routines/*.a
  gcc -O3 -c routines/*.c 2>/dev/null
  ar rcs libddtsa.a ./*.o
  for p in lyap_k false_nearest mutual d2 lyap_r nrlazy; do gcc -O3 -o "$p" "$p.c" libddtsa.a -lm 2>/dev/null; done
)
if command -v gfortran >/dev/null; then
  cp -r "$SRC/source_f" "$TB/source_f"
  (
    cd "$TB/source_f"
    FF="gfortran -O3 -std=legacy -w"
    rm -f ./*.o ./*.a slatec/*.o
    sed "s#ERRUNIT#0#" istdio_temp.f >istdio.f
    (cd slatec && for f in d1mach r1mach i1mach rand rgauss dqk15 rs tql2 tqlrat tred1 tred2 pythag \
      rffti1 rfftf1 rfftb1 radf2 radf3 radf4 radf5 radfg radb2 radb3 radb4 radb5 radbg snls1 fdjac3 \
      lmpar rwupdt chkder qrfac qrsolv enorm xercnt xermsg xerhlt xersve j4save xgetua xerprn fdump; do
      $FF -c $f.f; done && ar rcs ../libsla.a ./*.o)
    for f in readfile xreadfile arguments commandline any_s istdio help verbose d1 neigh normal rank \
      nmore store_spec tospec; do $FF -c $f.f; done
    ar rcs libtsa.a readfile.o xreadfile.o arguments.o commandline.o any_s.o istdio.o help.o \
      verbose.o d1.o neigh.o normal.o rank.o nmore.o store_spec.o tospec.o
    $FF -o "$TB/surrogates" surrogates.f libtsa.a libsla.a
  ) >/dev/null 2>&1 || echo "TISEAN surrogates (Fortran) did not build" >&2
fi
echo "TISEAN built in $TB from $SRC"

# --- pdamp and the series -------------------------------------------------------------------
# the series generator is built only if a series is missing (a build of the crate can take
# minutes on a loaded machine)
for n in $LENGTHS; do
  if [[ ! -s "$WORK/lorenz_x_n$n.dat" ]]; then
    (cd "$ROOT" && cargo build --release --quiet --example gen_series)
    break
  fi
done
if [[ -z "${PDAMP:-}" ]]; then
  (cd "$ROOT" && cargo build --release --quiet --bin pdamp)
  PDAMP="$ROOT/target/release/pdamp"
fi
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

# compare_rows TISEAN_FILE PDAMP_CSV KEY_COL VALUE_COL: TISEAN's rows "key value" (comments
# and blank lines dropped) against pdamp's CSV rows (header dropped), key equal, value to
# TISEAN's print precision (mutual: τ, I; lyap_r: Δn, S)
compare_rows() {
  awk -v kc="$3" -v vc="$4" 'FNR == NR { if ($0 ~ /^#/ || NF == 0) next; n++; tk[n] = $1; tv[n] = $2; next }
       FNR == 1 { next }
       { split($0, f, ","); k++; if (f[kc] != tk[k] || !near(f[vc], tv[k])) bad++ }
       function near(p, g,   e, h, a) { e = g; sub(/.*[eE]/, "", e); h = 0.5 * 10 ^ (e - 6); a = g < 0 ? -g : g
         return (p - g <= h + 1e-12 * a) && (g - p <= h + 1e-12 * a) }
       END { if (k != n) { print "rows " k " vs " n; exit 1 } ; if (bad) { print bad " rows differ"; exit 1 }
             print "equal (" n " rows)" }' "$1" "$2"
}

# compare_c2 TISEAN_C2 PDAMP_CSV: d2's C(m, ε), both printed with %e: at most one unit of the
# last digit apart (pdamp's rows with C = 0 are absent from TISEAN's file)
compare_c2() {
  awk 'FNR == NR { if ($1 == "#dim=") { m = $2; next } ; if ($0 ~ /^#/ || NF == 0) next
                   n++; key[m " " sprintf("%.5e", $1)] = $2; next }
       FNR == 1 { next }
       { split($0, f, ","); if (f[3] + 0 == 0) next; k++
         g = key[f[1] " " sprintf("%.5e", f[2])]
         if (g == "") { miss++; next }
         e = g; sub(/.*[eE]/, "", e); h = 10 ^ (e - 6) * (1 + 1e-9)
         if (f[3] - g > h || g - f[3] > h) bad++ }
       END { if (k != n || miss) { print "rows " k " vs " n ", " miss + 0 " not found"; exit 1 }
             if (bad) { print bad " rows differ"; exit 1 } ; print "equal (" n " rows)" }' "$1" "$2"
}

# compare_laz TISEAN_FILE PDAMP_FILE: one value per line, to TISEAN's print precision
compare_laz() {
  paste "$1" "$2" | awk '{ n++; g = $1; p = $2; e = g; sub(/.*[eE]/, "", e); h = 0.5 * 10 ^ (e - 6); a = g < 0 ? -g : g
       if (p - g > h + 1e-12 * a || g - p > h + 1e-12 * a) bad++ }
       END { if (bad) { print bad " of " n " samples differ"; exit 1 } ; print "equal (" n " samples)" }'
}

# compare_surr TISEAN_FILE PDAMP_FILE DATA: both a permutation of the first samples of the data
# (sorted values equal; TISEAN computes and prints in single precision: 7 digits)
compare_surr() {
  local n
  n=$(grep -c . "$1" || true)
  [[ $n -gt 0 ]] || { echo "no TISEAN output"; return 1; }
  if paste <(grep . "$1" | sort -g) <(head -n "$n" "$3" | sort -g) |
      awk '{ d = $1 - $2; a = $2 < 0 ? -$2 : $2; if (d > 6e-7 * a + 1e-6 || -d > 6e-7 * a + 1e-6) bad++ } END { exit bad > 0 }' &&
    paste <(grep -v '^#' "$2" | sort -g) <(sort -g "$3") |
      awk '{ d = $1 - $2; a = $2 < 0 ? -$2 : $2; if (d > 1e-10 * a || -d > 1e-10 * a) bad++ } END { exit bad > 0 }'; then
    echo "both permutations of the data ($n and $(grep -vc '^#' "$2") samples; spectra: tests/golden_tisean.rs)"
  else
    echo "not a permutation of the data"; return 1
  fi
}

echo
echo "machine: $(nproc) cores, $(uname -m); $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
# with autogroup scheduling the cores are shared between sessions, not between threads: while
# another session keeps a core busy, this one's two threads get about one core between them
[[ $(cat /proc/sys/kernel/sched_autogroup_enabled 2>/dev/null || echo 0) == 1 ]] &&
  echo "kernel.sched_autogroup_enabled = 1: CPU time is shared per session; busy other sessions cap pdamp's 2 threads near 1 core"
RESULTS=()
for prog in $PROGRAMS; do
  for n in $LENGTHS; do
    dat="$WORK/lorenz_x_n$n.dat"
    topts=""; popts=""; ptisean=""
    case $prog in
      lyap_k) opts=$LYAP_OPTS; verb="lyap-k"; ext=lyap; ptisean="--tisean" ;;
      false_nearest) opts=$FNN_OPTS; verb="fnn"; ext=fnn; ptisean="--tisean" ;;
      mutual) opts=$MUT_OPTS; verb="mutual"; ext=mut ;;
      d2) opts=$D2_OPTS; topts="-N0"; verb="d2"; ext=c2 ;;
      lyap_r) opts=$LYAPR_OPTS; verb="lyap-r"; ext=ros ;;
      nrlazy) opts=""; topts=$NRLAZY_TOPTS; popts=$NRLAZY_POPTS; verb="nrlazy"; ext=laz; ptisean="--tisean" ;;
      surrogates) opts=""; topts=$SURR_TOPTS; popts=$SURR_POPTS; verb="surrogates"; ext=surr ;;
      *) echo "unknown program $prog" >&2; exit 2 ;;
    esac
    tfile="$WORK/tisean_n$n.$ext"
    pfile="$WORK/pdamp_n$n.$ext.csv"
    echo "== $prog, N = $n: $prog $(basename "$dat") $opts $topts -V0   |   pdamp $verb $(basename "$dat") $ptisean $opts $popts"
    run_tisean=1
    [[ $SKIP_TISEAN_ABOVE -gt 0 && $n -gt $SKIP_TISEAN_ABOVE && ($prog == lyap_k || $prog == d2) ]] && run_tisean=0
    if [[ $prog == surrogates && ($n -gt 100000 || ! -x $TB/surrogates) ]]; then
      run_tisean=0
      echo "   TISEAN surrogates skipped: its arrays hold 100 000 samples (parameter nx), or it did not build"
    fi
    rm -f "$tfile"
    tt=(); tp2=(); tp1=(); tb2=(); tb1=()
    for ((rep = 1; rep <= REPEAT; rep++)); do
      echo "   load: $(uptime | sed 's/.*load/load/')"
      if [[ $run_tisean -eq 1 ]]; then
        # shellcheck disable=SC2086
        case $prog in
          lyap_k | lyap_r) OUT=/dev/null; t=$(timed "$TB/$prog" "$dat" $opts -V0 -o "$tfile") ;;
          d2) OUT=/dev/null; t=$(timed "$TB/d2" "$dat" $opts $topts -V0 -o "$WORK/tisean_n$n") ;;
          *) OUT=$tfile; t=$(timed "$TB/$prog" "$dat" $opts $topts -V0) ;;
        esac
        tt+=("$t")
      fi
      # shellcheck disable=SC2086
      OUT=$pfile; t=$(timed "$PDAMP" "$verb" "$dat" $ptisean $opts $popts); tp2+=("$t")
      # shellcheck disable=SC2086
      OUT=$pfile.1; t=$(RAYON_NUM_THREADS=1 timed $ONE_CORE "$PDAMP" "$verb" "$dat" $ptisean $opts $popts); tp1+=("$t")
      last_t="- -"
      [[ ${#tt[@]} -gt 0 ]] && last_t=${tt[-1]}
      echo "   run $rep wall/cpu s: TISEAN $last_t | pdamp 2 thr ${tp2[-1]} | pdamp 1 thr ${tp1[-1]}"
      if [[ -n "${PDAMP_BASE:-}" ]]; then
        # shellcheck disable=SC2086
        OUT=$pfile.base; t=$(timed "$PDAMP_BASE" "$verb" "$dat" $ptisean $opts $popts); tb2+=("$t")
        # shellcheck disable=SC2086
        OUT=$pfile.base1; t=$(RAYON_NUM_THREADS=1 timed $ONE_CORE "$PDAMP_BASE" "$verb" "$dat" $ptisean $opts $popts); tb1+=("$t")
        echo "   run $rep wall/cpu s: base 2 thr ${tb2[-1]} | base 1 thr ${tb1[-1]}"
        cmp -s "$pfile" "$pfile.base" || echo "   note: PDAMP_BASE's output differs from PDAMP's"
      fi
    done
    t_t="- -"
    [[ $run_tisean -eq 1 ]] && t_t=$(median "${tt[@]}")
    t_p2=$(median "${tp2[@]}")
    t_p1=$(median "${tp1[@]}")
    [[ $REPEAT -gt 1 ]] && echo "   medians of $REPEAT: TISEAN $t_t | pdamp 2 thr $t_p2 | pdamp 1 thr $t_p1"
    cmp -s "$pfile" "$pfile.1" || { echo "   pdamp output depends on the thread count!"; exit 1; }
    if [[ -s $tfile && $t_t != "- -" ]]; then
      case $prog in
        lyap_k) eq=$(compare_lyap "$tfile" "$pfile") ;;
        false_nearest) eq=$(compare_fnn "$tfile" "$pfile") ;;
        mutual) eq=$(compare_rows "$tfile" "$pfile" 1 2) ;;
        d2) eq=$(compare_c2 "$tfile" "$pfile") ;;
        lyap_r) eq=$(compare_rows "$tfile" "$pfile" 1 2) ;;
        nrlazy) eq=$(compare_laz "$tfile" "$pfile") ;;
        surrogates) eq=$(compare_surr "$tfile" "$pfile" "$dat") ;;
      esac || { echo "   outputs: $eq"; exit 1; }
      echo "   outputs: $eq"
    fi
    RESULTS+=("$prog $n $t_t $t_p2 $t_p1")
    [[ ${#tb2[@]} -gt 0 ]] && RESULTS+=("$prog(base) $n $t_t $(median "${tb2[@]}") $(median "${tb1[@]}")")
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
