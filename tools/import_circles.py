#!/usr/bin/env python3
"""Import circles between the modules of a crate (usage: import_circles.py engine/src).
Edges come from `use crate::..`/`super::..`
statements and from inline `crate::a::b` paths, test modules excluded."""
import os, re, sys
root = sys.argv[1] if len(sys.argv) > 1 else 'engine/src'
mods = {}
for dp, dn, fn in os.walk(root):
    for f in fn:
        if f.endswith('.rs'):
            p = os.path.join(dp, f)
            parts = os.path.relpath(p, root)[:-3].split('/')
            if parts[-1] in ('mod', 'lib'):
                parts = parts[:-1]
            mods['::'.join(parts)] = p

def resolve(cur, path):
    segs = path.split('::')
    if segs[0] == 'crate':
        base, segs = [], segs[1:]
    elif segs[0] == 'super':
        base, segs = cur[:-1], segs[1:]
        while segs and segs[0] == 'super':
            base, segs = base[:-1], segs[1:]
    elif segs[0] == 'self':
        base, segs = cur[:], segs[1:]
    else:
        return None
    for k in range(len(segs), -1, -1):
        cand = '::'.join(base + segs[:k])
        if cand in mods:
            return cand
    return None

def strip_tests(text):
    return re.split(r'#\[cfg\(test\)\]\s*mod tests', text)[0]

def strip_comments(text):
    return '\n'.join(l for l in text.split('\n') if not l.lstrip().startswith('//'))

def expand_use(base, body):
    """Paths named by `use base::{body}` (nested braces flattened one level)."""
    out = [base]
    depth, item = 0, ''
    for ch in body + ',':
        if ch == '{': depth += 1
        if ch == '}': depth -= 1
        if ch == ',' and depth == 0:
            it = item.strip()
            if it:
                head = re.match(r'[A-Za-z_0-9]+(?:::[A-Za-z_0-9]+)*', it)
                if head: out.append(base + '::' + head.group(0))
            item = ''
        else:
            item += ch
    return out

edges = {m: set() for m in mods}
for m, p in mods.items():
    text = strip_comments(strip_tests(open(p).read()))
    cur = m.split('::') if m else []
    targets = []
    for base, body in re.findall(r'use\s+((?:crate|super|self)(?:::[A-Za-z_0-9]+)*)(?:::\{([^;]*)\})?\s*;', text):
        targets += expand_use(base, body) if body else [base]
    targets += re.findall(r'(?<![A-Za-z_0-9:])((?:crate|super)(?:::[A-Za-z_0-9]+)+)', text)
    for t in targets:
        r = resolve(cur, t)
        if r and r != m and not m.startswith(r + '::') and not r.startswith(m + '::') if m else False:
            edges[m].add(r)

index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]
sys.setrecursionlimit(10000)
def visit(v):
    index[v] = low[v] = counter[0]; counter[0] += 1
    stack.append(v); on.add(v)
    for w in edges[v]:
        if w not in index:
            visit(w); low[v] = min(low[v], low[w])
        elif w in on:
            low[v] = min(low[v], index[w])
    if low[v] == index[v]:
        comp = []
        while True:
            w = stack.pop(); on.discard(w); comp.append(w)
            if w == v: break
        if len(comp) > 1: found.append(sorted(comp))
for v in edges:
    if v not in index: visit(v)
for c in found: print(c)
print(len(found), 'circles over', len(mods), 'modules,', sum(map(len, edges.values())), 'edges')
