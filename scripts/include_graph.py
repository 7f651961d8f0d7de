#!/usr/bin/env python3
"""The firmware's module graph: fails on a cycle, on a header that speaks for another file, or on
the controller's private layout included from outside the firmware.

    scripts/include_graph.py [--print] [ROOT ...]        (default ROOT: firmware)

A module is a C file and the header of the same name (src/move.c, include/fw/move.h); a header
with no C file of its name is a module of its own (types only, or inline code).  Module A depends
on module B when a file of A includes B's header.  Two rules, each a failure with what breaks it:

  1. no cycle: A depends on B and B, by any path, on A (a call circle between files shows as one,
     since a file calls another only through the header that declares it);
  2. a header declares only functions of its own module: a function a header declares is defined
     in that module's C file (or in the header itself, inline).  Otherwise one header could gather
     the functions of several files, and the cycle between them would not show in rule 1.

And over the whole repository (the parent of this script's folder):

  3. controller_internal.h (the controller's layout, firmware/src) is included by files of
     firmware/src only: tools, tests and benchmarks read the controller through fw/controller.h,
     fw/inspect.h and fw/testing.h.

Comments and strings are ignored; declarations are found at file scope (brace depth 0), a
function pointer typedef is not a declaration.  --print lists the modules and their edges.
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)
IDENT = r'[A-Za-z_]\w*'


def strip(text):
    """Comments, strings and character constants blanked; preprocessor lines dropped (their
    includes are read separately)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append('\n' * text.count('\n', i, j))
            i = j
        elif text.startswith('//', i):
            j = text.find('\n', i)
            i = n if j < 0 else j
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == '\\' else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    lines = []
    cont = False
    for line in ''.join(out).split('\n'):
        if cont or line.lstrip().startswith('#'):
            cont = line.rstrip().endswith('\\')
            lines.append('')
        else:
            lines.append(line)
    return '\n'.join(lines)


def functions(text):
    """(declared, defined): names of functions declared (prototype, extern) and defined (with a
    body) at file scope.  Static functions are the file's own and are left out of both."""
    code = strip(text)
    declared, defined = set(), set()
    depth, start = 0, 0
    statements = []
    for i, c in enumerate(code):
        if c == '{':
            if depth == 0:
                statements.append((code[start:i], '{'))
            depth += 1
        elif c == '}':
            depth -= 1
            if depth == 0:
                start = i + 1
        elif c == ';' and depth == 0:
            statements.append((code[start:i], ';'))
            start = i + 1
    for head, end in statements:
        head = ' '.join(head.split())
        if not head or head.startswith('typedef') or re.match(r'(struct|union|enum)\s+\w*\s*$', head):
            continue
        if re.search(r'\bstatic\b', head) and not re.search(r'\binline\b', head):
            continue
        m = re.search(r'(' + IDENT + r')\s*\((?:[^()]|\([^()]*\))*\)\s*(?:__attribute__\s*\(\(.*\)\))?\s*$', head)
        if not m or '(*' in head[:m.start()] or '=' in head[:m.start()]:
            continue
        name = m.group(1)
        if name in ('if', 'while', 'for', 'switch', 'return', 'sizeof', '_Static_assert', '__attribute__'):
            continue
        (defined if end == '{' else declared).add(name)
    return declared, defined


def scan(roots):
    files = {}
    for root in roots:
        for d, _, names in os.walk(root):
            for f in names:
                if f.endswith(('.c', '.h')):
                    p = os.path.join(d, f)
                    with open(p, encoding='utf-8') as fh:
                        files[p] = fh.read()
    return files


def module_of(path):
    return os.path.splitext(os.path.basename(path))[0]


def check(roots, show=False):
    files = scan(roots)
    by_header = {}   # include spelling -> path
    for p in files:
        if p.endswith('.h'):
            rel = os.path.basename(p)
            by_header.setdefault(rel, []).append(p)
            parent = os.path.basename(os.path.dirname(p))
            by_header.setdefault(parent + '/' + rel, []).append(p)
    defined_in = {}
    for p, text in files.items():
        if p.endswith('.c'):
            for name in functions(text)[1]:
                defined_in.setdefault(name, set()).add(module_of(p))
    problems = []
    # Rule 2: a header speaks for its own module.
    for p, text in sorted(files.items()):
        if not p.endswith('.h'):
            continue
        declared, inline = functions(text)
        for name in sorted(declared - inline):
            owners = defined_in.get(name, set())
            if owners and module_of(p) not in owners:
                problems.append('%s declares %s, which %s defines: a header declares its own '
                                'module\'s functions only' % (p, name, ' and '.join(sorted(o + '.c' for o in owners))))
    # Rule 1: the graph of modules.
    edges = {}
    for p, text in files.items():
        a = module_of(p)
        edges.setdefault(a, set())
        for inc in INCLUDE.findall(text):
            targets = by_header.get(inc) or by_header.get(os.path.basename(inc)) if '/' not in inc else by_header.get(inc)
            for t in targets or []:
                b = module_of(t)
                if b != a:
                    edges[a].add(b)
    if show:
        for a in sorted(edges):
            print('%s -> %s' % (a, ' '.join(sorted(edges[a])) or '(nothing)'))
    colour, stack = {}, []

    def visit(a):
        colour[a] = 1
        stack.append(a)
        for b in sorted(edges.get(a, ())):
            if colour.get(b) == 1:
                cyc = stack[stack.index(b):] + [b]
                problems.append('cycle: ' + ' -> '.join(cyc))
            elif b not in colour:
                visit(b)
        stack.pop()
        colour[a] = 2

    sys.setrecursionlimit(10000)
    for a in sorted(edges):
        if a not in colour:
            visit(a)
    return problems, len(edges)


PRIVATE = 'controller_internal.h'
SKIP_DIRS = ('.git', 'build', '__pycache__')


def private_includes(repo):
    """Files outside firmware/src that include the controller's private layout."""
    inside = os.path.join(repo, 'firmware', 'src')
    found = []
    for d, dirs, names in os.walk(repo):
        dirs[:] = sorted(x for x in dirs if x not in SKIP_DIRS and not x.startswith('build'))
        if os.path.abspath(d) == os.path.abspath(inside):
            continue
        for f in sorted(names):
            if not f.endswith(('.c', '.h', '.cc', '.cpp')):
                continue
            p = os.path.join(d, f)
            with open(p, encoding='utf-8', errors='replace') as fh:
                text = fh.read()
            for inc in INCLUDE.findall(text):
                if os.path.basename(inc) == PRIVATE:
                    found.append('%s includes %s, the controller\'s private layout: read it through '
                                 'fw/controller.h, fw/inspect.h or fw/testing.h' % (os.path.relpath(p, repo), inc))
    return found


def main(argv):
    show = '--print' in argv
    roots = [a for a in argv if a != '--print'] or ['firmware']
    for r in roots:
        if not os.path.isdir(r):
            print('include_graph: %s is not a directory' % r, file=sys.stderr)
            return 2
    problems, n = check(roots, show)
    problems += private_includes(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    for p in problems:
        print('include_graph: ' + p)
    if problems:
        print('include_graph: %d problem(s) in %d modules of %s' % (len(problems), n, ' '.join(roots)))
        return 1
    print('include_graph: %d modules of %s, no cycle, every header its own module\'s; %s included in '
          'firmware/src only' % (n, ' '.join(roots), PRIVATE))
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
