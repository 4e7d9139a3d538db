"""dashpot: a Python client for dashpotd, the HTTP service that simulates mechanical oscillators with
implicit constitutive laws (Coulomb friction, Bingham dashpots, ropes, networks of masses, contacts and
impacts, linear complementarity systems, Painlevé's rod).

    import dashpot
    with dashpot.Client() as c:                      # starts the build's dashpotd on a free loopback port
        r = c.simulate({"model": {"mass": 1, "spring": {"law": "linear", "k": 1},
                                  "damper": {"law": "coulomb", "phi0": 1}},
                        "initial": {"x": 4.5}, "solver": {"dt": 1e-3, "t_end": 10, "theta": 0.5}})
        r.t, r.x, r.v, r.events, r.summary["final"]

The client is this package's reason to exist; the numbers all come from the daemon. See python/README.md.
"""

__version__ = "0.1.0"

from .errors import DaemonError, DashpotError, FieldError, ProblemError, StreamError  # noqa: E402
from .result import Result  # noqa: E402
from .answers import Modes, Response, Stability, StabilityMap  # noqa: E402
from .daemon import LocalDaemon, find_daemon  # noqa: E402
from .client import Client, encode_spec  # noqa: E402
from .sweep import sweep  # noqa: E402
from .quakes import carlson_langer, gutenberg_richter  # noqa: E402

__all__ = ["Client", "Result", "ProblemError", "StreamError", "DaemonError", "DashpotError", "FieldError",
           "Stability", "StabilityMap", "Modes", "Response", "LocalDaemon", "find_daemon", "encode_spec", "sweep",
           "carlson_langer", "gutenberg_richter", "__version__"]
