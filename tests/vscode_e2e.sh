#!/usr/bin/env bash
# The extension inside a real VS Code: code-server 4.100.3 (VS Code 1.100.3, from npm) with the
# packaged .vsix installed, opened in Debian's chromium driven by playwright-core
# (editors/vscode/test/e2e/vscode.e2e.mjs), on a workspace holding copies of the examples.
# Needs the release build of millpath (in $CARGO_TARGET_DIR or target/) and
# editors/vscode/millpath.vsix (npm run package bundles that build).
# Prints 'ok - …' / 'not ok - …' per check and 'N passed, M failed'; screenshots in
# editors/vscode/test-artifacts/vscode-*.png.
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$PWD"
vsix="$repo/editors/vscode/millpath.vsix"
bin="${CARGO_TARGET_DIR:-$repo/target}/release/millpath"
[ -x "$bin" ] || cargo build --release --quiet
[ -f "$vsix" ] || (cd editors/vscode && MILLPATH_BIN="$bin" npm run package >/dev/null)
[ -d editors/vscode/node_modules/playwright-core ] || (cd editors/vscode && npm ci --no-audit --no-fund)
if [ ! -x /usr/bin/chromium ]; then
  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium
fi
code_server="$(bash tests/vscode_e2e_install.sh)"

tmp="$(mktemp -d)"
pid=""
cleanup() {
  if [ -n "$pid" ]; then kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; fi
  if [ -n "${KEEP_TMP:-}" ]; then echo "kept $tmp"; else rm -rf "$tmp"; fi
}
trap cleanup EXIT
ws="$tmp/workspace"
mkdir -p "$ws" "$tmp/user/User" "$tmp/extensions"
cp examples/text/*.mpath examples/text/millpath.toml examples/plate/1234.1P.dxf "$ws/"
# a drawing with an error that is never opened: the workspace pull shows it in Problems
printf 'path 3002.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (50, 0)\n  sweep (0, 0) -> (10, 10)\n  mill (10, 10) -> (40, 10)  O-3\n  sweep (40, 10) -> (50, 0)\n}\n' >"$tmp/3002.mpath"
"$bin" text2dxf "$tmp/3002.mpath" -o "$ws/3002.dxf" >/dev/null
# a git repository (the diff editor's effect summary opens git's changes of a drawing)
git -C "$ws" init -q
git -C "$ws" add -A
git -C "$ws" -c user.email=e2e@millpath.invalid -c user.name=e2e commit -qm "the examples"
cat > "$tmp/user/User/settings.json" <<'JSON'
{
  "security.workspace.trust.enabled": false,
  "workbench.startupEditor": "none",
  "workbench.tips.enabled": false,
  "workbench.enableExperiments": false,
  "telemetry.telemetryLevel": "off",
  "update.mode": "none",
  "extensions.autoCheckUpdates": false,
  "extensions.autoUpdate": false,
  "extensions.ignoreRecommendations": true,
  "editor.codeLens": true,
  "millpath.trace.server": "messages",
  "files.autoSave": "off",
  "editor.minimap.enabled": false,
  "editor.hover.delay": 100,
  "files.simpleDialog.enable": true,
  "workbench.colorTheme": "Default Dark Modern",
  "chat.commandCenter.enabled": false,
  "workbench.secondarySideBar.defaultVisibility": "hidden"
}
JSON
cs=("$code_server" --config "$tmp/config.yaml" --user-data-dir "$tmp/user" --extensions-dir "$tmp/extensions")
"${cs[@]}" --install-extension "$vsix" >"$tmp/install.log" 2>&1 || { cat "$tmp/install.log"; exit 1; }
port="$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')"
"${cs[@]}" --auth none --bind-addr "127.0.0.1:$port" --disable-telemetry --disable-update-check \
  --disable-workspace-trust --disable-getting-started-override --ignore-last-opened "$ws" \
  >"$tmp/code-server.log" 2>&1 &
pid=$!
for _ in $(seq 1 120); do
  curl -sf -o /dev/null "http://127.0.0.1:$port/healthz" && break
  kill -0 "$pid" 2>/dev/null || { cat "$tmp/code-server.log"; exit 1; }
  sleep 0.5
done
status=0
VSCODE_URL="http://127.0.0.1:$port/?folder=$ws" WORKSPACE="$ws" USER_DATA_DIR="$tmp/user" \
  timeout 900 node editors/vscode/test/e2e/vscode.e2e.mjs || status=$?
if [ "$status" -ne 0 ]; then
  echo "--- code-server log (tail)"; tail -n 30 "$tmp/code-server.log"
fi
exit "$status"
