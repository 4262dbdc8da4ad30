# SPDX-License-Identifier: MIT
"""fbrl-station's page (--http) in a real browser: Debian's chromium, headless with software
WebGL, driven over the DevTools protocol (cdp.py). The truth is outside the page: fbrlsim's
command log, the cell as .CELL lists it, the pose the station reads from fbrlsim and its forward
kinematics from the library, projected here with the camera's own matrices, against the
screenshot's pixels. Run with -s to see the figures (time to an interactive page, the delay from
a reading to the drawn pose)."""
import io
import json
import re
import os
import statistics
import time

import pytest

from conftest import ROOT, MethodLab, assert_aborted_safely, wait_for

import fbrl
from fbrl_station import pb
from fbrl_station.sila import I, S

PIL = pytest.importorskip("PIL.Image", reason="python3-pil reads the screenshots")
cdp = pytest.importorskip("cdp", reason="python3-websocket drives chromium")
SHOTS = os.environ.get("FBRL_PAGE_SHOTS")  # a folder for the screenshots (docs/page.md's come from here)
COLOURS = {"box": (0xb8, 0xb8, 0xb8), "cylinder": (0xc8, 0xa0, 0x70), "tool": (0xff, 0x00, 0xff),
           "table": (0xe2, 0xdc, 0xcb), "background": (0xf4, 0xf6, 0xf8)}  # page.js's COLOURS


class Lab(MethodLab):
    """The method library of the station's tests, fbrlsim with its log, a station serving the
    page on a free loopback port, a browser on it."""

    def __init__(self, directory):
        super().__init__(directory, "--http", "127.0.0.1:0", sample_prep=False)
        try:
            wait_for(lambda: any("the page on http://" in l for l in self.station.lines), what="the page's address")
            line = next(l for l in self.station.lines if "the page on http://" in l)
            self.url = line[line.index("http://"):].strip()
            self.browser = cdp.Browser()
        except BaseException:
            super().stop()
            raise

    def stop(self):
        self.browser.close()
        super().stop()


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    lab = Lab(str(tmp_path_factory.mktemp("page")))
    yield lab
    lab.stop()


def shot(lab, name):
    png = lab.browser.screenshot()
    if SHOTS:
        os.makedirs(SHOTS, exist_ok=True)
        with open(os.path.join(SHOTS, name), "wb") as f:
            f.write(png)
    return PIL.open(io.BytesIO(png)).convert("RGB")


def project(cam, p):
    """Page pixel of the cell's point p, from the camera's matrices (column-major, as three.js
    keeps them): clip = P V p, then the canvas's viewport."""
    P, V = cam["projection"], cam["view"]

    def mul(m, v):
        return [sum(m[c * 4 + r] * v[c] for c in range(4)) for r in range(4)]

    clip = mul(P, mul(V, [p[0], p[1], p[2], 1.0]))
    x, y = clip[0] / clip[3], clip[1] / clip[3]
    return cam["left"] + (x + 1) / 2 * cam["width"], cam["top"] + (1 - y) / 2 * cam["height"]


def near(c, want, tol=14):
    return all(abs(a - b) <= tol for a, b in zip(c, want))


def the_cell():
    """The obstacles as the station's cell files describe them (.CELL of the same files)."""
    with fbrl.Engine() as e:
        e.eval("INCLUDE %s" % os.path.join(ROOT, "examples", "asps_cell_objects.fbrl"))
        out = e.eval(".CELL")
    return out


def ready(lab):
    """The page, opened unless it is open already (a test may run alone: pytest -k)."""
    if not lab.browser.eval("!!(window.fbrlPage && window.fbrlPage.ready)"):
        open_page(lab)
    return lab.browser


def open_page(lab):
    b = lab.browser
    t0 = time.monotonic()
    b.goto(lab.url)
    b.wait_for("window.fbrlPage && window.fbrlPage.ready === true", seconds=60, what="an interactive page")
    return time.monotonic() - t0


# ------------------------------------------------------------------ the view
def test_the_page_loads_and_shows_the_cell_where_the_model_puts_it(lab):
    took = open_page(lab)
    b = lab.browser
    assert b.eval("fbrlPage.errors.length") == 0, b.eval("fbrlPage.errors")
    print("\ntime to an interactive page: %.2f s (page's own clock from navigation: %.0f ms)"
          % (took, b.eval("fbrlPage.readyAt")))
    print("  (ms from navigation: script %(script).0f, scene and methods fetched %(fetched).0f, view built %(view).0f, "
          "WebSocket open %(open).0f)" % b.eval("fbrlPage.marks"))
    scene = b.eval("fbrlPage.scene")
    listed = the_cell()
    for o in scene["obstacles"]:  # every obstacle of the cell files, with its numbers
        assert o["name"] in listed
    assert {o["name"] for o in scene["obstacles"]} >= {"HEATING-BLOCK-BODY", "SEPARATION-UNIT", "OPERATOR-SIDE"}
    assert any(p["site"] == "HEATING-BLOCK" and p["count"] == 24 for p in scene["places"])
    # the block's name is a site here, not a calibration structure: the guard and the page leave it as taught
    assert next(o for o in scene["obstacles"] if o["name"] == "HEATING-BLOCK-BODY")["placed"] is None
    shot(lab, "page.png")
    b.eval("document.getElementById('show-labels').click(); fbrlPage.setView('top'); true")
    time.sleep(0.5)
    img = shot(lab, "page-top.png")
    cam = b.eval("fbrlPage.camera()")
    drawn = 0
    for o in scene["obstacles"]:
        if o["kind"] not in ("box", "cylinder"):
            continue
        # points of its top face (inset from the edges) show its colour, or the arm or a place
        # marker above it, never the table: the heating block under the arm at READY shows its
        # colour at 6 to 12 of 25; one drawn elsewhere would show the table
        steps = (0.2, 0.35, 0.5, 0.65, 0.8)
        pts = [(o["lo"][0] + (o["hi"][0] - o["lo"][0]) * fx, o["lo"][1] + (o["hi"][1] - o["lo"][1]) * fy, o["hi"][2])
               for fx in steps for fy in steps]
        if o["kind"] == "cylinder":
            pts = [(o["c"][0] + (fx - 0.5) * o["r"], o["c"][1] + (fy - 0.5) * o["r"], o["hi"][2]) for fx in steps
                   for fy in steps]
        seen = [img.getpixel(tuple(int(round(v)) for v in project(cam, p))) for p in pts]
        hits = sum(near(c, COLOURS[o["kind"]]) for c in seen)
        ground = [c for c in seen if near(c, COLOURS["table"], 20) or near(c, COLOURS["background"], 8)]
        assert hits >= 5 and not ground, "%s: %d of 25 points show its colour, %d the table" % (
            o["name"], hits, len(ground))
        drawn += 1
    assert drawn >= 5
    # and the table between them is the table: the picture is not all obstacle
    x, y = project(cam, (4.0, -4.0, 0.0))
    assert near(img.getpixel((int(x), int(y))), COLOURS["table"], 20)
    b.eval("document.getElementById('show-labels').click(); fbrlPage.setView('3d'); true")


# the heating block put back turned a quarter about z, its body's corner (9, -3) now at (3, 9):
# p = r p_taught + t as CAL-STRU! stores it, row by row [r | t]
TURNED = ((0.0, -1.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0))
TURN_BLOCK = "CREATE-CAL-STRU HEATING-BLOCK " + " ".join(
    "%rE0 HEATING-BLOCK %d CAL-STRU!" % (v, 4 * i + j + 1) for i, row in enumerate(TURNED) for j, v in enumerate(row))


def test_a_block_moved_by_its_calibration_is_drawn_where_the_guard_checks_it(tmp_path):
    """The heating block's calibration (the CREATE-CAL-STRU the guard looks up by the block's
    name before every motion) turns it: its body is drawn turned, and nothing of it where it
    was taught. The truth is the matrix stored here and the cell file's box, not the page."""
    from conftest import SITES, Sim, Station, launcher, method_library
    sim = Sim(str(tmp_path / "sim"))
    station = browser = None
    try:  # as MethodLab starts it (no place inside the block: the method files describe the cell again)
        station = Station(launcher(), str(tmp_path / "data"), "--port", sim.port, "--no-discovery", "--methods",
                          method_library(str(tmp_path), sample_prep=False), "--http", "127.0.0.1:0", SITES,
                          "-e", TURN_BLOCK)
        wait_for(lambda: any("the page on http://" in l for l in station.lines), what="the page's address")
        line = next(l for l in station.lines if "the page on http://" in l)
        browser = cdp.Browser()
        browser.goto(line[line.index("http://"):].strip())
        browser.wait_for("window.fbrlPage && window.fbrlPage.ready === true", seconds=60, what="an interactive page")
        body = next((o for o in browser.eval("fbrlPage.scene.obstacles") if o["name"] == "HEATING-BLOCK-BODY"), None)
        assert body is not None, "\n".join(station.lines)
        assert body["placed"] == {"r": [list(r[:3]) for r in TURNED], "t": [r[3] for r in TURNED]}, body
        browser.eval("document.getElementById('show-labels').click(); fbrlPage.setView('top'); true")
        time.sleep(0.5)
        img = PIL.open(io.BytesIO(browser.screenshot())).convert("RGB")
        cam = browser.eval("fbrlPage.camera()")
        lo, hi = (9.0, -3.0, 0.0), (14.0, 3.0, 1.75)  # asps_cell_objects.fbrl's box, as taught
        steps = (0.2, 0.35, 0.5, 0.65, 0.8)
        taught = [(lo[0] + (hi[0] - lo[0]) * fx, lo[1] + (hi[1] - lo[1]) * fy, hi[2]) for fx in steps for fy in steps]
        moved = [tuple(sum(r[k] * p[k] for k in range(3)) + r[3] for r in TURNED) for p in taught]
        at = lambda pts: [img.getpixel(tuple(int(round(v)) for v in project(cam, p))) for p in pts]  # noqa: E731
        there = sum(near(c, COLOURS["box"]) for c in at(moved))
        left = sum(near(c, COLOURS["box"]) for c in at(taught))
        assert there >= 20 and left == 0, "turned: %d of 25 points grey; as taught: %d" % (there, left)
        # and the guard sees it there too: BUMP's move into the body as taught now passes (the
        # station's own dry run, the same cell files and texts; refused with the block as taught)
        browser.eval("var s = document.getElementById('method'); s.value = 'BUMP'; s.onchange(); "
                     "window.fbrlPage.plan = null; document.getElementById('dry').click(); true")
        plan = browser.wait_for("fbrlPage.plan", seconds=60, what="the dry run")
        assert plan["outcome"] == "completed" and not plan["refused"], plan["report"]
        into = plan["segments"][-1]
        assert into["sent"] and all(abs(a - b) < 1e-3 for a, b in zip(into["points"][-1], (10.0, -2.0, 0.5))), into
    finally:
        if browser is not None:
            browser.close()
        if station is not None:
            station.stop()
        sim.stop()


def magenta_centre(img, cx, cy, r=60):
    xs, ys = [], []
    for x in range(max(0, int(cx) - r), min(img.width, int(cx) + r)):
        for y in range(max(0, int(cy) - r), min(img.height, int(cy) + r)):
            r, g, b = img.getpixel((x, y))
            if r >= 200 and b >= 170 and g <= 110:  # magenta, also seen through a translucent keep-out zone
                xs.append(x)
                ys.append(y)
    assert xs, "no tool point drawn near (%d, %d)" % (cx, cy)
    return sum(xs) / len(xs), sum(ys) / len(ys)


def test_a_run_from_the_page_goes_to_its_end_as_fbrlsim_logs_it(lab):
    b = ready(lab)
    b.eval("document.getElementById('take').click(); true")
    b.wait_for("document.getElementById('control').textContent === 'you control the runs'", what="control")
    b.eval("var s = document.getElementById('method'); s.value = 'QUICK'; s.onchange(); true")
    # out of range: the page refuses it, nothing reaches the station
    before = len(lab.sim.log())
    b.eval("document.querySelector('#params input[name=\"#ITEMS\"]').value = '9'; "
           "document.getElementById('run').click(); true")
    time.sleep(0.5)
    assert b.eval("document.getElementById('messages').textContent").count("#ITEMS must be a whole number in 1..6")
    assert b.eval("fbrlPage.run === undefined")
    # and the station refuses it too when a page sends it all the same
    b.eval("window.fbrlPage.errors = []; true")
    b.eval("document.querySelector('#params input[name=\"#ITEMS\"]').value = '2'; "
           "document.querySelector('#params input[name=\"HOLD-DS\"]').value = '1'; "
           "document.getElementById('run').click(); true")
    end = b.wait_for("fbrlPage.run && fbrlPage.run.end", seconds=120, what="the run's end")
    assert end["outcome"] == "completed", end
    assert [(s["sample"], s["outcome"]) for s in end["samples"]] == [(1, "succeeded"), (2, "succeeded")]
    events = [(e["event"], e["step_name"], e["sample"]) for e in b.eval("fbrlPage.run.events")]
    assert events == [("StepStarted", "Home", 0), ("StepEnded", "Home", 0), ("StepStarted", "Item", 1),
                      ("StepEnded", "Item", 1), ("StepStarted", "Item", 2), ("StepEnded", "Item", 2)]
    log = lab.sim.log()[before:]
    assert "HOME" in log and log.count("OUTPUT 1") == 2 and log.count("OUTPUT -1") == 2
    on = [i for i, l in enumerate(log) if l == "OUTPUT 1"]
    assert all(any(l.startswith("MOVE") for l in log[a:b]) for a, b in zip([0] + on, on + [len(log)])), log
    rows = b.eval("[...document.querySelectorAll('#steps tr')].map(r => r.className)")
    assert rows == ["done", "done"]
    b.wait_for("document.getElementById('arm-state').textContent === 'Idle'", what="the arm idle after the run")
    b.wait_for("document.getElementById('reading').className === ''", what="a fresh reading, not an estimate")
    shot(lab, "page-run.png")


def test_the_drawn_tool_point_is_the_fk_of_the_pose_read_from_fbrlsim(lab):
    """Moves by a SiLA client: the page draws the pose the station
    read from fbrlsim; the library's forward kinematics of its joints, projected here, is where
    the page's tool point is in the screenshot."""
    b, client = ready(lab), lab.client
    arm = fbrl.Arm("a255")
    am = pb.messages("ArmController")
    result, _ = client.run("ArmController", "Home")
    assert not hasattr(result, "identifier"), result
    for place, index in (("HEATING-BLOCK", 5), ("SEPARATOR", 0)):
        result, _ = client.run("ArmController", "MoveToPlace", Place=am.DataType_PlaceName(PlaceName=S(place)),
                               Index=I(index))
        assert not hasattr(result, "identifier"), result
        stream = client.subscribe("ArmController", "Position")
        read = next(iter(stream)).Position
        stream.cancel()
        joints = [j.Degrees.value for j in read.Joints]
        loc = read.Location.Location
        world = [loc.X.Inches.value, loc.Y.Inches.value, loc.Z.Inches.value]
        wait_for(lambda: b.eval("fbrlPage.lastPose && fbrlPage.lastPose.joints") == joints,
                 what="the page to draw the pose read")
        time.sleep(0.3)  # a frame or two
        fk = arm.fk(joints)
        assert all(abs(a - w) < 0.01 for a, w in zip(fk[:3], world)), (fk, world)  # fbrlsim's own answer agrees
        cam = b.eval("fbrlPage.camera()")
        x, y = project(cam, fk[:3])
        img = shot(lab, "page-tool-%s.png" % place.lower())
        mx, my = magenta_centre(img, x, y)
        print("\n%s: tool point drawn at (%.1f, %.1f), FK projected (%.1f, %.1f)" % (place, mx, my, x, y))
        assert abs(mx - x) <= 3 and abs(my - y) <= 3, ((mx, my), (x, y))
        assert b.eval("document.getElementById('p-x').textContent") == "%.3f in" % world[0]
    delays = b.eval("fbrlPage.delays")
    print("delay from a controller reading to the drawn pose: median %.0f ms, max %.0f ms over %d readings"
          % (statistics.median(delays), max(delays), len(delays)))


def test_the_arm_is_drawn_as_it_moves_in_a_run(lab):
    """A run's slow moves (CROSS, 1 % speed): the station reads the arm while it moves (W2 in
    fbrlsim's log between a MOVE and the next command), the page draws each reading where the
    library's forward kinematics puts the tool point, and marks the pose estimated meanwhile."""
    b = ready(lab)
    if b.eval("document.getElementById('control').textContent") != "you control the runs":
        b.eval("document.getElementById('take').click(); true")
    b.wait_for("document.getElementById('control').textContent === 'you control the runs'", what="control")
    b.eval("var s = document.getElementById('method'); s.value = 'CROSS'; s.onchange(); true")
    arm = fbrl.Arm("a255")
    before = len(lab.sim.log())
    t0 = time.time()
    earlier = b.eval("fbrlPage.run ? fbrlPage.run.uuid : ''")
    drawn_before = b.eval("fbrlPage.poses")
    b.eval("document.getElementById('run').click(); true")
    b.wait_for("fbrlPage.run && fbrlPage.run.uuid !== %s" % json.dumps(earlier), what="the run to start")
    poses, drawn, estimated = {}, 0, 0
    deadline = time.monotonic() + 120
    while not b.eval("!!(fbrlPage.run && fbrlPage.run.end)") and time.monotonic() < deadline:
        p = b.eval("fbrlPage.lastPose")
        if p and p["read_at"] > t0 and p["read_at"] not in poses:
            poses[p["read_at"]] = p
            estimated += b.eval("document.getElementById('reading').className") == "estimated"
            if drawn < 2 and b.eval("document.getElementById('arm-state').textContent") == "Running":
                time.sleep(0.3)  # a frame or two
                img = shot(lab, "page-moving.png")
                # a screenshot is slow on a loaded machine: the next reading may be drawn by then
                if b.eval("fbrlPage.lastPose.read_at") == p["read_at"]:
                    x, y = project(b.eval("fbrlPage.camera()"), arm.fk(p["joints"])[:3])
                    mx, my = magenta_centre(img, x, y)
                    print("\nmoving: tool point drawn at (%.1f, %.1f), FK projected (%.1f, %.1f)" % (mx, my, x, y))
                    assert abs(mx - x) <= 3 and abs(my - y) <= 3, ((mx, my), (x, y))
                    drawn += 1
        time.sleep(0.1)
    end = b.eval("fbrlPage.run.end")
    assert end["outcome"] == "completed", end
    log = lab.sim.log()[before:]
    slow = log.index("SPEED 1")
    back = log.index("SPEED 50", slow)
    readings = log[slow:back].count("W2")
    moving = list(poses.values())  # the readings this test saw drawn (it looks every 0.1 s)
    worlds = {tuple(round(v, 2) for v in p["world"][:3]) for p in moving}
    drawn_by_page = b.eval("fbrlPage.poses") - drawn_before
    print("readings while the run moved: %d in fbrlsim's log; the page drew %d poses in the run, this test "
          "saw %d of them at %d places and checked %d against the FK in the screenshot"
          % (readings, drawn_by_page, len(moving), len(worlds), drawn))
    assert readings >= 6, log[slow:back]  # two moves of about 6 s, one reading a second
    assert drawn_by_page >= readings, (drawn_by_page, readings)  # every reading drawn
    # (every screenshot taken while its reading was still the one drawn was checked above; on a
    # machine so loaded that each took over a second there may be none: the FK test below holds)
    assert len(worlds) >= 4 and estimated >= len(moving) - 2, (worlds, estimated)
    for p in moving:  # each reading is fbrlsim's own: its joints' FK is its position
        assert all(abs(a - w) < 0.01 for a, w in zip(arm.fk(p["joints"])[:3], p["world"][:3])), p


def test_abort_from_the_page_halts_the_arm(lab):
    b = ready(lab)
    if b.eval("document.getElementById('control').textContent") != "you control the runs":
        b.eval("document.getElementById('take').click(); true")
    b.eval("var s = document.getElementById('method'); s.value = 'QUICK'; s.onchange(); "
           "document.querySelector('#params input[name=\"#ITEMS\"]').value = '3'; "
           "document.querySelector('#params input[name=\"HOLD-DS\"]').value = '50'; "
           "window.asked = 0; window.confirm = () => { window.asked++; return true; }; true")
    before = len(lab.sim.log())
    b.eval("document.getElementById('run').click(); true")
    wait_for(lambda: "OUTPUT 1" in lab.sim.log()[before:], what="the pump to run")
    b.wait_for("document.getElementById('reading').className === 'estimated'", what="the pose marked estimated")
    b.eval("document.getElementById('abort').click(); true")
    end = b.wait_for("fbrlPage.run && fbrlPage.run.end", seconds=60, what="the run's end")
    assert b.eval("window.asked") == 1
    assert end["outcome"] == "error" and "MethodCancelled" in end["summary"] and "page 1" in end["summary"], end
    assert_aborted_safely(lab.sim.log()[before:])


def test_one_page_controls_the_runs_the_other_is_told_who(lab):
    b = ready(lab)
    if b.eval("document.getElementById('control').textContent") != "you control the runs":
        b.eval("document.getElementById('take').click(); true")
        b.wait_for("document.getElementById('control').textContent === 'you control the runs'")
    other = cdp.Browser()
    try:
        other.goto(lab.url)
        other.wait_for("window.fbrlPage && window.fbrlPage.ready === true", seconds=60, what="the second page")
        assert other.eval("document.getElementById('control').textContent") == "page 1 (127.0.0.1) controls the runs"
        assert other.eval("document.getElementById('run').disabled") is True
        other.eval("document.getElementById('take').disabled = false; document.getElementById('take').click(); true")
        other.wait_for("fbrlPage.errors.length > 0", what="the refusal")
        assert "page 1 (127.0.0.1) controls the runs" in other.eval("fbrlPage.errors[0]")
        b.eval("document.getElementById('release').click(); true")
        other.wait_for("document.getElementById('control').textContent === 'no one controls the runs'")
    finally:
        other.close()


def test_a_dry_run_from_the_page_shows_the_plan_and_moves_nothing(lab):
    b = ready(lab)
    before = len(lab.sim.log())
    b.eval("var s = document.getElementById('method'); s.value = 'QUICK'; s.onchange(); "
           "document.querySelector('#params input[name=\"#ITEMS\"]').value = '3'; "
           "document.querySelector('#params input[name=\"HOLD-DS\"]').value = '10'; "
           "window.fbrlPage.plan = null; document.getElementById('dry').click(); true")
    plan = b.wait_for("fbrlPage.plan", seconds=60, what="the dry run")
    assert plan["method"] == "QUICK" and plan["outcome"] == "completed", plan["report"]
    assert [(s["sample"], s["outcome"]) for s in plan["samples"]] == [(1, "succeeded"), (2, "succeeded"),
                                                                      (3, "succeeded")]
    assert plan["duration_s"] > 3 * 1.0  # three holds of a second (the method's own waits)
    assert plan["picture"].startswith("<?xml") and not plan["refused"]
    # a method the guard refuses: the refusal names the obstacle, the closest approach is marked
    b.eval("var s = document.getElementById('method'); s.value = 'BUMP'; s.onchange(); "
           "window.fbrlPage.plan = null; document.getElementById('dry').click(); true")
    plan = b.wait_for("fbrlPage.plan", seconds=60, what="the dry run")
    assert plan["refused"] and "HEATING-BLOCK-BODY" in plan["refused"][0], plan["report"]
    assert "refused: " in b.eval("document.getElementById('plan').textContent")
    # nothing reached the controller but the page's once-a-second readings of the arm
    assert [l for l in lab.sim.log()[before:] if l not in ("W2", "STATUS")] == []
    shot(lab, "page-dry-run.png")
    # the point of contact the guard names is marked red in the view
    hit = re.search(r"at X (\S+) Y (\S+) Z (\S+) in", plan["refused"][0])
    b.eval("document.getElementById('show-labels').click(); true")
    time.sleep(0.3)
    x, y = project(b.eval("fbrlPage.camera()"), [float(v) for v in hit.groups()])
    img = shot(lab, "page-dry-run-nolabels.png")
    b.eval("document.getElementById('show-labels').click(); true")
    assert near(img.getpixel((int(round(x)), int(round(y)))), (0xff, 0, 0), 30)


def cell_solids():
    """The solid obstacles and the table of the cell files, read here from .CELL: [(name,
    distance function of a point)], and the tool envelope's radius."""
    solids, tool_r = [], None
    for line in the_cell().splitlines():
        w = line.replace(",", "").split()
        if line.startswith("cell:"):
            z = float(w[w.index("table") + 1])
            tool_r = float(w[w.index("radius") + 1])
            solids.append(("the table", lambda p, z=z: p[2] - z))
        elif len(w) >= 10 and w[1] == "cylinder":
            x, y, r = float(w[3]), float(w[5]), float(w[9])
            lo, hi = (float(v) for v in w[7].split(".."))

            def cyl(p, x=x, y=y, r=r, lo=lo, hi=hi):
                dr = max(((p[0] - x) ** 2 + (p[1] - y) ** 2) ** 0.5 - r, 0.0)
                dz = max(lo - p[2], p[2] - hi, 0.0)
                return (dr * dr + dz * dz) ** 0.5
            solids.append((w[0], cyl))
        elif len(w) >= 9 and w[1] == "box":
            lo, hi = [float(v) for v in w[2:5]], [float(v) for v in w[6:9]]
            solids.append((w[0], lambda p, lo=lo, hi=hi: sum(max(lo[i] - p[i], p[i] - hi[i], 0.0) ** 2
                                                               for i in range(3)) ** 0.5))
    return solids, tool_r


def test_the_dry_run_path_is_drawn_coloured_by_its_clearance_a_refused_move_red(lab):
    """SKIM goes down close over the heating block (clear), then into it (refused). The
    clearance fbrlmon reports for the close move is the tool envelope's distance to the
    nearest solid, worked out here from the cell file's boxes and the reported tool points;
    the refused move ends at the block it names, and is drawn red there."""
    b = ready(lab)
    before = len(lab.sim.log())
    b.eval("var s = document.getElementById('method'); s.value = 'SKIM'; s.onchange(); "
           "window.fbrlPage.plan = null; document.getElementById('dry').click(); true")
    plan = b.wait_for("fbrlPage.plan", seconds=60, what="the dry run")
    segs = plan["segments"]
    assert [(x["word"], x["step"], x["sent"]) for x in segs] == [("READY", "Over", True), ("MOV", "Over", True),
                                                                ("READY", "Into", True), ("MOV", "Into", False)], plan
    solids, tool_r = cell_solids()
    over, into = segs[1], segs[3]
    assert len(over["points"]) == 9 and len(into["points"]) == 9  # joint moves: 8 steps
    # the move ends where the method sends it (the tool point of SPOT)
    assert all(abs(a - b) < 1e-3 for a, b in zip(over["points"][-1], (11.5, 0.0, 2.15))), over
    worked = min((f(p) - tool_r, name) for p in over["points"] for name, f in solids)
    assert abs(over["clearance"] - worked[0]) < 0.01 and over["near"] == worked[1] == "HEATING-BLOCK-BODY", (
        over, worked)
    assert 0 < over["clearance"] < 0.5 and segs[0]["clearance"] >= 0.5  # orange, and the first green
    # the refused one stops at the block it names: its last tool point within the envelope of it
    assert into["hit"] == "HEATING-BLOCK-BODY" and "would hit HEATING-BLOCK-BODY" in into["message"], into
    body = dict(solids)["HEATING-BLOCK-BODY"]
    assert body(into["points"][-1]) <= tool_r + 0.1 + 1e-3, into["points"][-1]
    assert [l for l in lab.sim.log()[before:] if l not in ("W2", "STATUS")] == []  # nothing moved
    # in the view: the refused move's rod is red where it nears the block (a step short of the
    # contact, away from the contact's ball), the close one orange, the first green
    b.eval("document.getElementById('show-labels').click(); fbrlPage.setView('top'); true")
    time.sleep(0.5)
    cam = b.eval("fbrlPage.camera()")
    img = shot(lab, "page-dry-run-path.png")
    b.eval("document.getElementById('show-labels').click(); fbrlPage.setView('3d'); true")
    mid = lambda a, c: [(x + y) / 2 for x, y in zip(a, c)]  # noqa: E731
    red = mid(into["points"][-3], into["points"][-2])
    assert 0.6 < body(red) < 4.0 and ((red[0] - into["at"][0]) ** 2 + (red[1] - into["at"][1]) ** 2 + (
        red[2] - into["at"][2]) ** 2) ** 0.5 > 1.0, red  # near the block, clear of the contact's ball
    assert near(img.getpixel(tuple(int(round(v)) for v in project(cam, red))), (0xff, 0, 0), 30)
    assert near(img.getpixel(tuple(int(round(v)) for v in project(cam, mid(*over["points"][-3:-1])))),
                (0xff, 0x99, 0), 30)
    assert "refused: MOV would hit HEATING-BLOCK-BODY" in b.eval("document.getElementById('labels').textContent")


def test_other_web_sites_cannot_reach_the_station_through_the_browser(lab):
    """A web site the operator has open could open a WebSocket to 127.0.0.1 (browsers allow it)
    or point its own name at 127.0.0.1 (DNS rebinding): both are refused; the page's own are not."""
    import urllib.error
    import urllib.request

    import websocket
    ws_url = lab.url.replace("http://", "ws://") + "ws"
    host = lab.url[len("http://"):].rstrip("/")
    with pytest.raises(websocket.WebSocketBadStatusException) as e:
        websocket.create_connection(ws_url, origin="http://evil.example", timeout=10)
    assert e.value.status_code == 403
    with pytest.raises(websocket.WebSocketBadStatusException):
        websocket.create_connection(ws_url, suppress_origin=True, timeout=10)  # no Origin: not a page of ours
    with pytest.raises(urllib.error.HTTPError) as e:
        urllib.request.urlopen(urllib.request.Request(lab.url + "api/scene", headers={"Host": "evil.example"}),
                               timeout=10)
    assert e.value.code == 403
    ws = websocket.create_connection(ws_url, origin="http://" + host, timeout=10)
    try:
        assert json.loads(ws.recv())["t"] == "hello"
    finally:
        ws.close()


def test_the_history_lists_past_runs_and_opens_their_log(lab):
    """The runs of this module's earlier tests (run alone, one of its own): newest first, with
    outcome and who started it; each opens its log. The record is the station's file."""
    import urllib.request
    b = ready(lab)
    if not b.eval("fbrlPage.history && fbrlPage.history.length > 0"):
        test_a_run_from_the_page_goes_to_its_end_as_fbrlsim_logs_it(lab)
    b.wait_for("fbrlPage.history && fbrlPage.history.some(r => r.outcome === 'completed')", what="the history")
    runs = b.eval("fbrlPage.history")
    assert [r["start"] for r in runs] == sorted((r["start"] for r in runs), reverse=True)
    done = next(r for r in runs if r["outcome"] == "completed" and r["method"] == "QUICK")
    assert done["method"] == "QUICK" and done["by"].startswith("page ") and done["values"] == [["#ITEMS", 2],
                                                                                               ["HOLD-DS", 1]]
    assert b.eval("document.querySelectorAll('#history li').length") == len(runs)
    # its method version: the files' hash as fbrl-audit names it for the library's file
    import subprocess
    from conftest import launcher
    audit = os.environ.get("FBRL_AUDIT") or os.path.join(os.path.dirname(launcher()), "fbrl-audit")
    out = subprocess.run([audit, "method", "status", os.path.join(lab.lib, "station_tests.fbrl"), "--lab",
                          lab.station.data], capture_output=True, text=True, timeout=30)
    version = re.match(r"\S+ version ([0-9a-f]{64}): ", out.stdout)
    assert version and done["version"] == version.group(1), (done, out.stdout, out.stderr)
    assert "version %s" % done["version"][:12] in b.eval("document.getElementById('history').textContent")
    text = urllib.request.urlopen(lab.url + "history/" + done["uuid"], timeout=10).read().decode()
    assert "method version: %s" % done["version"] in text
    assert "outcome: completed" in text and "StepEnded          Item, sample 2" in text, text
    assert "sample 2: succeeded" in text
    with open(os.path.join(lab.station.data, "runs.jsonl")) as f:
        assert sum(1 for _ in f) == len(runs)


def test_a_page_that_cannot_be_served_stops_the_station_cleanly(tmp_path):
    """The page's port is taken: the station says so, exits 3 and leaves no emulator behind."""
    import socket
    import subprocess

    from conftest import fbrlsim, launcher
    wrapper = tmp_path / "fbrlsim"
    pid_file = tmp_path / "sim.pid"
    wrapper.write_text("#!/bin/sh\necho $$ > '%s'\nexec '%s' \"$@\"\n" % (pid_file, fbrlsim()))
    wrapper.chmod(0o755)
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        p = subprocess.run([launcher(), "--sim", "--data", str(tmp_path / "data"), "--no-discovery", "--sila",
                            "127.0.0.1:0", "--http", "127.0.0.1:%d" % port], capture_output=True, text=True,
                           timeout=120, env=dict(os.environ, FBRL_SIM=str(wrapper)))
    assert p.returncode == 3 and "cannot serve the page on 127.0.0.1:%d" % port in p.stderr, p.stderr
    pid = int(pid_file.read_text())
    wait_for(lambda: not os.path.exists("/proc/%d" % pid) or open("/proc/%d/stat" % pid).read().split()[2] == "Z",
             seconds=10, what="the emulator to end")
