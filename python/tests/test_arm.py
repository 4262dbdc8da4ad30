# SPDX-License-Identifier: MIT
"""fbrl.Arm: the library's arm models (fbrl/arm.h) from Python. The truth is the A255's
published geometry (docs/robot.md: 10 in to the shoulder, 10 + 10 in arms, 2 in to the
flange), worked out here by hand for poses where it is plain arithmetic."""
import math

import pytest

import fbrl


def close(a, b, eps=1e-9):
    return all(abs(x - y) <= eps for x, y in zip(a, b))


def test_the_models_are_the_library_s():
    assert fbrl.arm.names() == ["a255", "a465"]
    with pytest.raises(ValueError, match="a255, a465"):
        fbrl.Arm("a999")


def test_the_a255_chain_at_ready_and_turned():
    arm = fbrl.Arm("A255")
    # READY: upper arm straight up, forearm level, the wrist straight: the tool points forward
    chain = arm.chain([0, 90, -90, 0, 0])
    for got, want in zip(chain, ([0, 0, 10], [0, 0, 20], [10, 0, 20], [12, 0, 20])):
        assert close(got, want), chain
    assert close(arm.fk([0, 90, -90, 0, 0])[:3], [12, 0, 20])
    # the waist turned 30 degrees, the tool 3 in past the flange
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    chain = arm.chain([30, 90, -90, 0, 0], tool=3)
    assert close(chain[2], [10 * c, 10 * s, 20]) and close(chain[3], [15 * c, 15 * s, 20]), chain
    assert close(arm.fk([30, 90, -90, 0, 0], tool=3)[:3], chain[3])


def test_more_joints_than_an_arm_has_are_refused():
    with pytest.raises(ValueError, match="at most 6"):
        fbrl.Arm().chain([0] * 7)
