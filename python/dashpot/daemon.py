"""Starting and stopping a private dashpotd for a Client that was given no URL.

A researcher on a laptop should not have to start a server by hand: ``Client()`` runs the daemon of the
build on a free loopback port and stops it when the client is closed, garbage-collected, or the interpreter
exits. Which binary (first found wins):

1. the environment variable ``DASHPOT_DAEMON``;
2. ``<repository>/build/dashpotd`` when this package is imported from the source tree (``python/dashpot``);
3. ``dashpotd`` on ``PATH`` (``make install`` puts it in ``PREFIX/bin``).

The daemon writes its start-up line (``... listening on http://127.0.0.1:PORT ...``) and then one log line
per request to stderr. A thread reads stderr for the daemon's whole life: it finds the port, keeps the last
lines for error messages, and above all keeps the pipe drained (a full pipe would block the daemon's next
log write, and with it the request being answered).
"""

import collections
import os
import re
import shutil
import signal
import subprocess
import threading
import weakref
from pathlib import Path

from .errors import DaemonError

_LISTENING = re.compile(r"listening on (http://\S+)")


def find_daemon():
    """The path of the dashpotd binary to start (see the module's docstring), or raises DaemonError."""
    env = os.environ.get("DASHPOT_DAEMON")
    if env:
        if os.path.isfile(env) and os.access(env, os.X_OK):
            return env
        raise DaemonError("DASHPOT_DAEMON=%s is not an executable file" % env)
    # python/dashpot/daemon.py -> the repository is two directories above the package.
    in_tree = Path(__file__).resolve().parent.parent.parent / "build" / "dashpotd"
    if in_tree.is_file() and os.access(in_tree, os.X_OK):
        return str(in_tree)
    on_path = shutil.which("dashpotd")
    if on_path:
        return on_path
    raise DaemonError("dashpotd not found: set DASHPOT_DAEMON, build it (make) in the repository this package "
                      "comes from, or put it on PATH; or pass Client(url=...) for a daemon already running")


def _stop(proc, grace):
    """SIGTERM, then SIGKILL after `grace` seconds. Used by LocalDaemon.stop and its finalizer."""
    if proc.poll() is not None:
        return
    try:
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=grace)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait(timeout=grace)
    except ProcessLookupError:
        pass


class LocalDaemon:
    """One dashpotd child process on 127.0.0.1 and a free port.

    ``url`` is its base URL, ``pid`` its process id, ``log_tail()`` its last stderr lines. ``stop()`` sends
    SIGTERM (the daemon then finishes runs in flight and exits 0) and waits; it is idempotent and also runs
    when the object is collected or the interpreter exits.
    """

    def __init__(self, binary=None, args=(), start_timeout=10.0, stop_timeout=15.0):
        self.binary = binary or find_daemon()
        self.stop_timeout = stop_timeout
        self._lines = collections.deque(maxlen=200)
        self._ready = threading.Event()
        self.url = None
        # The binary's directory as working directory: dashpotd looks for api/openapi.yaml and web/ there and
        # beside it, so a stray api/ or web/ in the caller's directory is never served instead.
        command = [self.binary, "--port", "0", "--bind", "127.0.0.1"] + [str(a) for a in args]
        try:
            self.proc = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                         stderr=subprocess.PIPE, cwd=os.path.dirname(os.path.abspath(self.binary)),
                                         start_new_session=True)
        except OSError as e:
            raise DaemonError("cannot start %s: %s" % (self.binary, e)) from e
        self.pid = self.proc.pid
        self._finalizer = weakref.finalize(self, _stop, self.proc, stop_timeout)
        self._reader = threading.Thread(target=self._read_stderr, name="dashpotd-stderr-%d" % self.pid, daemon=True)
        self._reader.start()
        if not self._ready.wait(start_timeout) or self.url is None:
            self.stop()
            raise DaemonError("%s did not start within %g s; its log:\n%s"
                              % (self.binary, start_timeout, self.log_tail()))

    def _read_stderr(self):
        for raw in self.proc.stderr:
            line = raw.decode("utf-8", "replace").rstrip("\n")
            self._lines.append(line)
            if self.url is None:
                m = _LISTENING.search(line)
                if m:
                    self.url = m.group(1)
                    self._ready.set()
        self._ready.set()  # EOF: the daemon exited; wake a start-up still waiting for its line.

    def log_tail(self, n=20):
        """The daemon's last `n` stderr lines, as one string."""
        return "\n".join(list(self._lines)[-n:])

    @property
    def running(self):
        return self.proc.poll() is None

    def stop(self):
        """Stops the daemon (SIGTERM, SIGKILL after stop_timeout s) and returns its exit status."""
        self._finalizer()
        self._reader.join(timeout=5)
        if self.proc.stderr is not None and not self._reader.is_alive():
            self.proc.stderr.close()
        return self.proc.returncode
