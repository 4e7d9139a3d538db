"""The HTTP client: one object per daemon, one method per route of dashpotd's API (api/openapi.yaml).

Simulations are read as the NDJSON stream (``Accept: application/x-ndjson``) line by line, so a long run is
turned into arrays as it arrives instead of being held as one JSON document, and a failure that comes after
the answer started (an ``"error"`` line: divergence, the daemon's wall-time limit, its shutdown) raises the
same ProblemError as a 4xx answer would. The analysis routes answer one small JSON document each.
"""

import json
import math
import os
from pathlib import Path

import requests

from . import __version__
from .answers import Modes, Response, Stability, StabilityMap
from .daemon import LocalDaemon
from .errors import DaemonError, ProblemError, StreamError
from .result import ResultBuilder

#: (connect, read) seconds. The read timeout bounds the wait for each piece of an answer, not the whole
#: answer; it is above the daemon's default wall-time limit (120 s), so a slow run ends with the daemon's own
#: 503 problem rather than a client-side timeout.
DEFAULT_TIMEOUT = (5.0, 150.0)


def _json_default(value):
    """Lets specs hold numpy arrays and numbers (json.dumps knows neither)."""
    if hasattr(value, "tolist"):  # numpy arrays and numpy scalars
        return value.tolist()
    raise TypeError("%r is not JSON serializable" % (value,))


def encode_spec(spec):
    """The request body for `spec`: a dict (or list) is encoded as JSON, numpy values included; ``str`` or
    ``bytes`` are taken as JSON text; a ``pathlib.Path`` is read from that file."""
    if isinstance(spec, Path):
        return spec.read_bytes()
    if isinstance(spec, bytes):
        return spec
    if isinstance(spec, str):
        return spec.encode("utf-8")
    # allow_nan=False: NaN and Infinity are not JSON; say so here rather than as the daemon's 400.
    return json.dumps(spec, default=_json_default, allow_nan=False).encode("utf-8")


def _ndjson_records(response):
    """The JSON objects of an NDJSON answer, one per line, as the chunks arrive."""
    pending = []
    for chunk in response.iter_content(chunk_size=1 << 16):
        if b"\n" not in chunk:  # a long line (a big network's row) arrives in pieces: join it once
            pending.append(chunk)
            continue
        lines = (b"".join(pending) + chunk if pending else chunk).split(b"\n")
        pending = [lines.pop()] if lines[-1] else []
        for line in lines:
            if line.strip():
                yield _parse_line(line)
    rest = b"".join(pending)
    if rest.strip():
        yield _parse_line(rest)


_decode = json.JSONDecoder().decode


def _parse_line(line):
    try:
        return _decode(line.decode("utf-8"))
    except ValueError as e:
        raise StreamError("the stream sent a line that is not JSON: %r" % line[:200]) from e


class Client:
    """A connection to dashpotd.

    ``Client()`` starts a private daemon (see dashpot.daemon) on a free loopback port and stops it on
    ``close()``; ``Client("http://host:8080")`` talks to a daemon already running. Use it as a context
    manager (``with dashpot.Client() as c: ...``) to be sure the daemon stops.

    Parameters: ``timeout`` -- seconds, a number or a (connect, read) pair, for every request (each method
    takes its own ``timeout`` too); ``token`` -- the bearer token of a daemon started with one (default: the
    environment's ``DASHPOT_TOKEN``, which a daemon started here also reads); ``daemon`` -- the dashpotd binary
    to start instead of the one found; ``daemon_args`` -- more flags for it (e.g. ``["--body-limit",
    "8388608"]`` for a large network); ``start_timeout`` -- seconds to wait for it to listen.
    """

    def __init__(self, url=None, timeout=DEFAULT_TIMEOUT, token=None, daemon=None, daemon_args=(),
                 start_timeout=10.0):
        self.timeout = timeout
        self._daemon = None
        self._session = requests.Session()
        if url is None:
            self._daemon = LocalDaemon(daemon, daemon_args, start_timeout)
            url = self._daemon.url
            # Our own daemon is on loopback: never send its requests through a proxy from the environment
            # (requests would, for http_proxy without a no_proxy naming 127.0.0.1).
            self._session.trust_env = False
        self.url = url.rstrip("/")
        self._session.headers["User-Agent"] = "dashpot-python/%s" % __version__
        token = os.environ.get("DASHPOT_TOKEN") if token is None else token
        if token:
            self._session.headers["Authorization"] = "Bearer %s" % token

    # ---- life cycle ----
    @property
    def pid(self):
        """The process id of the daemon this client started, or None."""
        return self._daemon.pid if self._daemon else None

    def daemon_log(self, n=20):
        """The last `n` lines the started daemon wrote on stderr ("" for a daemon given by URL)."""
        return self._daemon.log_tail(n) if self._daemon else ""

    def close(self):
        """Closes the connections and stops the daemon this client started (idempotent). Returns the
        daemon's exit status (0 after a clean SIGTERM), or None for a daemon given by URL."""
        self._session.close()
        if self._daemon is not None:
            return self._daemon.stop()
        return None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        return "<dashpot.Client %s%s>" % (self.url, " (daemon pid %d)" % self.pid if self.pid else "")

    # ---- plumbing ----
    def _request(self, method, path, body=None, accept="application/json", stream=False, timeout=None):
        headers = {"Accept": accept}
        if body is not None:
            headers["Content-Type"] = "application/json"
        try:
            response = self._session.request(method, self.url + path, data=body, headers=headers, stream=stream,
                                             timeout=self.timeout if timeout is None else timeout)
        except requests.exceptions.ConnectionError as e:
            if self._daemon is not None and not self._daemon.running:  # our daemon died: say so, with its log
                raise DaemonError("dashpotd (pid %d) is not running (exit status %s); its last lines:\n%s"
                                  % (self._daemon.pid, self._daemon.proc.returncode, self._daemon.log_tail())) from e
            raise
        if response.status_code >= 400:
            self._raise_problem(response)
        return response

    @staticmethod
    def _raise_problem(response):
        try:
            body = response.content
        finally:
            response.close()
        try:
            document = json.loads(body)
        except ValueError:
            document = None
        if isinstance(document, dict):
            raise ProblemError.from_document(response.status_code, document)
        # An answer libmicrohttpd gives itself (431, 414, ...) has no problem document.
        raise ProblemError(response.status_code, response.reason or "HTTP %d" % response.status_code,
                           body.decode("utf-8", "replace").strip())

    def _post_json(self, path, spec, timeout=None):
        return self._request("POST", path, encode_spec(spec), timeout=timeout).json()

    # ---- simulations ----
    def stream(self, spec, progress=False, timeout=None):
        """The run's records as they arrive: dicts with ``"type"`` "meta" (first), "sample", "event",
        "summary" (last).

        The request is sent at once (an invalid spec raises here); the daemon then computes only as fast as
        the iterator is read. Leaving a ``for`` loop over it early closes the connection, which stops the run
        (an iterator kept in a variable: call its ``close()``). An ``"error"`` line raises ProblemError (``in_stream`` True) after
        the records before it were yielded; a stream that ends without a summary raises StreamError.
        ``progress=True`` draws a tqdm bar of simulated time (sample t against the meta line's t_end).
        """
        # The request goes out now, so an invalid spec raises here, not at the first next().
        response = self._request("POST", "/v1/simulate", encode_spec(spec), accept="application/x-ndjson",
                                 stream=True, timeout=timeout)
        return _records(response, progress)

    def simulate(self, spec, progress=False, timeout=None):
        """Runs a simulation and returns its Result (numpy arrays per column, events, meta, summary).

        Read from the NDJSON stream (see ``stream``), so the answer is never held as one document.
        Raises ProblemError for an invalid spec (4xx, with every error's JSON Pointer) and for a run that
        fails after it started (an error line in the stream).
        """
        builder = ResultBuilder(spec if isinstance(spec, dict) else None)
        for record in self.stream(spec, progress=progress, timeout=timeout):
            builder.add(record)
        return builder.result()

    def sweep(self, doc, timeout=None):
        """POST /v1/sweep: the run lines (dicts, in index order) of a sweep document (docs/sweep.md). An
        error line (wall time, step budget, shutdown) raises ProblemError, a cut stream StreamError. Over
        several daemons or a Dask cluster: ``dashpot.sweep(doc, urls=[...])``."""
        response = self._request("POST", "/v1/sweep", encode_spec(doc), accept="application/x-ndjson",
                                 stream=True, timeout=timeout)
        lines = []
        with response:
            for raw in response.iter_lines():
                line = json.loads(raw) if raw else None
                if line and line["type"] == "run":
                    lines.append(line)
                elif line and line["type"] == "error":
                    raise ProblemError.from_document(line.get("status", 503), line, in_stream=True)
                elif line and line["type"] == "summary":
                    return sorted(lines, key=lambda l: l["index"])
        raise StreamError("the sweep's stream ended without its summary line")

    # ---- analyses ----
    def stability(self, spec, timeout=None):
        """POST /v1/stability: a Stability (a dict, with ``roots`` as a complex array) for a law, or a
        StabilityMap (a dict, with the grid as arrays and ``plot()``) when the spec has a ``map``."""
        answer = self._post_json("/v1/stability", spec, timeout)
        return StabilityMap(answer) if "map" in answer else Stability(answer)

    def wellposedness(self, spec, timeout=None):
        """POST /v1/wellposedness: the existence and uniqueness report, as a dict."""
        return self._post_json("/v1/wellposedness", spec, timeout)

    def modes(self, spec, timeout=None):
        """POST /v1/modes: a Modes (a dict, with ``omega`` and ``shapes`` as arrays)."""
        return Modes(self._post_json("/v1/modes", spec, timeout))

    def response(self, spec, timeout=None):
        """POST /v1/response: a Response (a dict, with ``omega``, ``magnitude``, ``phase`` and the complex
        receptance ``H`` as arrays)."""
        return Response(self._post_json("/v1/response", spec, timeout))

    def lcp(self, problem, timeout=None):
        """POST /v1/lcp: one linear complementarity problem {"M": ..., "q": ...}; the answer as a dict."""
        return self._post_json("/v1/lcp", problem, timeout)

    def convergence(self, spec, timeout=None):
        """POST /v1/convergence: the regularized solver's convergence study, as a dict."""
        return self._post_json("/v1/convergence", spec, timeout)

    # ---- operations ----
    def health(self, timeout=None):
        """GET /healthz (``{"status": "ok"}``)."""
        return self._request("GET", "/healthz", timeout=timeout).json()

    def ready(self, timeout=None):
        """GET /readyz: True when the daemon takes work; False while it is busy or shutting down (503)."""
        try:
            self._request("GET", "/readyz", timeout=timeout)
            return True
        except ProblemError as e:
            if e.status == 503:
                return False
            raise

    def metrics(self, timeout=None):
        """GET /metrics: Prometheus text."""
        return self._request("GET", "/metrics", accept="text/plain", timeout=timeout).text

    def openapi(self, timeout=None):
        """GET /openapi.yaml: the API's contract, as text."""
        return self._request("GET", "/openapi.yaml", accept="*/*", timeout=timeout).text


def _records(response, progress):
    """The generator behind Client.stream: records of an open NDJSON answer, errors turned into exceptions."""
    bar = None
    try:
        finished = False
        for record in _ndjson_records(response):
            kind = record.get("type")
            if kind == "error":
                raise ProblemError.from_document(record.get("status"), record, in_stream=True)
            if progress:
                bar = _advance(bar, record)
            finished = kind == "summary"
            yield record
        if not finished:
            raise StreamError("the stream ended without its summary line: the connection was cut")
    except requests.exceptions.ChunkedEncodingError as e:
        raise StreamError("the stream was cut: %s" % e) from e
    except requests.exceptions.ConnectionError as e:
        # requests reports a read timeout inside a stream as a ConnectionError; say what it is.
        if "timed out" in str(e).lower():
            raise requests.exceptions.ReadTimeout(str(e)) from e
        raise
    finally:
        response.close()
        if bar is not None:
            bar.close()


def _advance(bar, record):
    """Moves the progress bar: created at the meta line (total = t_end), advanced to each sample's t."""
    kind = record.get("type")
    if kind == "meta":
        try:
            from tqdm import tqdm
        except ImportError as e:
            raise ImportError("progress=True needs tqdm (Debian: python3-tqdm)") from e
        total = record.get("t_end")
        # unit_scale: simulated time is a float; tqdm then prints 93.1/100, not 93.10000000000001/100.0
        return tqdm(total=float(total) if total is not None else None, unit="t", unit_scale=True,
                    desc="simulate", leave=True)
    if bar is None:
        return None
    if kind == "sample":
        t = record.get("t")
        if isinstance(t, (int, float)) and math.isfinite(t) and t > bar.n:
            bar.update(t - bar.n)
    elif kind == "summary" and bar.total is not None and bar.n < bar.total:
        bar.update(bar.total - bar.n)
    return bar
