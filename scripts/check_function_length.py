#!/usr/bin/python3
"""Lists the C++ functions longer than a limit (60 lines by default) in the given folders and
exits 1 when there is any: the house rule that a function reads as a sequence of named steps.

    scripts/check_function_length.py core io sim nav viz logs bench fuzz

A function is a body at namespace or class scope whose header ends in a parameter list
(constructors with their initialiser lists included; lambdas and local classes count towards
the function they are in). Its length runs from the first line of its header to its closing
brace. Comments, string and character literals are blanked first, so braces in them do not count.
"""
import argparse
import pathlib
import re
import sys

LITERAL = re.compile(r'//[^\n]*|/\*.*?\*/|R"(\w*)\(.*?\)\1"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'',
                     re.S)
CONTROL = re.compile(r'\b(if|for|while|switch|catch|do|else|return)\b')
SCOPE = re.compile(r'\b(namespace|class|struct|union|enum)\b')


def blank(text):
    """Comments and literals replaced by spaces, newlines kept (line numbers stay)."""
    return LITERAL.sub(lambda m: re.sub(r'[^\n]', ' ', m.group(0)), text)


def strip_templates(h):
    """h without its leading template <...> clauses (their `class` is no class)."""
    while h.startswith('template'):
        depth, i = 0, h.find('<')
        if i < 0:
            return h
        for j in range(i, len(h)):
            depth += {'<': 1, '>': -1}.get(h[j], 0)
            if depth == 0:
                h = h[j + 1:].lstrip()
                break
        else:
            return h
    return h


def header_kind(header):
    h = strip_templates(' '.join(header.split()))
    if not h or h.startswith('#'):
        return 'other'
    if CONTROL.match(h) or h.endswith('=') or h.endswith(','):
        return 'other'  # a statement block or a braced initialiser
    paren = h.find('(')
    scope = SCOPE.search(h)
    if scope and (paren < 0 or scope.start() < paren) and 'operator' not in h[:paren if paren >= 0 else len(h)]:
        return 'scope'
    if re.search(r'\)\s*(const|noexcept|override|final|mutable|&|&&|->[^{;]*|\s)*$', h) or \
            re.search(r'\)\s*:\s*\w', h):
        return 'function'
    return 'other'


def functions(path):
    """(name line, length) of each function in one file."""
    text = blank(path.read_text(errors='replace'))
    stack = []  # kinds of the open braces
    start = 0  # offset where the current header begins
    out = []
    line_at = lambda offset: text.count('\n', 0, offset) + 1
    for i, ch in enumerate(text):
        if ch == '{':
            header = text[start:i]
            # Preprocessor lines are not part of a header.
            header = '\n'.join(l for l in header.split('\n') if not l.strip().startswith('#'))
            inside_function = any(k[0] == 'function' for k in stack)
            kind = 'other' if inside_function else header_kind(header)
            first = start + len(text[start:i]) - len(text[start:i].lstrip())
            stack.append((kind, line_at(first), header.strip().split('(')[0].split()[-1:]))
            start = i + 1
        elif ch == '}':
            if stack:
                kind, first, name = stack.pop()
                if kind == 'function':
                    out.append((name[0] if name else '?', first, line_at(i) - first + 1))
            start = i + 1
        elif ch == ';':
            start = i + 1
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('folders', nargs='+')
    p.add_argument('--limit', type=int, default=60)
    a = p.parse_args()
    long = []
    for folder in a.folders:
        for path in sorted(pathlib.Path(folder).rglob('*')):
            if path.suffix in ('.cpp', '.hpp', '.h', '.cc'):
                long += [(path, f) for f in functions(path) if f[2] > a.limit]
    for path, (name, line, length) in sorted(long, key=lambda x: -x[1][2]):
        print(f'{path}:{line}: {name} is {length} lines')
    print(f'{len(long)} function(s) over {a.limit} lines')
    return 1 if long else 0


if __name__ == '__main__':
    sys.exit(main())
