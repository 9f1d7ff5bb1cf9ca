// Puts the millpath binary of this platform into server/, so the .vsix brings its server.
// Uses MILLPATH_BIN, else the release build of the repository.
import { copyFileSync, mkdirSync, chmodSync, existsSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const exe = process.platform === 'win32' ? 'millpath.exe' : 'millpath';
const src = process.env.MILLPATH_BIN || join(root, '../../target/release', exe);
if (!existsSync(src)) {
  console.error(`no server binary at ${src}: run 'cargo build --release' first`);
  process.exit(1);
}
mkdirSync(join(root, 'server'), { recursive: true });
copyFileSync(src, join(root, 'server', exe));
chmodSync(join(root, 'server', exe), 0o755);
// smaller download: drop debug information when `strip` is there
const strip = spawnSync('strip', ['--strip-debug', join(root, 'server', exe)]);
if (strip.error || strip.status !== 0) console.log('strip not available: bundling the binary as it is');
console.log(`bundled ${src}`);
