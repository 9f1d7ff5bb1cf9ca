// Bundles the page (src/main.js with CodeMirror and wasm-bindgen's glue) with esbuild into
// OUT/assets/, copies the wasm and writes OUT/index.html. The examples (examples/text) and
// the toolpath viewer page (editors/toolpath/toolpath.html, built from editors/toolpath/src
// and checked against it in CI) go into the bundle: the site needs nothing else.
// Usage: node build.mjs GLUE_DIR OUT_DIR (build.sh passes them).
import { build } from 'esbuild';
import { copyFileSync, mkdirSync, readFileSync, readdirSync, rmSync, writeFileSync, statSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const repo = join(here, '../..');
const [glue, out] = process.argv.slice(2).map((p) => resolve(p));
if (!glue || !out) { console.error('usage: node build.mjs GLUE_DIR OUT_DIR'); process.exit(2); }

const exampleDir = join(repo, 'examples/text');
const examples = Object.fromEntries(readdirSync(exampleDir)
  .filter((n) => n.endsWith('.mpath') || n === 'millpath.toml')
  .sort()
  .map((n) => [n, readFileSync(join(exampleDir, n), 'utf8')]));
const viewer = readFileSync(join(repo, 'editors/toolpath/toolpath.html'), 'utf8');

// virtual modules: the examples, the viewer page, the wasm glue
const virtual = {
  name: 'virtual',
  setup(b) {
    b.onResolve({ filter: /^virtual:/ }, (a) => ({ path: a.path, namespace: 'virtual' }));
    b.onLoad({ filter: /.*/, namespace: 'virtual' }, (a) => {
      if (a.path === 'virtual:examples') return { contents: JSON.stringify(examples), loader: 'json' };
      if (a.path === 'virtual:viewer') return { contents: viewer, loader: 'text' };
      return null;
    });
    b.onResolve({ filter: /^millpath-wasm$/ }, () => ({ path: join(glue, 'millpath_wasm.js') }));
  },
};

rmSync(out, { recursive: true, force: true });
mkdirSync(join(out, 'assets'), { recursive: true });
await build({
  entryPoints: [join(here, 'src/main.js')],
  bundle: true,
  minify: true,
  format: 'esm',
  target: 'es2022',
  legalComments: 'none',
  outfile: join(out, 'assets/playground.js'),
  plugins: [virtual],
  logLevel: 'warning',
});
copyFileSync(join(glue, 'millpath_wasm_bg.wasm'), join(out, 'assets/millpath.wasm'));
writeFileSync(join(out, 'index.html'), readFileSync(join(here, 'src/index.html'), 'utf8'));
for (const f of ['index.html', 'assets/playground.js', 'assets/millpath.wasm']) {
  console.log(`${f.padEnd(24)} ${statSync(join(out, f)).size} bytes`);
}
