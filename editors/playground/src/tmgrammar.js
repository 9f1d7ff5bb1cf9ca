// A line tokenizer that runs grammar/millpath.tmLanguage.json itself (the grammar the
// repository's tests keep in step with crates/syntax), so the playground highlights as VS
// Code does without a second grammar. TextMate rules: at each position the earliest match
// among the context's patterns and its end wins (the end on a tie); `begin` pushes a
// context, `end` pops it; a context that ends at `$` ends with its line.
// Pure JavaScript without the DOM: the node test runs it over the examples.

/** The grammar's contexts: {patterns: [{re, name, captures, push}], end, endCaptures, endsAtEol}. */
export function compile(grammar) {
  const repo = grammar.repository || {};
  const flat = (patterns) => patterns.flatMap((p) => (p.include ? flat([repo[p.include.slice(1)]]) : [p]));
  const rule = (p) => ({
    re: new RegExp(p.match || p.begin, 'gd'),
    name: p.name || null,
    captures: p.captures || p.beginCaptures || null,
    push: p.begin ? ctx(p) : null,
  });
  const ctxs = new Map();
  function ctx(p) {
    if (ctxs.has(p)) return ctxs.get(p);
    const c = { name: p.name || null, end: null, endCaptures: null, endsAtEol: false, patterns: [] };
    ctxs.set(p, c);
    if (p.end !== undefined) {
      c.end = new RegExp(p.end, 'gd');
      c.endCaptures = p.endCaptures || null;
      c.endsAtEol = p.end === '$';
    }
    c.patterns = flat(p.patterns || []).map(rule);
    return c;
  }
  return ctx({ patterns: grammar.patterns });
}

/** The tokens of `line` from context stack `stack` (changed in place): [{from, to, scopes}]. */
export function tokenizeLine(line, stack) {
  const out = [];
  const emit = (from, to, scopes) => { if (to > from) out.push({ from, to, scopes: scopes.filter(Boolean) }); };
  const scopeOf = () => stack.map((c) => c.name);
  let pos = 0;
  for (let guard = 0; guard < 10000; guard++) {
    const top = stack[stack.length - 1];
    let best = null;
    const tryRe = (re, kind, r) => {
      re.lastIndex = pos;
      const m = re.exec(line);
      if (m && (!best || m.index < best.m.index)) best = { m, kind, r };
    };
    if (top.end && !top.endsAtEol) tryRe(top.end, 'end');
    for (const r of top.patterns) tryRe(r.re, 'rule', r);
    if (!best) break;
    const { m } = best;
    const start = m.index, end = start + m[0].length;
    emit(pos, start, scopeOf());
    if (best.kind === 'end') {
      captured(m, top.endCaptures, scopeOf(), emit);
      stack.pop();
    } else if (best.r.push) {
      const scopes = [...scopeOf(), best.r.name];
      captured(m, best.r.captures, scopes, emit);
      stack.push(best.r.push);
    } else {
      captured(m, best.r.captures, [...scopeOf(), best.r.name], emit);
    }
    // a zero-length match that changes nothing must not stop the walk
    pos = end > pos || best.kind === 'end' || (best.r && best.r.push) ? end : pos + 1;
    if (pos > line.length) break;
  }
  emit(pos, line.length, scopeOf());
  while (stack.length > 1 && stack[stack.length - 1].endsAtEol) stack.pop();
  return out;
}

/** A match, cut into its captured groups (each with its own scope) and the rest. */
function captured(m, captures, scopes, emit) {
  const start = m.index, end = start + m[0].length;
  if (!captures || !m.indices) { emit(start, end, scopes); return; }
  let at = start;
  const groups = Object.keys(captures).map(Number).filter((g) => m.indices[g]).sort((a, b) => m.indices[a][0] - m.indices[b][0]);
  for (const g of groups) {
    const [s, e] = m.indices[g];
    if (s < at) continue;
    emit(at, s, scopes);
    emit(s, e, [...scopes, captures[g].name]);
    at = e;
  }
  emit(at, end, scopes);
}

/** The highlight class of a token's innermost scope that has one. */
export function styleOf(scopes) {
  for (let i = scopes.length - 1; i >= 0; i--) {
    const s = scopes[i];
    if (s.startsWith('comment')) return 'comment';
    if (s.startsWith('keyword.control')) return 'kind';
    if (s.startsWith('keyword.operator')) return 'operator';
    if (s.startsWith('keyword')) return 'keyword';
    if (s.startsWith('entity.name')) return 'name';
    if (s.startsWith('constant.numeric')) return 'number';
    if (s.startsWith('string')) return 'string';
    if (s.startsWith('variable.parameter')) return 'param';
    if (s.startsWith('punctuation')) return 'brace';
  }
  return null;
}
