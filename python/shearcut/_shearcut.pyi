"""Type stubs of shearcut's native module. Units: SI (m, s, N, N·m, J)."""

from typing import Dict, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

Vec3 = Tuple[float, float, float]
Wrench6 = Tuple[float, float, float, float, float, float]

class Scenario:
    """A scenario (TOML path or built-in name) set up for a controller
    ("mpc", "press", "slice:XI", "force:N"; None: the scenario's own).
    Raises ValueError naming the key, value and what is allowed."""

    def __init__(self, scenario: str, controller: Optional[str] = None) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def controller(self) -> str: ...
    @property
    def period(self) -> float:
        """Servo period, s."""
    @property
    def target_depth(self) -> float:
        """Depth of the cut below the object's top, m."""
    @property
    def touch_height(self) -> float:
        """Knife origin's height when its edge first meets the object, m."""
    @property
    def blade_budget(self) -> float:
        """Tangential blade travel available, m."""
    @property
    def max_ticks(self) -> int:
        """Most ticks of a simulated run before it times out."""
    @property
    def start_position(self) -> Vec3:
        """Where the simulated plant starts the knife's origin, m."""

class Reading:
    """One servo tick's reading: what an arm with a wrist F/T sensor reports."""

    def __init__(
        self,
        time: float,
        position: Vec3,
        velocity: Vec3,
        wrench: Wrench6,
        status: str = "moving",
        violation: float = 0.0,
    ) -> None: ...
    @property
    def time(self) -> float:
        """Time of the reading, s."""
    @property
    def position(self) -> Vec3:
        """Knife frame origin (heel end of the edge), world frame, m."""
    @property
    def velocity(self) -> Vec3:
        """Knife velocity executed over the last tick, m/s."""
    @property
    def wrench(self) -> Wrench6:
        """F/T wrench (fx, fy, fz, tx, ty, tz), N and N·m, object on knife."""
    @property
    def status(self) -> str:
        """"moving", "velocity_limit", "acceleration_limit", "jerk_limit" or "not_finite"."""
    @property
    def violation(self) -> float:
        """The refused command's value of the broken limit (m/s, m/s², m/s³)."""

class Command:
    """A knife twist (vx, vy, vz), m/s; Command() is the arm at rest."""

    def __init__(self, velocity: Vec3 = (0.0, 0.0, 0.0)) -> None: ...
    @property
    def velocity(self) -> Vec3: ...

class Truth:
    """What only the simulated plant knows (for scoring, never for control)."""

    @property
    def force(self) -> Vec3:
        """Noise-free force on the knife at the sensor, N (fy > 0 pushes up)."""
    @property
    def torque(self) -> Vec3:
        """Noise-free torque about the sensor, N·m."""
    @property
    def crack_depth(self) -> float:
        """Crack front depth below the object's top, m."""
    @property
    def contact_length(self) -> float:
        """Edge length in contact with material, m."""
    @property
    def fractured_sections(self) -> int: ...
    @property
    def work(self) -> float:
        """Cumulative knife work on the object, J."""
    @property
    def deformation(self) -> float:
        """Largest surface deformation next to the blade, m."""

class Telemetry:
    """What the controller's last tick planned."""

    @property
    def slice_push_ratio(self) -> float:
        """Planned ξ = v_t / v_n."""
    @property
    def normal_speed(self) -> float:
        """Planned normal speed (down), m/s."""
    @property
    def tangential_speed(self) -> float:
        """Planned tangential speed (towards the tip), m/s."""
    @property
    def blade_travel(self) -> float:
        """Blade travel used so far, m."""
    @property
    def phase(self) -> str:
        """"cutting" or "done"."""
    @property
    def planned(self) -> bool: ...
    @property
    def fallbacks(self) -> int: ...
    @property
    def scale(self) -> Vec3:
        """Believed scale factors (toughness, stiffness, friction)."""

class Plant:
    """The simulated plant: arm (limits checked), F/T sensor and object."""

    def __init__(self, scenario: Scenario) -> None: ...
    def step(self, command: Command) -> Tuple[Reading, Truth]:
        """Executes command for one period; raises RuntimeError if the model fails."""
    def reset(self) -> None: ...

class Controller:
    """The scenario's knife controller, as `shearcut run` builds it."""

    def __init__(self, scenario: Scenario) -> None: ...
    def tick(self, reading: Reading) -> Command:
        """One servo tick: reading in, command for the next tick out."""
    def telemetry(self) -> Telemetry: ...
    @property
    def name(self) -> str: ...
    def reset(self) -> None: ...

def run(
    scenario: Union[Scenario, str], controller: Optional[str] = None
) -> Tuple[Dict[str, npt.NDArray[np.float64]], Dict[str, Union[str, int, float, bool]]]:
    """The Rust closed loop (`shearcut run ... --transport inproc`):
    (series of NumPy arrays, summary dict)."""
