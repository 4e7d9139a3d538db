"""Sweeps from Python (docs/sweep.md): one daemon's answer (Client.sweep) against Den Hartog's closed form,
the same lines from two daemons (dashpot.sweep(doc, urls)) and from a Dask LocalCluster of two workers over
two daemons, and the same lines again when one daemon is killed mid-sweep: its runs retried on the other,
none lost, none duplicated."""

import math
import threading
import time
import urllib.request

import pytest

import dashpot
from dashpot.daemon import LocalDaemon

distributed = pytest.importorskip("distributed")  # python3-distributed: scripts/install-deps.sh installs it

DOC = {
    "base": {"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.1},
                       "forcing": {"kind": "harmonic", "amplitude": 1, "omega": 2}},
             "solver": {"dt": 0.005, "t_end": 600}},
    "vary": [{"pointer": "/model/forcing/omega", "from": 1.5, "to": 3, "count": 24}],
    "record": {"after": 450, "features": ["amplitude", "period"]},
}


def den_hartog(beta, f_over_p=0.1):
    """Den Hartog 1931: the non-stop amplitude over P/k (derived in docs/sweep.md)."""
    u = math.sin(math.pi / beta) / (beta * (1 + math.cos(math.pi / beta)))
    return math.sqrt(1 / (1 - beta * beta) ** 2 - (f_over_p * u) ** 2)


@pytest.fixture(scope="module")
def reference(client):
    return client.sweep(DOC)


def test_one_daemon_matches_den_hartog(reference):
    assert [l["index"] for l in reference] == list(range(24))
    for line in reference:
        beta = line["values"][0]
        # theta = 1/2 at dt = 0.005: the scheme's error is ~1e-5 of the amplitude here
        assert line["features"]["amplitude"] == pytest.approx(den_hartog(beta), rel=2e-4)


def test_two_daemons_and_dask_give_one_daemons_lines(reference):
    a, b = LocalDaemon(), LocalDaemon()
    try:
        assert dashpot.sweep(DOC, urls=[a.url, b.url], chunk=3) == reference
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                      dashboard_address=None) as cluster, distributed.Client(cluster) as dask:
            assert len(dask.scheduler_info()["workers"]) == 2
            assert dashpot.sweep(DOC, urls=[a.url, b.url], dask=dask, chunk=3) == reference
    finally:
        a.stop()
        b.stop()


def _kill_when_busy(daemon, when):
    """Kills the daemon once it is streaming a part of the sweep (its dashpot_runs_in_flight >= 1): mid-sweep
    by construction, however fast the sweep runs (its runs now go at once on the daemon's threads)."""
    def busy():
        try:
            with urllib.request.urlopen(daemon.url + "/metrics", timeout=1) as r:
                for line in r.read().decode().splitlines():
                    if line.startswith("dashpot_runs_in_flight "):
                        return float(line.split()[1]) >= 1
        except OSError:
            pass
        return False

    def kill():
        deadline = time.monotonic() + 10
        while not busy() and time.monotonic() < deadline:
            time.sleep(0.002)
        daemon.proc.kill()
        when.append(time.monotonic())
    t = threading.Thread(target=kill, daemon=True)
    t.start()
    return t


@pytest.mark.parametrize("use_dask", [False, True])
def test_a_daemon_stopped_mid_sweep_loses_nothing(reference, use_dask):
    a, b = LocalDaemon(), LocalDaemon()
    try:
        killed = []
        killer = _kill_when_busy(b, killed)
        if use_dask:
            with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                          dashboard_address=None) as cluster, distributed.Client(cluster) as dask:
                lines = dashpot.sweep(DOC, urls=[b.url, a.url], dask=dask, chunk=3)
        else:
            lines = dashpot.sweep(DOC, urls=[b.url, a.url], chunk=3)
        done = time.monotonic()
        killer.join()
        assert killed and killed[0] < done, "the daemon was to be killed during the sweep"
        assert lines == reference  # every run once, in order, each the one daemon's line
    finally:
        a.stop()
        b.stop()


def test_bad_document_raises_by_pointer():
    a = LocalDaemon()
    try:
        with pytest.raises(dashpot.ProblemError) as e:
            dashpot.sweep(dict(DOC, vary=[{"pointer": "/model/nope/x", "values": [1]}]), urls=[a.url])
        assert e.value.status == 422
    finally:
        a.stop()
