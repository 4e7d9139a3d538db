#!/usr/bin/env python3
"""tests/robustness/faults.py - precise faults against a running dashpotd (Python standard library only).

    python3 faults.py disconnects URL PID N CONCURRENCY   N clients hang up at random points of streams
    python3 faults.py slowloris URL N TIMEOUT             N clients send their head a byte at a time
    python3 faults.py limits URL                          over-limit bodies, deep nesting, huge numbers,
                                                          NaN/Infinity literals, a diverging solution
    python3 faults.py sigterm URL PID STREAMS             SIGTERM while streams and small requests run

Each prints "ok - ..." / "not ok - ..." lines and, last, "COUNTS passed failed" for tests/robustness/
faults.sh to add up. Traffic goes to the URL given (127.0.0.1) only. Every socket has a timeout.
"""
import http.client
import json
import os
import random
import re
import signal
import socket
import struct
import sys
import threading
import time
from urllib.parse import urlparse

PASSED = FAILED = 0


def check(ok, what, why=""):
    global PASSED, FAILED
    print(("ok - " if ok else "not ok - ") + what + ("" if ok or not why else "\n    " + str(why)[:600]))
    sys.stdout.flush()
    PASSED, FAILED = PASSED + bool(ok), FAILED + (not ok)
    return ok


def note(text):
    print("    " + text)
    sys.stdout.flush()


def spec(t_end, dt=1e-6, every=1, phi0=0.3):
    return json.dumps({"model": {"mass": 1, "spring": {"law": "linear", "k": 1},
                                 "damper": {"law": "coulomb", "phi0": phi0},
                                 "forcing": {"kind": "harmonic", "amplitude": 0.5, "omega": 1.3}},
                       "initial": {"x": 1, "v": 0}, "solver": {"dt": dt, "t_end": t_end},
                       "output": {"every": every}}).encode()


class Daemon:
    def __init__(self, url):
        u = urlparse(url)
        self.host, self.port = u.hostname, u.port

    def request(self, method, path, body=None, headers=None, timeout=30):
        c = http.client.HTTPConnection(self.host, self.port, timeout=timeout)
        try:
            c.request(method, path, body=body, headers=headers or {})
            r = c.getresponse()
            return r.status, dict(r.getheaders()), r.read()
        finally:
            c.close()

    def metrics(self):
        _, _, text = self.request("GET", "/metrics")
        out = {}
        for line in text.decode().splitlines():
            if line and not line.startswith("#"):
                name, _, value = line.rpartition(" ")
                out[name] = float(value)
        return out

    def connect(self, timeout=10):
        return socket.create_connection((self.host, self.port), timeout=timeout)

    def raw(self, data, timeout=10, read_all=True):
        """Sends bytes on a fresh connection, returns what comes back until the server closes."""
        s = self.connect(timeout)
        try:
            try:
                s.sendall(data)
            except (BrokenPipeError, ConnectionResetError):
                pass  # answered and closed before all was sent: read what came back
            chunks = []
            while True:
                try:
                    b = s.recv(65536)
                except (ConnectionResetError, socket.timeout):
                    break
                if not b:
                    break
                chunks.append(b)
                if not read_all:
                    break
            return b"".join(chunks)
        finally:
            s.close()


def head(method, path, body=b"", extra=()):
    lines = [f"{method} {path} HTTP/1.1", "Host: 127.0.0.1", "Connection: close"] + list(extra)
    if body is not None:
        lines.append(f"Content-Length: {len(body)}")
    return ("\r\n".join(lines) + "\r\n\r\n").encode() + (body or b"")


def rss_kb(pid):
    with open(f"/proc/{pid}/status") as f:
        return int(re.search(r"^VmRSS:\s+(\d+)", f.read(), re.M).group(1))


def wait_idle(d, seconds=15):
    """Waits until no run is in flight and only our own connection is open."""
    until = time.time() + seconds
    m = d.metrics()
    while time.time() < until:
        if m.get("dashpot_runs_in_flight") == 0 and m.get("dashpot_connections_open", 99) <= 1:
            return m
        time.sleep(0.1)
        m = d.metrics()
    return m


# ---- 1. clients that hang up at random points ----------------------------------------------------------------

ACCEPTS = ["application/x-ndjson", "application/json", "text/event-stream", "text/csv"]


def one_disconnect(d, rng, kind):
    body = spec(100)  # 10^8 steps: never finishes before the client leaves
    req = head("POST", "/v1/simulate", body, [f"Accept: {rng.choice(ACCEPTS)}"])
    s = d.connect(timeout=30)
    try:
        if kind == "rst":  # an abortive close: RST instead of FIN
            s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        if kind == "in_head":
            s.sendall(req[:rng.randrange(1, req.index(b"\r\n\r\n"))])
            return 0
        if kind == "in_body":
            s.sendall(req[:rng.randrange(req.index(b"\r\n\r\n") + 4, len(req))])
            return 0
        s.sendall(req)
        if kind == "after_request":
            return 0
        want, got = rng.randrange(1, 2_000_000), 0
        while got < want:
            b = s.recv(min(65536, want - got))
            if not b:
                raise RuntimeError("the stream ended before the client left")
            got += len(b)
        return got
    finally:
        s.close()


def disconnects(url, pid, n, concurrency):
    d = Daemon(url)
    pid, n, concurrency = int(pid), int(n), int(concurrency)
    rng = random.Random(8)
    # Warm-up: twenty streams read whole, so arenas and pools are at their working size for the baseline.
    for i in range(20):
        st, _, b = d.request("POST", "/v1/simulate", spec(0.02), {"Accept": "application/x-ndjson"})
        assert st == 200, st
    base = wait_idle(d)
    rss0 = rss_kb(pid)
    kinds = (["mid_stream"] * 6 + ["rst"] * 2 + ["after_request", "in_head", "in_body"])
    plan = [rng.choice(kinds) for _ in range(n)]
    counts = {k: plan.count(k) for k in set(plan)}
    errors, read = [], [0]
    lock = threading.Lock()
    peak = [rss0]

    def worker(idx):
        r = random.Random(idx)
        for i in range(idx, n, concurrency):
            try:
                got = one_disconnect(d, r, plan[i])
                with lock:
                    read[0] += got
            except Exception as e:  # noqa: BLE001 - every failure is reported
                with lock:
                    errors.append(f"{plan[i]}: {e!r}")

    t0 = time.time()
    threads = [threading.Thread(target=worker, args=(i,)) for i in range(concurrency)]
    for t in threads:
        t.start()
    while any(t.is_alive() for t in threads):
        peak[0] = max(peak[0], rss_kb(pid))
        time.sleep(0.05)
    elapsed = time.time() - t0
    note(f"{n} clients ({concurrency} at a time) in {elapsed:.1f} s: " +
         ", ".join(f"{k} {v}" for k, v in sorted(counts.items())) + f"; {read[0] / 1e6:.0f} MB read")
    check(not errors, f"all {n} clients connected and left as planned", errors[:5])
    m = wait_idle(d)
    check(m.get("dashpot_runs_in_flight") == 0, "afterwards no run is in flight",
          m.get("dashpot_runs_in_flight"))
    check(m.get("dashpot_connections_open") == 1, "afterwards only the metrics request's connection is open",
          m.get("dashpot_connections_open"))
    delta = {k: m[k] - base[k] for k in ("dashpot_runs_started_total", "dashpot_runs_cancelled_total",
                                         "dashpot_runs_completed_total", "dashpot_runs_failed_total")}
    note("runs started {dashpot_runs_started_total:.0f}, cancelled {dashpot_runs_cancelled_total:.0f}, "
         "completed {dashpot_runs_completed_total:.0f}, failed {dashpot_runs_failed_total:.0f}".format(**delta))
    left_mid = counts.get("mid_stream", 0) + counts.get("rst", 0)
    check(delta["dashpot_runs_cancelled_total"] >= left_mid,
          f"/metrics counts every mid-stream hang-up as a cancelled run (>= {left_mid})", delta)
    check(delta["dashpot_runs_started_total"] == delta["dashpot_runs_cancelled_total"]
          and delta["dashpot_runs_completed_total"] == 0 and delta["dashpot_runs_failed_total"] == 0,
          "every run started was cancelled: none completed, none failed, none lost", delta)
    st, _, b = d.request("GET", "/healthz")
    check(st == 200, "afterwards GET /healthz is 200", st)
    st, _, b = d.request("POST", "/v1/simulate", spec(0.01), {"Accept": "application/x-ndjson"})
    lines = b.decode().splitlines()
    check(st == 200 and len(lines) == 10003 and json.loads(lines[-1])["type"] == "summary",
          "afterwards a 10^4-sample stream is served whole", (st, len(lines)))
    time.sleep(1)
    rss1 = rss_kb(pid)
    note(f"VmRSS baseline {rss0} kB, peak {peak[0]} kB, after {rss1} kB")
    # "Back near baseline": within 10% of the baseline or 2 MiB of it, whichever is larger (the daemon trims
    # the allocator's arenas a second after a burst; a few blocks may stay).
    check(rss1 <= max(1.10 * rss0, rss0 + 2048), "RSS back near the baseline (<= max(+10%, +2 MiB))",
          (rss0, rss1))


# ---- 2. slowloris ---------------------------------------------------------------------------------------------

def slowloris(url, n, timeout):
    d = Daemon(url)
    n, timeout = int(n), float(timeout)
    before = d.metrics().get("dashpot_connections_timed_out_total", 0)
    closed_after, lock = [], threading.Lock()
    req = head("GET", "/healthz", None, ["X-Padding: " + "a" * 200])

    def slow(i):
        s = d.connect(timeout=timeout + 10)
        t0 = time.time()
        try:
            for b in req:  # a byte every 0.2 s: never idle long enough for an idle timeout
                s.send(bytes([b]))
                time.sleep(0.2)
            got = s.recv(100)
            outcome = "answered" if got else "closed"
        except (BrokenPipeError, ConnectionResetError):
            outcome = "closed"
        except socket.timeout:
            outcome = "hung"
        finally:
            s.close()
        with lock:
            closed_after.append((outcome, time.time() - t0))

    slow_threads = [threading.Thread(target=slow, args=(i,)) for i in range(n)]
    for t in slow_threads:
        t.start()
    time.sleep(0.5)
    served, t_end = [], time.time() + timeout + 1.5
    while time.time() < t_end:  # a normal client meanwhile
        st, _, _ = d.request("GET", "/healthz", timeout=5)
        served.append(st)
        time.sleep(0.05)
    # A slow client that does finish in time is served: its head over ~1/3 of the deadline.
    quick = head("GET", "/healthz", None)
    s = d.connect(timeout=10)
    step = timeout / 3 / len(quick)
    for b in quick:
        s.send(bytes([b]))
        time.sleep(step)
    slow_but_ok = s.recv(100).startswith(b"HTTP/1.1 200")
    s.close()
    for t in slow_threads:
        t.join(timeout + 10)
    outcomes = [o for o, _ in closed_after]
    times = [t for _, t in closed_after]
    note(f"{n} slow clients: {outcomes.count('closed')} closed after {min(times):.2f} .. {max(times):.2f} s; "
         f"{len(served)} normal requests meanwhile")
    check(outcomes.count("closed") == n, f"the {n} byte-at-a-time clients are closed, none answered or left hanging",
          outcomes)
    check(all(timeout - 0.1 <= t <= timeout + 1.0 for t in times),
          f"...within 1 s after the --timeout of {timeout:g} s", times)
    m = d.metrics()
    check(m.get("dashpot_connections_timed_out_total", 0) - before == n,
          "dashpot_connections_timed_out_total counts them", m.get("dashpot_connections_timed_out_total"))
    check(served and all(s == 200 for s in served), "other clients were served 200 meanwhile", served[:10])
    check(slow_but_ok, "a slow client that completes its request within --timeout is answered 200")


# ---- 3. limits, malformed and hostile bodies --------------------------------------------------------------------

NONFINITE = re.compile(rb"\b(nan|NaN|NAN|inf|Inf|INF|Infinity|-Infinity)\b")


def status_of(raw):
    m = re.match(rb"HTTP/1\.[01] (\d{3})", raw)
    return int(m.group(1)) if m else 0


def problem(d, body, accept="*/*"):
    st, h, b = d.request("POST", "/v1/simulate", body, {"Accept": accept})
    try:
        doc = json.loads(b)
    except ValueError:
        doc = {}
    return st, h.get("Content-Type", ""), doc


def limits(url):
    d = Daemon(url)
    # Bodies over --body-limit (1 MiB here).
    t0 = time.time()
    raw = d.raw(head("POST", "/v1/simulate", None, ["Content-Length: 1000000000000"]) + b"{")
    check(status_of(raw) == 413 and b"problem+json" in raw,
          "Content-Length: 10^12 is 413 problem+json before any of the body is read",
          raw[:200])
    check(time.time() - t0 < 2, "...at once")
    raw = d.raw(head("POST", "/v1/simulate", None, ["Content-Length: 99999999999999999999999999"]) + b"{")
    check(status_of(raw) in (400, 413), "a Content-Length beyond 64 bits is 400 or 413, never 5xx", raw[:100])
    # A client that asks before sending (Expect: 100-continue, as curl does above 1 MB) is told 413 instead.
    s = d.connect()
    s.sendall(head("POST", "/v1/simulate", None, ["Content-Length: 1200000", "Expect: 100-continue"]))
    raw = s.recv(4096)
    s.close()
    check(status_of(raw) == 413 and b"problem+json" in raw,
          "a 1.2 MB body announced with Expect: 100-continue is 413 problem+json, not 100 Continue", raw[:100])
    chunks = b"".join(b"%x\r\n%s\r\n" % (65536, b" " * 65536) for _ in range(20)) + b"0\r\n\r\n"
    raw = d.raw(b"POST /v1/simulate HTTP/1.1\r\nHost: x\r\nConnection: close\r\n"
                b"Transfer-Encoding: chunked\r\n\r\n" + chunks)
    check(status_of(raw) == 413, "a 1.3 MB chunked body (no Content-Length) is 413", raw[:100])
    # Deeply nested JSON.
    for depth in (100, 1000, 200_000):
        st, ct, doc = problem(d, b"[" * depth + b"]" * depth)
        check(st == 400 and doc.get("type") == "/problems/malformed-json",
              f"JSON nested {depth} deep is 400 /problems/malformed-json", (st, doc))
    nested_obj = b'{"model": ' * 5000 + b"1" + b"}" * 5000
    st, ct, doc = problem(d, nested_obj)
    check(st == 400, "objects nested 5000 deep are 400", (st, doc))
    # Huge numbers: finite-looking text that is not a finite double, named by pointer.
    base = json.loads(spec(1, dt=0.1))
    for text, ptr in ((b"1e999", "/model/mass"), (b"1" + b"0" * 400, "/model/mass"), (b"-1e400", "/model/mass")):
        body = json.dumps(base).encode().replace(b'"mass": 1', b'"mass": ' + text)
        st, ct, doc = problem(d, body)
        check(st == 422 and doc.get("type") == "/problems/invalid-spec"
              and [e["pointer"] for e in doc.get("errors", [])] == [ptr],
              f"mass {text[:12].decode()}{'...' if len(text) > 12 else ''} is 422 naming {ptr}", (st, doc))
    body = json.dumps(base).encode().replace(b'"dt": 0.1', b'"dt": 1e-320')
    st, ct, doc = problem(d, body)
    check(st == 422 and doc.get("errors", [{}])[0].get("pointer", "").startswith("/solver"),
          "a denormal dt (10^-320: 10^320 steps) is 422 naming /solver/...", (st, doc))
    # NaN and Infinity are not JSON.
    for lit in (b"NaN", b"Infinity", b"-Infinity", b"nan", b"inf"):
        body = json.dumps(base).encode().replace(b'"mass": 1', b'"mass": ' + lit)
        st, ct, doc = problem(d, body)
        check(st == 400 and doc.get("type") == "/problems/malformed-json",
              f"the literal {lit.decode()} is 400 /problems/malformed-json", (st, doc))
    # A solution that diverges: driven at resonance (omega^2 = k/m) with amplitude 1e307, x grows like
    # 1e307 t/2 and leaves the doubles at t = 40.65, sample 4065: well after the first block went out. The
    # document holds a number beyond 1e100, so the error names the overflow of the step's quantities (with
    # finite numbers) rather than a divergence of the dynamics (tests/test_hostile.c).
    div = {"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1},
                     "forcing": {"kind": "harmonic", "amplitude": 1e307, "omega": 1}},
           "initial": {"x": 0, "v": 0}, "solver": {"dt": 0.01, "t_end": 2000, "theta": 1},
           "output": {"every": 1}}
    for accept in ACCEPTS:
        st, h, b = d.request("POST", "/v1/simulate", json.dumps(div).encode(), {"Accept": accept})
        last = b.rstrip(b"\n").split(b"\n")[-1]
        said = "the step's quantities overflow at t = 40.6"
        if accept == "text/csv":
            ok = last.startswith(b"# error: 422 " + said.encode())
        elif accept == "application/json":
            ok = json.loads(b)["error"]["detail"].startswith(said)
        else:
            obj = json.loads(last[len(b"data: "):] if accept == "text/event-stream" else last)
            ok = obj["type"] == "error" and obj["status"] == 422 and obj["detail"].startswith(said)
        check(st == 200 and ok, f"a diverging run streams and ends with a clear error ({accept})", last[:200])
        check(not NONFINITE.search(b), f"...and no NaN or Infinity anywhere in its {len(b)} bytes ({accept})",
              NONFINITE.search(b))
    # m = 1e-300 under the same load, at dt = 1: diverges at t = 189, within the first block of 512 records,
    # before any byte was sent: a problem document instead of a stream.
    div["model"]["mass"], div["solver"]["dt"] = 1e-300, 1
    del div["output"]
    st, ct, doc = problem(d, json.dumps(div).encode())
    check(st == 422 and doc.get("type") == "/problems/run-failed" and "overflow at t = 18" in doc.get("detail", ""),
          "a run that diverges in its first block is 422 /problems/run-failed", (st, doc))
    # A regularized run whose tolerances no double can meet fails with a clear error too.
    reg = {"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1}},
           "initial": {"x": 4.5, "v": 0},
           "solver": {"kind": "regularized", "n": 1000, "t_end": 10, "dt": 0.5, "rtol": 0, "atol": 1e-300}}
    st, ct, doc = problem(d, json.dumps(reg).encode())
    check(st == 422 and doc.get("type") == "/problems/run-failed" and not NONFINITE.search(json.dumps(doc).encode()),
          "an impossible tolerance is 422 /problems/run-failed with a finite message", (st, doc))


# ---- 4. SIGTERM under load ---------------------------------------------------------------------------------

def sigterm(url, pid, streams):
    d = Daemon(url)
    pid, streams = int(pid), int(streams)
    results, small, lock = [], [], threading.Lock()
    stop = threading.Event()

    def stream(i):
        # 2 10^7 steps, 10^5 samples: ~0.3 s of solver time alone, seconds under load: in flight at the signal.
        try:
            st, _, b = d.request("POST", "/v1/simulate", spec(20, every=200), {"Accept": "application/x-ndjson"},
                                 timeout=60)
            last = json.loads(b.rstrip(b"\n").split(b"\n")[-1])
            with lock:
                results.append((st, last["type"], last.get("samples")))
        except Exception as e:  # noqa: BLE001
            with lock:
                results.append((0, repr(e), None))

    def hammer():
        while not stop.is_set():
            try:
                st, _, _ = d.request("POST", "/v1/stability", b'{"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]}}',
                                     timeout=10)
            except OSError:
                st = "refused"  # after the listening socket closed
            with lock:
                small.append(st)

    threads = [threading.Thread(target=stream, args=(i,)) for i in range(streams)]
    threads += [threading.Thread(target=hammer) for _ in range(4)]
    for t in threads:
        t.start()
    until = time.time() + 10
    while time.time() < until and d.metrics().get("dashpot_runs_in_flight", 0) < streams:
        time.sleep(0.02)
    in_flight = d.metrics().get("dashpot_runs_in_flight", 0)
    note(f"{in_flight:.0f} streams in flight and 4 clients sending small requests: SIGTERM")
    os.kill(pid, signal.SIGTERM)
    t0 = time.time()
    for t in threads[:streams]:
        t.join(60)
    drained = time.time() - t0
    stop.set()
    for t in threads[streams:]:
        t.join(15)
    codes = sorted(set(map(str, small)))
    note(f"streams drained {drained:.2f} s after the signal; small requests: {len(small)}, statuses {codes}")
    check(in_flight == streams, f"all {streams} streams were in flight at the signal", in_flight)
    check(len(results) == streams and all(r[0] == 200 and r[1] == "summary" and r[2] == 100_001 for r in results),
          f"every stream in flight finished whole with its summary (graceful drain)", results[:5])
    check(all(s in (200, 503, "refused") for s in small),
          "small requests got 200, 503 while draining, or a refused connection after; never another status",
          codes)


def main():
    cmd, args = sys.argv[1], sys.argv[2:]
    {"disconnects": disconnects, "slowloris": slowloris, "limits": limits, "sigterm": sigterm}[cmd](*args)
    print(f"COUNTS {PASSED} {FAILED}")


if __name__ == "__main__":
    main()
