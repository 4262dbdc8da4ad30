#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""svg_check.py SVG FBRL-FILE... [--refused OBSTACLE]

Checks a work-cell picture (CELL-SVG, fbrlmon --dry-run's) as a reader sees it, against facts
taken from outside the code that drew it: the SVG as parsed by Python's xml.etree, the cell
and rack descriptions read from the FBRL files, the obstacle named by the dry run's report.

  a. the obstacles and the tool path fill more than half the canvas in its larger dimension
     (the two views' heights added) and a third in the other, and nothing drawn (shapes,
     label boxes) lies outside the canvas;
  b. no two labels overlap: a label's box is its font size x characters x 0.6 wide (an
     average sans-serif character) and one font size tall (0.8 above the baseline, 0.2 below);
  c. a scale bar (g#scalebar: a line and "N in") whose length is N inches at the picture's
     scale, the scale measured from a fixed CELL-BOX of the FBRL files (its drawn width in
     the top view over its width in inches);
  d. a legend (g#legend) holding a swatch of every kind (class) of shape the views draw;
  e. every position of each "ROWS COLS CELL-RACK NAME" of the FBRL files drawn in both
     views: ROWS x COLS markers titled "NAME i j" at distinct places in the top view;
  f. with --refused OBSTACLE: a refused motion drawn in red in both views, and a red label
     naming OBSTACLE.

Prints what it measured; exit 0 when every check holds, 1 with each failure named.
"""
import re
import sys
import xml.etree.ElementTree as ET

NS = "{http://www.w3.org/2000/svg}"
CHAR_W = 0.6  # em per character: the label width estimate


def tag(e):
    return e.tag[len(NS):] if e.tag.startswith(NS) else e.tag


def fnum(s):
    return float(s)


def is_red(c):
    c = (c or "").strip().lower()
    m = re.fullmatch(r"#([0-9a-f]{6})", c) or re.fullmatch(r"#([0-9a-f]{3})", c)
    if not m:
        return c == "red"
    h = m.group(1)
    if len(h) == 3:
        h = "".join(ch * 2 for ch in h)
    r, g, b = int(h[0:2], 16), int(h[2:4], 16), int(h[4:6], 16)
    return r >= 0xB0 and g <= 0x50 and b <= 0x50


def read_fbrl(paths):
    """The fixed boxes (name -> x0, x1) and the racks (name -> rows, cols) of the files."""
    boxes, racks = {}, {}
    for p in paths:
        in_block = False
        for line in open(p, encoding="utf-8"):
            line = re.sub(r"\\\s.*$|\\$", "", line)
            line = re.sub(r"\(\s[^)]*\)", "", line)
            t = line.split()
            for k, w in enumerate(t):
                u = w.upper()
                if u == "CELL-BLOCK":
                    in_block = True
                elif u == "CELL-WORLD":
                    in_block = False
                elif u == "CELL-BOX" and k >= 6 and k + 1 < len(t) and not in_block:
                    v = [fnum(x) for x in t[k - 6:k]]
                    boxes[t[k + 1].upper()] = (min(v[0], v[3]), max(v[0], v[3]))
                elif u == "CELL-RACK" and k >= 2 and k + 1 < len(t):
                    racks[t[k + 1].upper()] = (int(t[k - 2]), int(t[k - 1]))
    return boxes, racks


def walk(e, group=None):
    """(element, the id of the nearest enclosing g) for every element."""
    for c in e:
        g = c.get("id") if tag(c) == "g" and c.get("id") else group
        yield c, g
        yield from walk(c, g)


def main(argv):
    refused = None
    files = []
    i = 1
    while i < len(argv):
        if argv[i] == "--refused":
            refused = argv[i + 1].upper()
            i += 2
        else:
            files.append(argv[i])
            i += 1
    if len(files) < 2:
        print(__doc__)
        return 2
    svg, fbrl = files[0], files[1:]
    root = ET.parse(svg).getroot()
    W, H = fnum(root.get("width")), fnum(root.get("height"))
    style = "".join(s.text or "" for s in root.iter(NS + "style"))
    m = re.search(r"text\{[^}]*font:[^};]*?(\d+(?:\.\d+)?)px", style)
    font = float(m.group(1)) if m else 16.0  # SVG's default
    boxes, racks = read_fbrl(fbrl)
    fails = []

    def fail(msg):
        fails.append(msg)
        print("FAIL: " + msg)

    shapes = []  # (group, class, x0, y0, x1, y1, element)
    texts = []  # (group, text, x0, y0, x1, y1, element)
    for e, g in walk(root):
        t, cls = tag(e), e.get("class", "")
        if t == "rect" and e.get("width", "").endswith("%"):
            continue  # the white background
        if t == "rect":
            x, y, w, h = (fnum(e.get(a)) for a in ("x", "y", "width", "height"))
            shapes.append((g, cls, x, y, x + w, y + h, e))
        elif t == "circle":
            x, y, r = (fnum(e.get(a)) for a in ("cx", "cy", "r"))
            shapes.append((g, cls, x - r, y - r, x + r, y + r, e))
        elif t == "line":
            x1, y1, x2, y2 = (fnum(e.get(a)) for a in ("x1", "y1", "x2", "y2"))
            shapes.append((g, cls, min(x1, x2), min(y1, y2), max(x1, x2), max(y1, y2), e))
        elif t == "polyline":
            pts = [tuple(map(fnum, p.split(","))) for p in e.get("points").split()]
            xs, ys = [p[0] for p in pts], [p[1] for p in pts]
            shapes.append((g, cls, min(xs), min(ys), max(xs), max(ys), e))
        elif t == "text":
            s = "".join(e.itertext())
            fs = float(e.get("font-size", font))
            x, y = fnum(e.get("x")), fnum(e.get("y"))
            texts.append((g, s, x, y - 0.8 * fs, x + len(s) * CHAR_W * fs, y + 0.2 * fs, e))
    print("canvas %.0f x %.0f px, %d shapes, %d labels (font %.0f px, %.1f px per character)"
          % (W, H, len(shapes), len(texts), font, CHAR_W * font))

    # a. the frame: in each view, the box around its obstacles and path; the views stand one
    # above the other, so their heights add up (the space between them is not the cell's)
    drawn = {}
    for s in shapes:
        if s[0] in ("top", "side") and s[1] in ("box", "cylinder", "keepout", "path"):
            b = drawn.get(s[0], [s[2], s[3], s[4], s[5]])
            drawn[s[0]] = [min(b[0], s[2]), min(b[1], s[3]), max(b[2], s[4]), max(b[3], s[5])]
    if len(drawn) != 2:
        fail("a: the top and the side view do not both draw obstacles or a path")
    else:
        fx = max(b[2] - b[0] for b in drawn.values()) / W
        fy = sum(b[3] - b[1] for b in drawn.values()) / H
        big, small = (fy, fx) if H >= W else (fx, fy)
        print("a: obstacles and path span %.0f%% of the width, %.0f%% of the height (both views)"
              % (100 * fx, 100 * fy))
        if big <= 0.5 or small <= 1 / 3:
            fail("a: the obstacles and the path fill %.0f%% of the canvas's larger dimension (want > 50%%) "
                 "and %.0f%% of the smaller (want > 33%%)" % (100 * big, 100 * small))
    for s in shapes + texts:
        if s[2] < -0.5 or s[3] < -0.5 or s[4] > W + 0.5 or s[5] > H + 0.5:
            fail("a: %s %r lies outside the canvas (%.1f %.1f .. %.1f %.1f)"
                 % (tag(s[6]), s[1], s[2], s[3], s[4], s[5]))

    # b. labels
    over = 0
    for i in range(len(texts)):
        a = texts[i]
        for b in texts[i + 1:]:
            if a[2] < b[4] and b[2] < a[4] and a[3] < b[5] and b[3] < a[5]:
                over += 1
                if over <= 10:
                    fail("b: labels %r and %r overlap" % (a[1], b[1]))
    print("b: %d labels, %d overlapping pairs" % (len(texts), over))
    if over > 10:
        fail("b: %d overlapping pairs in all" % over)

    # c. the scale bar
    ref = None
    for name, (bx0, bx1) in boxes.items():
        r = [s for s in shapes if s[0] == "top" and tag(s[6]) == "rect" and
             (s[6].findtext(NS + "title") or "").split(" ")[0].upper() == name]
        if r and bx1 > bx0:
            ref = (name, (r[0][4] - r[0][2]) / (bx1 - bx0))
            break
    bar = [s for s in shapes if s[0] == "scalebar" and tag(s[6]) == "line" and s[5] - s[3] < 0.01]
    bar_text = " ".join(t[1] for t in texts if t[0] == "scalebar")
    m = re.search(r"(\d+(?:\.\d+)?) in\b", bar_text)
    if ref is None:
        fail("c: no fixed CELL-BOX of the files is drawn in the top view: the scale cannot be measured")
    elif not bar or not m:
        fail("c: no scale bar (g#scalebar with a line and 'N in')")
    else:
        length = max(s[4] - s[2] for s in bar)
        want = float(m.group(1)) * ref[1]
        print("c: %s drawn at %.3f px per inch; the bar says %s in: %.2f px, measured %.2f px"
              % (ref[0], ref[1], m.group(1), want, length))
        if abs(length - want) > 0.5:
            fail("c: the scale bar is %.2f px, %s in at the picture's scale is %.2f px" % (length, m.group(1), want))

    # d. the legend
    legend = {s[1] for s in shapes if s[0] == "legend"}
    used = {s[1] for s in shapes if s[0] in ("top", "side")} - {"frame", "leader"}
    ltexts = [t for t in texts if t[0] == "legend"]
    print("d: the views draw %s; the legend shows %s with %d texts"
          % (sorted(used), sorted(legend), len(ltexts)))
    if not legend or not ltexts:
        fail("d: no legend (g#legend)")
    elif used - legend:
        fail("d: the legend lacks %s" % sorted(used - legend))

    # e. racks drawn whole
    for name, (rows, cols) in racks.items():
        for view in ("top", "side"):
            at = {(round((s[2] + s[4]) / 2, 1), round((s[3] + s[5]) / 2, 1)) for s in shapes
                  if s[0] == view and tag(s[6]) == "circle" and
                  re.fullmatch(re.escape(name) + r" \d+ \d+", s[6].findtext(NS + "title") or "")}
            n = len([s for s in shapes if s[0] == view and tag(s[6]) == "circle" and
                     re.fullmatch(re.escape(name) + r" \d+ \d+", s[6].findtext(NS + "title") or "")])
            print("e: %s %dx%d: %d positions drawn in the %s view, %d distinct places"
                  % (name, rows, cols, n, view, len(at)))
            if n != rows * cols or (view == "top" and len(at) != rows * cols):
                fail("e: %s has %d x %d positions; the %s view draws %d at %d places"
                     % (name, rows, cols, view, n, len(at)))

    # f. the refused motion
    if refused:
        for view in ("top", "side"):
            red = [s for s in shapes if s[0] == view and is_red(s[6].get("stroke"))
                   and tag(s[6]) in ("polyline", "line")]
            named = [t for t in texts if t[0] == view and refused in t[1].upper() and "refused" in t[1].lower()
                     and is_red(t[6].get("fill"))]
            print("f: %s view: %d red strokes, labels %s" % (view, len(red), [t[1] for t in named]))
            if not red:
                fail("f: the %s view draws no refused motion in red" % view)
            if not named:
                fail("f: the %s view has no red label naming %s as refused" % (view, refused))

    print("%s: %d failures" % (svg, len(fails)))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
