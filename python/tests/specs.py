"""Specs several test files use."""


def coulomb_spec(x0=4.5, m=1.0, k=1.0, phi0=1.0, solver=None, output=None):
    """A mass on a linear spring with Coulomb friction, released from rest at x0; every step a sample unless
    `output` says otherwise (the daemon's own default is a budget of 10 001 samples)."""
    spec = {"model": {"mass": m, "spring": {"law": "linear", "k": k}, "damper": {"law": "coulomb", "phi0": phi0}},
            "initial": {"x": x0, "v": 0},
            "solver": solver or {"kind": "stick-slip", "dt": 1e-3, "t_end": 10, "theta": 0.5}}
    spec["output"] = output or {"every": 1}
    return spec


# The three-mass chain of docs/networks.md: friction on node 0, a spring to node 1, a dashpot to node 2,
# which a harmonic load shakes. Nodes 0 and 2 and element 0 are written.
CHAIN = {"model": {"masses": [1, 2, 1.5],
                   "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1},
                                 "damper": {"law": "coulomb", "phi0": 0.3, "belt_velocity": 0}},
                                {"between": [0, 1], "spring": {"law": "linear", "k": 2}},
                                {"between": [1, 2], "damper": {"law": "linear", "c": 0.1}}],
                   "forcing": [{"node": 2, "kind": "harmonic", "amplitude": 1, "omega": 2, "phase": 0}]},
         "initial": {"x": [1, -0.5, 2], "v": [0, 0.3, 0]},
         "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 20, "theta": 0.5},
         "output": {"every": 100, "nodes": [0, 2], "elements": [0]}}

# A run that diverges after its first block of 512 records: gamma = 50 v feeds energy in, x grows like
# e^(25 t), and the daemon ends the 200 stream with an error line at t = 10.24 (docs/http.md).
DIVERGING = {"model": {"mass": 1, "spring": {"law": "linear", "k": 1},
                       "damper": {"law": "linear", "c": 0, "relaxation": {"kind": "linear", "L": 50}}},
             "initial": {"x": 1}, "solver": {"dt": 0.01, "t_end": 100, "theta": 1}}
