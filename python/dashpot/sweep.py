"""Sweeps over several daemons, or over a Dask cluster (docs/sweep.md).

A sweep document ({"base", "vary", "record"}) names a grid of runs; each run's answer is one line, a pure
function of the document and the run's index. So the runs can go anywhere: ``sweep(doc, urls=[...])`` cuts
them into chunks (the document's ``"runs"`` member), posts each chunk as a sweep to a daemon, keeps the lines
that came back, and sends the runs a failed or stopped daemon did not answer to another one, until every run
has exactly one line. With ``dask=`` (a ``distributed.Client``) each chunk is a Dask task that does the same
from a worker, trying the daemons in turn.

    lines = dashpot.sweep(doc, urls=["http://a:8080", "http://b:8080"])
    [l["features"]["amplitude"] for l in lines]          # in index order
"""

import json
import math
import queue
import threading

import requests

from .errors import DashpotError, ProblemError

DEFAULT_TIMEOUT = (5, 600)


def grid_size(doc):
    """Runs in the grid of a sweep document: the product of its axes' sizes."""
    n = 1
    for axis in doc.get("vary", []):
        n *= len(axis["values"]) if "values" in axis else int(axis["count"])
    return n


def _selected(doc):
    """The run indices the document asks for (its "runs", else the whole grid), its shard applied."""
    runs = doc.get("runs", range(grid_size(doc)))
    shard = doc.get("shard", {"index": 0, "count": 1})
    return [i for i in runs if i % shard["count"] == shard["index"]]


def post_runs(url, doc, runs, timeout=DEFAULT_TIMEOUT, token=None, session=None):
    """Posts the sweep of `doc` restricted to `runs` to the daemon at `url`; returns (lines, error): the run
    lines that arrived (dicts) and None, or those that arrived before the stream was cut and the reason.
    A bad document (4xx) raises ProblemError: no other daemon would answer otherwise."""
    body = dict(doc, runs=list(runs))
    body.pop("shard", None)
    headers = {"Content-Type": "application/json", "Accept": "application/x-ndjson"}
    if token:
        headers["Authorization"] = "Bearer %s" % token
    lines = []
    http = session or requests
    try:
        with http.post(url.rstrip("/") + "/v1/sweep", data=json.dumps(body), headers=headers, stream=True,
                       timeout=timeout) as r:
            if 400 <= r.status_code < 500:
                raise ProblemError.from_document(r.status_code, r.json())
            if r.status_code != 200:
                return lines, "HTTP %d" % r.status_code
            for raw in r.iter_lines():
                if not raw:
                    continue
                line = json.loads(raw)
                if line["type"] == "run":
                    lines.append(line)
                elif line["type"] == "error":
                    return lines, line.get("detail", "an error line")
                elif line["type"] == "summary":
                    return lines, None
    except (requests.exceptions.RequestException, ValueError) as e:
        return lines, "%s: %s" % (type(e).__name__, e)
    return lines, "the stream ended without its summary line"


def _chunks(runs, size):
    return [runs[i:i + size] for i in range(0, len(runs), size)]


def _run_chunk(urls, doc, runs, first, timeout, token):
    """A chunk's lines, trying the daemons from urls[first] on; the runs not answered by one go to the next.
    Runs as a Dask task too (a plain function of plain data)."""
    got, why = {}, []
    for k in range(len(urls) * 2):  # each daemon twice: a transient hang-up is retried once
        missing = [i for i in runs if i not in got]
        if not missing:
            break
        url = urls[(first + k) % len(urls)]
        lines, error = post_runs(url, doc, missing, timeout, token)
        for line in lines:
            got[line["index"]] = line
        if error:
            why.append("%s: %s" % (url, error))
    missing = [i for i in runs if i not in got]
    if missing:
        raise DashpotError("runs %s were answered by no daemon: %s" % (missing[:10], "; ".join(why[-4:])))
    return [got[i] for i in runs]


def _over_threads(doc, urls, chunks, timeout, token):
    """One thread per daemon takes chunks from a queue; the runs a daemon leaves unanswered go back on the
    queue for the others, and that daemon takes no more."""
    todo = queue.Queue()
    for c in chunks:
        todo.put(c)
    got, lock, alive, errors = {}, threading.Lock(), [len(urls)], []

    def work(url):
        while True:
            try:
                chunk = todo.get(timeout=0.05)
            except queue.Empty:
                with lock:
                    if len(got) >= total or alive[0] == 0:
                        return
                continue
            try:
                lines, error = post_runs(url, doc, chunk, timeout, token)
            except ProblemError as e:
                with lock:
                    errors.append(e)
                    alive[0] = 0
                return
            with lock:
                for line in lines:
                    got.setdefault(line["index"], line)
                left = [i for i in chunk if i not in got]
            if left:
                todo.put(left)
            if error:
                with lock:
                    errors.append(DashpotError("%s: %s" % (url, error)))
                    alive[0] -= 1
                return

    total = sum(len(c) for c in chunks)
    threads = [threading.Thread(target=work, args=(u,), daemon=True) for u in urls]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    if len(got) < total:
        raise errors[0] if errors and isinstance(errors[0], ProblemError) else DashpotError(
            "%d of %d runs were answered by no daemon: %s" % (total - len(got), total, "; ".join(map(str, errors))))
    return got


def sweep(doc, urls, dask=None, chunk=None, timeout=DEFAULT_TIMEOUT, token=None):
    """The run lines of the sweep `doc` (dicts, in index order), computed by the daemons at `urls`.

    ``chunk`` runs go in one request (default: a quarter of an even share per daemon, so a stopped daemon
    costs little). ``dask``: a ``distributed.Client``; each chunk is then a task on its workers. A bad
    document raises ProblemError; runs no daemon answered raise DashpotError."""
    urls = [urls] if isinstance(urls, str) else list(urls)
    if not urls:
        raise ValueError("sweep needs at least one daemon URL")
    runs = _selected(doc)
    size = chunk or max(1, math.ceil(len(runs) / (4 * len(urls))))
    chunks = _chunks(runs, size)
    if dask is not None:
        futures = [dask.submit(_run_chunk, urls, doc, c, k, timeout, token, pure=False) for k, c in enumerate(chunks)]
        got = {line["index"]: line for part in dask.gather(futures) for line in part}
    else:
        got = _over_threads(doc, urls, chunks, timeout, token)
    return [got[i] for i in sorted(got)]
