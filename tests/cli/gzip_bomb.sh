#!/usr/bin/env bash
# A gzip that inflates past the 1 GiB cap is refused by name within a memory limit below the cap: the
# decompressed data are counted before they are held.
#   gzip_bomb.sh IMPACTLAB   (not under a sanitizer: its shadow memory does not fit a ulimit)
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$(mktemp -d "${TMPDIR:-/tmp}/impactlab_gzip_bomb.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 2
head -c 1200M /dev/zero | gzip -1 >z.csv.gz   # 1.2 GB of zeros in about 1 MB
out=$( (ulimit -v 1000000 && "$exe" fit z.csv.gz --model A1H --report r) 2>&1)
rc=$?
[[ $rc == 2 ]] || { echo "FAIL: exit status $rc, expected 2: $out"; exit 1; }
grep -q "z.csv.gz: decompressed data exceed 1 GiB" <<<"$out" || { echo "FAIL: $out"; exit 1; }
echo "gzip_bomb: refused within a 1 GB address space: $out"
