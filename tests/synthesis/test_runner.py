"""Where a search runs: scheduler='auto' starts a local Dask cluster only where the search's
projected time pays for it (the decision checked on given numbers, not on timings), and the
answer is the same wherever it runs."""

from __future__ import annotations

from symkin.synthesis import runner
from symkin.synthesis.plan import SearchPlan
from symkin.synthesis.problem import derive
from symkin.synthesis.request import Target
from symkin.trains import load_train


def small_plan():
    return SearchPlan.build(derive(load_train("simple"), driver="S", driven="C", fixed="R", zmax=80), Target.of(4), chunk=10)


def test_a_local_cluster_pays_once_the_time_it_saves_exceeds_its_cost():
    cost = runner.LOCAL_CLUSTER_COST
    assert not runner.cluster_pays(2 * cost, 2)  # halving 2 cost saves exactly its cost: not more
    assert runner.cluster_pays(2 * cost + 1, 2) and runner.cluster_pays(1.5 * cost + 1, 4)
    assert not runner.cluster_pays(1e9, 1)  # one worker saves nothing


def test_auto_searches_here_when_the_search_is_short_and_finds_the_same(monkeypatch):
    plan = small_plan()
    here = runner.run(plan)
    ran = []
    auto = runner.run(plan, scheduler="auto", execution=ran)
    assert (auto.found, auto.counts, auto.top) == (here.found, here.counts, here.top) and here.found == 3
    assert ran[0].scheduler.startswith("here (a local cluster of") and ran[0].chunks == len(plan.chunks)


def test_auto_takes_the_cluster_where_it_pays(monkeypatch):
    plan = small_plan()
    calls = []

    def fake_dask(plan, chunks, scheduler, workers, limit, progress, spent):
        calls.append((scheduler, len(chunks)))
        return runner._local(plan, chunks, limit, progress, spent), 2, "local cluster of 2 workers (stand-in)"

    monkeypatch.setattr(runner, "cluster_pays", lambda projected, workers: True)
    monkeypatch.setattr(runner, "_dask", fake_dask)
    result = runner.run(plan, scheduler="auto", workers=2)
    assert calls == [("local", len(plan.chunks))] and result.found == runner.run(plan).found
