"""The client itself: errors as ProblemError (a 422 with its pointers, an error line inside a 200 stream),
a cut stream as StreamError, timeouts, streaming with a progress bar and an early stop, the daemon's life
cycle (started, drained, stopped with no process left), a token, and the pictures."""

import http.server
import os
import socket
import threading
import time

import numpy as np
import pytest
import requests

import dashpot
from specs import CHAIN, DIVERGING, coulomb_spec


# ---- errors ----
def test_invalid_spec_raises_problem_error_with_pointers(client):
    bad = {"model": {"mass": -1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.3}},
           "solver": {"dt": 0}}
    with pytest.raises(dashpot.ProblemError) as info:
        client.simulate(bad)
    e = info.value
    assert e.status == 422 and e.type == "/problems/invalid-spec" and not e.in_stream
    assert e.pointers == ["/model/mass", "/solver/dt"]
    assert e.errors[0].detail == "must be a finite number > 0, got -1"
    assert "/solver/dt" in str(e)


def test_malformed_json_is_a_400_at_the_document(client):
    with pytest.raises(dashpot.ProblemError) as info:
        client.simulate('{"model": ')
    assert info.value.status == 400 and info.value.pointers == [""]


def test_error_line_in_a_200_stream_raises_after_the_records_before_it(client):
    records = []
    with pytest.raises(dashpot.ProblemError) as info:
        for record in client.stream(DIVERGING):
            records.append(record)
    e = info.value
    assert e.in_stream and e.status == 422 and "diverged" in e.title and "t = 10.24" in e.detail
    # the answer had started: the meta line and the samples up to the divergence came first
    assert records[0]["type"] == "meta" and len(records) > 512 and records[-1]["type"] == "sample"
    with pytest.raises(dashpot.ProblemError, match="diverged"):
        client.simulate(DIVERGING)


class _Handler(http.server.BaseHTTPRequestHandler):
    """A fake daemon for what the real one never does: a stream cut short, an answer that never comes."""
    protocol_version = "HTTP/1.1"

    def do_POST(self):
        self.rfile.read(int(self.headers.get("Content-Length", 0)))
        if self.path == "/v1/simulate" and self.server.mode == "cut":
            body = (b'{"type":"meta","t_end":1}\n{"type":"sample","t":0,"x":1,"v":0}\n')
            self.send_response(200)
            self.send_header("Content-Type", "application/x-ndjson")
            self.send_header("Transfer-Encoding", "chunked")
            self.end_headers()
            self.wfile.write(b"%x\r\n%s\r\n" % (len(body), body))
            self.wfile.flush()
            self.connection.shutdown(socket.SHUT_RDWR)  # no last chunk, no summary: the connection dies
        else:  # "silent": never answers
            time.sleep(3)

    def log_message(self, *args):
        pass


@pytest.fixture
def fake_daemon():
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), _Handler)
    server.daemon_threads = True
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield server
    server.shutdown()
    server.server_close()


def test_a_cut_stream_raises_stream_error(fake_daemon):
    fake_daemon.mode = "cut"
    c = dashpot.Client("http://127.0.0.1:%d" % fake_daemon.server_address[1])
    with pytest.raises(dashpot.StreamError):
        c.simulate(coulomb_spec())


def test_read_timeout_is_settable(fake_daemon):
    fake_daemon.mode = "silent"
    c = dashpot.Client("http://127.0.0.1:%d" % fake_daemon.server_address[1], timeout=(2, 0.2))
    start = time.monotonic()
    with pytest.raises(requests.exceptions.ReadTimeout):
        c.simulate(coulomb_spec())
    assert time.monotonic() - start < 2
    with pytest.raises(requests.exceptions.ReadTimeout):  # and per call
        dashpot.Client("http://127.0.0.1:%d" % fake_daemon.server_address[1]).lcp({"M": [[1]], "q": [1]}, timeout=0.2)


# ---- streaming ----
def test_stream_yields_meta_samples_events_summary_and_draws_progress(client, capsys):
    kinds = [record["type"] for record in client.stream(coulomb_spec(output={"every": 100}), progress=True)]
    assert kinds[0] == "meta" and kinds[-1] == "summary" and kinds.count("sample") == 101 and "event" in kinds
    bar = capsys.readouterr().err
    assert "100%" in bar and "10.0/10" in bar  # tqdm's last state: t_end reached


def test_leaving_a_stream_early_stops_the_run(client):
    """The daemon computes as the client reads; breaking out of the loop closes the connection, and the
    daemon counts the run as cancelled (dashpot_runs_cancelled_total)."""
    def cancelled():
        line = [l for l in client.metrics().splitlines() if l.startswith("dashpot_runs_cancelled_total")]
        return int(line[0].split()[-1])
    before = cancelled()
    long_run = coulomb_spec(solver={"kind": "stick-slip", "dt": 1e-6, "t_end": 50, "theta": 0.5})  # 5e7 steps
    for n, record in enumerate(client.stream(long_run)):
        if n == 2000:
            break
    deadline = time.monotonic() + 10
    while cancelled() == before and time.monotonic() < deadline:
        time.sleep(0.05)
    assert cancelled() == before + 1


# ---- the daemon's life cycle ----
def _gone(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    return False


def test_context_manager_stops_the_daemon():
    with dashpot.Client() as c:
        pid, url = c.pid, c.url
        assert c.health() == {"status": "ok"} and c.ready() and not _gone(pid)
    assert _gone(pid)  # stopped and reaped: no process left, not even a zombie
    with pytest.raises(requests.exceptions.ConnectionError):
        requests.get(url + "/healthz", timeout=2)
    # idempotent; 0 is the daemon's status after SIGTERM (under ASan also: no leak reported at exit)
    assert c.close() == 0


def test_daemon_log_is_drained(client):
    """The daemon writes a log line per request to the pipe the client holds. 300 requests for a long
    unknown path log about 90 KB (the log keeps ~250 bytes of a path), more than a 64 KiB pipe holds: if
    nothing read the pipe, the daemon's log write would block and the answers would stop coming. The
    requests are pipelined on one connection, so this takes a fraction of a second."""
    host, port = client.url.rsplit("/", 1)[-1].split(":")
    request = b"GET /no-such-page-" + b"x" * 1000 + b" HTTP/1.1\r\nHost: " + host.encode() + b"\r\n\r\n"
    answers = b""
    with socket.create_connection((host, int(port)), timeout=10) as s:
        s.sendall(request * 300)
        while answers.count(b"HTTP/1.1 404") < 300:
            data = s.recv(1 << 16)
            if not data:
                break
            answers += data
    assert answers.count(b"HTTP/1.1 404") == 300
    deadline = time.monotonic() + 5  # the log line may follow its answer by a moment
    while '"/no-such-page-xxx' not in client.daemon_log(1) and time.monotonic() < deadline:
        time.sleep(0.01)
    last = client.daemon_log(1)
    assert '"/no-such-page-xxx' in last and " 404 " in last and len(last) > 250


def test_bad_daemon_path_is_a_daemon_error(monkeypatch, tmp_path):
    monkeypatch.setenv("DASHPOT_DAEMON", str(tmp_path / "no-such-dashpotd"))
    with pytest.raises(dashpot.DaemonError):
        dashpot.Client()


def test_token(tmp_path):
    token_file = tmp_path / "token"
    token_file.write_text("s3cret\n")
    with dashpot.Client(token="s3cret", daemon_args=["--token-file", token_file]) as c:
        assert c.lcp({"M": [[2]], "q": [-4]})["lemke"]["z"] == [2]
        with pytest.raises(dashpot.ProblemError) as info:
            dashpot.Client(c.url, token="").lcp({"M": [[2]], "q": [-4]})
        assert info.value.status == 401


# ---- frames and pictures ----
def test_events_frame(client):
    r = client.simulate(CHAIN)
    frame = r.events_frame()
    assert len(frame) == len(r.events) == r.summary["events"]
    assert list(frame.columns[:3]) == ["kind", "element", "t"] and set(frame["kind"]) == {"stick", "slip"}


def test_plot_one_mass_marks_stick_bands_and_events(client, tmp_path):
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon, Rectangle
    # The forced oscillator of docs/http.md, longer: it sticks and slips again and again.
    r = client.simulate({"model": {"mass": 1, "spring": {"law": "linear", "k": 1},
                                   "damper": {"law": "coulomb", "phi0": 0.5},
                                   "forcing": {"kind": "harmonic", "amplitude": 1, "omega": 0.5}},
                         "initial": {"x": 1, "v": 0}, "solver": {"dt": 1e-3, "t_end": 30, "theta": 0.5},
                         "output": {"every": 10}})
    fig = r.plot()
    x_axes = fig.axes[0]
    bands = [p for p in x_axes.patches if isinstance(p, (Polygon, Rectangle))]
    assert len(r.stick_intervals()) >= 2 and len(bands) == len(r.stick_intervals())
    event_lines = [l for l in x_axes.lines if l.get_linestyle() == "--"]
    assert len(event_lines) == len(r.events)
    fig.savefig(tmp_path / "one.png")
    assert (tmp_path / "one.png").stat().st_size > 10000
    plt.close(fig)


def test_plot_network_is_a_space_time_image(client, tmp_path):
    import matplotlib.pyplot as plt
    n = 12
    spec = {"model": {"masses": [1] * n, "elements":
                      [{"between": ["ground", i], "spring": {"law": "linear", "k": 1},
                        "damper": {"law": "coulomb", "phi0": 0.2, "belt_velocity": -0.1}} for i in range(n)] +
                      [{"between": [i, i + 1], "spring": {"law": "linear", "k": 0.5}} for i in range(n - 1)]},
            "initial": {"x": [0.1 * (i % 3) for i in range(n)], "v": [-0.1] * n},
            "solver": {"dt": 0.01, "t_end": 30, "theta": 0.5}, "output": {"every": 10}}
    r = client.simulate(spec)
    fig = r.plot(field="x")
    (image,) = fig.axes[0].images
    assert image.get_array().shape == (n, len(r))  # nodes along the vertical, t along the horizontal
    assert np.array_equal(np.asarray(image.get_array()), r.x.T)
    fig.savefig(tmp_path / "network.png")
    plt.close(fig)


def test_plot_stability_map_and_response(client, tmp_path):
    import matplotlib.pyplot as plt
    smap = client.stability({"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]},
                             "map": {"x": {"param": "mu[1]", "from": 0, "to": 2, "steps": 21},
                                     "y": {"param": "lambda[1]", "from": 0.25, "to": 1.75, "steps": 11}}})
    fig = smap.plot()
    fig.savefig(tmp_path / "map.png")
    plt.close(fig)
    resp = client.response({"model": {"masses": [1, 1], "elements": [
        {"between": ["ground", 0], "spring": {"law": "linear", "k": 1}},
        {"between": [0, 1], "spring": {"law": "linear", "k": 1}, "damper": {"law": "linear", "c": 0.05}}]},
        "force_node": 0, "response_node": 0, "omega": {"from": 0.1, "to": 3, "points": 300}})
    fig = resp.plot()
    assert len(fig.axes[0].lines) == 1 + len(resp["resonances"]) + len(resp["antiresonances"])
    plt.close(fig)
