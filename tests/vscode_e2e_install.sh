#!/usr/bin/env bash
# Installs code-server (VS Code 1.100.3 in a browser) from npm into a cache directory outside
# the repository, so that later runs reuse it. Prints the code-server executable.
# Only the package registries are reachable: @vscode/ripgrep's postinstall, which downloads rg
# from elsewhere, is given Debian's rg through its download cache.
set -euo pipefail
version=4.100.3
dir="${MILLPATH_CODE_SERVER_DIR:-$HOME/.cache/millpath-code-server}"
exe="$dir/node_modules/.bin/code-server"
if [ -f "$dir/installed-$version" ] && [ -x "$exe" ]; then
  echo "$exe"
  exit 0
fi
need=()
for p in libkrb5-dev libxkbfile-dev libsecret-1-dev libx11-dev pkg-config ripgrep python3 make g++; do
  dpkg -s "$p" >/dev/null 2>&1 || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${need[@]}"; } >&2
fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
# @vscode/ripgrep looks for $TMPDIR/vscode-ripgrep-cache-<its version>/ripgrep-<rg version>-<target>.tar.gz
for v in 1.15.11 1.15.10 1.15.9; do
  mkdir -p "$tmp/vscode-ripgrep-cache-$v"
  for rgv in v13.0.0-10 v13.0.0-13; do
    tar czf "$tmp/vscode-ripgrep-cache-$v/ripgrep-$rgv-x86_64-unknown-linux-musl.tar.gz" -C /usr/bin rg
  done
done
rm -rf "$dir"
mkdir -p "$dir"
cd "$dir"
echo '{"name":"millpath-code-server","private":true}' > package.json
# npm 11 runs no dependency's install scripts unless allowed; code-server's postinstall runs
# `npm install` in lib/vscode (native modules), which inherits the setting through the
# environment
TMPDIR="$tmp" npm_config_unsafe_perm=true npm_config_nodedir=/usr npm_config_yes=true \
  npm_config_dangerously_allow_all_scripts=true \
  npm install --no-audit --no-fund --loglevel=warn "code-server@$version" >&2
test -e "$dir/node_modules/code-server/lib/vscode/node_modules/node-pty/build/Release/pty.node" \
  || { echo "code-server's postinstall did not build its native modules" >&2; exit 1; }
"$exe" --config "$tmp/config.yaml" --version >&2
touch "installed-$version"
echo "$exe"
