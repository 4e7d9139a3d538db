#!/usr/bin/env python3
"""tests/fuzz/seeds.py - writes the fuzzers' seed corpora from api/openapi.yaml and the HTTP tests.

    python3 tests/fuzz/seeds.py          (from the repository root; needs python3-yaml)

tests/fuzz/corpus/openapi-*.json   every request example of the OpenAPI document, as a body (fuzz_spec);
tests/fuzz/corpus-http/*           raw HTTP/1.1 requests for fuzz_http: every request example sent to its
                                   route with each media type the route answers, the GET routes, and the
                                   shapes tests/test_http.sh and the fault tests use (chunked bodies,
                                   pipelining, Expect: 100-continue, HEAD, 405/404/406/413, a missing or
                                   wrong token, a declared length larger than the body, header folding).
The files are committed; run this again when the document's examples change.
"""
import json
import os
import sys

import yaml

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
TOKEN = "fuzz-token"  # tests/fuzz/fuzz_http.c
SPEC_DIR = os.path.join(ROOT, "tests", "fuzz", "corpus")
HTTP_DIR = os.path.join(ROOT, "tests", "fuzz", "corpus-http")


def request(method, path, body=b"", accept=None, token=TOKEN, extra=(), chunked=False):
    head = [f"{method} {path} HTTP/1.1", "Host: 127.0.0.1"]
    if accept:
        head.append("Accept: " + accept)
    if token:
        head.append("Authorization: Bearer " + token)
    head.extend(extra)
    if chunked:
        head.append("Transfer-Encoding: chunked")
        parts = [body[i:i + 7] for i in range(0, len(body), 7)]
        body = b"".join(b"%x\r\n%s\r\n" % (len(p), p) for p in parts) + b"0\r\n\r\n"
    elif body or method == "POST":
        head.append(f"Content-Length: {len(body)}")
    return ("\r\n".join(head) + "\r\n\r\n").encode() + body


def main():
    doc = yaml.safe_load(open(os.path.join(ROOT, "api", "openapi.yaml")))
    os.makedirs(HTTP_DIR, exist_ok=True)
    seeds = {}
    bodies = {}
    for path, item in doc["paths"].items():
        for method, op in item.items():
            if method == "get":
                seeds[f"get{path.replace('/', '-')}"] = request("GET", path)
                seeds[f"head{path.replace('/', '-')}"] = request("HEAD", path)
                continue
            content = op.get("requestBody", {}).get("content", {}).get("application/json", {})
            medias = sorted({m for r in op["responses"].values() if isinstance(r, dict)
                             for m in r.get("content", {}) if not m.startswith("application/problem")})
            for name, ex in content.get("examples", {}).items():
                value = ex["value"]
                body = (value if isinstance(value, str) else json.dumps(value)).encode()
                stem = f"{path.strip('/').replace('/', '-')}-{name}"
                bodies[f"openapi-{stem}.json"] = body
                for media in medias or ["*/*"]:
                    seeds[f"{stem}-{media.replace('/', '_').replace('+', '_')}"] = request(
                        "POST", path, body, accept=media)
    simulate = bodies["openapi-v1-simulate-coulomb.json"]
    stability = bodies["openapi-v1-stability-analysis.json"] if "openapi-v1-stability-analysis.json" in bodies \
        else next(v for k, v in bodies.items() if k.startswith("openapi-v1-stability"))
    seeds.update({
        "chunked-simulate": request("POST", "/v1/simulate", simulate, accept="application/x-ndjson",
                                    chunked=True),
        "pipelined": request("GET", "/healthz") + request("POST", "/v1/stability", stability)
                     + request("GET", "/metrics"),
        "expect-continue": request("POST", "/v1/simulate", simulate, extra=["Expect: 100-continue"]),
        "no-token": request("POST", "/v1/simulate", simulate, token=None),
        "wrong-token": request("POST", "/v1/simulate", simulate, token="fuzz-tokem"),
        "method-405": request("DELETE", "/v1/simulate"),
        "route-404": request("GET", "/a%22b%01c?x=1"),
        "accept-406": request("POST", "/v1/simulate", simulate, accept="text/html;q=0.9, */*;q=0"),
        "accept-q": request("POST", "/v1/simulate", simulate, accept="text/csv;q=0.5, application/x-ndjson;q=0.7"),
        "declared-413": ("POST /v1/simulate HTTP/1.1\r\nHost: 127.0.0.1\r\nAuthorization: Bearer " + TOKEN
                         + "\r\nContent-Length: 100000000\r\n\r\n{").encode(),
        "chunked-413": request("POST", "/v1/simulate", b" " * 20000, chunked=True),
        "short-body": request("POST", "/v1/simulate", simulate)[:-10],
        "folded-header": request("GET", "/healthz", extra=["X-A: 1", " continued"]),
        "http10": b"GET /healthz HTTP/1.0\r\n\r\n",
        "page": request("GET", "/", extra=['If-None-Match: "0123456789abcdef"']),
        "nested": request("POST", "/v1/simulate", b"[" * 200 + b"]" * 200),
        "nan": request("POST", "/v1/simulate", simulate.replace(b'"mass": 1', b'"mass": NaN')),
        "huge": request("POST", "/v1/simulate", simulate.replace(b'"mass": 1', b'"mass": 1e999')),
        "convergence-chunked": request("POST", "/v1/convergence", bodies["openapi-v1-convergence-coulomb.json"],
                                       chunked=True),
    })
    for name, body in bodies.items():
        with open(os.path.join(SPEC_DIR, name), "wb") as f:
            f.write(body)
    for name, raw in seeds.items():
        with open(os.path.join(HTTP_DIR, name), "wb") as f:
            f.write(raw)
    print(f"{len(bodies)} spec seeds into {SPEC_DIR}, {len(seeds)} HTTP seeds into {HTTP_DIR}", file=sys.stderr)


if __name__ == "__main__":
    main()
