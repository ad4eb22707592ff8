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


def test_the_time_limit_stops_a_search_only_once_it_is_passed():
    # found in review: the search for 9/2 up to zmax 10000 finishes in about 2 s, but after 28 % of its
    # outer tuples in 1.8 s a projection from that pace (about 6 s) stopped it under a limit of 4 s:
    # the work is front-loaded (large suns make no tuples). The decision on given numbers:
    from types import SimpleNamespace

    import pytest

    from symkin.errors import TimeLimitError

    o = SimpleNamespace(zmin=12, zmax=10000)
    plan = SimpleNamespace(size=1000, outer=("z_s",), problem=SimpleNamespace(options=o))
    runner._check_time(plan, 0.1, 1.7, 280, 4.0)  # 1.8 s of 4: goes on, whatever the pace says
    with pytest.raises(TimeLimitError, match=r"did 28% in 4\.1 s, about 14 s in all at that pace, more than the time "
                                             r"limit of 4 s; narrow the tooth limits \(e\.g\. zmax \d+"):
        runner._check_time(plan, 0.1, 4.0, 280, 4.0)  # 4.1 s: stops; at that pace 0.1 + 4.0 / 0.28 = 14 s
