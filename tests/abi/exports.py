#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""exports.py --shared LIB.so HEADER_DIR... | --static LIB.a HEADER_DIR...

--shared: the dynamic symbols LIB.so defines are exactly the names its public headers
declare with FBRL_API (nothing internal leaks, nothing public is missing), and the headers
declare no function or variable without FBRL_API (it would not be exported).
--static: every global name LIB.a defines carries the library's prefix: fbrl_ (public),
fbrl__ (the engine's internals) or fbrli_ (the word sets' internals), so no program's
own names can collide with it. Uses nm from binutils."""
import glob
import os
import re
import subprocess
import sys

DECL = re.compile(r"\bFBRL_API\b[^;]*?\b(fbrl_\w+)\s*(?:\(|\[|;|,)")
PREFIX = re.compile(r"^(fbrl_|fbrl__|fbrli_)")


def declared(dirs):
    names = set()
    for d in dirs:
        for h in glob.glob(os.path.join(d, "*.h")):
            text = re.sub(r"/\*.*?\*/", "", open(h, encoding="utf-8").read(), flags=re.S)
            for decl in re.findall(r"\bFBRL_API\b[^;]*;", text):
                # a declaration may name several variables: extern FBRL_API const T a, b;
                head = decl.split("(")[0]
                if "(" in decl:
                    names.add(re.findall(r"\b(fbrl_\w+)\s*$", head)[0])
                else:
                    names.update(n for n in re.findall(r"\b(fbrl_\w+)\b", decl)[1:])
    return names


def statements(text):
    """The file-scope statements of a header, comments, preprocessor lines and C++ guards
    taken out; a struct's or a static inline function's body is kept whole."""
    text = re.sub(r"/\*.*?\*/|//[^\n]*", " ", text, flags=re.S)
    text = re.sub(r"#ifdef __cplusplus.*?#endif", " ", text, flags=re.S)
    text = re.sub(r"^[ \t]*#(?:[^\n]*\\\n)*[^\n]*", " ", text, flags=re.M)
    out, cur, depth = [], [], 0
    for c in text:
        cur.append(c)
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0 and "".join(cur).lstrip().startswith("static"):
                out.append("".join(cur).strip())
                cur = []
        elif c == ";" and depth == 0:
            out.append("".join(cur).strip())
            cur = []
    return out


def unexported(dirs):
    """Functions and variables a public header declares without FBRL_API: a program that
    uses one fails to link against the shared library."""
    bad = []
    for d in dirs:
        for h in sorted(glob.glob(os.path.join(d, "*.h"))):
            for st in statements(open(h, encoding="utf-8").read()):
                st = st.rstrip(";").strip()
                if re.match(r"(typedef|static|enum|struct\s+\w+\s*\{|union)\b", st) or "FBRL_API" in st:
                    continue
                if re.match(r"struct\s+\w+$", st):  # a forward declaration
                    continue
                m = re.search(r"\b(fbrl_\w+)\s*(?:\(|\[|=|$)", st.split("(")[0] + ("(" if "(" in st else ""))
                if m:
                    bad.append("%s: %s" % (os.path.basename(h), m.group(1)))
    return bad


def nm(args, lib):
    out = subprocess.run(["nm"] + args + [lib], check=True, capture_output=True, text=True).stdout
    syms = set()
    for line in out.splitlines():
        f = line.split()
        if len(f) == 3 and f[1] not in "UvwV":
            syms.add(f[2])
    return syms


def main(argv):
    mode, lib, dirs = argv[0], argv[1], argv[2:]
    if mode == "--shared":
        have = nm(["-D", "--defined-only"], lib)
        want = declared(dirs)
        leaked = sorted(have - want)
        missing = sorted(want - have)
        for n in leaked:
            print("exported but not public: " + n)
        for n in missing:
            print("public but not exported: " + n)
        hidden = unexported(dirs)
        for n in hidden:
            print("declared public without FBRL_API (not exported): " + n)
        missing += hidden
        print("exports: %d symbols exported, %d public names declared; %d leaked, %d missing"
              % (len(have), len(want), len(leaked), len(missing)))
        return 1 if leaked or missing else 0
    have = nm(["-g", "--defined-only"], lib)
    bad = sorted(n for n in have if not PREFIX.match(n))
    for n in bad:
        print("global name without the prefix: " + n)
    print("prefix: %d global names in %s, %d without the prefix" % (len(have), os.path.basename(lib), len(bad)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
