#!/usr/bin/env bash
# Checks that the C++ sources conform to .clang-format (every tracked file) and .clang-tidy (the
# library and the program; tests and benchmarks are held to the format only).
#
# clang-tidy is most of the lint's time (about 13 minutes on 2 cores for every file), so it checks
# the translation units whose result can differ from the commit named in .ci/tidy-clean, at which
# every one was clean: those whose source or any file they include changed since, by the build's
# own dependency record (`ninja -t deps`). It checks every file when that commit is not an
# ancestor of HEAD, when the checks, a CMake file or this script changed since, when a file has
# no dependency record in BUILD_DIR, or with --all. A commit at which `scripts/lint.sh --all`
# passed may be written into .ci/tidy-clean.
#
# Usage: scripts/lint.sh [--all] [BUILD_DIR]   BUILD_DIR holds compile_commands.json and a Ninja
# build of it (default build/ci).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
all=0
if [ "${1:-}" = "--all" ]; then
  all=1
  shift
fi
build=${1:-build/ci}
if [ ! -f "$build/compile_commands.json" ]; then
  echo "lint: $build/compile_commands.json not found; configure first (cmake --preset ci)" >&2
  exit 2
fi

git ls-files '*.cpp' '*.hpp' | xargs clang-format --dry-run --Werror
echo "lint: clang-format clean"

mapfile -t sources < <(git ls-files 'core/*.cpp' 'mesh/*.cpp' 'harmonic/*.cpp' 'matching/*.cpp' \
  'screening/*.cpp' 'report/*.cpp' 'tools/*.cpp' 'python/*.cpp')
clean=$(tr -d '[:space:]' < .ci/tidy-clean 2>/dev/null || true)
reason=""
if [ "$all" = 1 ]; then
  reason="--all"
elif [ -z "$clean" ] || ! git merge-base --is-ancestor "$clean" HEAD 2>/dev/null; then
  reason="no clean commit in .ci/tidy-clean that HEAD descends from"
elif [ -n "$(git diff --name-only "$clean" -- .clang-tidy scripts/lint.sh CMakePresets.json \
               'CMakeLists.txt' '*/CMakeLists.txt' '*.cmake' '*.cmake.in')" ]; then
  reason="the checks or the build changed since $clean"
elif [ ! -f "$build/.ninja_deps" ]; then
  reason="$build has no Ninja dependency record"
fi

selected=("${sources[@]}")
if [ -z "$reason" ]; then
  # Files changed since the clean commit (committed or not), as absolute paths; each source with
  # the files it includes, from the build's record; a source is checked when one of those changed
  # or when the record lacks it.
  changed=$(mktemp)
  trap 'rm -f "$changed"' EXIT
  git diff --name-only "$clean" | sed "s|^|$PWD/|" > "$changed"
  mapfile -t selected < <(
    ninja -C "$build" -t deps | awk -v root="$PWD/" -v changed_list="$changed" \
      -v list="$(printf '%s\n' "${sources[@]}")" '
      BEGIN {
        while ((getline line < changed_list) > 0) changed[line] = 1
        n = split(list, names, "\n")
        for (i = 1; i <= n; ++i) if (names[i] != "") wanted[root names[i]] = names[i]
      }
      /^[^ ]/ { source = ""; next }
      /^    / {
        path = substr($0, 5)
        if (source == "") { source = path; seen[source] = 1 }
        if (path in changed) dirty[source] = 1
      }
      END { for (path in wanted) if (!(path in seen) || (path in dirty)) print wanted[path] }' |
      sort)
  echo "lint: clang-tidy over ${#selected[@]} of ${#sources[@]} files (the others are as at" \
    "$clean, where every file was clean)"
else
  echo "lint: clang-tidy over all ${#sources[@]} files ($reason)"
fi

# GCC's warning flags in the compile commands are unknown to clang; -Wno-unknown-warning-option
# keeps them from failing the run.
if [ "${#selected[@]}" -gt 0 ]; then
  printf '%s\n' "${selected[@]}" |
    xargs -P "$(nproc)" -n 4 clang-tidy -p "$build" --quiet \
      --extra-arg=-Wno-unknown-warning-option 2>/dev/null
fi
echo "lint: clang-tidy clean"
