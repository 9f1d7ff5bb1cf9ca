#!/usr/bin/env bash
# The Python package (crates/python) as a user gets it: a fresh virtual environment, the
# package installed as the README says (`pip install ./crates/python`, a release build by
# maturin that reuses target/release), then pytest (crates/python/tests): every example and
# shared drawing compiled through Python in every dialect equals the command line's files
# byte for byte, check's diagnostics equal `check --format json`'s (also on 1,000 random
# builder programs), the manual's three examples pass verify and LinuxCNC's rs274, hostile
# input raises. Prints the build and test times, the wheel's size and the import time.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
if ! command -v rs274 >/dev/null; then
  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q linuxcnc-uspace >/dev/null
fi
if [ -z "${MILLPATH_BIN:-}" ]; then
  cargo build --release --quiet -p millpath
  export MILLPATH_BIN="${CARGO_TARGET_DIR:-$PWD/target}/release/millpath"
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 -m venv "$tmp/venv" 2>/dev/null \
  || { apt-get update -q && apt-get install -y -q python3-venv && python3 -m venv "$tmp/venv"; }
py=$tmp/venv/bin/python3
# the README's command, built once: the wheel's size from pip's own line ("Created wheel for
# millpath: filename=… size=…"), not from a second build by `pip wheel`
"$py" -m pip install --disable-pip-version-check ./crates/python >"$tmp/install.log" 2>&1 \
  || { cat "$tmp/install.log"; exit 1; }
built=$SECONDS
wheel=$(sed -n 's/.*Created wheel for millpath: filename=\([^ ]*\) size=\([0-9]*\).*/\1 \2/p' "$tmp/install.log")
[ -n "$wheel" ] || { cat "$tmp/install.log"; echo "python: no wheel was built" >&2; exit 1; }
set -- $wheel
echo "python: installed in $((built - start)) s; wheel $1: $(($2 / 1024)) KiB"
"$py" -m pip install -q --disable-pip-version-check pytest hypothesis
# the import time of the package (its native module and the builder), best of five
"$py" - <<'PY'
import subprocess, sys
times = []
for _ in range(5):
    out = subprocess.run([sys.executable, "-X", "importtime", "-c", "import millpath"],
                         capture_output=True, text=True).stderr
    total = [int(l.split("|")[1]) for l in out.splitlines() if l.rstrip().endswith("| millpath")]
    times.append(total[0] / 1000)
print(f"python: import millpath takes {min(times):.1f} ms")
PY
# from outside the source tree: the installed package is the one imported
cd "$tmp"
t0=$SECONDS
"$py" -m pytest -q -p no:cacheprovider "$OLDPWD/crates/python/tests"
echo "python: tests in $((SECONDS - t0)) s, all in $((SECONDS - start)) s"
