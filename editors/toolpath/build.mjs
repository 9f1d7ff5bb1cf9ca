// Builds toolpath.html: src/viewer.js bundled with three.js (esbuild, pinned versions) and
// inlined into src/template.html, so the page is one file with no network at run time.
// `node build.mjs --check` fails when the committed page differs from its sources (CI).
import { build } from 'esbuild';
import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const out = join(here, 'toolpath.html');
const result = await build({
  entryPoints: [join(here, 'src/viewer.js')],
  bundle: true,
  minify: true,
  format: 'iife',
  target: 'es2020',
  legalComments: 'none',
  write: false,
  logLevel: 'warning',
});
const js = result.outputFiles[0].text.replace(/<\/(script)/gi, '<\\/$1');
const template = readFileSync(join(here, 'src/template.html'), 'utf8');
const three = JSON.parse(readFileSync(join(here, 'node_modules/three/package.json'), 'utf8')).version;
const page = template.replace('<!--BUNDLE-->', () => `<script>/* three.js ${three} (MIT), bundled */\n${js}</script>`);
if (process.argv.includes('--check')) {
  const committed = readFileSync(out, 'utf8');
  if (committed !== page) {
    console.error('editors/toolpath/toolpath.html is not up to date with src/: run `npm run build` in editors/toolpath');
    process.exit(1);
  }
  console.log('toolpath.html is up to date');
} else {
  writeFileSync(out, page);
  console.log(`wrote ${out} (${page.length} bytes)`);
}
