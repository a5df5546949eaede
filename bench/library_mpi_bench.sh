#!/usr/bin/env bash
# A library built with one process and with `mpirun -np R`, and a build killed (SIGKILL) halfway
# then resumed: the times, the peak resident memory per process, and whether the three libraries
# have the same bytes (the index and every shard). Not part of the test command
# (docs/benchmarks.md#library-builds-across-processes-library_mpi_bench).
#
# Usage: bench/library_mpi_bench.sh INPUT WORKDIR [SURFCOMP] [R] [BUILD OPTIONS...]
#   INPUT    molecule files for `library build` (e.g. an SDF of conformers with coordinates)
#   WORKDIR  a folder for the libraries (made; earlier libraries in it are removed)
#   SURFCOMP the program (default build/release/tools/surfcomp)
#   R        processes of the MPI build (default 2); the threads are split so that both runs use
#            $(nproc) cores
set -euo pipefail
input=${1:?usage: library_mpi_bench.sh INPUT WORKDIR [SURFCOMP] [R] [BUILD OPTIONS...]}
work=${2:?usage: library_mpi_bench.sh INPUT WORKDIR [SURFCOMP] [R] [BUILD OPTIONS...]}
surfcomp=${3:-build/release/tools/surfcomp}
ranks=${4:-2}
shift $(($# < 4 ? $# : 4))
options=("$@")
cores=$(nproc)
threads=$(((cores + ranks - 1) / ranks))
mpirun=(mpirun --oversubscribe --bind-to none -np "$ranks")
[ "$(id -u)" -ne 0 ] || mpirun+=(--allow-run-as-root)

# Each library in a folder of its own under one name: an index names its shard folder.
mkdir -p "$work"
rm -rf "$work"/one "$work"/mpi "$work"/resumed
mkdir -p "$work"/one "$work"/mpi "$work"/resumed

# Runs a command under /usr/bin/time -v; prints its wall time and peak RSS (of the largest
# process: mpirun's children report theirs through their own time -v).
timed() {
  local label=$1
  shift
  local start=$SECONDS
  /usr/bin/time -f "$label: %e s wall, peak RSS %M KB" "$@" >"$work/$label.out" 2>"$work/$label.err" ||
    { tail -5 "$work/$label.err"; return 1; }
  grep -E "^$label: " "$work/$label.err"
  grep -E "records ->|core time" "$work/$label.err" | sed 's/^/    /' || true
  echo "    ($((SECONDS - start)) s)"
}

# Whether two libraries have the same bytes: the index (or the file) and every shard.
same_library() {
  cmp -s "$1" "$2" || return 1
  if [ -d "$1.d" ]; then
    for shard in "$1.d"/*.sclib; do cmp -s "$shard" "$2.d/$(basename "$shard")" || return 1; done
  fi
}

echo "library_mpi_bench: $input, $cores cores; one process x $cores threads against $ranks x $threads"
timed one "$surfcomp" library build "$input" -o "$work/one/lib.sclib" --threads "$cores" "${options[@]}"
timed mpi "${mpirun[@]}" /usr/bin/time -f "mpi rank: peak RSS %M KB" \
  "$surfcomp" library build "$input" -o "$work/mpi/lib.sclib" --threads "$threads" "${options[@]}"
grep "mpi rank:" "$work/mpi.err" | sed 's/^/    /'
shards=$( (find "$work/one/lib.sclib.d" -name '*.sclib' 2>/dev/null || true) | wc -l)
if same_library "$work/one/lib.sclib" "$work/mpi/lib.sclib"; then
  echo "same bytes: one process and $ranks processes ($shards shards)"
else
  echo "DIFFERENT bytes: one process and $ranks processes"
  exit 1
fi

# The build killed once half the shards are written, then resumed.
"$surfcomp" library build "$input" -o "$work/resumed/lib.sclib" --threads "$cores" "${options[@]}" \
  >"$work/killed.out" 2>"$work/killed.err" &
pid=$!
while kill -0 "$pid" 2>/dev/null; do
  done_shards=$( (find "$work/resumed/lib.sclib.d" -name '*.sclib' 2>/dev/null || true) | wc -l)
  [ "$done_shards" -lt $((shards / 2)) ] || break
  sleep 0.2
done
kill -9 "$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
kept=$( (find "$work/resumed/lib.sclib.d" -name '*.sclib' 2>/dev/null || true) | wc -l)
echo "killed (SIGKILL) with $kept of $shards shards written"
timed resumed "$surfcomp" library build "$input" -o "$work/resumed/lib.sclib" --threads "$cores" \
  --resume "${options[@]}"
if same_library "$work/one/lib.sclib" "$work/resumed/lib.sclib"; then
  echo "same bytes: uninterrupted and resumed after SIGKILL"
else
  echo "DIFFERENT bytes: uninterrupted and resumed"
  exit 1
fi
