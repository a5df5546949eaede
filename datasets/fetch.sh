#!/usr/bin/env bash
# Fetches the reference data surfcomp ships itself: downloads the Debian packages named in
# datasets/manifest.tsv with `apt-get download`, extracts the listed files into datasets/cache
# and checks each against its sha256. Idempotent: verified files are not fetched again.
# Usage: datasets/fetch.sh [--print-hashes]   (--print-hashes: show hashes, do not check them)
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cache="$here/cache"
manifest="$here/manifest.tsv"
print_hashes=0
[ "${1:-}" = "--print-hashes" ] && print_hashes=1

mkdir -p "$cache/debs"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

failed=0
while IFS=$'\t' read -r cache_path package member sha; do
  case "$cache_path" in ''|'#'*) continue ;; esac
  target="$cache/$cache_path"
  if [ "$print_hashes" -eq 0 ] && [ -f "$target" ] && \
     [ "$(sha256sum "$target" | cut -d' ' -f1)" = "$sha" ]; then
    continue
  fi
  deb=$(ls "$cache/debs/${package}"_*.deb 2>/dev/null | head -n 1 || true)
  if [ -z "$deb" ]; then
    (cd "$cache/debs" && apt-get download -q -o APT::Sandbox::User="$(id -un)" "$package" >/dev/null) || {
      echo "fetch: cannot download Debian package '$package' (run 'apt-get update' as root?)" >&2
      exit 1
    }
    deb=$(ls "$cache/debs/${package}"_*.deb | head -n 1)
  fi
  if [ ! -d "$work/$package" ]; then dpkg-deb -x "$deb" "$work/$package"; fi
  source_file="$work/$package/$member"
  case "$member" in
    *//*)  # a file inside a tarball of the package: TARBALL//PATH
      tarball="${member%%//*}"
      unpacked="$work/tar/$package/$tarball"
      if [ ! -d "$unpacked" ]; then
        mkdir -p "$unpacked"
        tar -xzf "$work/$package/$tarball" -C "$unpacked"
      fi
      source_file="$unpacked/${member#*//}"
      ;;
  esac
  if [ ! -f "$source_file" ]; then
    echo "fetch: $package has no $member" >&2
    failed=1
    continue
  fi
  mkdir -p "$(dirname "$target")"
  case "$member" in
    *//*) cp "$source_file" "$target.part" ;;
    *.gz) gzip -dc "$source_file" > "$target.part" ;;
    *) cp "$source_file" "$target.part" ;;
  esac
  actual=$(sha256sum "$target.part" | cut -d' ' -f1)
  if [ "$print_hashes" -eq 1 ]; then
    printf '%s\t%s\n' "$cache_path" "$actual"
    mv "$target.part" "$target"
  elif [ "$actual" != "$sha" ]; then
    echo "fetch: $cache_path from $deb has sha256 $actual, manifest says $sha" >&2
    rm -f "$target.part"
    failed=1
  else
    mv "$target.part" "$target"
  fi
done < "$manifest"

[ "$failed" -eq 0 ] || exit 1
echo "fetch: datasets/cache is complete and verified"
