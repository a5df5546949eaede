#!/usr/bin/env bash
# Runs the suites labelled `threaded` (tests/CMakeLists.txt) under ThreadSanitizer.
#
# ThreadSanitizer sees a thread join, a task steal or a lock only in instrumented code, and
# Debian's libtbb is not instrumented: against it every parallel loop reports races inside TBB's
# own header code. So this script first builds the same oneTBB as the installed libtbb-dev from
# Debian's source package, with TBB_SANITIZE=thread, into build/tbb-tsan (kept between runs), then
# builds the `tsan` preset against it and runs the threaded suites; the preset's TSAN_OPTIONS name
# tests/tsan.supp, which suppresses nothing: every threaded library the suites call is then
# instrumented.
#
# Usage: scripts/tsan.sh [CTEST_ARGS...]   e.g. scripts/tsan.sh -R Match
# Needs: the packages of scripts/install-deps.sh and access to Debian's source archive (once).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$PWD
jobs=$(nproc)
tbb_prefix=$root/build/tbb-tsan
version=$(dpkg-query -W -f='${Version}' libtbb-dev)

if [ "$(cat "$tbb_prefix/VERSION" 2>/dev/null)" != "$version" ]; then
  echo "tsan.sh: building oneTBB $version with ThreadSanitizer into $tbb_prefix"
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  mkdir -p "$work/apt/lists/partial" "$work/apt/cache/archives/partial"
  # The machine's own Debian sources (mirror, proxy or snapshot included), as deb-src.
  mkdir -p "$work/apt/sources.list.d"
  touch "$work/apt/sources.list"
  if [ -f /etc/apt/sources.list ]; then
    sed -n 's/^deb /deb-src /p' /etc/apt/sources.list > "$work/apt/sources.list"
  fi
  for f in /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    case $f in
      *.list) sed -n 's/^deb /deb-src /p' "$f" > "$work/apt/sources.list.d/$(basename "$f")" ;;
      *.sources) sed 's/^Types:.*/Types: deb-src/' "$f" > "$work/apt/sources.list.d/$(basename "$f")" ;;
    esac
  done
  apt_options=(-q -o "Dir::Etc::SourceList=$work/apt/sources.list"
               -o "Dir::Etc::SourceParts=$work/apt/sources.list.d"
               -o "Dir::State::Lists=$work/apt/lists" -o "Dir::Cache=$work/apt/cache")
  apt-get "${apt_options[@]}" update >/dev/null || true  # a source without deb-src is not fatal
  (cd "$work" && apt-get "${apt_options[@]}" source --download-only "onetbb=$version" >/dev/null) || {
    echo "tsan.sh: Debian's source archive has no onetbb $version (the installed libtbb-dev)" >&2
    exit 1
  }
  (cd "$work" && dpkg-source --no-check -x onetbb_*.dsc src >/dev/null)
  cmake -S "$work/src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBBMALLOC_BUILD=OFF -DTBB_STRICT=OFF \
    -DCMAKE_INSTALL_PREFIX="$tbb_prefix" >/dev/null
  cmake --build "$work/build" -j "$jobs" >/dev/null
  rm -rf "$tbb_prefix"
  cmake --install "$work/build" >/dev/null
  echo "$version" > "$tbb_prefix/VERSION"
fi

launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake --preset tsan "${launcher[@]}" -DTBB_DIR="$tbb_prefix/lib/cmake/TBB" >/dev/null
cmake --build --preset tsan -j "$jobs" --target threaded_tests
# Left out here (the asan suite runs them all): tests whose parallel code a faster test of the
# same suite runs with several threads, on larger structures or other options (SES of every
# thermolysin structure: Ses.Protein4we2; matches of moved copies, thermolysin ligands, with
# masks, principal-axes starts, polishing or refine-top 0: Match.TheThreadCountDoesNotChangeThe
# Alignments, Match.SurfaceAgainstItselfGivesTheIdentity, Match.SiteMatchWithoutCliques...; a
# pocket library screened: Screen.QueryInTheLibraryFindsItselfFirstWithTheIdentity; LP cut-off
# sums: Potentials.ProteinSizedCaseAgreesWithASerialSum; critical points of thermolysin
# ligands: Descriptors.ResultDoesNotDependOnTheThreadCount; a library of .hsi files:
# LibraryBuild.ConformersShareTheirMolecule...), and the .hsi reader's tests, which read files
# in one thread; what they cost under ThreadSanitizer is in
# docs/benchmarks.md#threadsanitizer.
slow='^(Ses\.AllThermolysinStructuresGiveClosedSurfaces|Match\.MovedCopyOfASurfaceRecoversTheMotion'
slow+='|Match\.ThermolysinLigandsAlignFromRandomPoses|Match\.PrincipalAxesStartsJoinTheRefinedAlignments'
slow+='|Match\.AnAllTrueMaskInWholeSurfaceModeChangesNothing|Match\.PolishedAlignmentsScoreAtLeastAsHighAndStayOrdered'
slow+='|Match\.RefinedAlignmentsLeadByOverlayScoreAndRefineTopZeroKeepsTheConsensus'
slow+='|Screen\.SiteQueryFindsItsOwnPocketFirstAndKindsDoNotMix|LipophilicPotential\.CutoffSumsExactlyTheNearAtomsWithinItsBound'
slow+='|Descriptors\.ThermolysinCriticalPointCountsAreOfTheThesisOrder'
slow+='|LibraryBuild\.HsiFilesBecomeEntriesThatKeepTheirSurfaceAndFindThemselves|HsiFile\..*)$'
ctest --preset tsan -L threaded -E "$slow" -j "$jobs" "$@"
