// Puts the millpath binary of the target platform into server/, so the .vsix brings its
// server. The target is VSCE_TARGET (win32-x64, linux-x64, darwin-arm64, …), else this
// platform's; a Windows target's server is server/millpath.exe. Uses MILLPATH_BIN, else the
// release build of the repository.
import { copyFileSync, mkdirSync, chmodSync, existsSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const target = process.env.VSCE_TARGET || `${process.platform}-${process.arch}`;
const windows = target.startsWith('win32-');
const exe = windows ? 'millpath.exe' : 'millpath';
const src = process.env.MILLPATH_BIN || join(root, '../../target/release', exe);
if (!existsSync(src)) {
  console.error(`no server binary at ${src}: run 'cargo build --release' first`);
  process.exit(1);
}
mkdirSync(join(root, 'server'), { recursive: true });
copyFileSync(src, join(root, 'server', exe));
chmodSync(join(root, 'server', exe), 0o755);
// smaller download: drop debug information when a strip for the target's format is there
// (MinGW's for a Windows .exe built on Linux)
const strips = windows && process.platform !== 'win32' ? ['x86_64-w64-mingw32-strip'] : ['strip'];
const stripped = strips.some((s) => {
  const r = spawnSync(s, ['--strip-debug', join(root, 'server', exe)]);
  return !r.error && r.status === 0;
});
if (!stripped) console.log('strip not available: bundling the binary as it is');
console.log(`bundled ${src} as server/${exe} (${target})`);
