# SPDX-License-Identifier: MIT
"""The work cell as a scheduler sees it: the sites and plate types the cell files declare
(sites.fbrl), and the places taught through the station (kept in the data folder). The
engine holds them; this keeps the lists other threads read, and builds the only FBRL text a
client's names ever reach: known indexes and numbers, never the client's text itself."""
import os
import re
import threading

from .controller import RobotFailure

SITES_FBRL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "sites.fbrl")
KIND_WORD, KIND_LOC = 0, 1
# What a place's name may be (ArmController's PlaceName): FBRL reads it as a word, never as a
# number, a comment or a string.
NAME_RE = re.compile(r"[A-Za-z][A-Za-z0-9_.:+\-]{0,30}\Z")
PLACES_FILE = "places.json"


def forth_float(v):
    """A float as FBRL reads it back exactly."""
    return "%.17E" % v


class Site:
    def __init__(self, index, name, count, kind):
        self.index, self.name, self.count, self.kind = index, name, count, kind


class Cell:
    def __init__(self, data):
        self.data = data
        self._mutex = threading.Lock()
        self._sites = []
        self._plates = []
        self.taught = {k: [float(x) for x in v] for k, v in data.read_json(PLACES_FILE, {}).items()}

    # ---------------------------------------------------------------- any thread
    @property
    def sites(self):
        with self._mutex:
            return list(self._sites)

    @property
    def plates(self):
        with self._mutex:
            return list(self._plates)

    def site(self, name):
        """The site of that name (without regard to case), or None."""
        for s in self.sites:
            if s.name.upper() == name.upper():
                return s
        return None

    def plate(self, name):
        """(index, name, width) of the plate type, or None."""
        for p in self.plates:
            if p[1].upper() == name.upper():
                return p
        return None

    def is_taught(self, name):
        return any(k.upper() == name.upper() for k in self.taught)

    # ---------------------------------------------------------------- owner thread
    def install(self, c):
        """The site words, before the cell files."""
        c.engine.include(SITES_FBRL)

    def refresh(self, c):
        """Read the declared sites and plate types from the engine."""
        sites = []
        for i, line in enumerate(c.eval(".SITES").splitlines()):
            name, count, kind = line.split()
            sites.append(Site(i, name, int(count), int(kind)))
        plates = []
        for i, line in enumerate(c.eval(".PLATE-TYPES").splitlines()):
            name, width = line.split()
            plates.append((i, name, float(width)))
        with self._mutex:
            self._sites, self._plates = sites, plates

    def restore(self, c, warn):
        """Define the places taught earlier (the taught position wins over a cell file's)."""
        for name, loc in sorted(self.taught.items()):
            if not NAME_RE.match(name):
                warn("%s: %r is not a place name: left out" % (PLACES_FILE, name))
                continue
            values = " ".join(forth_float(v) for v in loc)
            s = self.site(name)
            if s is not None and s.kind == KIND_LOC:
                c.eval("%s %s DEFINE-LOC" % (values, name))
            elif s is None and not self.defined(c, name):
                c.eval("CREATE-LOC %s %s %s DEFINE-LOC LOC-SITE %s" % (name, values, name, name))
            else:
                warn("%s: %s is now a %s of the cell, not a place: the taught position is not used"
                     % (PLACES_FILE, name, "device" if s is not None else "word"))
        self.refresh(c)

    @staticmethod
    def defined(c, name):
        return c.eval("[DEFINED] %s ." % name).split() == ["-1"]

    def teach(self, c, name):
        """Store the arm's position as place name (ARM-HERE); the location (6 values).
        ValueError when name is a device of several sites or another word."""
        s = self.site(name)
        if s is not None and s.kind != KIND_LOC:
            raise ValueError("%s is a device of %d sites, not a place to teach" % (s.name, s.count))
        if s is None:
            if self.defined(c, name):
                raise ValueError("%s is a word of the cell, not a place" % name)
            c.eval("CREATE-LOC %s LOC-SITE %s" % (name, name))
            self.refresh(c)
            s = self.site(name)
        _, loc = c.eval("%s ARM-HERE %s" % (s.name, " ".join("%s GET%s" % (s.name, a) for a in "XYZOAT")),
                        floats=True)
        self.taught = {k: v for k, v in self.taught.items() if k.upper() != s.name.upper()}
        self.taught[s.name] = loc
        self.data.write_json(PLACES_FILE, self.taught)
        return loc

    # ---------------------------------------------------------------- FBRL for the motions
    def site_loc(self, name, index):
        """FBRL text that leaves the location of site index of name; RobotFailure SiteNotFound."""
        s = self.site(name)
        if s is None:
            raise RobotFailure("SiteNotFound", "the cell has no site %r (Sites lists them)" % name)
        if not 0 <= index < s.count:
            raise RobotFailure("SiteNotFound", "%s has %d site%s (0..%d), not %d" % (
                s.name, s.count, "s" if s.count != 1 else "", s.count - 1, index))
        return "%d %d SITE-LOC" % (index, s.index)

    def transfer(self, origin, target, plate):
        """FBRL text of a transfer with the cell's PICK and PLACE."""
        p = self.plate(plate)
        if p is None:
            raise ValueError("no plate type %r (Plate Types lists them)" % plate)
        return "%s %d PLATE-WIDTH PICK %s PLACE" % (self.site_loc(*origin), p[0], self.site_loc(*target))
