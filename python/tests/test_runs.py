# SPDX-License-Identifier: MIT
"""Link.runs: how many times the last command ran, against fbrlsim's command log."""


def test_runs_are_the_controllers(sim, link):
    link.raw("V1=2.5")
    assert link.runs == (1, 0)
    before = len(sim.log())
    assert link.typev("V1") == 2.5
    ran = sim.log()[before:]
    # a value is believed when two reads agree: the controller ran TYPEV twice
    assert ran == ["TYPEV V1", "TYPEV V1"]
    assert link.runs == (2, 0)
