"""shearcut from Python: the knife controller (MPC and baselines) and the
simulated plant of a cut, stepped tick by tick from your own loop, and
``run``, the whole closed loop in Rust.

Units are SI (m, s, N, N·m, J). World frame: origin on the cutting board,
y up; the knife moves in its own plane (y, z), +z along the edge from the
heel towards the tip. A loop that follows shearcut's lockstep (first
command ``Command()``, the arm at rest; then reading -> ``tick`` ->
command -> ``step``) reproduces ``shearcut run ... --transport inproc``
bit for bit. Guide: docs/embedding.md.
"""

from ._shearcut import (
    Command,
    Controller,
    Plant,
    Reading,
    Scenario,
    Telemetry,
    Truth,
    __version__,
    run,
)

__all__ = [
    "Command",
    "Controller",
    "Plant",
    "Reading",
    "Scenario",
    "Telemetry",
    "Truth",
    "__version__",
    "run",
]
