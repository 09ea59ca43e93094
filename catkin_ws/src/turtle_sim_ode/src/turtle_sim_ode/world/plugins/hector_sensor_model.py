"""hector_gazebo_plugins' sensor error model (include/hector_gazebo_plugins/sensor_model.h, SensorModel_), shared by its
IMU and GPS plugins: an offset, a first-order Gauss-Markov drift with its frequency, white gaussian noise and a scale
error, read from the plugin's tags with a prefix (SensorModel_::Load)."""
from __future__ import annotations

import math
import random
from dataclasses import dataclass, replace
from typing import Dict, Mapping, Optional, Tuple

from turtle_sim_ode.models.text import ModelError, read_number
from turtle_sim_ode.models.description import GazeboPlugin

Vec3 = Tuple[float, float, float]


@dataclass(frozen=True)
class ErrorModel:
    """SensorModel_'s parameters of one quantity (3 axes; yaw uses the first)."""

    offset: Vec3 = (0.0, 0.0, 0.0)
    drift: Vec3 = (0.0, 0.0, 0.0)
    drift_frequency: Vec3 = (1.0 / 3600.0,) * 3  # SensorModel_(): a time constant of one hour
    gaussian_noise: Vec3 = (0.0, 0.0, 0.0)
    scale_error: Vec3 = (1.0, 1.0, 1.0)


def vector_tag(plugin: GazeboPlugin, tag: str, default: Vec3, minimum: float = -math.inf) -> Vec3:
    given = plugin.params.get(tag)
    if given is None or not given.strip():
        return default
    parts = given.split()
    if len(parts) == 1:  # a yaw model's scalar
        parts = parts * 3
    if len(parts) != 3:
        raise ModelError(f"{plugin.filename} <{tag}> must be 1 or 3 numbers, got '{given}'")
    return tuple(read_number(part, f"{plugin.filename} <{tag}>", minimum=minimum) for part in parts)  # type: ignore


def error_model(plugin: GazeboPlugin, prefix: str) -> ErrorModel:
    """SensorModel_::Load: <prefixOffset>, Drift, DriftFrequency, GaussianNoise, ScaleError; without a prefix
    <offset>, <drift>, <driftFrequency>, <gaussianNoise>, <scaleError>."""
    base = ErrorModel()

    def tag(name: str) -> str:
        return prefix + name if prefix else name[0].lower() + name[1:]

    return ErrorModel(
        offset=vector_tag(plugin, tag("Offset"), base.offset),
        drift=vector_tag(plugin, tag("Drift"), base.drift, 0.0),
        drift_frequency=vector_tag(plugin, tag("DriftFrequency"), base.drift_frequency, 0.0),
        gaussian_noise=vector_tag(plugin, tag("GaussianNoise"), base.gaussian_noise, 0.0),
        scale_error=vector_tag(plugin, tag("ScaleError"), base.scale_error),
    )


class SensorError:
    """SensorModel_ of one quantity: ``apply(value, dt)`` = value * scale + offset + drift + white noise, the drift
    a first-order Gauss-Markov process (exp(-dt f) drift + dt N(0, sqrt(2 f) drift_stddev))."""

    def __init__(self, model: ErrorModel, rng: random.Random) -> None:
        self.model = model
        self._rng = rng
        self.current_drift: Vec3 = (0.0, 0.0, 0.0)
        self.reset()

    def reset(self, drift: Optional[Vec3] = None) -> None:
        """reset(): a drift drawn from N(0, drift); reset(value): that drift (the calibrate and set-bias services)."""
        if drift is None:
            drift = tuple(self._rng.gauss(0.0, sigma) if sigma else 0.0 for sigma in self.model.drift)  # type: ignore
        self.current_drift = drift

    @property
    def bias(self) -> Vec3:
        """getCurrentBias: drift + offset."""
        return tuple(d + o for d, o in zip(self.current_drift, self.model.offset))  # type: ignore[return-value]

    def apply(self, value: Vec3, dt: float) -> Vec3:
        m, gauss = self.model, self._rng.gauss
        drift = []
        result = []
        for axis in range(3):
            frequency, sigma, noise = m.drift_frequency[axis], m.drift[axis], m.gaussian_noise[axis]
            walk = gauss(0.0, math.sqrt(2 * frequency) * sigma) if sigma and frequency else 0.0
            current = math.exp(-dt * frequency) * self.current_drift[axis] + dt * walk
            drift.append(current)
            error = m.offset[axis] + current + (gauss(0.0, noise) if noise else 0.0)
            result.append(value[axis] * m.scale_error[axis] + error)
        self.current_drift = tuple(drift)  # type: ignore[assignment]
        return tuple(result)  # type: ignore[return-value]


# SensorModel.cfg's fields (hector_gazebo_plugins/cfg/SensorModel.cfg), every one at reconfiguration level 1.
RECONFIGURE_FIELDS = ("gaussian_noise", "offset", "drift", "drift_frequency", "scale_error")
RECONFIGURE_LEVEL = 1


def reconfigure(error: SensorError, values: Mapping[str, float], level: int, scalar: bool = False) -> Dict[str, float]:
    """SensorModel_::dynamicReconfigureCallback. At level 1 (a client changed something) each field of ``values``
    becomes the model's value on every axis; at any other level (the server's first call, level ~0) the model stays
    and its values are reported: the mean of the three axes (helpers::scalar_value), or the first for a ``scalar``
    model (yaw). Returns the values the server publishes. A non-finite value is refused (a ValueError naming it),
    the model unchanged."""
    if level == RECONFIGURE_LEVEL:
        bad = [name for name in RECONFIGURE_FIELDS if not math.isfinite(values[name])]
        if bad:
            raise ValueError(f"{bad[0]} must be finite, got {values[bad[0]]}")
        fields = {name: (float(values[name]),) * 3 for name in RECONFIGURE_FIELDS}
        error.model = replace(error.model, **fields)  # type: ignore[arg-type]
    return current_values(error.model, scalar)


def current_values(model: ErrorModel, scalar: bool = False) -> Dict[str, float]:
    """The model's SensorModel.cfg values: each field's mean over the axes, or its first axis for a scalar model."""
    found = {}
    for name in RECONFIGURE_FIELDS:
        axes = getattr(model, name)
        mean = sum(a / 3.0 for a in axes)  # each third first, and held within the axes: no overflow to inf
        found[name] = axes[0] if scalar else min(max(mean, min(axes)), max(axes))
    return found
