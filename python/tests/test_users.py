# SPDX-License-Identifier: MIT
"""fbrl.Users: the lab's users from Python; the file's mode and hashes checked from outside
(os.stat, the file's text), the lockout as the library counts it."""
import os
import stat

import pytest

import fbrl


def test_users_file_sign_in_and_lockout(tmp_path):
    path = str(tmp_path / "users")
    u = fbrl.Users()
    u.add("admin", "administrator", "admin pass 1")
    u.add("ann", "operator", "ann's password")
    u.set("max_tries", 3)
    u.save(path)
    assert stat.S_IMODE(os.stat(path).st_mode) == 0o600
    text = open(path).read()
    assert "ann's password" not in text and "$argon2id$" in text
    v = fbrl.Users(path)
    assert v.admins() == 1 and v.user("ann")["role"] == "operator" and v.user("nobody") is None
    v.login("ann", "ann's password", now_ms=1000)
    for k in range(3):
        with pytest.raises(fbrl.Error) as e:
            v.login("ann", "wrong", now_ms=1000)
        assert e.value.name == "FBRL_EAUTH"
    assert v.user("ann")["failures"] == 3 and v.user("ann")["locked_until"] == 1000 + 900 * 1000
    with pytest.raises(fbrl.Error) as e:
        v.login("ann", "ann's password", now_ms=2000)
    assert e.value.name == "FBRL_ELOCKED"
    v.save()
    assert fbrl.Users(path).user("ann")["failures"] == 3  # the count outlives the program
    assert fbrl.Users.may("operator", "run") and not fbrl.Users.may("operator", "run_draft")
    assert fbrl.Users.may("reviewer", "release") and not fbrl.Users.may("reviewer", "run")
    os.chmod(path, 0o620)
    with pytest.raises(fbrl.Error) as e:
        fbrl.Users(path)
    assert e.value.name == "FBRL_EPERM"
