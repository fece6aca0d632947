#!/usr/bin/env python3
"""The layers of the library: which top-level modules of src/ each one names, and the cycles among them.

A top-level module is a file `src/x.rs` or a folder `src/x/` (lib.rs and main.rs are the crate roots, not modules).
A reference is a path in the code (comments and strings left out) that reaches another top-level module: `crate::x`,
`crate::{x, y::z}`, or `super::...::x` climbing to the crate root from a file or an inline `mod` block. Doc links
are not code and are not counted.

Prints each module's references, then the strongly connected components of more than one module (the cycles), and
exits 1 if there is any; without cycles, the layers: each module on the line above the highest module it names.

Usage: python3 scripts/layers.py [SRC]    (SRC: the crate's src/ folder; by default the one beside scripts/)
"""

import re
import sys
from pathlib import Path

TOKEN = re.compile(
    r"""
    (?P<block>/\*)                              # block comment (nested: handled below)
  | (?P<line>//[^\n]*)                          # line and doc comments
  | (?P<raw>b?r(?P<hashes>\#*)")                # raw string opener
  | (?P<str>b?"(?:\\.|[^"\\])*")                # string
  | (?P<char>b?'(?:\\.|[^'\\])')                # character literal (a lifetime does not close)
  | (?P<ident>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<colons>::)
  | (?P<punct>[{}(),;\[\]])
  | (?P<other>\S)
  | (?P<space>\s+)
    """,
    re.VERBOSE | re.DOTALL,
)


def tokens(text):
    """Identifiers, `::` and brackets of Rust source, without comments, strings and characters."""
    i, out = 0, []
    while i < len(text):
        m = TOKEN.match(text, i)
        if m.group("block"):
            depth, j = 1, i + 2
            while depth and j < len(text):
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            i = j
            continue
        if m.group("raw"):
            end = text.find('"' + m.group("hashes"), m.end())
            i = len(text) if end < 0 else end + 1 + len(m.group("hashes"))
            continue
        for kind in ("ident", "colons", "punct"):
            if m.group(kind):
                out.append(m.group(kind))
        i = m.end()
    return out


def module_path(src, file):
    """The module path of a file: src/a/b.rs and src/a/b/mod.rs are ['a', 'b']."""
    parts = list(file.relative_to(src).with_suffix("").parts)
    if parts[-1] == "mod":
        parts.pop()
    return parts


def group_heads(toks, i):
    """The first names of the items of a `{ ... }` group starting at toks[i] == '{'."""
    heads, depth, expect = [], 0, True
    while i < len(toks):
        t = toks[i]
        if t == "{":
            depth += 1
            expect = depth == 1
        elif t == "}":
            depth -= 1
            if depth == 0:
                break
        elif depth == 1 and t == ",":
            expect = True
        elif depth == 1 and expect and t != "::":
            heads.append(t)
            expect = False
        i += 1
    return heads


def references(src, file, tops):
    """The top-level modules that a file's code names."""
    toks = tokens(file.read_text())
    base = module_path(src, file)
    found = set()
    # Inline modules: `mod name {` pushes onto the path until its brace closes.
    stack, inline, depth = [], [], 0
    i = 0
    while i < len(toks):
        t = toks[i]
        if t == "mod" and i + 2 < len(toks) and toks[i + 2] == "{":
            inline.append(toks[i + 1])
            stack.append(depth)
            depth += 1
            i += 3
            continue
        if t == "{":
            depth += 1
        elif t == "}":
            depth -= 1
            if stack and stack[-1] == depth:
                stack.pop()
                inline.pop()
        here = base + inline
        if t == "crate" and toks[i + 1 : i + 2] == ["::"] and (i == 0 or toks[i - 1] != "::"):
            after = toks[i + 2] if i + 2 < len(toks) else ""
            found.update(group_heads(toks, i + 2) if after == "{" else [after])
        elif t == "super" and toks[i + 1 : i + 2] == ["::"] and (i == 0 or toks[i - 1] != "::"):
            level, j = len(here) - 1, i + 2
            while toks[j : j + 2] == ["super", "::"]:
                level, j = level - 1, j + 2
            if level < 0:
                raise SystemExit(f"{file}: super:: climbs above the crate root")
            if level == 0:
                found.update(group_heads(toks, j) if toks[j] == "{" else [toks[j]])
            else:
                found.add(here[0])
        i += 1
    return {m for m in found if m in tops}


def components(graph):
    """Tarjan's strongly connected components, each sorted."""
    index, low, on, stack, out, n = {}, {}, set(), [], [], [0]

    def visit(v):
        index[v] = low[v] = n[0]
        n[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
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
            out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main():
    src = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "src"
    tops = {p.stem for p in src.glob("*.rs") if p.stem not in ("lib", "main")}
    tops |= {p.name for p in src.iterdir() if p.is_dir()}
    graph = {m: set() for m in tops}
    for file in sorted(src.rglob("*.rs")):
        parts = module_path(src, file)
        if parts[0] in ("lib", "main"):
            continue
        graph[parts[0]] |= references(src, file, tops) - {parts[0]}
    for m in sorted(graph):
        print(f"{m:14} -> {', '.join(sorted(graph[m])) or '-'}")
    cycles = [c for c in components(graph) if len(c) > 1]
    print()
    if not cycles:
        print("cycles: none")
        print()
        print("layers, from the top (each module names only modules on lower lines):")
        rank = {}

        def height(m):
            if m not in rank:
                rank[m] = 1 + max((height(n) for n in graph[m]), default=-1)
            return rank[m]

        for m in graph:
            height(m)
        for level in range(max(rank.values()), -1, -1):
            print(f"  {level:2}  {'  '.join(sorted(m for m in rank if rank[m] == level))}")
        return 0
    for c in cycles:
        print("cycle:", " <-> ".join(c))
        for m in c:
            print(f"    {m} -> {', '.join(sorted(graph[m] & set(c)))}")
    return 1


if __name__ == "__main__":
    sys.exit(main())
