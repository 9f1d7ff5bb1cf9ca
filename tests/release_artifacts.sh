#!/usr/bin/env bash
# Builds the release artefacts (scripts/release.sh, the same parts the release workflow runs)
# and checks them as a user gets them: the Linux binary is static and passes the conformance
# cases and the README's command, the .exe is a Windows x64 program and passes the conformance
# cases under Wine, each .vsix holds the server of its platform, the Linux wheel is manylinux2014
# (auditwheel and its symbols agree: glibc 2.17) and installs as the README says, the Windows
# one runs in Windows CPythons under Wine (tests/windows.sh), SHA256SUMS matches. Prints the
# wheels' sizes and the import time. Not part of .ci/run: four more release builds (musl,
# Windows, the two wheels: 3-17 min each) make it about 40 minutes on two shared cores, then
# 3 minutes while they are built (Wine: 2); run it before a release.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/release.sh
a=target/release-artifacts
passed=0
failed=0
check() {
  local name=$1
  shift
  if "$@" >/tmp/millpath-release-check.log 2>&1; then
    echo "ok - $name"; passed=$((passed + 1))
  else
    echo "not ok - $name"; sed 's/^/    /' /tmp/millpath-release-check.log | head -30; failed=$((failed + 1))
  fi
}
static() { file "$a/millpath-linux-x64" | grep -q 'statically linked\|static-pie linked' && ! ldd "$a/millpath-linux-x64" 2>/dev/null | grep -q '=>'; }
check "millpath-linux-x64 is static (file, ldd)" static
check "millpath.exe is a Windows x64 program" bash -c "file '$a/millpath.exe' | grep -q 'PE32+ executable.*x86-64'"
check "SHA256SUMS matches" bash -c "cd '$a' && sha256sum -c SHA256SUMS"
readme() {
  local d
  d=$(mktemp -d)
  cp examples/plate/1234.1P.dxf examples/plate/millpath.toml "$d/"
  (cd "$d" && "$OLDPWD/$a/millpath-linux-x64" compile 1234.1P.dxf) && test -s "$d/1234.1P_Milling.gcode"
}
check "the README's command with the static binary" readme
if [ -f ../shared/conformance/run.py ]; then
  check "conformance with the static binary" python3 ../shared/conformance/run.py --bin "$a/millpath-linux-x64"
else
  echo "skipped: ../shared/conformance is not there"
fi
vsix_server() { # VSIX FILE PATTERN: the .vsix holds extension/server/FILE of that kind
  local d
  d=$(mktemp -d)
  python3 -c "import zipfile,sys; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])" "$1" "$d"
  file "$d/extension/server/$2" | grep -q "$3" && [ "$(ls "$d/extension/server")" = "$2" ]
}
check "millpath-win32-x64.vsix: server/millpath.exe, a Windows x64 program" \
  vsix_server "$a/millpath-win32-x64.vsix" millpath.exe 'PE32+ executable.*x86-64'
check "millpath-linux-x64.vsix: server/millpath, a static Linux program" \
  vsix_server "$a/millpath-linux-x64.vsix" millpath 'ELF 64-bit.*static'
# the Python wheels: the Linux one installs in a fresh venv by the README's command and
# compiles the example; the Windows one holds a .pyd, a Windows x64 DLL exporting the module's
# entry that needs only python3.dll (the abi3 DLL), and runs in tests/windows.sh below
wheel_venv=
wheel_linux() {
  local d
  d=$(mktemp -d)
  wheel_venv=$d/venv
  python3 -m venv "$d/venv" && "$d/venv/bin/pip" install -q --no-index --find-links "$a" millpath &&
    "$d/venv/bin/python3" -c "import millpath, sys; r = millpath.compile(open(sys.argv[1], 'rb').read(), file_name='1234.1P.dxf', settings={'feed': 300, 'sweep_speed': 1000, 'sweep_height': 10}); assert r.files, r.diagnostics" examples/plate/1234.1P.dxf
}
wheel_windows() {
  local d
  d=$(mktemp -d)
  python3 -c "import zipfile,sys; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])" "$(ls "$a"/millpath-*-cp39-abi3-win_amd64.whl)" "$d"
  # objdump's output in a file: `objdump | grep -q` fails under pipefail when grep stops
  # reading early (objdump gets SIGPIPE)
  x86_64-w64-mingw32-objdump -p "$d/millpath/_native.pyd" >"$d/pe.txt" &&
    file "$d/millpath/_native.pyd" | grep 'PE32+ executable (DLL).*x86-64' &&
    grep -E '\] PyInit__native$' "$d/pe.txt" &&
    [ "$(grep -io 'DLL Name: python[0-9]*\.dll' "$d/pe.txt")" = "DLL Name: python3.dll" ]
}
# the manylinux tag: maturin's name, auditwheel's verdict (PyPI's, pinned) and the module's
# glibc symbol versions, none newer than 2.17
wheel_tag() {
  local w d
  w=$(ls "$a"/millpath-*-cp39-abi3-*manylinux_2_17_x86_64*.whl)
  [ -x "$venv/bin/auditwheel" ] || "$venv/bin/pip" install -q 'auditwheel>=6.8,<7'
  "$venv/bin/auditwheel" show "$w" | tr -s ' \n' ' ' | grep -q 'consistent with the following platform tag: "manylinux_2_17_x86_64"' &&
    d=$(mktemp -d) &&
    python3 -c "import zipfile,sys; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])" "$w" "$d" &&
    objdump -T "$d"/millpath/_native*.so | grep -o 'GLIBC_[0-9.]*' | sort -uV | tail -1 |
    python3 -c "import sys; v = sys.stdin.read().strip(); print(v); assert tuple(map(int, v[6:].split('.'))) <= (2, 17), v"
}
venv=target/release-venv
check "the Linux wheel is manylinux2014: glibc 2.17 (auditwheel show, objdump -T)" wheel_tag
check "the Linux wheel installs as the README says and compiles the example" wheel_linux
check "the Windows wheel: _native.pyd exports PyInit__native and needs only python3.dll" wheel_windows
# the .exe of the release under Wine: conformance, command line, language server
check "the release millpath.exe and Windows wheel under Wine (tests/windows.sh)" \
  env MILLPATH_WINE_EXE="$PWD/$a/millpath.exe" \
  MILLPATH_WINE_WHEEL="$PWD/$(ls "$a"/millpath-*-cp39-abi3-win_amd64.whl)" bash tests/windows.sh
ls -l "$a"
# the figures for the release notes: the wheels' sizes, the import time (best of five, fresh venv)
for w in "$a"/millpath-*.whl; do echo "wheel $(basename "$w"): $(($(stat -c %s "$w") / 1024)) KiB"; done
if [ -x "${wheel_venv:-}/bin/python3" ]; then
  "$wheel_venv/bin/python3" - <<'PY'
import subprocess, sys
times = []
for _ in range(5):
    out = subprocess.run([sys.executable, "-X", "importtime", "-c", "import millpath"],
                         capture_output=True, text=True).stderr
    times += [int(l.split("|")[1]) / 1000 for l in out.splitlines() if l.rstrip().endswith("| millpath")]
print(f"import millpath (the Linux wheel) takes {min(times):.1f} ms")
PY
fi
echo "release artefacts: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
