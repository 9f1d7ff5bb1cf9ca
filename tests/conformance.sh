#!/usr/bin/env bash
# Runs ../shared/conformance/run.py against the release binary (skips when ../shared is absent).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f ../shared/conformance/run.py ]; then
  echo "skipped: ../shared/conformance is not there"
  exit 0
fi
cargo build --release --quiet
python3 ../shared/conformance/run.py --bin target/release/millpath
