#!/usr/bin/env bash
# Static engine scaling on one machine (docs/static.md "Threads"): unpacks the bundle beside this
# script (contact2d_static_bundle.tar.gz, made by tools/device/make_bundle.sh), and runs the paper deck
# P1 --static at level 6 then 7 on 1, 2, 4, 8, 16 OpenMP threads (the BLAS of the factorisation
# follows them), interleaved, REPEATS times; one line per run: level, threads, the run's wall
# seconds and its static solve (assembly + factorisation, condensation, increments) from the
# summary, max |u| of the end state and max |u - u_1| / max |u_1| against the level's first
# 1-thread run, and the speed-up against the 1-thread median; a median line per level and thread
# count at the end. Runs that would start after BUDGET seconds are skipped (said so).
#
#   device/run_static_scaling.sh [LEVELS [THREADS [REPEATS [BUDGET]]]]
#   defaults: "6 7" "1 2 4 8 16" 2 330
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
levels=${1:-6 7}
threads=${2:-1 2 4 8 16}
repeats=${3:-2}
budget=${4:-330}
start=$SECONDS
work=$(mktemp -d "${TMPDIR:-/tmp}/c2d_static_scaling.XXXXXX")
trap 'rm -rf "$work"' EXIT
tar -xzf "$here/contact2d_static_bundle.tar.gz" -C "$work" || { echo "cannot unpack $here/contact2d_static_bundle.tar.gz" >&2; exit 1; }
root=$work/c2d
export LD_LIBRARY_PATH=$root/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
# the launcher's OpenMP wait (src/app/contact2d_launch.f90), unless the user chose one
if [ -z "${OMP_WAIT_POLICY:-}${GOMP_SPINCOUNT:-}" ]; then export GOMP_SPINCOUNT=2000; fi
solver=("$root/bin/contact2d-solver")
h5u=("$root/bin/c2d_h5u")
if ! "${solver[@]}" --version > /dev/null 2>&1; then
  # a host glibc older than the build's (Debian 12, glibc 2.36): the bundled loader and glibc
  ld=$root/lib-glibc/ld-linux-x86-64.so.2
  solver=("$ld" --library-path "$root/lib:$root/lib-glibc" "$root/bin/contact2d-solver")
  h5u=("$ld" --library-path "$root/lib:$root/lib-glibc" "$root/bin/c2d_h5u")
  "${solver[@]}" --version > /dev/null 2>&1 || { echo "the bundled contact2d-solver does not start:" >&2; "${solver[@]}" --version; exit 1; }
  echo "# using the bundled glibc loader"
fi
echo "# $(date -u '+%F %T UTC') $(uname -n); $(nproc) CPUs available of $(getconf _NPROCESSORS_ONLN);" \
     "$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)"
echo "# load average $(cut -d' ' -f1-3 /proc/loadavg); build $(head -1 "$root/COMMIT")"
echo "# BLAS: $(ldd "$root/bin/contact2d-solver" 2>/dev/null | grep -o 'libopenblas[^ ]* => [^ ]*' | sed "s|$root/||");" \
     "OpenBLAS core: $(OPENBLAS_VERBOSE=2 "${solver[@]}" --version 2>&1 | sed -n 's/^Core: //p' | head -1)"
printf '%-5s %-7s %-3s %9s %9s %9s %9s %9s %12s %16s %8s\n' level threads rep "wall s" "static s" "(factor" condense "incr)" "max|u|" "max|du|/max|u|1" speedup
declare -A med_in
for level in $levels; do
  ref=""
  for rep in $(seq 1 "$repeats"); do
    for t in $threads; do
      # the run's expected length: this level and count's first run, else the level's first
      # 1-thread run / t, else the previous level's 1-thread run x 8 (work ~ 8x per level)
      est=$(echo "${med_in["$level $t"]:-}" | awk '{print $1}')
      if [ -z "$est" ] && [ -n "${med_in["$level 1"]:-}" ]; then est=$(echo "${med_in["$level 1"]}" | awk -v t="$t" '{print $1 / t}'); fi
      if [ -z "$est" ] && [ -n "${prev1:-}" ]; then est=$(awk -v p="$prev1" 'BEGIN {print 8 * p}'); fi
      if awk -v e="${est:-0}" -v now=$((SECONDS - start)) -v b="$budget" 'BEGIN {exit !(now + e > b)}'; then
        echo "$level $t $rep skipped: it would end after the budget of $budget s (expected ${est} s)"
        continue
      fi
      out=$work/k${level}_t${t}_r${rep}.h5
      log=$work/k${level}_t${t}_r${rep}.log
      OMP_NUM_THREADS=$t "${solver[@]}" "$root/inputs/baillet_sassi_2002_p1.nml" --static -q \
        --set mesh:level="$level" --set output:xdmf=.false. -o "$out" > "$log" 2>&1
      rc=$?
      if [ $rc -ne 0 ]; then
        echo "$level $t $rep failed (exit $rc): $(grep -m1 'error' "$log")"
        continue
      fi
      wall=$(sed -n 's/^ *wall time *\([0-9.E+-]*\) s.*/\1/p' "$log")
      read -r st fa co inc < <(sed -n 's/^ *static solve *\([0-9.]*\) s (assembly + factorisation \([0-9.]*\), condensation \([0-9.]*\), increments \([0-9.]*\)).*/\1 \2 \3 \4/p' "$log")
      if [ -z "$ref" ] && [ "$t" = 1 ]; then ref=$out; umax=$("${h5u[@]}" "$out"); diff=bitwise
      elif [ -z "$ref" ]; then umax=$("${h5u[@]}" "$out"); diff="-"
      else read -r umax diff < <("${h5u[@]}" "$out" "$ref"); fi
      if [ "$out" != "$ref" ]; then rm -f "$out"; fi
      med_in["$level $t"]+="$wall "
      base=$(echo "${med_in["$level 1"]:-}" | tr ' ' '\n' | sed '/^$/d' | sort -g | awk '{a[NR]=$1} END {if (NR) print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}')
      sp=$( [ -n "$base" ] && awk -v b="$base" -v w="$wall" 'BEGIN {printf "%.2f", b / w}' || echo "-")
      printf '%-5s %-7s %-3s %9s %9s %9s %9s %9s %12s %16s %8s\n' "$level" "$t" "$rep" "$wall" "$st" "$fa" "$co" "$inc" "$umax" "$diff" "$sp"
    done
  done
  grep -m1 '^static engine:' "$work/k${level}_t1_r1.log" 2>/dev/null | sed 's/^/# /'
  prev1=$(echo "${med_in["$level 1"]:-}" | awk '{print $1}')
done
# the largest level on the most threads once more with spinning OpenMP waits (libgomp's default
# wait, OMP_WAIT_POLICY=active) instead of the launcher's short spin: what the BLAS's fork and
# join cost with threads that sleep between calls
last_level=${levels##* }
last_t=${threads##* }
est=$(echo "${med_in["$last_level $last_t"]:-}" | awk '{print $1}')
if [ -n "$est" ] && awk -v e="$est" -v now=$((SECONDS - start)) -v b="$budget" 'BEGIN {exit !(now + 2 * e <= b)}'; then
  log=$work/active.log
  env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=active OMP_NUM_THREADS=$last_t "${solver[@]}" "$root/inputs/baillet_sassi_2002_p1.nml" \
    --static -q --set mesh:level="$last_level" --set output:xdmf=.false. -o "$work/active.h5" > "$log" 2>&1 &&
  echo "# level $last_level threads $last_t OMP_WAIT_POLICY=active: wall $(sed -n 's/^ *wall time *\([0-9.E+-]*\) s.*/\1/p' "$log") s," \
       "$(sed -n 's/^ *static solve *//p' "$log")"
  rm -f "$work/active.h5"
fi
echo "# medians of the wall time (speed-up against 1 thread):"
for level in $levels; do
  base=""
  for t in $threads; do
    m=$(echo "${med_in["$level $t"]:-}" | tr ' ' '\n' | sed '/^$/d' | sort -g | awk '{a[NR]=$1} END {if (NR) print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}')
    [ -z "$m" ] && continue
    [ -z "$base" ] && [ "$t" = 1 ] && base=$m
    echo "# level $level threads $t median wall $m s speed-up $( [ -n "$base" ] && awk -v b="$base" -v w="$m" 'BEGIN {printf "%.2f", b / w}' || echo -)"
  done
done
echo "# total $((SECONDS - start)) s"
