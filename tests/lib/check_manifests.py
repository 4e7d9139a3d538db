"""tests/lib/check_manifests.py - the checks of tests/test_manifests.sh (which runs this from the repository's
top directory with $BUILD as the argument): the deployment files against each other, against the daemon and
against the binaries, without a container engine or a cluster. Prints "ok - ..." / "not ok - ..." per check
and "N passed, M failed"; exits 1 if any failed."""
import fnmatch, os, re, shlex, shutil, subprocess, sys, tempfile, traceback, urllib.parse
import manifests as m

BUILD = sys.argv[1] if len(sys.argv) > 1 else "build"
passed = failed = 0


def check(desc, fn):
    """Runs fn(); a falsy result or an exception is a failure, printed with its reason."""
    global passed, failed
    try:
        ok, why = fn(), ""
    except Exception as e:  # a missing key is as much a failure as a wrong value
        ok, why = False, f"{type(e).__name__}: {e}"
    if ok:
        passed += 1
        print(f"ok - {desc}")
    else:
        failed += 1
        print(f"not ok - {desc}" + (f"\n    {why}" if why else ""))


def run(cmd, timeout=60, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, **kw)


def subset(a, b, what="not found"):
    """set(a) <= set(b), printing what is not."""
    extra = sorted(set(a) - set(b))
    if extra:
        print(f"    {what}: {extra}")
    return not extra


def main():
    # ---- the manifests ----------------------------------------------------------------------------------------
    docs = []
    check("every deploy/kubernetes/*.yaml parses as YAML", lambda: docs.extend(m.load_manifests()) or docs)
    check("each document has apiVersion, kind and metadata.name",
          lambda: all(d.get("apiVersion") and d.get("kind") and d.get("metadata", {}).get("name") for _, d in docs
                      if d.get("kind") != "Kustomization"))
    kinds = sorted(d.get("kind") for _, d in docs)
    check(f"one each of ConfigMap, Deployment, Service, HPA, PDB, Job, Kustomization (found {kinds})",
          lambda: kinds == sorted(["ConfigMap", "Deployment", "Service", "HorizontalPodAutoscaler",
                                   "PodDisruptionBudget", "Job", "Kustomization"]))

    kust = m.one(docs, "Kustomization")
    check("kustomization.yaml lists every service manifest, and not the example Job",
          lambda: sorted(kust["resources"]) == sorted(f for f, d in docs if d["kind"] not in ("Kustomization", "Job")))

    dep = m.one(docs, "Deployment")
    pod = dep["spec"]["template"]["spec"]
    labels = dep["spec"]["template"]["metadata"]["labels"]
    ctr = m.container(dep)
    cm = m.one(docs, "ConfigMap")
    env = m.container_env(docs, dep)
    settings = m.daemon_settings()

    def matches(selector):
        return bool(selector) and all(labels.get(k) == v for k, v in selector.items())

    check("Deployment selector matches its pod labels", lambda: matches(dep["spec"]["selector"]["matchLabels"]))
    check("Deployment leaves replicas to the HPA", lambda: "replicas" not in dep["spec"])
    check("the image is the one kustomization.yaml sets",
          lambda: ctr["image"].split(":")[0] in [i["name"] for i in kust.get("images", [])])

    # Settings: every variable is one the daemon reads, every value one it accepts.
    check(f"src/http/config.c has DASHPOT_* settings ({len(settings)})", lambda: len(settings) >= 10)
    check("every ConfigMap key is a DASHPOT_* variable src/http/config.c reads",
          lambda: subset(cm["data"], settings))
    check("ConfigMap values are strings (Kubernetes rejects numbers in data)",
          lambda: all(isinstance(v, str) for v in cm["data"].values()))
    check("every variable the container gets is a daemon setting", lambda: subset(env, settings))
    check("the ConfigMap carries the limits: max-connections, max-steps, max-wall, timeout, body-limit",
          lambda: {"DASHPOT_MAX_CONNECTIONS", "DASHPOT_MAX_STEPS", "DASHPOT_MAX_WALL", "DASHPOT_TIMEOUT",
                   "DASHPOT_BODY_LIMIT"} <= set(cm["data"]))
    check("the Deployment takes the ConfigMap through envFrom",
          lambda: {"configMapRef": {"name": cm["metadata"]["name"]}} in ctr["envFrom"])
    daemon = os.path.join(BUILD, "dashpotd")
    # config_load reads the environment before the flags, so --version exits 0 only if every value is valid.
    check("dashpotd accepts every value (env -i <manifest env> dashpotd --version exits 0)",
          lambda: run(["env", "-i"] + [f"{k}={v}" for k, v in env.items()] + [daemon, "--version"],
                      timeout=10).returncode == 0)
    check("a bad value is caught the same way (DASHPOT_MAX_WALL=abc exits 2)",
          lambda: run(["env", "-i", "DASHPOT_MAX_WALL=abc", daemon, "--version"], timeout=10).returncode == 2)
    check("DASHPOT_BIND listens on every interface (the kubelet probes the pod IP)",
          lambda: env["DASHPOT_BIND"] in ("0.0.0.0", "::"))
    check("DASHPOT_THREADS follows the CPU limit (resourceFieldRef limits.cpu), resolved >= 1",
          lambda: any(e["name"] == "DASHPOT_THREADS" and e["valueFrom"]["resourceFieldRef"]["resource"] == "limits.cpu"
                      for e in ctr["env"]) and int(env["DASHPOT_THREADS"]) >= 1)
    check("service links are off (they would inject <SERVICE>_PORT=tcp://... variables)",
          lambda: pod.get("enableServiceLinks") is False)

    help_text = run([daemon, "--help"], timeout=10).stdout
    flags = re.findall(r"^\s+--([a-z-]+)\s+(\S*)", help_text, re.M)
    check("every flag in dashpotd --help has its DASHPOT_* variable (but --help, --version)",
          lambda: flags and all(v.startswith("DASHPOT_") for f, v in flags if f not in ("help", "version")))
    http_md = open("docs/http.md").read()
    check("docs/http.md's settings table names every flag and variable",
          lambda: subset([f"`--{f}` | `{v}`" for v, f in settings.items()], re.findall(r"`--[a-z-]+` \| `\w+`", http_md)))

    # Ports and probes.
    port = next(p for p in ctr["ports"] if p["name"] == "http")
    def resolve(p):
        return port["containerPort"] if p == port["name"] else p
    check("container port 'http' is DASHPOT_PORT", lambda: str(port["containerPort"]) == env["DASHPOT_PORT"])
    routes = open("src/http/routes.c").read()
    for probe, path in (("readinessProbe", "/readyz"), ("livenessProbe", "/healthz")):
        pr = ctr[probe]
        check(f"{probe}: GET {path} on the daemon's port, with a timeout",
              lambda: pr["httpGet"]["path"] == path and resolve(pr["httpGet"]["port"]) == port["containerPort"]
              and pr["timeoutSeconds"] >= 1)
        check(f"{path} is a route of src/http/routes.c (tests/test_install.sh probes it live)",
              lambda: f'"{path}"' in routes)
    check("liveness is more patient than readiness (a busy replica leaves rotation before it is killed)",
          lambda: ctr["livenessProbe"]["periodSeconds"] * ctr["livenessProbe"]["failureThreshold"]
          > ctr["readinessProbe"]["periodSeconds"] * ctr["readinessProbe"]["failureThreshold"])

    # Resources.
    res = ctr["resources"]
    check("requests and limits for cpu and memory, requests <= limits",
          lambda: all(m.quantity(res["requests"][r]) <= m.quantity(res["limits"][r]) for r in ("cpu", "memory")))

    # Hardening, for the daemon and for the Job's pods alike.
    def hardened(podspec, c):
        psc, csc = podspec.get("securityContext", {}), c.get("securityContext", {})
        uid = csc.get("runAsUser", psc.get("runAsUser"))
        return (psc.get("runAsNonRoot") is True and csc.get("runAsNonRoot", True) is True and isinstance(uid, int)
                and uid > 0 and csc.get("readOnlyRootFilesystem") is True
                and csc.get("allowPrivilegeEscalation") is False and csc.get("capabilities", {}).get("drop") == ["ALL"]
                and not csc.get("capabilities", {}).get("add") and not csc.get("privileged", False)
                and podspec.get("automountServiceAccountToken") is False)
    check("dashpotd pod: runAsNonRoot, uid > 0, read-only root, no privilege escalation, capabilities drop ALL, "
          "no service-account token", lambda: hardened(pod, ctr))

    # Shutdown timeline: preStop sleep, then SIGTERM, then the grace for runs in flight, then ABORT_WAIT for
    # their error lines (src/http/server.c) must end before the kubelet's SIGKILL.
    def shutdown_fits():
        pre = ctr["lifecycle"]["preStop"]["exec"]["command"]
        assert pre[0] == "sleep", pre
        abort = float(re.search(r"#define ABORT_WAIT ([0-9.]+)", open("src/http/server.c").read()).group(1))
        total = float(pre[1]) + float(env["DASHPOT_SHUTDOWN_GRACE"]) + abort
        return total < pod["terminationGracePeriodSeconds"] or print(f"    {total} s >= grace period")
    check("preStop + DASHPOT_SHUTDOWN_GRACE + ABORT_WAIT < terminationGracePeriodSeconds", shutdown_fits)

    # Service, HPA, PDB.
    svc = m.one(docs, "Service")
    check("Service selector matches the pod labels", lambda: matches(svc["spec"]["selector"]))
    check("Service targets the daemon's port",
          lambda: [resolve(p["targetPort"]) for p in svc["spec"]["ports"]] == [port["containerPort"]])
    hpa = m.one(docs, "HorizontalPodAutoscaler")
    check("HPA (autoscaling/v2) targets the Deployment",
          lambda: hpa["apiVersion"] == "autoscaling/v2"
          and hpa["spec"]["scaleTargetRef"] == {"apiVersion": "apps/v1", "kind": "Deployment",
                                                "name": dep["metadata"]["name"]})
    check("HPA keeps 2 <= minReplicas <= maxReplicas",
          lambda: 2 <= hpa["spec"]["minReplicas"] <= hpa["spec"]["maxReplicas"])
    check("HPA scales on CPU utilization, which the container's cpu request defines",
          lambda: any(x["type"] == "Resource" and x["resource"]["name"] == "cpu"
                      and x["resource"]["target"]["type"] == "Utilization" for x in hpa["spec"]["metrics"])
          and "cpu" in res["requests"])
    pdb = m.one(docs, "PodDisruptionBudget")
    check("PDB selects the dashpotd pods", lambda: matches(pdb["spec"]["selector"]["matchLabels"]))

    # The sweep Job.
    job = m.one(docs, "Job")
    jpod = job["spec"]["template"]["spec"]
    jctr = jpod["containers"][0]
    jenv = {e["name"]: e["value"] for e in jctr["env"]}
    check("Job is Indexed with completions x RUNS_PER_INDEX = 10^6 runs",
          lambda: job["spec"]["completionMode"] == "Indexed"
          and job["spec"]["completions"] * int(jenv["RUNS_PER_INDEX"]) == 10**6)
    check("Job runs in parallel, retries per index, restartPolicy Never",
          lambda: job["spec"]["parallelism"] > 1 and job["spec"]["backoffLimitPerIndex"] >= 1
          and jpod["restartPolicy"] == "Never")
    def job_url():
        u = urllib.parse.urlsplit(jenv["DASHPOT_URL"])
        return (u.hostname == svc["metadata"]["name"] and (u.port or 80) == svc["spec"]["ports"][0]["port"]
                and u.path == "/v1/simulate")
    check("Job calls the Service's name and port, POST /v1/simulate", job_url)
    check("Job pod is hardened the same way", lambda: hardened(jpod, jctr))
    check("Job has resource requests and limits, and a writable volume at WORK_DIR",
          lambda: jctr["resources"]["requests"] and jctr["resources"]["limits"]
          and any(v["mountPath"] == jenv["WORK_DIR"] for v in jctr["volumeMounts"]))
    check("Job script is valid POSIX sh (sh -n)",
          lambda: run(["sh", "-n"], input=(jctr.get("command", []) + jctr["args"])[-1], timeout=10).returncode == 0)

    # ---- the Dockerfile ---------------------------------------------------------------------------------------
    stages = m.dockerfile()
    build, final = stages[0], stages[-1]
    check("Dockerfile is multi-stage: build on debian:12, run on debian:12-slim",
          lambda: len(stages) >= 2 and build["from"] in ("debian:12", "debian:bookworm")
          and final["from"] in ("debian:12-slim", "debian:bookworm-slim"))
    (user,) = m.instructions(final, "USER") or [""]
    check(f"runtime USER is a numeric non-root uid:gid ({user})",
          lambda: re.fullmatch(r"[1-9][0-9]*:[1-9][0-9]*", user))
    check("runtime uid:gid is the Deployment's runAsUser:runAsGroup",
          lambda: user == "%s:%s" % m.run_as(dep))
    hc = m.instructions(final, "HEALTHCHECK")
    check("HEALTHCHECK on /healthz with a timeout, in the runtime stage",
          lambda: len(hc) == 1 and "/healthz" in hc[0] and "--timeout=" in hc[0] and "CMD" in hc[0])
    denv = dict(re.findall(r"(DASHPOT_[A-Z_]+)=(\S+)", " ".join(m.instructions(final, "ENV"))))
    check("image ENV: only daemon settings, the same as the Deployment's",
          lambda: set(denv) <= set(settings) and all(denv[k] == env[k] for k in denv))
    check("EXPOSE is DASHPOT_PORT", lambda: m.instructions(final, "EXPOSE") == [denv["DASHPOT_PORT"]])
    install = re.search(r"make install DESTDIR=(\S+) PREFIX=(\S+)", " ".join(m.instructions(build, "RUN")))
    stage_dir, prefix = install.group(1), install.group(2)
    check("DASHPOT_OPENAPI and DASHPOT_WEB_DIR are where make install puts them (PREFIX/share/dashpot)",
          lambda: denv["DASHPOT_OPENAPI"] == f"{prefix}/share/dashpot/openapi.yaml"
          and denv["DASHPOT_WEB_DIR"] == f"{prefix}/share/dashpot/web")
    check("ENTRYPOINT is the installed dashpotd",
          lambda: m.exec_form(m.instructions(final, "ENTRYPOINT")[0]) == [f"{prefix}/bin/dashpotd"])

    def apt_packages(stage):
        words = " ".join(m.instructions(stage, "RUN")).split()
        i = words.index("install")
        return [w for w in words[i + 1:words.index("&&", i)] if not w.startswith("-")]
    deps = re.search(r"^pkgs=\(([^)]*)\)", open("scripts/install-deps.sh").read(), re.M).group(1).split()
    check("build-stage packages are among scripts/install-deps.sh's", lambda: set(apt_packages(build)) <= set(deps))

    # Runtime packages: every package owning a library the binaries load directly must be installed, and nothing
    # outside what they load at all. libc6 and libgcc-s1 are in every Debian image; sanitizer runtimes only in
    # build-san.
    def owner(path):
        for p in (path, os.path.realpath(path), "/usr" + path if not path.startswith("/usr") else path):
            r = run(["dpkg", "-S", p], timeout=20)
            if r.returncode == 0:
                return r.stdout.split(":")[0]
        raise ValueError(f"no package owns {path}")
    def runtime_sets():
        direct, closure = set(), set()
        for b in (os.path.join(BUILD, "dashpotd"), os.path.join(BUILD, "dashpot")):
            paths = dict(re.findall(r"^\s*(\S+) => (/\S+)", run(["ldd", b]).stdout, re.M))
            needed = re.findall(r"\(NEEDED\).*\[(.*)\]", run(["readelf", "-d", b]).stdout)
            direct |= {owner(paths[n]) for n in needed}
            closure |= {owner(p) for p in paths.values()}
        base = re.compile(r"^(libc6|libgcc-s1|lib(asan|ubsan|lsan|tsan)\d+)$")
        return {p for p in direct if not base.match(p)}, closure
    direct, closure = runtime_sets()
    runtime = set(apt_packages(final))
    check(f"runtime packages {sorted(runtime)} cover every library the binaries load directly {sorted(direct)}",
          lambda: subset(direct, runtime, "missing"))
    check("and are all among the libraries the binaries load", lambda: subset(runtime, closure, "not loaded"))
    check("the runtime stage installs no compiler, -dev package or curl",
          lambda: not any(p.endswith("-dev") or p in ("build-essential", "gcc", "curl") for p in runtime))

    # ---- the build context and the build stage -------------------------------------------------------------------
    # .dockerignore as Docker reads it, for the patterns it uses: "*" and "!path" (a path is in when the last
    # matching pattern is an exception; a directory brings its contents).
    rules = [l.strip() for l in open(".dockerignore") if l.strip() and not l.startswith("#")]
    def in_context(path):
        keep = True
        for r in rules:
            neg = r.startswith("!")
            pat = r.lstrip("!").rstrip("/")
            parts = path.split("/")
            if any(fnmatch.fnmatchcase("/".join(parts[:i]), pat) for i in range(1, len(parts) + 1)):
                keep = neg
        return keep
    check(".dockerignore uses only '*' and '!path' patterns",
          lambda: rules[0] == "*" and all(r.startswith("!") and not set(r[1:]) & set("*?[") for r in rules[1:]))
    # Docker sends the working tree, not what git tracks.
    context = [f for f in (os.path.relpath(os.path.join(d, n)) for d, _, ns in os.walk(".") for n in ns)
               if in_context(f)]
    web = {"web/" + f for f in (os.listdir("web") if os.path.isdir("web") else []) if not f.startswith(".")}
    check("the context holds the Makefile, dashpot.pc.in, src/, include/, api/openapi.yaml, web/",
          lambda: subset({"Makefile", "dashpot.pc.in", "api/openapi.yaml"} | web, context, "left out")
          and any(f.startswith("src/") for f in context) and any(f.startswith("include/dashpot/") for f in context))
    check("and no build tree, .git, tests, docs or deploy files",
          lambda: not any(re.match(r"(build|build-san|\.git|tests|docs|deploy|bench)/", f) for f in context))

    # The build stage's RUN, in a copy of exactly that context, with its staging directory moved into scratch.
    with tempfile.TemporaryDirectory(prefix="dashpot-ctx.") as tmp:
        ctx, stage = os.path.join(tmp, "src"), os.path.join(tmp, "stage")
        for f in context:
            os.makedirs(os.path.dirname(os.path.join(ctx, f)), exist_ok=True)
            shutil.copy2(f, os.path.join(ctx, f))
        (cmd,) = [r for r in m.instructions(build, "RUN") if "make" in r]
        cmd = cmd.replace(stage_dir, stage)
        envb = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "BUILD")}
        r = None
        def build_stage():
            nonlocal r
            r = run(["bash", "-ec", cmd], cwd=ctx, env=envb, timeout=600)
            return r.returncode == 0
        check("the build stage's RUN succeeds in the .dockerignore'd context", build_stage)
        if r is not None and r.returncode != 0:
            print("    " + (r.stdout + r.stderr)[-2000:].replace("\n", "\n    "))
        for args in m.instructions(final, "COPY"):
            words = shlex.split(args)
            if words[0] == "--from=build":
                srcs = words[1:-1]
                check(f"COPY --from=build finds {' '.join(srcs)}",
                      lambda: all(os.path.exists(stage + s[len(stage_dir):]) for s in srcs))


try:
    main()
except Exception:  # a file too broken to get through: one failure, and still the closing line
    failed += 1
    print("not ok - the checks could not finish")
    traceback.print_exc(file=sys.stdout)
print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
