#!/usr/bin/env bash
# One HDRI panorama of the npm package @pmndrs/assets 1.7.0 (CC0-1.0) as an
# OpenEXR file: the package is fetched once with `npm pack` into CACHE
# (default: OUT's folder), and hdri/NAME.exr.js, a base64 data URL, decoded.
#   scripts/pmndrs-hdri.sh NAME OUT.exr [CACHE]
#   NAME: lobby, hall, lab, workshop, warehouse, studio, apartment, …
# Writes OUT only when whole (temp file + rename); exits non-zero with one
# message when npm cannot fetch the package or NAME is not in it.
set -euo pipefail
if (($# < 2)); then
  echo "usage: scripts/pmndrs-hdri.sh NAME OUT.exr [CACHE]" >&2
  exit 2
fi
name=$1 out=$2 cache=${3:-$(dirname "$2")}
version=1.7.0
mkdir -p "$cache" "$(dirname "$out")"
tgz="$cache/pmndrs-assets-$version.tgz"
if [ ! -f "$tgz" ]; then
  (cd "$cache" && npm pack --silent "@pmndrs/assets@$version" > /dev/null 2>&1) ||
    { echo "pmndrs-hdri: npm could not fetch @pmndrs/assets@$version" >&2; exit 1; }
fi
tmp="$out.tmp.$$"
trap 'rm -f "$tmp"' EXIT
if ! tar -xzOf "$tgz" "package/hdri/$name.exr.js" 2> /dev/null |
  sed -e "s/^export default 'data:application\/exr;base64,//" -e "s/'[; ]*$//" | base64 -d > "$tmp" ||
  [ ! -s "$tmp" ]; then
  echo "pmndrs-hdri: no hdri/$name.exr.js in @pmndrs/assets@$version" >&2
  exit 1
fi
mv "$tmp" "$out"
