# SPDX-License-Identifier: MIT
"""The station's data folder (--data): its identity (UUID, name), the places taught through
it, its TLS key and certificate. Files are written whole or not at all (a temporary, fsync,
rename), owner-only."""
import json
import os
import uuid as uuidlib

IDENTITY = "station.json"
PLACES = "places.json"


class DataDir:
    def __init__(self, path):
        self.path = path
        os.makedirs(path, mode=0o700, exist_ok=True)

    def file(self, name):
        return os.path.join(self.path, name)

    def read_json(self, name, default):
        try:
            with open(self.file(name), encoding="utf-8") as f:
                return json.load(f)
        except FileNotFoundError:
            return default
        except ValueError as e:
            raise ValueError("%s: not valid JSON (%s): repair or remove it" % (self.file(name), e))

    def write(self, name, data, mode=0o600):
        """Replace file name with data (bytes or str) atomically."""
        target = self.file(name)
        tmp = target + ".tmp"
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, mode)
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data.encode("utf-8") if isinstance(data, str) else data)
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, target)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise

    def write_json(self, name, value):
        self.write(name, json.dumps(value, indent=1, sort_keys=True) + "\n")

    def identity(self, default_name):
        """{"uuid": ..., "name": ...}: made at the first start and kept."""
        ident = self.read_json(IDENTITY, {})
        changed = False
        if not ident.get("uuid"):
            ident["uuid"] = str(uuidlib.uuid4())
            changed = True
        if not ident.get("name"):
            ident["name"] = default_name
            changed = True
        if changed:
            self.write_json(IDENTITY, ident)
        return ident

    def set_name(self, name):
        ident = self.read_json(IDENTITY, {})
        ident["name"] = name
        self.write_json(IDENTITY, ident)
