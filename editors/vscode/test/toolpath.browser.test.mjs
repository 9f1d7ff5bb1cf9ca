// The toolpath page in a real browser (Debian's chromium driven by playwright-core): the
// moves are drawn, and clicking a move reports its source element. Writes a screenshot to
// test-artifacts/toolpath.png.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, dirname } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';

const here = dirname(fileURLToPath(import.meta.url));
const repo = join(here, '../../..');
const bin = process.env.MILLPATH_BIN || join(repo, 'target/release/millpath');
const browser = process.env.CHROMIUM || '/usr/bin/chromium';

test('the toolpath page draws every move and reports the clicked element', { skip: !existsSync(browser) && `no browser at ${browser}` }, async () => {
  const dir = mkdtempSync(join(tmpdir(), 'millpath-toolpath-'));
  const html = join(dir, 'toolpath.html');
  execFileSync(bin, ['render', join(repo, 'examples/text/2010.mpath'), '--html', html], { stdio: 'ignore' });
  const data = JSON.parse(/<script id="toolpath-data" type="application\/json">(.*?)<\/script>/s.exec(readFileSync(html, 'utf8'))[1].replace(/<\\\//g, '</'));
  const b = await chromium.launch({
    executablePath: browser,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  try {
    const page = await b.newPage({ viewport: { width: 900, height: 600 } });
    await page.goto(pathToFileURL(html).href);
    const count = await page.locator('svg .move').count();
    assert.equal(count, data.moves.length);
    assert.ok(count > 20, `${count} moves`);
    assert.equal(await page.locator('svg .move.mill').count(), data.moves.filter((m) => m.kind === 'mill').length);
    // a milling move of the embedded part: its source is the part's mill line
    const i = data.moves.findIndex((m) => m.kind === 'mill');
    const events = page.evaluate(() => new Promise((resolve) => window.addEventListener('millpath-select', (e) => resolve(e.detail), { once: true })));
    await page.locator(`svg .move[data-i="${i}"]`).dispatchEvent('click');
    const detail = await events;
    assert.equal(detail.index, i);
    assert.ok(detail.source.text.startsWith('mill (5, 0) -> (25, 0)'), detail.source.text);
    assert.ok(detail.source.file.endsWith('2001.mpath'));
    assert.match(await page.locator('#info').textContent(), /2001\.mpath:7/);
    assert.equal(await page.locator('svg .move.selected').count(), 1);
    mkdirSync(join(here, '../test-artifacts'), { recursive: true });
    await page.screenshot({ path: join(here, '../test-artifacts/toolpath.png') });
  } finally {
    await b.close();
  }
});
