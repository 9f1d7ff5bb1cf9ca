#!/usr/bin/env bash
# Builds the release artefacts (scripts/release.sh) and checks them as a user gets them: the
# Linux binary is static and passes the conformance cases and the README's command, the .exe
# is a Windows x64 program and passes the conformance cases under Wine, each .vsix holds the
# server of its platform, the Linux wheel installs as the README says and the Windows one runs
# in Windows CPythons under Wine (tests/windows.sh), SHA256SUMS matches. Not part of .ci/run:
# four more release builds (musl, Windows, the two wheels) would cost CI about 20 minutes on
# two cores; run it before a release.
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
wheel_linux() {
  local d
  d=$(mktemp -d)
  python3 -m venv "$d/venv" && "$d/venv/bin/pip" install -q --no-index --find-links "$a" millpath &&
    "$d/venv/bin/python3" -c "import millpath, sys; r = millpath.compile(open(sys.argv[1], 'rb').read(), file_name='1234.1P.dxf', settings={'feed': 300, 'sweep_speed': 1000, 'sweep_height': 10}); assert r.files, r.diagnostics" examples/plate/1234.1P.dxf
}
wheel_windows() {
  local d
  d=$(mktemp -d)
  python3 -c "import zipfile,sys; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])" "$(ls "$a"/millpath-*-cp39-abi3-win_amd64.whl)" "$d"
  file "$d/millpath/_native.pyd" | grep -q 'PE32+ executable (DLL).*x86-64' &&
    x86_64-w64-mingw32-objdump -p "$d/millpath/_native.pyd" | grep -q 'PyInit__native' &&
    x86_64-w64-mingw32-objdump -p "$d/millpath/_native.pyd" | grep -q 'DLL Name: python3.dll'
}
check "the Linux wheel installs as the README says and compiles the example" wheel_linux
check "the Windows wheel: _native.pyd exports PyInit__native and needs only python3.dll" wheel_windows
# the .exe of the release under Wine: conformance, command line, language server
check "the release millpath.exe and Windows wheel under Wine (tests/windows.sh)" \
  env MILLPATH_WINE_EXE="$PWD/$a/millpath.exe" \
  MILLPATH_WINE_WHEEL="$PWD/$(ls "$a"/millpath-*-cp39-abi3-win_amd64.whl)" bash tests/windows.sh
ls -l "$a"
echo "release artefacts: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
