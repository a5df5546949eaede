#!/usr/bin/env bash
# Builds the libFuzzer harnesses (`fuzz` preset: clang, ASan + UBSan, fuzz/) and runs each for
# SECONDS_PER_HARNESS, one after the other, then prints the executions run per harness.
# Exits non-zero when a harness finds anything (crash, sanitizer report, leak, timeout, memory
# over the limit); the input that triggers it is copied to fuzz/findings/<harness>/ and the
# report is shown. Inputs saved under fuzz/regressions/<harness>/ are rerun first: a finding
# that once was must stay fixed.
#
# Usage: scripts/fuzz.sh [SECONDS_PER_HARNESS] [HARNESS...]
#   SECONDS_PER_HARNESS  default 60
#   HARNESS              sdf mol2 pdb pqr ply msms off obj hsi sclib options (default: all)
# Environment: FUZZ_RSS_LIMIT_MB (default 2048), FUZZ_TIMEOUT (seconds per input, default 10),
#   FUZZ_CORPUS_DIR (keep the grown corpora there between runs; default a temporary directory).
#
# Seeds are built at run time in a temporary directory from fuzz/seeds/<harness>/ (small inputs
# made for the purpose), the reference files of datasets/cache (datasets/fetch.sh) and
# ../shared/datasets when present (nothing from ../shared is copied into the repository).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
all_harnesses=(sdf mol2 pdb pqr ply msms off obj hsi sclib options)
seconds=${1:-60}
if [ $# -gt 0 ]; then shift; fi
harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then harnesses=("${all_harnesses[@]}"); fi
for h in "${harnesses[@]}"; do
  [[ " ${all_harnesses[*]} " == *" $h "* ]] || { echo "fuzz.sh: unknown harness '$h' (${all_harnesses[*]})" >&2; exit 2; }
done
rss_limit=${FUZZ_RSS_LIMIT_MB:-2048}
timeout=${FUZZ_TIMEOUT:-10}
shared=../shared/datasets
build=build/fuzz

launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake --preset fuzz "${launcher[@]}" >/dev/null
targets=()
for h in "${harnesses[@]}"; do targets+=("fuzz_$h"); done
[[ " ${harnesses[*]} " == *" hsi "* ]] && targets+=(make_hsi_seed)
[[ " ${harnesses[*]} " == *" sclib "* ]] && targets+=(make_sclib_seed)
cmake --build --preset fuzz -j "$(nproc)" --target "${targets[@]}"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}

# Up to `limit` files matching `pattern` (find -iname) under the data directories, smallest first.
data_files() {
  local pattern=$1 limit=$2 dirs=()
  for d in datasets/cache "$shared"; do [ -d "$d" ] && dirs+=("$d"); done
  [ ${#dirs[@]} -gt 0 ] || return 0
  find "${dirs[@]}" -type f -iname "$pattern" -printf '%s %p\n' | sort -n |
    awk -v limit="$limit" 'NR <= limit { sub(/^[0-9]+ /, ""); print }'
}

# Fills $work/seeds/<harness>/.
make_seeds() {
  local h=$1 dir=$work/seeds/$1 n=0 f
  mkdir -p "$dir"
  if [ -d "fuzz/seeds/$h" ]; then cp fuzz/seeds/"$h"/* "$dir"/; fi
  case $h in
    sdf)  # the first record of each file
      while read -r f; do
        n=$((n + 1)); sed '/^\$\$\$\$/q' "$f" >"$dir/data$n.sdf"
      done < <(data_files '*.sdf' 12) ;;
    mol2)
      while read -r f; do
        n=$((n + 1)); cp "$f" "$dir/data$n.mol2"
      done < <(data_files '*.mol2' 12) ;;
    pdb|pqr)  # the header, the first 60 atoms and the first 40 HETATM records of each file
      while read -r f; do
        n=$((n + 1))
        awk '!/^(ATOM|HETATM)/ && a++ < 20; /^ATOM/ && b++ < 60; /^HETATM/ && c++ < 40' "$f" \
          >"$dir/data$n.$h"
      done < <(data_files "*.$h" 12) ;;
    msms)  # the smallest .vert/.face pairs, joined by a NUL byte
      while read -r f; do
        [ -f "${f%.*}.face" ] || continue
        n=$((n + 1)); { cat "$f"; printf '\0'; cat "${f%.*}.face"; } >"$dir/data$n.vertface"
      done < <(data_files '*.vert' 3) ;;
    ply)
      while read -r f; do
        [ "$(stat -c %s "$f")" -le 65536 ] || continue
        n=$((n + 1)); cp "$f" "$dir/data$n.ply"
      done < <(data_files '*.ply' 4) ;;
    hsi)
      "$build/fuzz/make_hsi_seed" fuzz/seeds/off/bumpy_sphere.off "$dir/bumpy_sphere.hsi" >/dev/null ;;
    sclib)
      "$build/fuzz/make_sclib_seed" fuzz/seeds/off/bumpy_sphere.off "$dir/three_kinds.sclib" >/dev/null ;;
  esac
}

# Extra libFuzzer flags. RDKit leaks the molecule it was building whenever its MDL or MOL2 parser
# throws (fuzz/lsan.supp): libFuzzer then runs LeakSanitizer's whole-heap scan after nearly
# every malformed input, which then dominates fuzz_sdf's and fuzz_mol2's time. Those two run
# without leak detection; every other harness (PDB and PQR included) keeps it.
extra_flags_of() {
  case $1 in
    sdf|mol2) echo -detect_leaks=0 ;;
  esac
}

max_len_of() {
  case $1 in
    sdf|mol2|pdb|pqr) echo 16384 ;;
    hsi|sclib) echo 65536 ;;
    options) echo 1024 ;;
    *) echo 8192 ;;
  esac
}

failed=()
declare -A executions rate
for h in "${harnesses[@]}"; do
  binary=$build/fuzz/fuzz_$h
  make_seeds "$h"
  if [ -d "fuzz/regressions/$h" ] && [ -n "$(ls -A "fuzz/regressions/$h")" ]; then
    echo "== fuzz_$h: regression inputs"
    if ! "$binary" -rss_limit_mb="$rss_limit" -timeout="$timeout" fuzz/regressions/"$h"/* \
        >"$work/$h.regressions.log" 2>&1; then
      tail -n 40 "$work/$h.regressions.log"
      failed+=("$h (regression input)")
      continue
    fi
  fi
  corpus=${FUZZ_CORPUS_DIR:-$work/corpus}/$h
  mkdir -p "$corpus" "$work/artifacts/$h"
  echo "== fuzz_$h: ${seconds} s"
  status=0
  # -close_fd_mask=3: the readers' and the option parser's own output is noise here;
  # libFuzzer and the sanitizers still report on a duplicate of stderr.
  "$binary" "$corpus" "$work/seeds/$h" -max_total_time="$seconds" -rss_limit_mb="$rss_limit" \
    -timeout="$timeout" -max_len="$(max_len_of "$h")" -print_final_stats=1 -close_fd_mask=3 \
    $(extra_flags_of "$h") \
    -artifact_prefix="$work/artifacts/$h/" >"$work/$h.log" 2>&1 || status=$?
  executions[$h]=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/$h.log" | tail -n 1)
  if [ -z "${executions[$h]}" ]; then  # a run that stopped prints no final stats: its last count
    executions[$h]=$(sed -n 's/^#\([0-9][0-9]*\).*/\1/p' "$work/$h.log" | tail -n 1)
  fi
  rate[$h]=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$work/$h.log" | tail -n 1)
  # A slow-unit or timeout artifact is an input that once took longer than 10 s; on a loaded
  # machine a fuzzer starved of CPU writes one for any input (a timeout also ends the run, exit
  # 70). Each counts as a finding only if it is slow again alone (rerun with -timeout).
  for artifact in "$work/artifacts/$h"/slow-unit-* "$work/artifacts/$h"/timeout-*; do
    [ -f "$artifact" ] || continue
    if "$binary" -rss_limit_mb="$rss_limit" -timeout="$timeout" "$artifact" >"$work/slow.log" 2>&1; then
      echo "fuzz_$h: $(basename "$artifact") reran in $(sed -n 's/^Executed .* in //p' "$work/slow.log"): slow only under load, not a finding"
      rm "$artifact"
      if [ "$status" -eq 70 ] && [ -z "$(ls -A "$work/artifacts/$h")" ]; then
        echo "fuzz_$h: the run stopped early at that input"
        status=0
      fi
    fi
  done
  if [ "$status" -ne 0 ] || [ -n "$(ls -A "$work/artifacts/$h")" ]; then
    grep -v '^#\|^INFO\|^stat::' "$work/$h.log" | tail -n 60
    mkdir -p "fuzz/findings/$h"
    cp "$work/artifacts/$h"/* "fuzz/findings/$h"/ 2>/dev/null || true
    for artifact in "$work/artifacts/$h"/*; do  # again with the reader's own messages shown
      [ -f "$artifact" ] || continue
      echo "-- rerun on $(basename "$artifact"):"
      "$binary" -rss_limit_mb="$rss_limit" -timeout="$timeout" "$artifact" >"$work/rerun.log" 2>&1 || true
      tail -n 40 "$work/rerun.log"
    done
    echo "fuzz_$h: exit $status; input(s) in fuzz/findings/$h/"
    failed+=("$h")
  fi
done

echo
printf '%-8s %14s %10s\n' harness executions exec/s
for h in "${harnesses[@]}"; do
  printf '%-8s %14s %10s\n' "$h" "${executions[$h]:-n/a}" "${rate[$h]:-n/a}"
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz.sh: findings in: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz.sh: no findings"
