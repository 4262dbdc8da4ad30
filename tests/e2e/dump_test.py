#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""dump_test.py FBRLMON FBRL_DUMP TMPDIR - fbrl-dump against files fbrlmon wrote, and
against the bytes themselves: an independent reader of the on-disk format
(docs/files.md, "On-disk format") decodes every file too, and fbrl-dump's JSON and CSV
must say exactly what it found. Damaged files print nothing and exit 1."""
import csv
import io
import json
import os
import struct
import subprocess
import sys
import zlib

MAGIC = b"\x89FBRLD\r\n"
TYPES = {1: ("CHR", "<B"), 2: ("INTEGER", "<h"), 3: ("LONG", "<i"), 4: ("REAL", "<d"), 5: ("LOCATION", "<6d")}
AXES = ("x", "y", "z", "o", "a", "t")

fails = 0


def check(cond, what):
    global fails
    if not cond:
        fails += 1
        print("FAIL: " + what)


def read_fbrld(path):
    """The format as docs/files.md gives it: header, CRCs, records. Returns [(code, tag, payload)]."""
    data = open(path, "rb").read()
    assert data[:8] == MAGIC, "magic"
    version, hsize, length, count, dcrc, _res, hcrc = struct.unpack_from("<HHIIIII", data, 8)
    assert version == 1 and hsize == 32 and length == len(data)
    assert zlib.crc32(data[:28]) == hcrc and zlib.crc32(data[32:]) == (dcrc if length > 32 else 0)
    recs, pos = [], 32
    for _ in range(count):
        code, _r, tag, size = struct.unpack_from("<BBHI", data, pos)
        recs.append((code, tag, data[pos + 8:pos + 8 + size]))
        pos += 8 + size
    assert pos == length
    return recs


def run(*args, ok=True):
    p = subprocess.run(list(args), capture_output=True, text=True, timeout=60)
    if ok and p.returncode != 0:
        raise SystemExit("FAIL: %s exited %d: %s" % (args, p.returncode, p.stderr))
    return p


def main(mon, dump, tmp):
    os.makedirs(tmp, exist_ok=True)
    os.chdir(tmp)
    for f in ("d.fbd", "w.ws"):
        if os.path.exists(f):
            os.remove(f)
    # a data file with every built-in type and a user record, written by FBRL
    run(mon, "--offline", "-e", "CREATE B 16 ALLOT  FVARIABLE R  CREATE-LOC L1  CREATE-FILE d.fbd  OPEN-FILE H d.fbd"
        "  65 B C! B CHR H WRITE-FILE  -1234 B W! B INTEGER H WRITE-FILE  -70000 B ! B LONG-INTEGER H WRITE-FILE"
        "  0.1E0 R F! R REAL H WRITE-FILE  1.5E0 -2.25E0 3E0 90E0 -45E0 10E0 L1 DEFINE-LOC L1 LOCATION H WRITE-FILE"
        "  S\" A,B\" B SWAP MOVE B 3 H WRITE-FILE  H CLOSE-FILE DROP")
    truth = read_fbrld("d.fbd")
    check(len(truth) == 6, "the data file holds %d records, not 6" % len(truth))
    doc = json.loads(run(dump, "d.fbd").stdout)
    check(doc["format"] == "fbrl-data" and doc["count"] == len(truth), "JSON header: %r" % {k: doc[k] for k in ("format", "count")})
    rows = list(csv.DictReader(io.StringIO(run(dump, "--format=csv", "d.fbd").stdout, newline="")))
    for i, (code, tag, payload) in enumerate(truth):
        rec = doc["records"][i]
        mine = [r for r in rows if r["index"] == str(i)]
        if code in TYPES:
            name, fmt = TYPES[code]
            vals = struct.unpack(fmt, payload)
            check(rec["type"] == name, "record %d type %s, the bytes say %s" % (i, rec["type"], name))
            if code == 5:
                check([rec["value"][a] for a in AXES] == list(vals), "record %d location %r vs %r" % (i, rec["value"], vals))
                check([float(r["value"]) for r in mine] == list(vals) and [r["field"] for r in mine] == list(AXES),
                      "record %d CSV location" % i)
            else:
                check(rec["value"] == vals[0], "record %d value %r, the bytes say %r" % (i, rec["value"], vals[0]))
                check(len(mine) == 1 and float(mine[0]["value"]) == vals[0], "record %d CSV value" % i)
        else:
            check(rec["type"] == "USER" and rec["tag"] == tag and bytes.fromhex(rec["hex"]) == payload,
                  "user record %d: %r vs %r" % (i, rec, payload))
            check(len(mine) == 1 and bytes.fromhex(mine[0]["value"]) == payload, "record %d CSV hex" % i)
    check(doc["records"][3]["value"] == 0.1, "0.1 does not read back to the same double")

    # a workspace: named objects with named numbers
    run(mon, "--offline", "-e", "CREATE-LOC P  1.5E0 -2E0 3E0 0E0 -90E0 0E0 P DEFINE-LOC  P 0.75E0 0.5E0 0E0 RECTMAT RACK"
        "  CREATE-LOC \"Q,1\"  SAVE-WORKSPACE w.ws")
    truth = read_fbrld("w.ws")
    ws = json.loads(run(dump, "w.ws").stdout)
    check(ws["format"] == "fbrl-workspace", "w.ws is not seen as a workspace: " + ws["format"])
    byname = {(r.get("kind"), r.get("name")): r for r in ws["records"]}
    check(("header", "FBRL-WORKSPACE") in byname, "no header record")
    p = byname.get(("location", "P"), {}).get("values", {})
    check([p.get(a) for a in AXES] == [1.5, -2.0, 3.0, 0.0, -90.0, 0.0], "location P: %r" % p)
    rack = byname.get(("rectmat", "RACK"), {}).get("values", {})
    check(rack.get("base_x") == 1.5 and rack.get("dx") == 0.75 and rack.get("dy") == 0.5, "RACK: %r" % rack)
    for r, (code, tag, payload) in zip(ws["records"], truth):  # every number as the bytes have it
        n = payload[0]
        vals = struct.unpack("<%dd" % ((len(payload) - 1 - n) // 8), payload[1 + n:])
        check(r["name"] == payload[1:1 + n].decode() and list(r["values"].values()) == list(vals),
              "workspace record %d: %r vs %r" % (r["index"], r, vals))
    rows = list(csv.DictReader(io.StringIO(run(dump, "-f", "csv", "w.ws").stdout, newline="")))
    check(any(r["name"] == '"Q,1"' and r["kind"] == "location" for r in rows), "a name with a comma does not survive CSV")

    # damaged files: nothing on stdout, the reason on stderr, status 1
    data = bytearray(open("d.fbd", "rb").read())
    data[40] ^= 0x01
    open("bad.fbd", "wb").write(bytes(data))
    p = run(dump, "bad.fbd", ok=False)
    check(p.returncode == 1 and p.stdout == "" and "checksum" in p.stderr, "damaged file: %d %r %r" % (p.returncode, p.stdout, p.stderr))
    p = run(dump, "no-such-file", ok=False)
    check(p.returncode == 1 and "no such" in p.stderr, "missing file: %d %r" % (p.returncode, p.stderr))
    p = run(dump, "--format", "xml", "d.fbd", ok=False)
    check(p.returncode == 2, "--format xml: status %d" % p.returncode)
    print("dump: %d failures" % fails)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
