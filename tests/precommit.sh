#!/usr/bin/env bash
# The pre-commit hooks (.pre-commit-hooks.yaml) against a scratch repository: pre-commit from
# PyPI in a venv, a good and a bad .mpath, the hooks used both as `repo: local` and from this
# repository at its current commit. Prints "N passed, M failed".
set -uo pipefail
cd "$(dirname "$0")/.."
repo="$PWD"
target="${CARGO_TARGET_DIR:-target}"
if [ ! -x "$target/release/millpath" ]; then
  cargo build --release --quiet -p millpath || exit 1
fi
export PATH="$(cd "$target/release" && pwd):$PATH"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export PRE_COMMIT_HOME="$work/cache"
python3 -m venv "$work/venv" || { echo "python3 -m venv failed (apt-get install python3-venv)"; exit 1; }
"$work/venv/bin/pip" install -q pre-commit || { echo "pip install pre-commit failed"; exit 1; }
pc="$work/venv/bin/pre-commit"
rev="$(git rev-parse HEAD)"
passed=0
failed=0
expect() { # expect pass|fail DESCRIPTION -- command...
  local want="$1" what="$2"
  shift 3
  local out status
  out="$("$@" 2>&1)"
  status=$?
  if { [ "$want" = pass ] && [ $status -eq 0 ]; } || { [ "$want" = fail ] && [ $status -ne 0 ]; }; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL: $what (expected to $want, exit $status)"
    echo "$out" | sed 's/^/    /'
  fi
}

good='path 3000.1P {
  start (0, 0)  M3 O2 T3 I1,5 B-0,2
  end (20, 0)
  mill (0, 0) -> (20, 0)
}'
bad='path 3000.2P {
  start (0, 0)  M3 O2 T3 I1,5 B-0,2
  end (20, 0)
  mill (0, 0) -> (10, 0)
}'   # the mill line stops 10 mm short of the end marker

for form in local rev; do
  dir="$work/$form"
  mkdir -p "$dir" && cd "$dir" || exit 1
  git init -q . && git config user.email ci@example.com && git config user.name ci
  printf 'feed = 300\nsweep_speed = 1000\nsweep_height = 10\n' > millpath.toml
  echo "$good" > good.mpath
  echo "$bad" > bad.mpath
  if [ $form = local ]; then
    cat > .pre-commit-config.yaml <<'YAML'
repos:
  - repo: local
    hooks:
      - id: millpath-check
        name: millpath check
        entry: millpath check
        language: system
        files: '\.(mpath|dxf|DXF)$'
YAML
  else
    cat > .pre-commit-config.yaml <<YAML
repos:
  - repo: $repo
    rev: $rev
    hooks:
      - id: millpath-check
      - id: millpath-fmt
YAML
  fi
  git add -A
  expect pass "$form: good file" -- "$pc" run millpath-check --files good.mpath
  expect fail "$form: bad file" -- "$pc" run millpath-check --files bad.mpath
  sed -i 's/(10, 0)$/(20, 0)/' bad.mpath   # fixed: the line reaches the end marker
  git add -A
  expect pass "$form: bad file after fixing" -- "$pc" run millpath-check --all-files
  if [ $form = rev ]; then
    printf 'path 3000.3P {\nstart (0, 0)    M3 O2 T3 I1,5 B-0,2\n  end (20, 0)\n  mill (0, 0) -> (20, 0)\n}\n' > ugly.mpath
    git add -A
    expect fail "$form: unformatted file" -- "$pc" run millpath-fmt --files ugly.mpath
    millpath fmt ugly.mpath >/dev/null
    git add -A
    expect pass "$form: file after millpath fmt" -- "$pc" run millpath-fmt --all-files
  fi
  cd "$repo" || exit 1
done

echo "pre-commit hooks: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
