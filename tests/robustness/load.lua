-- tests/robustness/load.lua - wrk script for tests/robustness/load.sh: every connection cycles through a
-- mix of valid, invalid and streaming requests (the table below, weights by repetition); each thread counts
-- the statuses it got, and done() prints them as "status CODE COUNT" lines for the shell to check.
--   40% GET /healthz; 15% a 3-sample simulate (JSON); 10% an invalid spec (422); 5% malformed JSON (400);
--   10% a 5001-sample NDJSON stream (~0.7 MB); 10% a stability analysis; 5% a CSV stream of 2001 rows;
--   and one each of 404, 405 and 406 in every 100.

local tiny = '{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.3}}, "solver": {"dt": 1, "t_end": 2}}'
local invalid = '{"model": {"mass": -1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.3}}, "solver": {"dt": 0}}'
local malformed = '{"model": {"mass": '
local stream = '{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.5}, "forcing": {"kind": "harmonic", "amplitude": 1, "omega": 0.5}}, "initial": {"x": 1, "v": 0}, "solver": {"dt": 0.002, "t_end": 10}}'
local csv = '{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.5}}, "initial": {"x": 3, "v": 0}, "solver": {"dt": 0.01, "t_end": 20}}'
local stab = '{"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]}}'

local kinds = {}
local function add(n, req)
    for i = 1, n do kinds[#kinds + 1] = req end
end

statuses = {}
local requests = {}
local counter = 0
local threads = {}

function setup(thread)
    thread:set("id", #threads + 1)
    threads[#threads + 1] = thread
end

function init(args)
    local json = { ["Content-Type"] = "application/json" }
    local nd = { ["Content-Type"] = "application/json", ["Accept"] = "application/x-ndjson" }
    local tcsv = { ["Content-Type"] = "application/json", ["Accept"] = "text/csv" }
    local html = { ["Content-Type"] = "application/json", ["Accept"] = "text/html" }
    add(40, wrk.format("GET", "/healthz"))
    add(15, wrk.format("POST", "/v1/simulate", json, tiny))
    add(10, wrk.format("POST", "/v1/simulate", json, invalid))
    add(5, wrk.format("POST", "/v1/simulate", json, malformed))
    add(10, wrk.format("POST", "/v1/simulate", nd, stream))
    add(10, wrk.format("POST", "/v1/stability", json, stab))
    add(5, wrk.format("POST", "/v1/simulate", tcsv, csv))
    add(1, wrk.format("GET", "/no/such/route"))
    add(1, wrk.format("PUT", "/v1/stability", json, stab))
    add(1, wrk.format("POST", "/v1/simulate", html, tiny))
    -- Each thread starts at a different place of the cycle.
    counter = (id or 0) * 37
end

function request()
    counter = counter + 1
    return kinds[counter % #kinds + 1]
end

function response(status, headers, body)
    statuses[status] = (statuses[status] or 0) + 1
end

function done(summary, latency, requests)
    local total = {}
    for _, t in ipairs(threads) do
        local s = t:get("statuses")
        for code, n in pairs(s) do total[code] = (total[code] or 0) + n end
    end
    for code, n in pairs(total) do io.write(string.format("status %d %d\n", code, n)) end
    local e = summary.errors
    io.write(string.format("requests %d\nerrors connect %d read %d write %d status %d timeout %d\n",
        summary.requests, e.connect, e.read, e.write, e.status, e.timeout))
    io.write(string.format("latency p50 %.1f p99 %.1f max %.1f ms\n", latency:percentile(50) / 1000,
        latency:percentile(99) / 1000, latency.max / 1000))
end
