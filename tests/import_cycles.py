#!/usr/bin/env python3
"""No import circles: every crate's module graph and the crate graph have no cycle.

A module's edges are the modules whose items its non-test code names: `use crate::…`,
`use super::…`, `use self::…`, a path to a child module, and `crate::…`/`super::…` paths in
expressions and types. A name is followed through re-exports (`pub use a::B`, globs) to the
module that defines it, so a façade `mod.rs` that re-exports its children is no edge of its own
unless its own code uses what it re-exports; a module's private `use` is. Method calls on a type
another module extends (`impl Session` in `build/`) are not seen. `#[cfg(test)]` items, test modules and `tests/` are left out.

Prints every strongly connected component of more than one module, with the references that
make it, and fails when one is not on the allow-list (ALLOWED, meant to be empty).

Usage: python3 tests/import_cycles.py [--graph] [--architecture]
  --graph         also print every crate's module edges
  --architecture  also check ARCHITECTURE.md: at most 15,000 characters, every file it names
                  exists
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CRATES = os.path.join(ROOT, "crates")

# cycles still to be broken, as printed after "cycle in crates/" (to be emptied)
ALLOWED = {
    "dxf: (crate root), entity, extra, tokens",
    "ide: (crate root), common, formatting, preview",
    "verify: (crate root), checks, clamps, execute, machine, reread, stock, stock_view, stream, surface_frame",
}

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"


def strip_comments_and_strings(src):
    """The source with comments, string and char literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(src)
    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            j = n if j < 0 else j
            i = j
            continue
        if src.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if src.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif src.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append("\n" * src.count("\n", i, j))
            i = j
            continue
        m = re.match(r'b?r(#*)"', src[i:i + 300]) if c in "rb" and (i == 0 or not (src[i - 1].isalnum() or src[i - 1] == "_")) else None
        if m:
            end = '"' + m.group(1)
            j = src.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append('""' + "\n" * src.count("\n", i, j))
            i = j
            continue
        if c == '"':
            j = i + 1
            while j < n and src[j] != '"':
                j += 2 if src[j] == "\\" else 1
            out.append('""' + "\n" * src.count("\n", i, j))
            i = j + 1
            continue
        if c == "'":
            m = re.match(r"'(\\(x..|u\{[0-9a-fA-F]+\}|.)|[^\\'])'", src[i:i + 16])
            if m:
                out.append("' '")
                i += m.end()
                continue
        out.append(c)
        i += 1
    return "".join(out)


def matching_end(text, i):
    """Index after the item starting at i: its `;` or its balanced `{…}` block."""
    depth = 0
    n = len(text)
    while i < n:
        c = text[i]
        if c in "([":
            depth += 1
        elif c in ")]":
            depth -= 1
        elif c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0:
                return i + 1
        elif c == ";" and depth == 0:
            return i + 1
        i += 1
    return n


TEST_CFG = re.compile(r"#\[cfg\((test|all\(test\b[^\]]*)\)\]")


def drop_test_items(text):
    """The text without `#[cfg(test)]` items; also the names of test modules declared `mod x;`."""
    test_mods = []
    while True:
        m = TEST_CFG.search(text)
        if not m:
            return text, test_mods
        j = m.end()
        # further attributes of the same item
        while True:
            k = re.match(r"\s*#\[", text[j:])
            if not k:
                break
            j = text.index("]", j) + 1
        decl = re.match(r"\s*(pub(\([^)]*\))?\s+)?mod\s+(" + IDENT + r")\s*;", text[j:])
        if decl:
            test_mods.append(decl.group(3))
        end = matching_end(text, j)
        text = text[: m.start()] + "\n" * text.count("\n", m.start(), end) + text[end:]


class Module:
    def __init__(self, crate, path, file):
        self.crate, self.path, self.file = crate, path, file
        self.text = ""
        self.children = set()
        self.items = set()          # names defined here
        self.imports = {}           # name -> (absolute path, public?)
        self.globs = []             # (absolute module path, public?)
        self.refs = []              # (absolute path, line)


def module_files(crate_dir):
    """{module path tuple: file} of a crate, from its root's `mod` tree."""
    src = os.path.join(crate_dir, "src")
    root = "lib.rs" if os.path.exists(os.path.join(src, "lib.rs")) else "main.rs"
    found = {}

    def visit(path, file):
        text = strip_comments_and_strings(open(file, encoding="utf-8").read())
        text, test_mods = drop_test_items(text)
        found[path] = (file, text)
        here = os.path.dirname(file)
        base = os.path.basename(file)
        own_dir = here if base in ("lib.rs", "main.rs", "mod.rs") else os.path.join(here, base[:-3])
        for m in re.finditer(r"(?m)^\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+(" + IDENT + r")\s*;", text):
            name = m.group(1)
            for cand in (os.path.join(own_dir, name + ".rs"), os.path.join(own_dir, name, "mod.rs")):
                if os.path.exists(cand):
                    visit(path + (name,), cand)
                    break

    visit((), os.path.join(src, root))
    return found


def split_use_tree(tree):
    """`a::{b, c::{d, *}}` -> ["a::b", "a::c::d", "a::c::*"] (whitespace removed)."""
    tree = re.sub(r"\s+", "", tree)
    out = []

    def walk(prefix, t):
        parts, depth, cur = [], 0, ""
        for c in t:
            if c == "," and depth == 0:
                parts.append(cur)
                cur = ""
                continue
            depth += c == "{"
            depth -= c == "}"
            cur += c
        parts.append(cur)
        for p in parts:
            b = p.find("{")
            if b >= 0:
                walk(prefix + p[:b], p[b + 1 : p.rindex("}")])
            elif p:
                out.append(prefix + p)

    walk("", tree)
    return out


def parse_crate(name, crate_dir):
    files = module_files(crate_dir)
    mods = {}
    for path, (file, text) in files.items():
        m = Module(name, path, file)
        m.text = text
        mods[path] = m
    for path in mods:
        if path:
            mods[path[:-1]].children.add(path[-1])
    item_re = re.compile(
        r"(?m)^\s*(?:pub(?:\([^)]*\))?\s+)?(?:unsafe\s+|const\s+|async\s+|extern\s+\"\"\s+)*"
        r"(?:fn|struct|enum|const|static|type|trait|union|mod)\s+(" + IDENT + ")"
    )
    for m in mods.values():
        m.items.update(x.group(1) for x in item_re.finditer(m.text))
        for x in re.finditer(r"macro_rules!\s*(" + IDENT + ")", m.text):
            m.items.add(x.group(1))
            exported = "#[macro_export]" in m.text[max(0, x.start() - 200) : x.start()]
            if exported:
                mods[()].imports[x.group(1)] = (m.path + (x.group(1),), True)
    for m in mods.values():
        text = m.text
        use_spans = []
        for u in re.finditer(r"(?s)(pub(?:\([^)]*\))?\s+)?\buse\s+([^;]*);", text):
            use_spans.append((u.start(), u.end()))
            public = bool(u.group(1))
            line = text.count("\n", 0, u.start()) + 1
            # `x as y`: the item x, known here as y
            raw = re.sub(r"\b(" + IDENT + r")\s+as\s+(" + IDENT + r")\b", r"\1@\2", u.group(2))
            for p in split_use_tree(raw):
                p, _, alias = p.partition("@")
                absolute = resolve_start(mods, m.path, [s for s in p.split("::") if s])
                if absolute is None:
                    continue
                if absolute[-1] == "*":
                    absolute = absolute[:-1]
                    m.globs.append((absolute, public))
                else:
                    if absolute[-1] == "self":
                        absolute = absolute[:-1]
                    if absolute:
                        m.imports[alias or absolute[-1]] = (absolute, public)
                # a re-export is a façade, not a dependency of the module's own code
                if not public and absolute:
                    m.refs.append((absolute, line))

        def in_use(pos):
            return any(a <= pos < b for a, b in use_spans)

        # a name re-exported here and also used by this module's own code is a dependency too
        code = text
        for a, b in reversed(use_spans):
            code = code[:a] + " " * (b - a) + code[b:]
        code = re.sub(r"\bmod\s+" + IDENT + r"\s*;", "", code)
        for name, (absolute, public) in m.imports.items():
            if public:
                hit = re.search(r"(?<![A-Za-z0-9_])" + re.escape(name) + r"(?![A-Za-z0-9_])", code)
                if hit:
                    m.refs.append((absolute, text.count("\n", 0, hit.start()) + 1))

        for r in re.finditer(r"(?<![A-Za-z0-9_:])((?:crate|super|self)(?:::(?:" + IDENT + "))+)", text):
            if in_use(r.start()):
                continue
            absolute = resolve_start(mods, m.path, r.group(1).split("::"))
            if absolute is not None:
                m.refs.append((absolute, text.count("\n", 0, r.start()) + 1))
        # a child module's name used as a path in the module's code (2018 paths)
        for child in m.children:
            for r in re.finditer(r"(?<![A-Za-z0-9_:])" + child + r"::(" + IDENT + ")", text):
                if in_use(r.start()):
                    continue
                m.refs.append((m.path + (child, r.group(1)), text.count("\n", 0, r.start()) + 1))
    return mods


def resolve_start(mods, here, segs):
    """An absolute path (tuple from the crate root) for a path written in module `here`."""
    if not segs:
        return None
    if segs[0] == "crate":
        return tuple(segs[1:]) if len(segs) > 1 else None
    cur = here
    i = 0
    if segs[0] in ("self", "super"):
        while i < len(segs) and segs[i] in ("self", "super"):
            if segs[i] == "super":
                if not cur:
                    return None
                cur = cur[:-1]
            i += 1
        return cur + tuple(segs[i:]) if i < len(segs) else (cur + ("self",) if cur else None)
    if segs[0] in mods.get(here, Module("", (), "")).children:
        return here + tuple(segs)
    return None  # another crate, std, or a local name


def defining_module(mods, path, depth=0):
    """The module that defines the item `path` names (following re-exports), or the deepest
    module on the path."""
    if depth > 20:
        return None
    i = 0
    cur = ()
    while i < len(path) and cur + (path[i],) in mods:
        cur = cur + (path[i],)
        i += 1
    if i == len(path):
        return cur
    name = path[i]
    m = mods[cur]
    if name in m.items:
        return cur
    if name in m.imports:
        target, _ = m.imports[name]
        if target != path:
            found = defining_module(mods, target, depth + 1)
            if found is not None:
                return found
    for g, _ in m.globs:
        if g in mods and g != cur:
            found = defining_module(mods, g + (name,), depth + 1)
            if found is not None and found != g or (found == g and name in mods[g].items):
                return found
    return cur


def graph(mods):
    edges = {}
    for m in mods.values():
        for target, line in m.refs:
            t = defining_module(mods, target)
            if t is None or t == m.path:
                continue
            edges.setdefault(m.path, {}).setdefault(t, []).append(line)
    return edges


def sccs(nodes, edges):
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]
    sys.setrecursionlimit(10000)

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(nodes):
        if v not in index:
            strong(v)
    return out


def mod_name(path):
    return "::".join(path) if path else "(crate root)"


def crate_graph():
    edges = {}
    names = {}
    for c in sorted(os.listdir(CRATES)):
        toml = os.path.join(CRATES, c, "Cargo.toml")
        if not os.path.exists(toml):
            continue
        text = open(toml, encoding="utf-8").read()
        pkg = re.search(r'(?m)^name\s*=\s*"([^"]+)"', text).group(1)
        names[pkg] = c
        deps = re.search(r"(?ms)^\[dependencies\](.*?)(^\[|\Z)", text)
        edges[pkg] = {d: [0] for d in re.findall(r"(?m)^(millpath[-a-z]*)", deps.group(1) if deps else "")}
    return names, edges


def check_architecture():
    problems = []
    path = os.path.join(ROOT, "ARCHITECTURE.md")
    text = open(path, encoding="utf-8").read()
    size = len(text)
    print(f"ARCHITECTURE.md: {size} characters (at most 15,000)")
    if size > 15000:
        problems.append(f"ARCHITECTURE.md has {size} characters, more than 15,000")
    for name in sorted(set(re.findall(r"`([A-Za-z0-9_./-]+\.(?:rs|sh|py|md|toml|mjs|ts|js))`", text))):
        candidates = [os.path.join(ROOT, name)] + [
            os.path.join(ROOT, "crates", c, "src", name) for c in os.listdir(CRATES)
        ]
        if not any(os.path.exists(p) for p in candidates):
            problems.append(f"ARCHITECTURE.md names `{name}`, which does not exist")
    return problems


def main():
    show_graph = "--graph" in sys.argv
    found = []
    for c in sorted(os.listdir(CRATES)):
        crate_dir = os.path.join(CRATES, c)
        if not os.path.isdir(os.path.join(crate_dir, "src")):
            continue
        mods = parse_crate(c, crate_dir)
        edges = graph(mods)
        if show_graph:
            for a in sorted(edges):
                for b in sorted(edges[a]):
                    print(f"{c}: {mod_name(a)} -> {mod_name(b)}")
        for comp in sccs(list(mods), edges):
            members = set(comp)
            key = f"{c}: {', '.join(mod_name(p) for p in comp)}"
            found.append(key)
            print(f"cycle in crates/{key}")
            for a in comp:
                for b in sorted(edges.get(a, {})):
                    if b in members:
                        lines = ", ".join(str(x) for x in sorted(set(edges[a][b]))[:5])
                        rel = os.path.relpath(mods[a].file, ROOT)
                        print(f"    {mod_name(a)} -> {mod_name(b)}  ({rel}:{lines})")
    names, cedges = crate_graph()
    for comp in sccs(list(cedges), cedges):
        found.append("crates: " + ", ".join(comp))
        print(f"cycle between crates: {', '.join(comp)}")
    problems = []
    for key in found:
        if key not in ALLOWED:
            problems.append("cycle in " + key)
    for key in sorted(ALLOWED - set(found)):
        problems.append("allowed cycle no longer exists (take it off ALLOWED): " + key)
    if "--architecture" in sys.argv:
        problems += check_architecture()
    if problems:
        print(f"import_cycles: {len(problems)} problem(s)", file=sys.stderr)
        for p in problems:
            print("  " + p, file=sys.stderr)
        return 1
    allowed = f" ({len(ALLOWED)} allowed still)" if ALLOWED else ""
    print(f"import_cycles: no new cycle in {len(os.listdir(CRATES))} crates{allowed}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
