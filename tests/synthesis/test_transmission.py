"""Whole transmissions synthesised: every state's ratio at once, against hand levers and the one-ratio search.

- The Simpson set's ratios by the lever analogy (typed here): second (sun held) 1 + s1/r1,
  first (rear carrier held) 1 + (s1/r1)(1 + r2/s2), reverse (sun driving) -r2/s2; every design
  meets them within the tolerance, and the ready-made set (30/21/72 twice) is found.
- One state at a time the search agrees with symkin's one-ratio search (a second route: the
  same designs as synthesize(state=...)).
- Split into chunks on Dask the search gives the designs of the search in one process, in its order.
"""

from __future__ import annotations

import json

import pytest
import sympy as sp

from symkin.cli import main
from symkin.errors import InputError
from symkin.synthesis import synthesize
from symkin.synthesis.transmission import synthesize_transmission
from symkin.trains import load_train

TARGETS = {"first": sp.Rational(29, 12), "second": sp.Rational(17, 12), "reverse": sp.Rational(-12, 5)}


def test_simpson_designs_meet_every_ratio_by_hand():
    res = synthesize_transmission(load_train("simpson"), TARGETS, tolerance=sp.Rational(1, 100), zmax=80, top=None)
    assert res.found == len(res.designs) > 1
    for d in res.designs:
        t = {k: sp.Integer(v) for k, v in d.teeth.items()}
        hand = {"second": 1 + t["z_s1"] / t["z_r1"], "first": 1 + t["z_s1"] / t["z_r1"] * (1 + t["z_r2"] / t["z_s2"]),
                "reverse": -t["z_r2"] / t["z_s2"]}
        assert d.ratios == hand
        assert all(abs(hand[s] - v) <= v * sp.sign(v) / 100 for s, v in TARGETS.items())
    errors = [d.error for d in res.designs]
    assert errors == sorted(errors)
    published = {"z_s1": 30, "z_p1": 21, "z_r1": 72, "z_s2": 30, "z_p2": 21, "z_r2": 72}
    assert published in [d.teeth for d in res.designs]


def test_one_state_agrees_with_the_one_ratio_search():
    train = load_train("simple")
    ours = synthesize_transmission(train, {"low": 4}, tolerance=sp.Rational(1, 50), zmax=70, top=None)
    theirs = synthesize(train, state="low", ratio=4, tolerance=sp.Rational(1, 50), planets=3, zmax=70, top=None)
    assert sorted(tuple(sorted(d.teeth.items())) for d in ours.designs) == \
        sorted(tuple(sorted((str(z), v) for z, v in d.values.items())) for d in theirs.designs)


def test_bad_requests_are_one_line_errors(capsys):
    with pytest.raises(InputError, match="at least one state"):
        synthesize_transmission(load_train("simple"), {})
    with pytest.raises(InputError, match="zero or positive"):
        synthesize_transmission(load_train("simple"), {"low": 4}, tolerance=-1)
    assert main(["synthesize", "--train", "simpson", "--ratios", "first=2.4,bogus=3", "--planets", "3"]) == 2
    assert "no state 'bogus'" in capsys.readouterr().err
    assert main(["synthesize", "--train", "simpson", "--ratios", "first=2.4", "--ratio", "2", "--planets", "3"]) == 2
    assert main(["synthesize", "--train", "simple", "--ratio", "4", "--state", "low", "--absolute", "--planets", "3"]) == 2


def test_the_cli_synthesises_a_transmission(capsys):
    assert main(["synthesize", "--train", "simpson", "--ratios", "first=29/12,second=17/12,reverse=-12/5",
                 "--tolerance", "0", "--absolute", "--planets", "3", "--zmax", "80", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["found"] == 1 and data["designs"][0]["teeth"]["z_r2"] == 72 and data["absolute"] is True


def test_the_search_distributed_on_dask_gives_the_same_designs_in_the_same_order():
    distributed = pytest.importorskip("distributed")

    kw = dict(tolerance=sp.Rational(3, 100), zmax=80, top=20)
    here = synthesize_transmission(load_train("simpson"), TARGETS, **kw)
    # threads in this process: fast and deterministic; 2 workers -> the first group's tuples in 8 chunks
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0") as cluster:
        there = synthesize_transmission(load_train("simpson"), TARGETS, scheduler=cluster.scheduler_address, **kw)
    assert here.found > 20 and len(here.designs) == 20 and there.designs == here.designs  # the same designs, the same order
    assert (there.found, there.kept, there.order) == (here.found, here.kept, here.order)
    assert "Dask scheduler" in there.where and "8 chunks" in there.where and here.where == "this process"


def test_auto_stays_here_when_a_cluster_would_not_pay_and_finds_the_same_designs(monkeypatch):
    # 'auto' times the first chunk here; the search of a few tenths of a second cannot pay for a cluster
    # (cluster_pays: the time saved must exceed the cluster's cost), so no Dask is started
    from symkin.synthesis import runner

    monkeypatch.setattr(runner, "_client", lambda *a: pytest.fail("auto started a cluster for a short search"))
    kw = dict(tolerance=sp.Rational(3, 100), zmax=80, top=20)
    here = synthesize_transmission(load_train("simpson"), TARGETS, **kw)
    auto = synthesize_transmission(load_train("simpson"), TARGETS, scheduler="auto", **kw)
    assert auto.designs == here.designs and (auto.found, auto.kept, auto.order) == (here.found, here.kept, here.order)
    assert auto.where.startswith("this process (a local cluster of") and "would not pay" in auto.where


def test_a_target_ratio_of_zero():
    # a neutral state (ratio 0) within an absolute tolerance: every design meets it exactly as
    # the search says, and the step between it and its neighbour is left out (no ratio of ratios)
    res = synthesize_transmission(load_train("simple"), {"low": 4, "reverse": 0}, tolerance=5, absolute=True, zmax=60)
    assert res.found > 0
    for d in res.designs:
        assert abs(d.ratios["low"] - 4) <= 5 and abs(d.ratios["reverse"]) <= 5 and d.step_error == 0
    with pytest.raises(InputError, match="state reverse has the target ratio 0, which a relative tolerance cannot hold"):
        synthesize_transmission(load_train("simple"), {"low": 4, "reverse": 0}, tolerance=sp.Rational(1, 100))
