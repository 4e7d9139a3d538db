"""tests/lib/manifests.py - reads what the deployment files say, for tests/test_manifests.sh and
tests/test_install.sh: the Kubernetes manifests (deploy/kubernetes/*.yaml), the container environment they
give dashpotd, the Dockerfile's stages and instructions, and the DASHPOT_* settings src/http/config.c reads.

Run as a script it prints one thing a shell test needs:
    manifests.py env                NUL-separated NAME=VALUE pairs: the dashpotd container's environment
    manifests.py user               "UID GID" the Deployment runs dashpotd as
    manifests.py probes             "PROBE PATH" per HTTP probe of the dashpotd container
    manifests.py healthcheck        the Dockerfile HEALTHCHECK command, as NUL-separated argv
    manifests.py job-script         the sweep Job's shell script
"""
import glob
import json
import math
import os
import re
import sys

try:
    import yaml
except ImportError:  # the python3 first on PATH (pyenv's, on some machines) may lack PyYAML; Debian's has it
    if sys.executable != "/usr/bin/python3" and os.path.exists("/usr/bin/python3"):  # (python3-yaml)
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    raise

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
KDIR = os.path.join(ROOT, "deploy", "kubernetes")


def load_manifests():
    """[(file name, document)] for every YAML document under deploy/kubernetes."""
    out = []
    for path in sorted(glob.glob(os.path.join(KDIR, "*.yaml"))):
        with open(path) as f:
            for doc in yaml.safe_load_all(f):
                if doc is not None:
                    out.append((os.path.basename(path), doc))
    return out


def by_kind(docs, kind):
    return [d for _, d in docs if d.get("kind") == kind]


def one(docs, kind):
    found = by_kind(docs, kind)
    if len(found) != 1:
        raise ValueError(f"expected one {kind}, found {len(found)}")
    return found[0]


def container(deploy, name="dashpotd"):
    for c in deploy["spec"]["template"]["spec"]["containers"]:
        if c["name"] == name:
            return c
    raise ValueError(f"no container {name}")


_SUFFIX = {"m": 1e-3, "": 1, "k": 1e3, "M": 1e6, "G": 1e9, "T": 1e12,
           "Ki": 2**10, "Mi": 2**20, "Gi": 2**30, "Ti": 2**40}


def quantity(q):
    """A Kubernetes resource quantity ("500m", "2", "256Mi") as a number."""
    m = re.fullmatch(r"([0-9.]+(?:e[0-9]+)?)(m|k|M|G|T|Ki|Mi|Gi|Ti)?", str(q))
    if not m:
        raise ValueError(f"not a quantity: {q!r}")
    return float(m.group(1)) * _SUFFIX[m.group(2) or ""]


def container_env(docs, deploy, cname="dashpotd"):
    """The environment Kubernetes gives the container: envFrom ConfigMaps first, then env (which wins).
    Resolves configMapKeyRef and resourceFieldRef (limits/requests, rounded up by the divisor, as the
    kubelet does); anything else (secrets, fieldRef) is an error rather than silently left out."""
    maps = {d["metadata"]["name"]: d.get("data", {}) for d in by_kind(docs, "ConfigMap")}
    c = container(deploy, cname)
    env = {}
    for src in c.get("envFrom", []):
        if set(src) != {"configMapRef"}:
            raise ValueError(f"unsupported envFrom {src}")
        env.update(maps[src["configMapRef"]["name"]])
    for e in c.get("env", []):
        if "value" in e:
            env[e["name"]] = e["value"]
            continue
        ref = e.get("valueFrom", {})
        if "configMapKeyRef" in ref:
            env[e["name"]] = maps[ref["configMapKeyRef"]["name"]][ref["configMapKeyRef"]["key"]]
        elif "resourceFieldRef" in ref:
            kind, res = ref["resourceFieldRef"]["resource"].split(".")
            value = quantity(c["resources"][kind][res])
            env[e["name"]] = str(math.ceil(value / quantity(ref["resourceFieldRef"].get("divisor", "1"))))
        else:
            raise ValueError(f"unsupported valueFrom {ref}")
    return env


def run_as(deploy, cname="dashpotd"):
    """(uid, gid) of the container: its securityContext over the pod's."""
    pod = deploy["spec"]["template"]["spec"].get("securityContext", {})
    ctr = container(deploy, cname).get("securityContext", {})
    return ctr.get("runAsUser", pod.get("runAsUser")), ctr.get("runAsGroup", pod.get("runAsGroup"))


def daemon_settings():
    """{variable: flag} for every option in src/http/config.c's table."""
    with open(os.path.join(ROOT, "src", "http", "config.c")) as f:
        text = f.read()
    return {env: flag for flag, env in re.findall(r'OPT\(\s*"([a-z-]+)",\s*"(DASHPOT_[A-Z_]+)"', text)}


def dockerfile(path=None):
    """The Dockerfile as stages: [{"from": image, "name": alias, "ins": [(KEYWORD, args)]}]; continuation
    lines joined, comments dropped."""
    with open(path or os.path.join(ROOT, "Dockerfile")) as f:
        lines = [l for l in f.read().split("\n") if not l.lstrip().startswith("#")]
    text = re.sub(r"\\\n", " ", "\n".join(lines))
    stages = []
    for line in text.split("\n"):
        if not line.strip():
            continue
        key, _, args = line.strip().partition(" ")
        key, args = key.upper(), args.strip()
        if key == "FROM":
            m = re.fullmatch(r"(\S+)(?:\s+AS\s+(\S+))?", args, re.I)
            stages.append({"from": m.group(1), "name": m.group(2), "ins": []})
        elif stages:
            stages[-1]["ins"].append((key, args))
    return stages


def instructions(stage, key):
    return [args for k, args in stage["ins"] if k == key]


def exec_form(args):
    """The argv of an exec-form instruction argument (a JSON array), after any --options."""
    return json.loads(args[args.index("["):])


def main():
    docs = load_manifests()
    what = sys.argv[1] if len(sys.argv) > 1 else ""
    if what == "env":
        env = container_env(docs, one(docs, "Deployment"))
        sys.stdout.write("".join(f"{k}={v}\0" for k, v in env.items()))
    elif what == "user":
        print(*run_as(one(docs, "Deployment")))
    elif what == "probes":
        for name, probe in container(one(docs, "Deployment")).items():
            if name.endswith("Probe") and "httpGet" in probe:
                print(name, probe["httpGet"]["path"])
    elif what == "healthcheck":
        (hc,) = instructions(dockerfile()[-1], "HEALTHCHECK")
        sys.stdout.write("".join(a + "\0" for a in exec_form(hc)))
    elif what == "job-script":
        job = one(docs, "Job")
        c = job["spec"]["template"]["spec"]["containers"][0]
        sys.stdout.write((c.get("command", []) + c.get("args", []))[-1])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
