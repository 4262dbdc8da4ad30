#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""check-arm-facts.py [--table FILE] ROOT - no arm number lives outside src/arm.c.

The arm model table (src/arm.c's `models[]`, or FILE) is the one place for an arm's
lengths, radii, speeds, limits, pulses per degree and READY. This reads the table's rows
and looks through the C sources under ROOT/src, ROOT/sim and ROOT/apps (comments left
out) for the same facts written again:

  - a literal with two or more decimals equal to a row's value finer than quarters, at the
    literal's precision (44.44 and 22.22 pulses per degree, 19.685 in/s, an A465 length in
    inches: 12.99);
  - a run of literals, separated only by commas, braces and blanks (an initializer), that
    repeats three or more values of one field in a row (geometry: 10.0, 10.0, 10.0, 2.0;
    pulses: 200.0, 200.0, 200.0; limits), or four or more when all are 0, 1, 90 or 180
    (READY: 0.0, 90.0, -90.0, 0.0, 0.0). A millimetre length MM(330.0) counts as both
    330 and its inches.

Each find is printed as FILE:LINE: what; exit status 1 when there is one."""
import os
import re
import sys

NUM = re.compile(r"(?<![\w.])[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?(?![\w.])")
TRIVIAL = {0.0, 1.0, 90.0, 180.0}
FIELDS = ("name", "naxes", "form", "base_h", "upper", "fore", "flange", "r_upper", "r_fore", "linear", "ppd",
          "min", "max", "speed", "ready")
GEOMETRY = ("base_h", "upper", "fore", "flange", "r_upper", "r_fore", "linear")


def strip_comments(text):
    """The text with /* */ and // comments and string literals blanked (lines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text[i] == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append('""' + " " * (min(j, n - 1) - i - 1))
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def value_forms(tok):
    """The numbers a field's text stands for: 10.0 -> {10}; MM(330.0) -> {330, 12.99...}."""
    m = re.fullmatch(r"MM\(\s*([-+0-9.eE]+)\s*\)", tok.strip())
    if m:
        mm = float(m.group(1))
        return [mm / 25.4, mm]
    return [float(tok)]


def split_top(s):
    """Split s at the commas outside braces and parentheses."""
    parts, depth, cur = [], 0, []
    for ch in s:
        if ch in "{(":
            depth += 1
        elif ch in "})":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append("".join(cur))
            cur = []
        else:
            cur.append(ch)
    if "".join(cur).strip():
        parts.append("".join(cur))
    return parts


def read_table(path):
    """The rows of the model table: {field: [[forms of value 1], [forms of value 2] ...]}."""
    with open(path, encoding="utf-8") as f:
        text = strip_comments(f.read())
    m = re.search(r"\bmodels\s*\[\s*\]\s*=\s*\{(.*?)\n\};", text, re.S)
    if not m:
        sys.exit(f"arm facts: no model table (models[] = {{...}};) in {path}")
    body, rows, depth, start = m.group(1), [], 0, None
    for i, ch in enumerate(body):
        if ch == "{":
            if depth == 0:
                start = i + 1
            depth += 1
        elif ch == "}":
            depth -= 1
            if depth == 0:
                rows.append(body[start:i])
    table = []
    for row in rows:
        fields = split_top(row)
        if len(fields) != len(FIELDS):
            sys.exit(f"arm facts: a row of {path} has {len(fields)} fields, not {len(FIELDS)}")
        entry = {}
        for name, text in zip(FIELDS, fields):
            if name in ("name", "naxes", "form"):
                continue
            items = split_top(text.strip().strip("{}")) if text.strip().startswith("{") else [text]
            entry[name] = [value_forms(t) for t in items if t.strip()]
        entry["geometry"] = [v for g in GEOMETRY for v in entry[g]]
        table.append(entry)
    return table


def distinctive(table):
    """The row values worth finding alone: those with a fraction finer than quarters."""
    vals = set()
    for entry in table:
        for name, seq in entry.items():
            for forms in seq:
                for v in forms:
                    if abs(v) >= 1 and abs(v * 4 - round(v * 4)) > 1e-9:
                        vals.add(v)
    return vals


def literal_matches(text, vals):
    if "." not in text or "e" in text.lower():
        return False
    decimals = len(text.split(".")[1])
    if decimals < 2:
        return False
    x = float(text)
    return any(abs(round(v, decimals) - x) < 1e-12 for v in vals)


def runs(text):
    """Runs of numeric literals separated only by commas, braces and blanks: lists of
    (line, literal)."""
    out, cur, last_end = [], [], 0
    for m in NUM.finditer(text):
        between = text[last_end:m.start()]
        if cur and re.fullmatch(r"[\s,{}]*", between) is None:
            out.append(cur)
            cur = []
        cur.append((text.count("\n", 0, m.start()) + 1, m.group(0)))
        last_end = m.end()
    if cur:
        out.append(cur)
    return out


def field_hits(run, table):
    """(start, length, row, field) of each stretch of run that repeats a field's values."""
    vals = [float(t) for _, t in run]
    hits = []
    for r, entry in enumerate(table):
        for name, seq in entry.items():
            if name in GEOMETRY:
                continue
            for s in range(len(vals)):
                for k in range(len(seq)):
                    n = 0
                    while s + n < len(vals) and k + n < len(seq) and \
                            any(abs(vals[s + n] - f) < 1e-9 for f in seq[k + n]):
                        n += 1
                    trivial = all(abs(v) in TRIVIAL for v in vals[s:s + n])
                    if n >= 4 or (n >= 3 and not trivial):
                        hits.append((s, n, r, name))
    return hits


def check(root, table):
    vals, bad = distinctive(table), []
    for sub in ("src", "sim", "apps"):
        for d, dirs, files in os.walk(os.path.join(root, sub)):
            dirs.sort()
            for f in sorted(files):
                path = os.path.join(d, f)
                rel = os.path.relpath(path, root)
                if not f.endswith((".c", ".h")) or rel == os.path.join("src", "arm.c"):
                    continue
                with open(path, encoding="utf-8", errors="replace") as fh:
                    text = strip_comments(fh.read())
                seen = set()
                for run in runs(text):
                    for line, lit in run:
                        if literal_matches(lit, vals) and (line, lit) not in seen:
                            seen.add((line, lit))
                            bad.append(f"{rel}:{line}: {lit} is an arm's number (src/arm.c)")
                    for s, n, r, name in field_hits(run, table):
                        line = run[s][0]
                        key = (line, name)
                        if key not in seen:
                            seen.add(key)
                            lits = ", ".join(t for _, t in run[s:s + n])
                            bad.append(f"{rel}:{line}: {lits} repeats row {r}'s {name} (src/arm.c)")
    return bad


def main(argv):
    args = argv[1:]
    table_path = None
    if len(args) >= 2 and args[0] == "--table":
        table_path, args = args[1], args[2:]
    if len(args) != 1:
        sys.exit(__doc__)
    root = args[0]
    table = read_table(table_path or os.path.join(root, "src", "arm.c"))
    bad = check(root, table)
    for b in bad:
        print("arm facts: " + b)
    if bad:
        print(f"arm facts: {len(bad)} arm numbers outside src/arm.c")
        return 1
    print(f"arm facts: {len(table)} models; src/, sim/ and apps/ hold none of their numbers outside src/arm.c")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
