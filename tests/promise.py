"""The promise a run makes, checked in one place: it exits 0 (converged) only with its true error
of p0, F and a within 1% and at most twice its own estimate; otherwise it says it is off (exit 5)."""
BAR = 0.01          # the error a converged run may have at most
ESTIMATE_SHARE = 0.5  # the least share of the true error its estimate reads


def check_promise(run, truth: float) -> tuple[float, float]:
    """A run either says it is off (exit 5) or keeps the promise; returns (truth, estimate)."""
    assert run.exit_code in (0, 5), run.output
    s = run.summary
    estimate = s["accuracy_predicted"]
    if run.exit_code == 0:
        assert s["status"] == "converged" and truth <= BAR, (truth, estimate)
        assert estimate >= ESTIMATE_SHARE * truth, (truth, estimate)
    return truth, estimate
