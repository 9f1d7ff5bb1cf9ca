// The tmLanguage tokenizer of the page over the examples: kinds, path names, comments,
// numbers and parameters get their classes (the grammar itself is kept in step with
// crates/syntax by the repository's grammar tests).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { join, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import { compile, tokenizeLine, styleOf } from '../src/tmgrammar.js';

const repo = join(dirname(fileURLToPath(import.meta.url)), '../../..');
const grammar = JSON.parse(readFileSync(join(repo, 'grammar/millpath.tmLanguage.json'), 'utf8'));

function classes(text) {
  const stack = [compile(grammar)];
  return text.split('\n').map((line) => tokenizeLine(line, stack).map((k) => [line.slice(k.from, k.to), styleOf(k.scopes)]));
}

test('a path with every kind of token', () => {
  const got = classes('# head\npath 2001.1P {\n  start (0, -1.5)  M10x3 O2  # c\n  mill (5, 0) -> (25, 0)  D2\n  drill (1, 2) d3\n}\n');
  assert.deepEqual(got[0], [['# head', 'comment']]);
  assert.deepEqual(got[1].filter((k) => k[1]), [['path', 'keyword'], ['2001.1P', 'name'], ['{', 'brace']]);
  const start = got[2].filter((k) => k[1]);
  assert.deepEqual(start, [['start', 'kind'], ['0', 'number'], ['-1.5', 'number'], ['M10x3', 'param'], ['O2', 'param'], ['# c', 'comment']]);
  assert.deepEqual(got[3].filter((k) => k[1]).map((k) => k[1]), ['kind', 'number', 'number', 'operator', 'number', 'number', 'param']);
  assert.deepEqual(got[4].filter((k) => k[1]).map((k) => k[1]), ['kind', 'number', 'number', 'number']);
  assert.deepEqual(got[5], [['}', 'brace']]);
});

test('every element line of the examples starts with its kind', () => {
  const dir = join(repo, 'examples/text');
  for (const f of readdirSync(dir).filter((n) => n.endsWith('.mpath'))) {
    const text = readFileSync(join(dir, f), 'utf8');
    const lines = text.split('\n');
    classes(text).forEach((toks, i) => {
      const word = lines[i].trim().split(/\s+/)[0];
      const styled = toks.filter((k) => k[1]);
      if (['start', 'end', 'mill', 'mark', 'sweep', 'sub', 'probe', 'drill'].includes(word)) assert.deepEqual(styled[0], [word, 'kind'], `${f}:${i + 1}`);
      if (word.startsWith('#')) assert.equal(styled[0][1], 'comment', `${f}:${i + 1}`);
      if (word === 'path') assert.equal(styled[1][1], 'name', `${f}:${i + 1}`);
    });
  }
});
