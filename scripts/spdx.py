#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""spdx.py [--fix] ROOT - every source file under ROOT names its licence.

A source file is a .c, .h, .S, .py, .sh, .cmake or CMakeLists.txt file (build
directories and .git are skipped). It must carry "SPDX-License-Identifier: MIT"
in its first three lines. With --fix, files without one get it: C files a
first line "/* SPDX-License-Identifier: MIT */", the others a "#" line after
their "#!" line, if any. Exit status 1 lists the files that lack it."""
import os
import sys

TAG = "SPDX-License-Identifier: MIT"
C_EXT = (".c", ".h", ".S")
HASH_EXT = (".py", ".sh", ".cmake")
SKIP_DIRS = {".git", "debian", ".pytest_cache", "__pycache__"}


def sources(root):
    for d, dirs, files in os.walk(root):
        # build trees: any folder with a CMakeCache.txt, or named build*/obj-*
        dirs[:] = sorted(x for x in dirs if x not in SKIP_DIRS and not x.startswith(("build", "obj-"))
                         and not os.path.exists(os.path.join(d, x, "CMakeCache.txt")))
        for f in sorted(files):
            if f.endswith(C_EXT + HASH_EXT) or f == "CMakeLists.txt":
                yield os.path.join(d, f)


def has_tag(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return any(TAG in f.readline() for _ in range(3))


def fix(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    if path.endswith(C_EXT):
        text = "/* " + TAG + " */\n" + text
    elif text.startswith("#!"):
        nl = text.index("\n") + 1
        text = text[:nl] + "# " + TAG + "\n" + text[nl:]
    else:
        text = "# " + TAG + "\n" + text
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def main(argv):
    do_fix = "--fix" in argv
    args = [a for a in argv if a != "--fix"]
    root = args[0] if args else "."
    missing = [p for p in sources(root) if not has_tag(p)]
    if do_fix:
        for p in missing:
            fix(p)
        return 0
    for p in missing:
        print("no SPDX line: " + os.path.relpath(p, root))
    count = sum(1 for _ in sources(root))
    print("spdx: %d source files, %d without an SPDX line" % (count, len(missing)))
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
