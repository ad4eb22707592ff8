"""Every test has a time limit (pytest-timeout, set in pyproject.toml): a test that hangs fails."""

import subprocess
import sys
import time


def test_the_suite_runs_with_a_per_test_time_limit(request):
    assert request.config.pluginmanager.hasplugin("timeout"), "pytest-timeout is in the test extra"
    assert 0 < float(request.config.getini("timeout")) <= 300


def test_a_hanging_test_fails_within_its_limit(tmp_path):
    # a residual that never simplifies stands for any hang: a busy loop the limit must end, here inside
    # one of symkin's time budgets (CPU time, SIGPROF), which must leave pytest-timeout's alarm (SIGALRM) alone
    (tmp_path / "test_hang.py").write_text("from symkin._util.budget import time_limit\n\n\ndef test_hang():\n"
                                           "    with time_limit(100, 'too long'):\n        while True:\n"
                                           "            pass\n")
    start = time.process_time()
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-o", "timeout=2",
                           "-o", "addopts=", str(tmp_path / "test_hang.py")], capture_output=True, text=True,
                          timeout=120, cwd=tmp_path)
    assert done.returncode == 1 and "Timeout" in done.stdout, done.stdout[-2000:]
    assert time.process_time() - start < 5  # the child's CPU time is its own; this process only waited
