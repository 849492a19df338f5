#!/usr/bin/env bash
# check_vectors.sh: the committed vectors/ must equal what the model
# generates now. A difference means the model changed without `make vectors`
# (or the vectors were edited by hand): regenerate, review the diff, commit.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
fresh="$root/build/vectors-fresh"
rm -rf "$fresh"
"$root/target/release/tbgen" gen --all --out "$fresh" > /dev/null
if diff -r -q --exclude=README.md "$root/vectors" "$fresh"; then
    echo "vectors: committed vectors equal freshly generated ones ($(find "$fresh" -name '*.hex' | wc -l) scenarios)"
else
    echo "vectors: committed vectors differ from the model's output; run 'make vectors', review and commit" >&2
    exit 1
fi
