# SPDX-License-Identifier: MIT
"""The page's sign-in (--lab DIR, docs/page.md): the lab's users (docs/compliance.md) sign
in with their names and passwords; the library checks them (fbrl.Users: Argon2id, the count
of wrong passwords, the lockout) and the users file keeps the count, as for fbrlmon. A
signed-in browser holds a random session token in a cookie (Secure, HttpOnly,
SameSite=Strict); a session idle for the lab's idle_s is signed out. What a user may do is
the role's rights (fbrl_users_may): controlling runs needs "run", viewing any signed-in user."""
import logging
import os
import secrets
import threading
import time

import fbrl

log = logging.getLogger("fbrl-station")

USERS_FILE = "users"  # the lab folder's users file (apps/lab.h LAB_USERS_FILE)
COOKIE = "fbrl_session"
TOKEN_BYTES = 32


class LabError(ValueError):
    """The lab's users file cannot be used (none, others may write it, not one): the station
    does not start (exit status 3)."""


class Refused(Exception):
    """A sign-in the library refused; the text says why, as fbrlmon says it."""


def _load(path):
    try:
        return fbrl.Users(path)
    except fbrl.Error as e:
        if e.name == "FBRL_EPERM":
            raise LabError("%s: its group or others may write it: refused (chmod 600 %s)" % (path, path))
        if e.name == "FBRL_EFORMAT":
            raise LabError("%s: not a users file" % path)
        raise LabError("%s: %s" % (path, e))


class Session:
    def __init__(self, name, role, now):
        self.name, self.role = name, role
        self.last = now  # the user's last request (idle sign-out counts from it)


class SignIn:
    """The lab's users and the page's sessions. check() blocks (Argon2id): call it off the
    event loop. The rest is quick and called on the page's loop only (the sessions are its)."""

    def __init__(self, lab, trail=None):
        self.trail = trail  # trail.LabTrail: each attempt and sign-out recorded in the lab's audit trail
        self.path = os.path.join(lab, USERS_FILE)
        if not os.path.exists(self.path):
            raise LabError("%s: no users file: make the first administrator with 'fbrl-users --lab %s setup NAME'"
                           % (self.path, lab))
        self.idle_s = self.idle_now = _load(self.path).settings()["idle_s"]  # refused now, not at a sign-in
        self.sessions = {}  # token -> Session
        self._file = threading.Lock()  # one sign-in at a time reads, counts and writes the file

    def check(self, name, password):
        """The user ({name, role, ...}) if the library accepts the password; Refused. Blocks
        (Argon2id, the audit trail): call it off the loop. The file is read afresh (fbrlmon may
        have counted wrong passwords meanwhile) and saved after the attempt so the count
        outlives us; the attempt is recorded in the lab's audit trail, and a sign-in that
        cannot be recorded is refused."""
        with self._file:
            users = _load(self.path)
            try:
                users.login(name, password)
                st = None
            except fbrl.Error as e:
                st = e.name
            finally:
                users.save()
            x = users.user(name)
            self.idle_now = users.settings()["idle_s"]
            if self.trail is not None:
                try:
                    self.trail.login(name, _outcome(x, st), x)
                except fbrl.Error as e:
                    raise Refused("the lab's audit trail cannot record the sign-in: %s" % (e.detail or e))
        if st is not None:
            raise Refused(_why(name, x, st))
        return x

    def open(self, user):
        """On the loop: a new session for a user check() accepted; its token."""
        token = secrets.token_urlsafe(TOKEN_BYTES)
        self.sessions[token] = Session(user["name"], user["role"], time.monotonic())
        self.idle_s = self.idle_now  # the lab's setting as it is now (fbrl-users set idle_s)
        return token

    def session(self, token, touch=True):
        """The signed-in session of that token, or None (none, or idle too long: then gone)."""
        s = self.sessions.get(token) if token else None
        if s is None:
            return None
        now = time.monotonic()
        if now - s.last >= self.idle_s:
            del self.sessions[token]
            return None
        if touch:
            s.last = now
        return s

    def expired(self):
        """Drop the sessions idle too long; [(token, session)]."""
        now = time.monotonic()
        gone = [(t, s) for t, s in self.sessions.items() if now - s.last >= self.idle_s]
        for t, _ in gone:
            del self.sessions[t]
        return gone

    def sign_out(self, token):
        """End the session of token; it, or None."""
        return self.sessions.pop(token, None)

    def record_sign_out(self, name, why):
        """In the lab's audit trail (blocks: call it off the loop). A sign-out happens even
        when it cannot be recorded: that is logged."""
        if self.trail is None:
            return
        try:
            self.trail.logout(name, why)
        except fbrl.Error as e:
            log.error("the lab's audit trail cannot record the sign-out of %s: %s", name, e)

    @staticmethod
    def may(session, right):
        return fbrl.Users.may(session.role, right)


def _outcome(x, st):
    """The attempt's outcome as fbrlmon records it (apps/lab.c record_attempt)."""
    if st is None:
        return "accepted"
    if x is None:
        return "unknown user"
    if x["disabled"]:
        return "disabled"
    return "locked" if st == "FBRL_ELOCKED" else "wrong password"


def _why(name, x, st):
    """The refusal's text, in fbrlmon's words (apps/lab.c)."""
    until = x and x["locked_until"] > time.time() * 1000
    at = time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime(x["locked_until"] / 1000)) if until else ""
    if st == "FBRL_ELOCKED" and x and not x["disabled"]:
        return "%s is locked until %s (too many wrong passwords)" % (name, at)
    if st == "FBRL_ELOCKED":
        return "%s is disabled" % name
    if x and until:
        return "wrong password: %s is now locked until %s" % (name, at)
    return "name or password not accepted"
