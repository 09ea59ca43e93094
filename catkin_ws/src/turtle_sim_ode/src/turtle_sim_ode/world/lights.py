"""Gazebo's light services without ROS: the world's lights by name, read, changed and deleted as gazebo_ros's
get_light_properties, set_light_properties and delete_light do (gazebo_ros_api_plugin.cpp)."""
from __future__ import annotations

from dataclasses import replace
from typing import Dict, List, Optional, Sequence

from turtle_sim_ode.models.lights import Light, Vec3, first_sun, sun_direction
from turtle_sim_ode.models.urdf import MAX_LENGTH
from turtle_sim_ode.world.values import WorldError, finite, orientation, vec3, vector


class LightControl:
    """The lights of the loaded world (mixed into Simulation)."""

    lights: Dict[str, Light]
    # Whether the loaded world had a directional light: once the services have taken the last one away, the cameras
    # see by ambient light alone (a world that never had one keeps Gazebo's default sun).
    had_sun: bool = False

    @property
    def light_direction(self) -> Optional[Vec3]:
        """What the cameras shade with: the first directional light's direction; (0, 0, 0) when the world's were
        deleted or turned to no direction; None when it never had one (the cameras' default sun)."""
        direction = sun_direction(self.lights.values())
        if direction is None and self.had_sun:
            return (0.0, 0.0, 0.0)
        return direction

    @property
    def camera_lights(self) -> List[Light]:
        """The lights the cameras add per pixel (sensors.lighting): every one but the directional light they shade
        with (light_direction's)."""
        sun = first_sun(self.lights.values())
        return [light for light in self.lights.values() if light is not sun]

    def _light(self, name: str) -> Light:
        light = self.lights.get(name)
        if light is None:
            known = ", ".join("'%s'" % known for known in self.lights) or "none"
            raise WorldError(f"light '{name}' does not exist (the world's lights: {known})")
        return light

    def light_properties(self, name: str) -> Light:
        return self._light(name)

    def set_light_properties(
        self,
        name: str,
        cast_shadows: bool,
        diffuse: Sequence[float],
        specular: Sequence[float],
        attenuation: Sequence[float],
        direction: Sequence[float],
        position: Sequence[float],
        quaternion: Sequence[float],
    ) -> None:
        """Every field at once, as gazebo_ros's setLightProperties sends the whole light message: colours (r, g, b,
        a), attenuation (constant, linear, quadratic), direction, world pose (a quaternion that is not unit
        length is normalised, all zeros are no rotation, as ignition's Quaternion::Normalize). Type and range stay."""
        light = self._light(name)
        constant, linear, quadratic = vector(attenuation, 3, "attenuation (constant, linear, quadratic)")
        self.lights[name] = replace(
            light,
            cast_shadows=bool(cast_shadows),
            diffuse=vector(diffuse, 4, "diffuse"),  # type: ignore[arg-type]
            specular=vector(specular, 4, "specular"),  # type: ignore[arg-type]
            attenuation_constant=finite(constant, "attenuation_constant"),
            attenuation_linear=finite(linear, "attenuation_linear"),
            attenuation_quadratic=finite(quadratic, "attenuation_quadratic"),
            direction=vec3(direction, "direction"),
            pose=(vec3(position, "position", MAX_LENGTH), _xyzw(orientation(quaternion, "orientation"))),
        )

    def delete_light(self, name: str) -> None:
        self._light(name)
        del self.lights[name]


def _xyzw(quaternion):  # type: ignore[no-untyped-def]
    w, x, y, z = quaternion
    return (x, y, z, w)
