#!/usr/bin/env bash
# The pull-request diff in CI (action.yml's `diff: true`; the GitLab job of
# docs/src/version-control.md): writes the markdown report of the drawings changed between
# BASE and HEAD on stdout and one PNG picture per changed drawing into DIR
# (DIR/<path with / as _>.png). Exit 0 (changed or not), 2 when millpath or git fails.
# Usage: bash scripts/ci-diff.sh BASE DIR   (in the repository, millpath on PATH)
set -uo pipefail
base=$1
mkdir -p "$2" && dir=$(cd "$2" && pwd) || exit 2
cd "$(git rev-parse --show-toplevel)" || exit 2
status=0
millpath diff "$base..HEAD" --format markdown || status=$?
[ "$status" -le 1 ] || exit 2
# the drawings git lists as changed, as millpath diff lists them (deleted ones have no picture)
while IFS= read -r -d '' file; do
  status=0
  millpath diff "$base..HEAD" --png "$dir/${file//\//_}.png" -- "$file" >/dev/null || status=$?
  [ "$status" -le 1 ] || exit 2
done < <(git diff --name-only --diff-filter=d -M -z "$base" HEAD -- '*.dxf' '*.DXF' '*.mpath')
