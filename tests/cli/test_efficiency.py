"""symkin efficiency with one-way clutches: what the output driving the input means (the state's
coast engagement, by the element chart of docs/trains.md) in the per-unit statics and at an
operating point."""

from __future__ import annotations

import json

from symkin.cli import main


def test_a_state_free_on_coast_has_no_efficiency_driven_back(capsys):
    # simpson-oneway D1: F holds C2 in drive and overruns when the output drives (its chart)
    assert main(["efficiency", "--train", "simpson-oneway", "--state", "D1"]) == 0
    text = capsys.readouterr().out
    assert "driven back  C1 -> R1: free (F overruns): the output cannot drive the input in this state" in text
    assert main(["efficiency", "--train", "simpson-oneway", "--state", "D1", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["efficiency_backward"] == "free (F overruns)" and data["coast"]["free"] is True


def test_an_operating_point_where_the_output_drives_takes_the_coast_engagement(capsys):
    # R1 turning forwards with -100 N m on it: power flows out of the input, the output drives,
    # and F, which holds C2 only against the drive's reaction, overruns: no such operating point
    # (it printed F's reaction, a torque the clutch cannot carry)
    argv = ["efficiency", "--train", "simpson-oneway", "--state", "D1", "--omega", "R1=2000rpm", "--torque", "S=0"]
    assert main([*argv, "--torque", "R1=-100"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == ("symkin efficiency: error: state 'D1' is free when its output drives its input (F overruns): "
                   "nothing carries the torque back")
    assert main([*argv, "--torque", "R1=100", "--json"]) == 0  # in drive: F holds C2
    data = json.loads(capsys.readouterr().out)
    assert data["torques"]["C2"]["exact"] != "0"
    assert main(["efficiency", "--train", "hub-3speed", "--state", "top", "--omega", "D=100", "--torque", "D=-10",
                 "--torque", "C=0", "--torque", "R=0"]) == 2
    assert "is free when its output drives its input" in capsys.readouterr().err
