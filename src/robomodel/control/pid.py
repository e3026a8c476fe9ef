"""control_toolbox's PID: the classic one (ROS 1 / Humble) and the Kilted/master one.

Classic (control_toolbox noetic-devel and humble ``Pid::computeCommand``): the derivative is
taken on the *error* (first call after a reset differentiates against 0, the "derivative
kick"); the integral is clamped to ``[i_min, i_max]`` — which are ``[0, 0]`` unless
``i_clamp`` is given, so ``pid: {p, i, d}`` acts as a PD controller (a documented gotcha).
"""

from __future__ import annotations

import enum
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from robomodel.control.exceptions import ConfigError

__all__ = ["AntiWindup", "Gains", "Pid", "PidBoundsError", "PidKilted", "check_bounds"]


class PidBoundsError(ConfigError, ValueError):
    """Bounds with min > max, which control_toolbox's Pid refuses (``std::invalid_argument``)."""


def check_bounds(kind: str, low: float, high: float) -> None:
    """Raise :class:`PidBoundsError` when ``low > high`` (``kind`` is ``i`` or ``u``).

    Matches control_toolbox: ``Pid(...)`` throws ``invalid_argument("received i_min >
    i_max")`` (Humble and master) and ``"received u_min > u_max"`` (master).
    """
    if low > high:
        raise PidBoundsError(
            f"received {kind}_min > {kind}_max ({kind}_min={low:g}, {kind}_max={high:g}); "
            f"control_toolbox's Pid needs {kind}_min <= {kind}_max"
        )


@dataclass(frozen=True, slots=True)
class Gains:
    """PID gains and integral clamp (control_toolbox ``Pid::Gains``)."""

    p: float = 0.0
    i: float = 0.0
    d: float = 0.0
    i_max: float = 0.0
    i_min: float = 0.0
    antiwindup: bool = False

    @classmethod
    def from_params(cls, params: Mapping[str, Any], prefix: str = "") -> Gains:
        """From ``p, i, d, i_clamp, i_clamp_min, i_clamp_max, antiwindup`` (ROS 1 ``Pid::init``).

        ``i_clamp`` sets ``i_max = |i_clamp|, i_min = -|i_clamp|``; the explicit min/max win.
        """

        def get(name: str, default: float) -> float:
            value = params.get(prefix + name, default)
            try:
                return float(value)
            except (TypeError, ValueError):
                raise ConfigError(
                    f"PID gain '{prefix}{name}' must be a number, got {value!r}"
                ) from None

        if prefix + "p" not in params:
            raise ConfigError(f"PID gain '{prefix}p' is required (control_toolbox Pid::init)")
        clamp = abs(get("i_clamp", 0.0))
        return cls(
            p=get("p", 0.0),
            i=get("i", 0.0),
            d=get("d", 0.0),
            i_max=get("i_clamp_max", clamp),
            i_min=get("i_clamp_min", -clamp),
            antiwindup=bool(params.get(prefix + "antiwindup", False)),
        )


class Pid:
    """The classic control_toolbox PID (see the module docstring)."""

    __slots__ = ("_i_hi", "_i_lo", "d_error", "error_last", "gains", "i_error", "p_error")

    def __init__(self, gains: Gains) -> None:
        check_bounds("i", gains.i_min, gains.i_max)
        self.gains = gains
        self._set_bounds()
        self.reset()

    def _set_bounds(self) -> None:
        g = self.gains
        if g.antiwindup and g.i != 0.0:
            a, b = g.i_min / g.i, g.i_max / g.i
            self._i_lo, self._i_hi = min(a, b), max(a, b)
        else:
            self._i_lo, self._i_hi = g.i_min, g.i_max

    def set_gains(self, gains: Gains) -> bool:
        """Use ``gains`` from the next update on; the integral is kept.

        As Humble's ``Pid::setGains``, gains with ``i_min > i_max`` are not taken: the old
        gains stay and a warning says why. Returns whether the gains were taken.
        """
        if gains.i_min > gains.i_max:
            warnings.warn(
                f"received i_min > i_max (i_min={gains.i_min:g}, i_max={gains.i_max:g}), "
                "skip new gains",
                RuntimeWarning,
                stacklevel=2,
            )
            return False
        self.gains = gains
        self._set_bounds()
        return True

    def reset(self) -> None:
        """Zero the integral and the last error (the next derivative kicks, as upstream)."""
        self.p_error = 0.0
        self.i_error = 0.0
        self.d_error = 0.0
        self.error_last = 0.0

    def compute(self, error: float, dt_s: float) -> float:
        """Command for ``error`` with the derivative by finite difference of the error.

        The same arithmetic as :meth:`compute_with_rate` with ``error_dot`` by finite
        difference, written out: this runs per joint per control cycle.
        """
        if dt_s == 0.0 or not math.isfinite(error):
            return 0.0
        error_dot = (error - self.error_last) / dt_s
        self.error_last = error
        if not math.isfinite(error_dot):
            return 0.0
        g = self.gains
        self.p_error = error
        self.d_error = error_dot
        i_err = self.i_error + dt_s * error
        gi = g.i
        if g.antiwindup and gi != 0.0:
            i_err = min(max(i_err, self._i_lo), self._i_hi)
            i_term = gi * i_err
        else:
            i_term = gi * i_err
            if i_term < g.i_min:  # min(max(i_term, i_min), i_max), as compute_with_rate
                i_term = g.i_min
            if i_term > g.i_max:
                i_term = g.i_max
        self.i_error = i_err
        return g.p * error + i_term + g.d * error_dot

    def compute_with_rate(self, error: float, error_dot: float, dt_s: float) -> float:
        """Command for ``error`` and a known error rate (e.g. a velocity error)."""
        if dt_s == 0.0 or not (math.isfinite(error) and math.isfinite(error_dot)):
            return 0.0
        g = self.gains
        self.p_error = error
        self.d_error = error_dot
        i_err = self.i_error + dt_s * error
        if g.antiwindup and g.i != 0.0:
            i_err = min(max(i_err, self._i_lo), self._i_hi)
            i_term = g.i * i_err
        else:
            i_term = min(max(g.i * i_err, g.i_min), g.i_max)
        self.i_error = i_err
        return g.p * error + i_term + g.d * error_dot


class AntiWindup(enum.Enum):
    """Kilted/master ``antiwindup_strategy``."""

    NONE = "none"
    BACK_CALCULATION = "back_calculation"
    CONDITIONAL_INTEGRATION = "conditional_integration"


class PidKilted:
    """control_toolbox master's ``compute_command`` (output clamp and anti-windup strategies)."""

    def __init__(
        self,
        p: float,
        i: float = 0.0,
        d: float = 0.0,
        *,
        u_clamp_min: float = -math.inf,
        u_clamp_max: float = math.inf,
        i_clamp_min: float = -math.inf,
        i_clamp_max: float = math.inf,
        antiwindup: AntiWindup = AntiWindup.NONE,
        tracking_time_constant: float = 0.0,
        error_deadband: float = 2.220446049250313e-16,
    ) -> None:
        check_bounds("i", i_clamp_min, i_clamp_max)
        check_bounds("u", u_clamp_min, u_clamp_max)
        self.p, self.i, self.d = p, i, d
        self.u_min, self.u_max = u_clamp_min, u_clamp_max
        self.i_min, self.i_max = i_clamp_min, i_clamp_max
        self.antiwindup = antiwindup
        if tracking_time_constant == 0.0 and i != 0.0:
            tracking_time_constant = math.sqrt(d / i) if d != 0.0 else p / i
        self.tracking_time_constant = tracking_time_constant
        self.error_deadband = error_deadband
        self.reset()

    def reset(self) -> None:
        self.i_term = 0.0
        self.error_last = 0.0
        self.cmd = 0.0

    def compute(self, error: float, dt_s: float) -> float:
        if dt_s == 0.0:
            return self.cmd
        if dt_s < 0.0:
            raise ValueError("PID: dt must be non-negative")
        if not math.isfinite(error):
            return math.nan
        error_dot = (error - self.error_last) / dt_s
        self.error_last = error
        unsat = self.p * error + self.i_term + self.d * error_dot
        cmd = min(max(unsat, self.u_min), self.u_max)
        if abs(error) > self.error_deadband:
            if self.antiwindup is AntiWindup.BACK_CALCULATION and self.i != 0.0:
                self.i_term += dt_s * (self.i * error + (cmd - unsat) / self.tracking_time_constant)
            elif self.antiwindup is AntiWindup.CONDITIONAL_INTEGRATION:
                if not (cmd != unsat and error * unsat > 0):
                    self.i_term += dt_s * self.i * error
            else:
                self.i_term += dt_s * self.i * error
        self.i_term = min(max(self.i_term, self.i_min), self.i_max)
        self.cmd = cmd
        return cmd
