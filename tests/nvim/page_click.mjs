// The Neovim plugin's toolpath page in real Chromium (playwright-core): waits until the page
// has drawn the data served by Neovim and highlights the element under Neovim's cursor, then
// clicks a move of that element for real (the page posts the click back to Neovim).
//   node tests/nvim/page_click.mjs URL
// Prints one JSON line: {drawn, highlighted, clicked: {line, gcodeLine}}.
import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const repo = join(dirname(fileURLToPath(import.meta.url)), '../..');
const { chromium } = createRequire(join(repo, 'editors/vscode/package.json'))('playwright-core');
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--no-first-run', '--disable-background-networking'],
});
try {
  const page = await browser.newPage({ viewport: { width: 900, height: 600 } });
  await page.goto(process.argv[2]);
  await page.waitForFunction(() => Number(document.body.dataset.moves) > 0, null, { timeout: 20000 });
  await page.waitForFunction(() => Number(document.body.dataset.highlighted) > 0, null, { timeout: 20000 });
  const [drawn, highlighted] = await page.evaluate(() => [Number(document.body.dataset.moves), Number(document.body.dataset.highlighted)]);
  // a cut of the highlighted element, clicked where it is drawn
  const target = await page.evaluate(() => {
    const w = window.millpathToolpath, d = w.data();
    const i = d.moves.findIndex((m, k) => m.kind !== 'rapid' && m.from[0] !== m.to[0] && w.highlighted().includes(k));
    return { i, xy: w.screenOf(i, 0.5), line: d.sources[d.moves[i].source].line, gcodeLine: d.moves[i].line };
  });
  const posted = page.waitForRequest((r) => r.url().endsWith('/click') && r.method() === 'POST');
  await page.mouse.click(target.xy[0], target.xy[1]);
  await posted;
  console.log(JSON.stringify({ drawn, highlighted, clicked: { line: target.line, gcodeLine: target.gcodeLine } }));
} finally {
  await browser.close();
}
