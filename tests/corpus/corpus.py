#!/usr/bin/env python3
"""tests/corpus/corpus.py - the answer corpus: every request document a user can send, run through the CLI
in each of its formats and through the daemon in each media type, answers kept bit for bit (tests/corpus/README.md).

    corpus.py gather                          freezes the inputs into tests/corpus/inputs/ and writes cases.tsv
                                              (needs node for web/presets.js and python3-yaml for the OpenAPI
                                              document; only record.sh --inputs runs it)
    corpus.py run OUT CLI URL URL_FUZZ        runs every case of cases.tsv, writes the masked answers into OUT
    corpus.py compare WANT GOT [COUNTS]       compares stored answers (WANT) with fresh ones (GOT) bit for bit:
                                              "not ok - CASE" and a short diff for each that differs; writes
                                              "PASSED FAILED" into COUNTS
    corpus.py store GOT DEST                  stores the answers of GOT in DEST (plain, gzip or digest by size)

URL is a daemon with the default limits and no token; URL_FUZZ one with tests/fuzz/fuzz_http.c's token and small
limits, for the raw requests of tests/fuzz/corpus-http. Only the Python standard library is needed for run,
compare and store.

Masking (the only text changed before comparing; nothing else, and never a number of the physics):
  - the version in a meta object, "version":"X.Y.Z" -> "version":"<version>" (it changes at every release);
  - HTTP responses keep their status line and their headers, sorted by name (their order carries no meaning),
    but Date (the time of the request) and the framing: Content-Length, Transfer-Encoding and
    X-Accel-Buffering (a /v1/simulate answer is sent whole or chunked depending on whether its first block
    took less than 10 ms: src/http/simulate.c); the daemon's log line with its duration is never read;
  - GET /metrics keeps only its "# HELP" and "# TYPE" lines (the counters depend on what ran before, the
    duration histogram on the machine's speed), and GET /openapi.yaml and GET / only their status and
    Content-Type (their bodies are files of api/ and web/, not answers).
Nothing else in any answer varies from run to run (record.sh --twice checks it).
"""
import concurrent.futures
import difflib
import gzip
import hashlib
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
INPUTS = os.path.join(HERE, "inputs")
CASES = os.path.join(HERE, "cases.tsv")

# The formats each CLI command and each route offer (`dashpot CMD --help`, src/http/*.c).
CLI_FORMATS = {"simulate": ["json", "ndjson", "csv"], "stability": ["json", "csv", "svg"],
               "response": ["json", "ndjson", "csv"], "wellposedness": [None], "convergence": [None],
               "modes": [None], "lcp": [None]}
HTTP_ACCEPTS = {"simulate": ["application/json", "application/x-ndjson", "text/event-stream", "text/csv"],
                "stability": ["application/json", "text/csv", "image/svg+xml"],
                "response": ["application/json", "application/x-ndjson", "text/csv"],
                "wellposedness": ["application/json"], "convergence": ["application/json"],
                "modes": ["application/json"], "lcp": ["application/json"]}
ROUTES = list(CLI_FORMATS)

# Answers up to PLAIN_MAX bytes are stored as text, up to GZIP_MAX gzip-compressed, larger ones as a digest
# (line count, sha256, the first and last 20 lines, and a sha256 and first line of every block of 1000 lines).
PLAIN_MAX = 16 * 1024
GZIP_MAX = 512 * 1024
DIGEST_BLOCK = 1000
DIGEST_ENDS = 20
MAX_DIFFS = 20  # changed cases shown with their diff; the rest by name

MASKS = [(re.compile(rb'"version":"[^"\\]*"'), b'"version":"<version>"')]


def mask(data):
    for pattern, repl in MASKS:
        data = pattern.sub(repl, data)
    return data


# ---------------------------------------------------------------------------------------------------------
# gather: freeze the inputs
# ---------------------------------------------------------------------------------------------------------

REQUEST_KEYS = {"model", "M", "q", "law", "mass", "solver", "initial", "omega", "force_node", "response_node",
                "map", "damping"}


def routes_for(doc):
    """The routes a document is meant for, from its members (empty when it is no request at all)."""
    if not isinstance(doc, dict):
        return []
    if "M" in doc or "q" in doc:
        return ["lcp"]
    law = doc.get("law")
    if isinstance(law, dict) and ("lambda" in law or "mu" in law):
        return ["stability"]
    if {"force_node", "response_node", "omega"} & set(doc):
        return ["modes", "response"]
    if "model" in doc:
        solver = doc.get("solver") if isinstance(doc.get("solver"), dict) else {}
        if solver.get("kind") == "regularized" and (isinstance(solver.get("n"), list) or
                                                    isinstance(solver.get("k"), list)):
            return ["convergence"]
        model = doc["model"] if isinstance(doc["model"], dict) else {}
        routes = ["simulate"]
        if "damping" in doc or "stiffness_matrix" in model or "mass_matrix" in model:
            routes.append("modes")
        return routes
    return []


# Documents left out, with why: each would run for minutes (the CLI has no wall-time limit; the daemon would
# stop them at --max-wall, 120 s, a time that depends on the machine).
EXCLUDE = {
    "tests/fuzz/corpus/regress-regularized-stiff.json": "a convergence study with k = 1.3e69: over 2 min",
    "tests/fuzz/corpus/regression-stiff-regularized.json": "a convergence study with k = 2.9e97: over 2 min",
    "tests/test_http.sh:n\": [100000, 1000000]": "rkf45 at n = 10^5, 10^6: about 8 s, stopped there at --max-wall",
}
MAX_CLI_STEPS = 1e8  # the daemon's default --max-steps: a spec over it is sent to the daemon only (its 422)


def too_long_for_cli(doc):
    try:
        solver = doc["solver"]
        return float(solver["t_end"]) / float(solver["dt"]) > MAX_CLI_STEPS
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return False


def excluded(source, data):
    return any(key == source or (key.startswith(source + ":") and key.split(":", 1)[1] in data)
               for key in EXCLUDE)


class Gather:
    def __init__(self):
        self.inputs = {}   # relative path -> bytes
        self.by_bytes = {}  # bytes -> relative path
        self.order = []    # relative paths in order of first appearance
        self.routes = {}   # relative path -> list of routes
        self.http = set()  # relative paths also sent over HTTP
        self.accepts = {}  # (path, route) -> extra Accept values
        self.gets = []     # (name, method, target, keep)
        self.raw = []      # relative paths of raw HTTP requests
        self.http_only = set()  # relative paths not run with the CLI

    def add(self, rel, data, routes, http=False, accepts=(), source=None):
        if isinstance(data, str):
            data = data.encode()
        if source and excluded(source, data.decode("utf-8", "replace")):
            return None
        if data in self.by_bytes:
            rel = self.by_bytes[data]
        else:
            base, ext = os.path.splitext(rel)
            n = 2
            while rel in self.inputs:
                rel = f"{base}-{n}{ext}"
                n += 1
            self.inputs[rel] = data
            self.by_bytes[data] = rel
            self.order.append(rel)
            self.routes[rel] = []
            try:
                if too_long_for_cli(json.loads(data)):
                    self.http_only.add(rel)
                    http = True
            except ValueError:
                pass
        for r in routes:
            if r not in self.routes[rel]:
                self.routes[rel].append(r)
        if http:
            self.http.add(rel)
        for r in routes:
            for a in accepts:
                lst = self.accepts.setdefault((rel, r), [])
                if a not in lst and a not in HTTP_ACCEPTS[r]:
                    lst.append(a)
        return rel

    def get(self, name, method, target, keep="body"):
        if not any(g[1:3] == (method, target) for g in self.gets):
            self.gets.append((name, method, target, keep))


def doc_blocks(text):
    return re.findall(r'<!-- (example|file: ([^ ]+)) -->\n```[a-z]*\n(.*?)```', text, re.S)


def example_command(body):
    """The command of an example block, as tests/test_docs.sh reads it."""
    lines = body.split("\n")
    cmd = [lines[0][2:]]

    def incomplete(t):
        try:
            shlex.split(t)
        except ValueError:
            return True
        return t.endswith("\\")
    while incomplete("\n".join(cmd)):
        cmd.append(lines[len(cmd)])
    return "\n".join(cmd)


def segments(cmd):
    lex = shlex.shlex(cmd.replace("\\\n", " "), posix=True, punctuation_chars="|;&")
    lex.whitespace_split = True
    seg, out = [], []
    for tok in lex:
        if tok in ("|", ";", "&&", "||", "&"):
            out.append(seg)
            seg = []
        else:
            seg.append(tok)
    out.append(seg)
    return [s for s in out if s]


def curl_request(args):
    """method, path, Accept, data (str, '@file' or None) of a curl command's arguments."""
    method, accept, data, url = None, None, None, None
    i = 0
    while i < len(args):
        a = args[i]
        if a in ("-H", "--header"):
            i += 1
            if args[i].lower().startswith("accept:"):
                accept = args[i].split(":", 1)[1].strip()
        elif a in ("-d", "--data", "--data-binary"):
            i += 1
            data = args[i]
        elif a in ("-X", "--request"):
            i += 1
            method = args[i]
        elif a in ("-o", "-w", "--max-time"):
            i += 1
        elif "localhost:8080" in a:
            url = a
        i += 1
    path = url.split("localhost:8080", 1)[1] if url else None
    if method is None:
        method = "POST" if data is not None else "GET"
    return method, path, accept, data


def gather_docs(g):
    docs = ["README.md"] + sorted(f"docs/{f}" for f in os.listdir(os.path.join(ROOT, "docs")) if f.endswith(".md"))
    for doc in docs:
        text = open(os.path.join(ROOT, doc), encoding="utf-8").read()
        stem = "readme" if doc == "README.md" else os.path.basename(doc)[:-3]
        files, uses = {}, {}  # file name -> bytes; file name -> [(route, accept)]
        inline = []           # (bytes, route, accept)
        n = 0
        for kind, name, body in doc_blocks(text):
            if kind.startswith("file"):
                files[name] = body.encode()
                continue
            n += 1
            cmd = example_command(body)
            segs = segments(cmd)
            for j, seg in enumerate(segs):
                prog = os.path.basename(seg[0])
                if prog == "dashpot" and len(seg) >= 3 and seg[1] in CLI_FORMATS:
                    route, src = seg[1], seg[2]
                    if src == "-":
                        prev = segs[j - 1] if j else []
                        if prev and prev[0] in ("echo", "printf") and len(prev) >= 2:
                            inline.append(((prev[-1] + ("\n" if prev[0] == "echo" else "")).encode(), route, None))
                    else:
                        uses.setdefault(src, []).append((route, None))
                elif prog == "curl":
                    method, path, accept, data = curl_request(seg[1:])
                    if path is None:
                        continue
                    route = path[len("/v1/"):] if path.startswith("/v1/") else None
                    if route in CLI_FORMATS and method == "POST":
                        if data is not None and data.startswith("@"):
                            uses.setdefault(data[1:], []).append((route, accept))
                        elif data is not None:
                            inline.append((data.encode(), route, accept))
                    elif method == "GET":
                        g.get(f"docs-{stem}", "GET", path, keep_for(path))
                    else:
                        g.get(f"docs-{stem}", method, path)
        for name, data in files.items():
            routes = [r for r, _ in uses.get(name, [])]
            if not routes:
                try:
                    routes = routes_for(json.loads(data))
                except ValueError:
                    routes = ["simulate"]
            for route in dict.fromkeys(routes):
                accepts = [a for r, a in uses.get(name, []) if a and r == route]
                g.add(f"docs/{stem}-{name}", data, [route], http=True, accepts=accepts)
        for k, (data, route, accept) in enumerate(inline, 1):
            g.add(f"docs/{stem}-inline{k:02d}.json", data, [route], http=True, accepts=[accept] if accept else [])
        # JSON requests shown without a marker (a ```json block that is a request document)
        k = 0
        for m in re.finditer(r'(<!-- [^>]*-->\n)?```json\n(.*?)```', text, re.S):
            if m.group(1):
                continue
            try:
                d = json.loads(m.group(2))
            except ValueError:
                continue
            routes = routes_for(d)
            if routes:
                k += 1
                g.add(f"docs/{stem}-block{k:02d}.json", m.group(2), routes, http=True)


def keep_for(path):
    return {"/metrics": "help", "/openapi.yaml": "head", "/": "head"}.get(path, "body")


def gather_openapi(g):
    import yaml
    doc = yaml.safe_load(open(os.path.join(ROOT, "api", "openapi.yaml"), encoding="utf-8"))
    for path, item in doc["paths"].items():
        for method, op in item.items():
            if method != "post":
                g.get("openapi", method.upper(), path, keep_for(path))
                continue
            route = path[len("/v1/"):]
            examples = op.get("requestBody", {}).get("content", {}).get("application/json", {}).get("examples", {})
            for name, ex in examples.items():
                value = ex["value"]
                body = value if isinstance(value, str) else json.dumps(value)
                accepts = [ex["x-accept"]] if "x-accept" in ex else []
                g.add(f"openapi/{route}-{name}.json", body, [route], http=True, accepts=accepts)


def gather_fuzz(g):
    d = os.path.join(ROOT, "tests", "fuzz", "corpus")
    for name in sorted(os.listdir(d)):
        data = open(os.path.join(d, name), "rb").read()
        m = re.match(r"openapi-v1-([a-z]+)-", name)
        if m:
            routes = [m.group(1)]
        else:
            try:
                routes = routes_for(json.loads(data)) or ["simulate"]
            except ValueError:
                routes = ["simulate"]
        g.add(f"fuzz/{name}", data, routes, source=f"tests/fuzz/corpus/{name}")
    d = os.path.join(ROOT, "tests", "fuzz", "corpus-http")
    for name in sorted(os.listdir(d)):
        rel = f"http-raw/{name}"
        g.inputs[rel] = open(os.path.join(d, name), "rb").read()
        g.raw.append(rel)


def gather_tests(g):
    """JSON request documents written out in the shell tests: quoted heredocs and single-quoted strings."""
    tdir = os.path.join(ROOT, "tests")
    for script in sorted(f for f in os.listdir(tdir) if f.endswith(".sh") and f != "test_corpus.sh"):
        text = open(os.path.join(tdir, script), encoding="utf-8").read()
        stem = script[len("test_"):-3] if script.startswith("test_") else script[:-3]
        found = []  # (offset, body, name hint)
        for m in re.finditer(r"<<-?\s*(['\"]?)(\w+)\1[^\n]*\n(.*?)\n\s*\2\n", text, re.S):
            body = m.group(3)
            if not m.group(1) and re.search(r"[$`\\]", body):
                continue  # expanded by the shell: not the bytes a user sends
            line = text[text.rfind("\n", 0, m.start()) + 1:m.start()]
            hint = re.search(r"/(\w+)\.json", line)
            found.append((m.start(), body + "\n", hint.group(1) if hint else None))
        for m in re.finditer(r"'(\{[^']*)'", text):
            line = text[text.rfind("\n", 0, m.start()) + 1:m.start()]
            hint = re.match(r"\s*(\w+)=$", line)
            found.append((m.start(), m.group(1), hint.group(1).lower() if hint else None))
        k = 0
        for off, body, hint in sorted(found):
            try:
                d = json.loads(body)
            except ValueError:
                continue
            if not isinstance(d, dict) or not (set(d) & REQUEST_KEYS):
                continue
            routes = routes_for(d)
            # a route the surrounding lines name (a CLI command or a path)
            end = text.find("\n", off + len(body))
            end = text.find("\n", end + 1) if end >= 0 else -1
            near = text[text.rfind("\n", 0, off) + 1:end if end >= 0 else len(text)]
            for r in re.findall(r'(?:/v1/|"\s|\bBIN"?\s|\bCLI"?\s|\bbin"?\s)(' + "|".join(ROUTES) + r")\b", near):
                if r not in routes and (r != "wellposedness" or "model" in d):
                    routes.append(r)
            if not routes:
                continue
            k += 1
            name = f"{k:02d}" + (f"-{hint}" if hint else "")
            g.add(f"tests/{stem}-{name}.json", body, routes, source=f"tests/{script}")


def gather_presets(g):
    """The browser page's presets (web/presets.js), as the page sends them: a simulate request without an
    "output" member gets "output": {"max_samples": 500} first, as web/app.js adds its plot width."""
    js = ("import(process.argv[1]).then(m => console.log(JSON.stringify("
          "m.PRESETS.map(p => ({id: p.id, kind: p.kind, spec: p.spec})))))")
    out = subprocess.run(["node", "--input-type=module", "-e", js, "file://" + os.path.join(ROOT, "web", "presets.js")],
                         capture_output=True, text=True, check=True).stdout
    for p in json.loads(out):
        spec = p["spec"]
        if p["kind"] == "simulate":
            routes = ["simulate"]
            if "output" not in spec:
                spec = {"output": {"max_samples": 500}, **spec}
        elif p["kind"] == "modes":
            routes = ["modes"] + (["response"] if "force_node" in spec and "response_node" in spec else [])
        else:
            routes = [p["kind"]]
        g.add(f"presets/{p['id']}.json", json.dumps(spec, indent=1) + "\n", routes, http=True)


def gather_extra(g):
    """tests/corpus/extra/ROUTE-NAME.json: a few documents written for the corpus where the sources above leave a
    solver option without an example (scheme PI, the steppers, a table forcing alone, output without samples or
    events, the well-posedness report of each kind of model)."""
    d = os.path.join(HERE, "extra")
    for name in sorted(os.listdir(d)):
        route = name.split("-", 1)[0]
        assert route in ROUTES, name
        g.add(f"extra/{name}", open(os.path.join(d, name), "rb").read(), [route])


def case_stem(rel):
    return re.sub(r"[^A-Za-z0-9_.-]", "_", rel.replace("/", "-").rsplit(".json", 1)[0])


def gather():
    g = Gather()
    gather_docs(g)
    gather_openapi(g)
    gather_fuzz(g)
    gather_tests(g)
    gather_presets(g)
    gather_extra(g)
    g.get("errors", "GET", "/no/such/route")
    g.get("errors", "DELETE", "/healthz")
    g.get("errors", "GET", "/v1/simulate")
    g.get("errors", "HEAD", "/healthz")
    # write the inputs afresh
    for dirpath, _, names in os.walk(INPUTS, topdown=False):
        for n in names:
            os.unlink(os.path.join(dirpath, n))
    for rel, data in g.inputs.items():
        path = os.path.join(INPUTS, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(data)
    rows = []
    for rel in g.order:
        stem = case_stem(rel)
        for route in g.routes[rel]:
            for fmt in CLI_FORMATS[route] if rel not in g.http_only else []:
                rows.append((f"{stem}.cli-{route}" + (f"-{fmt}" if fmt else ""), "inputs/" + rel, "cli", route, "-",
                             f"--format {fmt}" if fmt else "-", "body"))
            if rel in g.http:
                for acc in HTTP_ACCEPTS[route] + g.accepts.get((rel, route), []):
                    short = re.sub(r"[^a-z0-9]+", "_", acc.split("/")[-1].lower()).strip("_")
                    rows.append((f"{stem}.http-{route}-{short}", "inputs/" + rel, "http", "POST", f"/v1/{route}",
                                 acc, "body"))
    for name, method, target, keep in g.gets:
        slug = re.sub(r"[^a-z0-9]+", "_", target.lower()).strip("_") or "page"
        rows.append((f"route-{method.lower()}-{slug}", "-", "http", method, target, "-", keep))
    for rel in g.raw:
        target = parse_raw(g.inputs[rel])[1].split("?")[0]
        rows.append((case_stem(rel), "inputs/" + rel, "raw", "-", "-", "-", keep_for(target)))
    names = [r[0] for r in rows]
    assert len(names) == len(set(names)), [n for n in names if names.count(n) > 1]
    with open(CASES, "w") as f:
        f.write("# tests/corpus/cases.tsv - written by corpus.py gather (record.sh --inputs); one case a line:\n"
                "# name, input, via (cli: `dashpot ROUTE - [--format F]` with the input on stdin; http: METHOD "
                "TARGET with Accept OPTION\n# to the plain daemon; raw: the raw request in the input replayed "
                "with curl to the token daemon with small limits),\n# method or CLI command, target, option, "
                "keep (body, head: status and Content-Type only, help: the # HELP/# TYPE lines)\n")
        for r in rows:
            f.write("\t".join(r) + "\n")
    print(f"{len(g.inputs)} inputs, {len(rows)} cases into {os.path.relpath(HERE, ROOT)}", file=sys.stderr)


# ---------------------------------------------------------------------------------------------------------
# run: every case, masked answers into a directory
# ---------------------------------------------------------------------------------------------------------

def read_cases():
    rows = []
    for line in open(CASES, encoding="utf-8"):
        if line.startswith("#") or not line.strip():
            continue
        rows.append(line.rstrip("\n").split("\t"))
    return rows


def parse_raw(data):
    """method, target, headers (list of (name, value)), body of a raw HTTP/1.1 request (chunked bodies joined)."""
    head, _, rest = data.partition(b"\r\n\r\n")
    lines = head.split(b"\r\n")
    method, target = lines[0].split(b" ")[:2]
    headers = []
    for l in lines[1:]:
        if l[:1] in (b" ", b"\t") and headers:  # a folded line belongs to the header before it
            headers[-1] = (headers[-1][0], headers[-1][1] + b" " + l.strip())
        elif b":" in l:
            k, v = l.split(b":", 1)
            headers.append((k.strip(), v.strip()))
    names = {k.lower(): v for k, v in headers}
    if names.get(b"transfer-encoding", b"").lower() == b"chunked":
        body = b""
        while True:
            size_line, _, rest = rest.partition(b"\r\n")
            size = int(size_line.split(b";")[0] or b"0", 16)
            if size == 0:
                break
            body += rest[:size]
            rest = rest[size + 2:]
    else:
        length = int(names.get(b"content-length", b"0"))
        body = rest[:length]  # a declared length larger than what follows: what follows (curl sends its length)
    return method.decode(), target.decode(), headers, body


# Response headers not recorded: Date (the time of the request), and how the body is framed. A /v1/simulate
# run whose first block (512 records) is computed within one 10 ms slice is sent whole with a Content-Length,
# else streamed chunked with X-Accel-Buffering: no (src/http/simulate.c): the same bytes, framed by the
# machine's speed.
UNRECORDED_HEADERS = {b"date", b"content-length", b"transfer-encoding", b"x-accel-buffering"}


def http_answer(method, headers_file, body_file, keep):
    raw = open(headers_file, "rb").read()
    # the last response (after a 100 Continue, if any)
    blocks = [b for b in raw.split(b"\r\n\r\n") if b.strip()]
    lines = blocks[-1].split(b"\r\n") if blocks else [b"(no response)"]
    status = lines[0]
    hdrs = []
    for l in lines[1:]:
        k, _, v = l.partition(b":")
        if k.lower() in UNRECORDED_HEADERS or (keep == "head" and k.lower() != b"content-type"):
            continue
        hdrs.append(k + b": " + v.strip())
    hdrs.sort(key=lambda h: h.split(b":")[0].lower())
    body = open(body_file, "rb").read() if os.path.exists(body_file) else b""
    if keep == "head" or method == "HEAD":  # (curl -I writes the head where the body would go)
        body = b""
    elif keep == "help":
        body = b"".join(l for l in body.splitlines(True) if l.startswith((b"# HELP", b"# TYPE")))
    return b"\n".join([status] + hdrs) + b"\n\n" + body


def run_case(row, cli, url, url_fuzz, tmp):
    name, inp, via, method, target, option, keep = row
    t0 = time.monotonic()
    if via == "cli":
        args = [cli, method, "-"] + (option.split() if option != "-" else [])
        data = open(os.path.join(HERE, inp), "rb").read()
        try:
            p = subprocess.run(args, input=data, capture_output=True, timeout=300)
            code, out, err = p.returncode, p.stdout, p.stderr
        except subprocess.TimeoutExpired:
            code, out, err = "timeout", b"", b""
        cmd = f"$ dashpot {method} -" + (f" {option}" if option != "-" else "") + f" < {inp}"
        answer = (cmd.encode() + b"\nexit " + str(code).encode() + b"\n--- stderr\n" + err +
                  b"--- stdout\n" + out)
    else:
        headers_file = os.path.join(tmp, name + ".h")
        body_file = os.path.join(tmp, name + ".b")
        args = ["curl", "-s", "-S", "--max-time", "300", "-D", headers_file, "-o", body_file]
        base = url
        if via == "raw":
            method, target, headers, body = parse_raw(open(os.path.join(HERE, inp), "rb").read())
            base = url_fuzz
            for k, v in headers:
                if k.lower() in (b"host", b"content-length", b"transfer-encoding", b"expect", b"connection"):
                    if k.lower() == b"transfer-encoding":
                        args += ["-H", "Transfer-Encoding: chunked"]
                    continue
                args += ["-H", (k + b": " + v).decode("latin-1")]
            if b"accept" not in {k.lower() for k, _ in headers}:
                args += ["-H", "Accept:"]  # none sent, as in the raw request
            if method == "POST" or body:
                args += ["--data-binary", "@" + os.path.join(tmp, name + ".in")]
                with open(os.path.join(tmp, name + ".in"), "wb") as f:
                    f.write(body)
            cmd = f"{method} {target} (raw request {inp})"
        else:
            if option != "-":
                args += ["-H", "Accept: " + option]
            if inp != "-":
                args += ["--data-binary", "@" + os.path.join(HERE, inp)]
            cmd = f"{method} {target}" + (f" Accept: {option}" if option != "-" else "") + \
                (f" < {inp}" if inp != "-" else "")
        if method == "HEAD":
            args += ["-I"]
        else:
            args += ["-X", method]
        args += ["--path-as-is", base + target]
        p = subprocess.run(args, capture_output=True)
        answer = cmd.encode() + b"\n" + (b"curl: " + p.stderr if p.returncode else b"") + \
            http_answer(method, headers_file, body_file, keep)
        for f in (headers_file, body_file):
            if os.path.exists(f):
                os.unlink(f)
    return name, mask(answer), time.monotonic() - t0


def run(out, cli, url, url_fuzz, jobs):
    os.makedirs(out, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="corpus.")
    rows = read_cases()
    slow = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        for name, answer, secs in pool.map(lambda r: run_case(r, cli, url, url_fuzz, tmp), rows):
            with open(os.path.join(out, name), "wb") as f:
                f.write(answer)
            slow.append((secs, name))
    shutil.rmtree(tmp)
    slow.sort(reverse=True)
    print("    slowest: " + ", ".join(f"{n} {s:.2f} s" for s, n in slow[:3]), file=sys.stderr)


# ---------------------------------------------------------------------------------------------------------
# store and compare
# ---------------------------------------------------------------------------------------------------------

def digest(data):
    lines = data.splitlines(True)
    out = [f"digest: {len(lines)} lines, {len(data)} bytes, sha256 {hashlib.sha256(data).hexdigest()}\n".encode()]
    cut = [l if len(l) <= 400 else l[:400] + b"...(%d bytes)\n" % len(l) for l in lines]
    out.append(b"--- head\n")
    out += cut[:DIGEST_ENDS]
    out.append(b"--- tail\n")
    out += cut[-DIGEST_ENDS:]
    out.append(b"--- blocks of %d lines: first line number, sha256, first line\n" % DIGEST_BLOCK)
    for i in range(0, len(lines), DIGEST_BLOCK):
        block = b"".join(lines[i:i + DIGEST_BLOCK])
        out.append(b"%d %s %s" % (i + 1, hashlib.sha256(block).hexdigest().encode(), lines[i][:200].rstrip(b"\n") + b"\n"))
    return b"".join(x if x.endswith(b"\n") else x + b"\n" for x in out)


def store(got, dest):
    os.makedirs(dest, exist_ok=True)
    names = set(os.listdir(got))
    for f in os.listdir(dest):
        os.unlink(os.path.join(dest, f))
    total = 0
    for name in sorted(names):
        data = open(os.path.join(got, name), "rb").read()
        if len(data) <= PLAIN_MAX:
            path, blob = name, data
        elif len(data) <= GZIP_MAX:
            path, blob = name + ".gz", gzip.compress(data, 9, mtime=0)
        else:
            path, blob = name + ".digest", digest(data)
        with open(os.path.join(dest, path), "wb") as f:
            f.write(blob)
        total += len(blob)
    print(f"{len(names)} answers, {total} bytes into {dest}", file=sys.stderr)


def load_wanted(want):
    out = {}
    for f in os.listdir(want):
        if f.endswith(".gz"):
            out[f[:-3]] = ("gz", os.path.join(want, f))
        elif f.endswith(".digest"):
            out[f[:-7]] = ("digest", os.path.join(want, f))
        else:
            out[f] = ("plain", os.path.join(want, f))
    return out


def short_diff(a, b, limit=24):
    a = [l[:300] for l in a.decode("utf-8", "replace").splitlines()]
    b = [l[:300] for l in b.decode("utf-8", "replace").splitlines()]
    d = list(difflib.unified_diff(a, b, "recorded", "now", n=1, lineterm=""))
    more = len(d) - limit
    return "\n".join("    " + l for l in d[:limit]) + (f"\n    ... ({more} more diff lines)" if more > 0 else "")


def compare_one(kind, path, got):
    """None if equal, else a description of the difference."""
    if kind == "plain":
        want = open(path, "rb").read()
        return None if want == got else short_diff(want, got)
    if kind == "gz":
        want = gzip.decompress(open(path, "rb").read())
        return None if want == got else short_diff(want, got)
    want = open(path, "rb").read()
    mine = digest(got)
    if want == mine:
        return None
    # the head and tail as text, then which blocks of lines changed
    w, m = want.split(b"--- blocks")[0], mine.split(b"--- blocks")[0]
    msg = short_diff(w, m) if w != m else ""
    wb = want.split(b"--- blocks", 1)[1].splitlines()[1:]
    mb = mine.split(b"--- blocks", 1)[1].splitlines()[1:]
    changed = [i for i in range(max(len(wb), len(mb))) if (wb[i] if i < len(wb) else None) != (mb[i] if i < len(mb) else None)]
    lines = got.splitlines()
    notes = []
    for i in changed[:3]:
        first = i * DIGEST_BLOCK
        old = wb[i].split(b" ", 2)[2] if i < len(wb) else b"(none)"
        notes.append(f"    block from line {first + 1} changed; recorded first line: {old[:200].decode('utf-8', 'replace')}")
        notes.append("    now: " + "\n    now: ".join(l[:200].decode("utf-8", "replace") for l in lines[first:first + 3]))
    if len(changed) > 3:
        notes.append(f"    ... and {len(changed) - 3} more blocks of {DIGEST_BLOCK} lines")
    return (msg + "\n" if msg else "") + "\n".join(notes)


def compare(want, got):
    wanted = load_wanted(want)
    names = [r[0] for r in read_cases()]
    passed = failed = changed = 0
    for name in names:
        path = os.path.join(got, name)
        if name not in wanted:
            print(f"not ok - {name}: no recorded answer (a new case: make corpus)")
            failed += 1
            continue
        if not os.path.exists(path):
            print(f"not ok - {name}: did not run")
            failed += 1
            continue
        diff = compare_one(*wanted[name], open(path, "rb").read())
        if diff is None:
            passed += 1
        else:
            failed += 1
            changed += 1
            print(f"not ok - {name}: the answer changed" + (f"\n{diff}" if changed <= MAX_DIFFS else " (diff not shown)"))
    extra = sorted(set(wanted) - set(names))
    for name in extra:
        print(f"not ok - {name}: a recorded answer without a case in cases.tsv")
        failed += 1
    print(f"    corpus: {passed} of {len(names)} answers bit for bit as recorded" +
          (f" (diffs shown for the first {MAX_DIFFS} of {changed} that changed)" if changed > MAX_DIFFS else ""))
    return passed, failed


def main():
    cmd = sys.argv[1] if len(sys.argv) > 1 else ""
    if cmd == "gather":
        gather()
    elif cmd == "run":
        out, cli, url, url_fuzz = sys.argv[2:6]
        run(out, cli, url, url_fuzz, int(os.environ.get("CORPUS_JOBS", "2")))
    elif cmd == "store":
        store(sys.argv[2], sys.argv[3])
    elif cmd == "compare":
        passed, failed = compare(sys.argv[2], sys.argv[3])
        if len(sys.argv) > 4:
            with open(sys.argv[4], "w") as f:
                f.write(f"{passed} {failed}\n")
        sys.exit(1 if failed else 0)
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
