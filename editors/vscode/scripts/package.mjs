// Packages the extension for one target platform (`vsce package --target`): the .vsix brings
// the millpath binary of that platform in server/. The target is the build platform's
// (linux-x64, darwin-arm64, win32-x64, …) unless VSCE_TARGET says otherwise; a .vsix for another
// platform needs MILLPATH_BIN pointing at that platform's binary. `VSCE_TARGET=universal`
// packages without a server: the extension then uses millpath.server.path or `millpath` on PATH.
// Writes millpath-<target>.vsix and a copy as millpath.vsix.
import { spawnSync } from 'node:child_process';
import { copyFileSync, rmSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const target = process.env.VSCE_TARGET || `${process.platform}-${process.arch}`;
const run = (cmd, args) => {
  const r = spawnSync(cmd, args, { cwd: root, stdio: 'inherit', shell: process.platform === 'win32' });
  if (r.status !== 0) process.exit(r.status ?? 1);
};
rmSync(join(root, 'server'), { recursive: true, force: true });
const out = `millpath-${target}.vsix`;
if (target === 'universal') {
  run('npx', ['vsce', 'package', '--no-dependencies', '--allow-missing-repository', '-o', out]);
} else {
  run(process.execPath, [join(root, 'scripts/bundle-server.mjs')]);
  run('npx', ['vsce', 'package', '--no-dependencies', '--allow-missing-repository', '--target', target, '-o', out]);
}
copyFileSync(join(root, out), join(root, 'millpath.vsix'));
console.log(`packaged ${out} (and millpath.vsix)`);
