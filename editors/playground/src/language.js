// The .mpath language for CodeMirror: a StreamLanguage over the tmLanguage tokenizer.
import { StreamLanguage, HighlightStyle, syntaxHighlighting } from '@codemirror/language';
import { tags as t } from '@lezer/highlight';
import grammar from '../../../grammar/millpath.tmLanguage.json';
import { compile, tokenizeLine, styleOf } from './tmgrammar.js';

const root = compile(grammar);

const mpath = StreamLanguage.define({
  name: 'millpath',
  startState: () => ({ stack: [root], queue: [] }),
  copyState: (s) => ({ stack: s.stack.slice(), queue: s.queue.slice() }),
  token(stream, state) {
    if (stream.sol()) {
      // the whole line at once; CodeMirror then takes the tokens one by one
      state.queue = tokenizeLine(stream.string, state.stack).map((k) => ({ to: k.to, style: styleOf(k.scopes) }));
    }
    while (state.queue.length && state.queue[0].to <= stream.pos) state.queue.shift();
    const next = state.queue.shift();
    if (!next) { stream.skipToEnd(); return null; }
    stream.pos = next.to;
    return next.style;
  },
  blankLine(state) { tokenizeLine('', state.stack); },
  tokenTable: {
    comment: t.lineComment, kind: t.controlKeyword, keyword: t.keyword, operator: t.operator,
    name: t.definition(t.typeName), number: t.number, string: t.string, param: t.attributeName, brace: t.brace,
  },
  languageData: { commentTokens: { line: '#' } },
});

const style = HighlightStyle.define([
  { tag: t.lineComment, color: 'var(--c-comment)', fontStyle: 'italic' },
  { tag: t.controlKeyword, color: 'var(--c-kind)', fontWeight: '600' },
  { tag: t.keyword, color: 'var(--c-keyword)' },
  { tag: t.operator, color: 'var(--c-keyword)' },
  { tag: t.definition(t.typeName), color: 'var(--c-name)', fontWeight: '600' },
  { tag: t.number, color: 'var(--c-number)' },
  { tag: t.string, color: 'var(--c-string)' },
  { tag: t.attributeName, color: 'var(--c-param)' },
]);

export const millpathLanguage = [mpath, syntaxHighlighting(style)];
