#!/usr/bin/env bash
# Time and peak resident memory of screens of one large library (made by
# bench/library_scale_bench): one query and several in one pass, on all cores of one process and
# with `mpirun -np 2` (each process its share of the cores). Not part of the test command
# (docs/benchmarks.md#screening-at-scale-screen_scale_bench).
#
# Usage: bench/screen_scale_bench.sh LIB WORKDIR SURFCOMP QUERY1 [QUERY2 ...]
#   Runs, each under /usr/bin/time: QUERY1 with the default stages; QUERY1 and all the queries
#   with --refine 0 (stage 1, then stage 3 of the candidates), in one process and under mpirun;
#   and QUERY1 with the default stages under mpirun. SCREEN_RUNS="a b ..." picks some of
#   one_default one_fast all_fast mpi_one_fast mpi_all_fast mpi_one_default.
set -euo pipefail
lib=${1:?usage: screen_scale_bench.sh LIB WORKDIR SURFCOMP QUERY1 [QUERY2 ...]}
work=${2:?usage}
surfcomp=${3:?usage}
shift 3
queries=("$@")
[ "${#queries[@]}" -ge 1 ] || { echo "screen_scale_bench: give at least one query" >&2; exit 2; }
cores=$(nproc)
mpirun=(mpirun --oversubscribe --bind-to none -np 2)
[ "$(id -u)" -ne 0 ] || mpirun+=(--allow-run-as-root)
runs=${SCREEN_RUNS:-one_default one_fast all_fast mpi_one_fast mpi_all_fast mpi_one_default}
mkdir -p "$work"
echo "screen_scale_bench: $lib ($(du -h "$lib" | cut -f1)), $cores cores"

screen() {
  local label=$1
  shift
  /usr/bin/time -f "$label: %e s wall, peak RSS %M KB" "$@" >"$work/$label.out" 2>"$work/$label.err" ||
    { tail -5 "$work/$label.err"; return 1; }
  cat "$work/$label.out" "$work/$label.err" | grep -E "^$label|entries, .* quer|rank:" | sed 's/^/    /'
}

for run in $runs; do
  case $run in
    one_default) screen one_default "$surfcomp" screen "${queries[0]}" "$lib" -o "$work/one_default.csv" \
                   --threads "$cores" ;;
    one_fast) screen one_fast "$surfcomp" screen "${queries[0]}" "$lib" -o "$work/one_fast.csv" \
                --threads "$cores" --refine 0 ;;
    all_fast) screen all_fast "$surfcomp" screen "${queries[@]}" "$lib" -o "$work/all_fast.csv" \
                --threads "$cores" --refine 0 ;;
    mpi_one_fast) screen mpi_one_fast "${mpirun[@]}" /usr/bin/time -f "rank: peak RSS %M KB" \
                    "$surfcomp" screen "${queries[0]}" "$lib" -o "$work/mpi_one_fast.csv" \
                    --threads $((cores / 2)) --refine 0
                  cmp "$work/mpi_one_fast.csv" "$work/one_fast.csv" && echo "    same table as one process" ;;
    mpi_all_fast) screen mpi_all_fast "${mpirun[@]}" /usr/bin/time -f "rank: peak RSS %M KB" \
                    "$surfcomp" screen "${queries[@]}" "$lib" -o "$work/mpi_all_fast.csv" \
                    --threads $((cores / 2)) --refine 0
                  cmp "$work/mpi_all_fast.csv" "$work/all_fast.csv" && echo "    same fused table as one process" ;;
    mpi_one_default) screen mpi_one_default "${mpirun[@]}" /usr/bin/time -f "rank: peak RSS %M KB" \
                       "$surfcomp" screen "${queries[0]}" "$lib" -o "$work/mpi_one_default.csv" \
                       --threads $((cores / 2))
                     cmp "$work/mpi_one_default.csv" "$work/one_default.csv" && echo "    same table as one process" ;;
    *) echo "screen_scale_bench: unknown run $run" >&2; exit 2 ;;
  esac
done
