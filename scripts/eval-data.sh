#!/usr/bin/env bash
# The broad tuning set's meshes (docs/denoising.md#the-evaluation, "The broad tuning set"): CGAL's
# demo data as Debian 12 ships it, package libcgal-demo 5.5.1-2, unpacked into
# build/eval-data/cgal-demo/meshes. Nothing of it is committed. Idempotent: a complete unpack is
# kept; a partial one (no stamp) is replaced.
#   scripts/eval-data.sh
set -euo pipefail
cd "$(dirname "$0")/.."
want=5.5.1-2
dest=build/eval-data/cgal-demo
stamp="$dest/.unpacked-$want"
[ -f "$stamp" ] && exit 0
command -v apt-get >/dev/null || { echo "eval-data: apt-get not found: the broad set needs Debian's libcgal-demo $want" >&2; exit 1; }
have=$(apt-cache policy libcgal-demo 2>/dev/null | awk '/Candidate:/{print $2}')
if [ -z "$have" ] || [ "$have" = "(none)" ]; then
  sudo=""; [ "$(id -u)" = 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  have=$(apt-cache policy libcgal-demo | awk '/Candidate:/{print $2}')
fi
[ "$have" = "$want" ] || { echo "eval-data: libcgal-demo $want wanted, the package index offers '$have'" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && apt-get download -qq "libcgal-demo=$want" 2>/dev/null)
dpkg-deb -x "$work"/libcgal-demo_*.deb "$work/x"
mkdir -p "$work/data"
tar -xzf "$work/x/usr/share/doc/libcgal-dev/data.tar.gz" -C "$work/data" data/meshes
rm -rf "$dest"
mkdir -p "$dest"
mv "$work/data/data/meshes" "$dest/meshes"
touch "$stamp"
echo "eval-data: $(ls "$dest/meshes" | wc -l) files of libcgal-demo $want in $dest/meshes" >&2
