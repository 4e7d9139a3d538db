#!/usr/bin/env python3
"""tests/lib/rawhttp.py - HTTP over a bare socket, for what curl will not send or cannot show.

  rawhttp.py framing PORT       each RFC 9112 framing fault, with a valid request pipelined behind it:
                                prints "NAME STATUSES CLOSED" (statuses comma-separated, CLOSED yes/no)
  rawhttp.py burst PORT N       N connections opened at once, then one GET /healthz on each, each kept
                                open until every answer is in: prints "SERVED REFUSED OTHER"
  rawhttp.py slowspec N T_END   the slow spec of the stop tests (N-point graph spring and damper, rational relaxation,
                                belt 0.3, N-point table load, dt 1e-7, t_end T_END, every 1e15) on stdout
"""
import json
import re
import socket
import sys

BODY = b'{"model":{"mass":0}}'
NEXT = b"GET /healthz HTTP/1.1\r\nHost: t\r\n\r\n"


def chunk(body):
    return b"%x\r\n" % len(body) + body + b"\r\n0\r\n\r\n"


FAULTS = [
    ("two-content-lengths", b"POST /v1/simulate HTTP/1.1\r\nHost: t\r\nContent-Length: %d\r\nContent-Length: 5\r\n\r\n"
     % len(BODY) + BODY),
    ("content-length-and-chunked", b"POST /v1/simulate HTTP/1.1\r\nHost: t\r\nContent-Length: %d\r\n"
     b"Transfer-Encoding: chunked\r\n\r\n" % len(BODY) + chunk(BODY)),
    ("transfer-encoding-gzip", b"POST /v1/simulate HTTP/1.1\r\nHost: t\r\nTransfer-Encoding: gzip\r\n\r\n" + BODY),
    ("transfer-encoding-gzip-chunked", b"POST /v1/simulate HTTP/1.1\r\nHost: t\r\n"
     b"Transfer-Encoding: gzip, chunked\r\n\r\n" + chunk(BODY)),
    ("no-host", b"GET /healthz HTTP/1.1\r\n\r\n"),
    ("two-hosts", b"GET /healthz HTTP/1.1\r\nHost: a\r\nHost: b\r\n\r\n"),
]
VALID = [
    ("get-pipelined", NEXT),
    ("http-1.0-without-host", b"GET /healthz HTTP/1.0\r\n\r\n"),
]


def exchange(port, data, wait=1.5):
    """Sends data, reads until the server closes or `wait` seconds of silence; (statuses, closed)."""
    s = socket.create_connection(("127.0.0.1", port))
    s.settimeout(wait)
    s.sendall(data)
    got, closed = b"", False
    try:
        while True:
            d = s.recv(65536)
            if not d:
                closed = True
                break
            got += d
    except socket.timeout:
        pass
    except ConnectionResetError:
        closed = True
    s.close()
    statuses = [m.decode() for m in re.findall(rb"HTTP/1\.[01] (\d{3}) ", got)]
    return statuses, closed


def framing(port):
    for name, req in FAULTS + VALID:
        statuses, closed = exchange(port, req + NEXT)
        print(name, ",".join(statuses) or "-", "yes" if closed else "no")


def burst(port, n):
    socks = [socket.create_connection(("127.0.0.1", port)) for _ in range(n)]
    for s in socks:
        s.settimeout(20)
        s.sendall(NEXT)
    codes = []
    for s in socks:
        got = b""
        try:
            while b"\r\n\r\n" not in got:
                d = s.recv(4096)
                if not d:
                    break
                got += d
        except OSError:
            pass
        codes.append(got.split(b" ")[1].decode() if got.startswith(b"HTTP/1.") else "none")
    for s in socks:
        s.close()
    print(codes.count("200"), codes.count("503"), n - codes.count("200") - codes.count("503"))


def slowspec(n, t_end):
    r = lambda v: round(v, 6)
    xs = [r(-1 + 2 * i / (n - 1)) for i in range(n)]
    spec = {"model": {"mass": 1,
                      "spring": {"law": "graph", "points": [[x, r(x * (1 + 0.1 * abs(x)))] for x in xs]},
                      "damper": {"law": "graph",
                                 "points": [[x, r(0.5 * x + (0.3 if i >= n // 2 else -0.3))] for i, x in enumerate(xs)],
                                 "relaxation": {"kind": "rational", "a": 1, "b": 1}, "belt_velocity": 0.3},
                      "forcing": {"kind": "table",
                                  "points": [[r(10 * i / (n - 1)), r(0.5 * ((i * 7919) % 13) / 13)] for i in range(n)]}},
            "initial": {"x": 0, "v": 0}, "solver": {"kind": "stick-slip", "dt": 1e-7, "t_end": t_end},
            "output": {"every": 1e15}}
    json.dump(spec, sys.stdout, separators=(",", ":"))


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "framing":
        framing(int(sys.argv[2]))
    elif cmd == "burst":
        burst(int(sys.argv[2]), int(sys.argv[3]))
    elif cmd == "slowspec":
        slowspec(int(sys.argv[2]), float(sys.argv[3]))
    else:
        sys.exit("usage: rawhttp.py framing PORT | burst PORT N | slowspec N T_END")
