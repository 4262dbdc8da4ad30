#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Replace raw THROW codes by their names from include/fbrl/vm_throw.h, in the contexts
where a number is a throw code: THROW(-n), a throw call's code argument (fbrl__throw_msg,
fbrl_vm_throw, fbrl_vmx_throwf, rb_fail, gl_throw, fail), `return -n;`, `code = -n;` and
`? -n :` / `: -n;` for n >= 3 (-1 and -2 are flags and "not found" as often as ABORT).
For the engine and the word sets (src/lang, src/words), whose int functions return throw
codes; elsewhere only the throw calls are safe (apps: fbrl_vm_throw lines only). Mechanical and
idempotent: run it again after merging code that brought raw codes back.
Usage: name-throws.py FILE...   (rewrites the files; prints what is left to name by hand)"""
import re
import sys
import os

here = os.path.dirname(os.path.abspath(__file__))
names = {}
for line in open(os.path.join(here, '..', 'include', 'fbrl', 'vm_throw.h')):
    m = re.match(r'\s*(FBRL_THROW_\w+) = (-\d+),', line)
    if m:
        names[int(m.group(2))] = m.group(1)


def name(m, group, minimum=1):
    code = int(m.group(group))
    if code > -minimum or code not in names:
        return m.group(0)
    s = m.group(0)
    a, b = m.span(group)
    a -= m.start(0)
    b -= m.start(0)
    return s[:a] + names[code] + s[b:]


rules = [
    (re.compile(r'\bTHROW\((-\d+)\)'), 1, 1),
    (re.compile(r'\b(?:fbrl__throw_msg|fbrl_vm_throw|fbrl_vmx_throwf|rb_fail|gl_throw|fail)\(\s*[\w>\-]+,\s*(-\d+)\b'), 1, 1),
    (re.compile(r'\breturn (-\d+);'), 1, 3),
    (re.compile(r'\? (-\d+) :'), 1, 3),
    (re.compile(r': (-\d+);'), 1, 3),
    (re.compile(r'\|\| \(r = (-\d+)\)'), 1, 3),
    (re.compile(r'\bFRES\(.*, (-\d+)\)'), 1, 1),
    (re.compile(r'\bcode = (-\d+);'), 1, 3),
    (re.compile(r'throw_code == (-\d+)'), 1, 1),
    (re.compile(r'#define (?:THROW|GL)_\w+ +\((-\d+)\)'), 1, 1),
]
left = 0
for path in sys.argv[1:]:
    text = open(path).read()
    new = text
    for rx, g, lo in rules:
        new = rx.sub(lambda m: name(m, g, lo), new)
    if new != text:
        open(path, 'w').write(new)
    for n, line in enumerate(new.split('\n'), 1):
        if re.search(r'(THROW|throw|fail)\w*\(.*\b-(?:[3-9]|[1-5]\d)\b', line):
            print('%s:%d: %s' % (path, n, line.strip()))
            left += 1
print('name-throws: %d lines with a raw code left' % left, file=sys.stderr)
