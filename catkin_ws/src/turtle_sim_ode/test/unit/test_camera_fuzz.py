"""Property-based tests of the cameras (issue #15): generated camera blocks, careless and hostile, on a model spawned
among generated shapes. Whatever the input: the spawn is a clean refusal or a success; a camera that spawned
renders in C and with numpy alike, every depth is NaN or within the clip range, camera_info serialises, and the
world steps on. CI runs a bounded number of examples with a fixed seed; scripts/fuzz_sim.sh runs many more."""
from __future__ import annotations

from io import BytesIO
from typing import Callable

import numpy as np
from hypothesis import event, given, seed
from hypothesis import strategies as st
from test_fuzz import CLEAN_REFUSALS, FUZZ, SEED, hostile, normal_floats, number_text, rarely, signed_text

from turtle_sim_ode.ros.camera_topics import templates
from turtle_sim_ode.sensors.camera import CameraSensor
from turtle_sim_ode.world.simulation import Simulation

NUMPY_PIXELS = 4096  # the numpy rays are compared on images up to this size (they are 50 times slower)
AGREEING_PIXELS = 0.99  # rays through a shape's very edge may go either way in C and numpy (last-bit rounding)

sides = rarely(
    st.integers(min_value=1, max_value=48).map(str), st.sampled_from(["0", "-3", "2048", "8192", "7.5", "x"])
)
fovs = rarely(st.floats(min_value=0.05, max_value=3.1).map(repr), hostile)


@st.composite
def camera_models(draw: Callable) -> str:
    kind, plugin = draw(
        st.sampled_from(
            [
                ("camera", "libgazebo_ros_camera.so"),
                ("depth", "libgazebo_ros_openni_kinect.so"),
                ("depth", "libgazebo_ros_depth_camera.so"),
            ]
        )
    )
    pose = " ".join(draw(signed_text) for _ in range(6))
    noise = f"<noise><type>gaussian</type><mean>0</mean><stddev>{draw(number_text)}</stddev></noise>"
    return f"""<robot name="cam"><link name="base"><inertial><mass value="1"/>
<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
<gazebo reference="base"><sensor type="{kind}" name="cam"><update_rate>{draw(number_text)}</update_rate>
<pose>{pose}</pose><camera><horizontal_fov>{draw(fovs)}</horizontal_fov>
<image><width>{draw(sides)}</width><height>{draw(sides)}</height>
<format>{draw(st.sampled_from(["R8G8B8", "B8G8R8", "L8", "BAYER_RGGB8", "", "junk"]))}</format></image>
<clip><near>{draw(number_text)}</near><far>{draw(rarely(st.floats(0.5, 50).map(repr), hostile))}</far></clip>
{noise if draw(st.booleans()) else ""}</camera>
<plugin name="c" filename="{plugin}"><cameraName>cam</cameraName><hackBaseline>{draw(signed_text)}</hackBaseline>
<pointCloudCutoff>{draw(number_text)}</pointCloudCutoff><focalLength>{draw(number_text)}</focalLength></plugin>
</sensor></gazebo></robot>"""


@st.composite
def shapes(draw: Callable) -> str:
    """An SDF model of a few static shapes about the camera, each visual maybe off its collision, in a colour."""
    links = []
    for index in range(draw(st.integers(min_value=1, max_value=4))):
        geometry = draw(
            st.sampled_from(
                [
                    "<box><size>0.4 0.3 0.5</size></box>",
                    "<sphere><radius>0.25</radius></sphere>",
                    "<cylinder><radius>0.2</radius><length>0.6</length></cylinder>",
                ]
            )
        )
        where = " ".join(repr(draw(normal_floats(-2.0, 2.0))) for _ in range(3))
        turn = " ".join(repr(draw(normal_floats(-3.0, 3.0))) for _ in range(3))
        offset = repr(draw(normal_floats(-0.3, 0.3)))
        colour = draw(st.sampled_from(["Gazebo/Red", "Gazebo/Blue", "Gazebo/Wood"]))
        links.append(
            f'<link name="s{index}"><pose>{where} {turn}</pose><collision name="c"><geometry>{geometry}</geometry>'
            f'</collision><visual name="v"><pose>{offset} 0 0 0 0 0</pose><geometry>{geometry}</geometry>'
            f"<material><script><name>{colour}</name></script></material></visual></link>"
        )
    return f'<sdf version="1.6"><model name="shapes"><static>true</static>{"".join(links)}</model></sdf>'


@FUZZ
@seed(int(SEED or 0))
@given(camera=camera_models(), scene=shapes())
def test_generated_cameras_are_refused_cleanly_or_render_sane_pictures(camera: str, scene: str) -> None:
    sim = Simulation()
    sim.spawn_sdf("shapes", scene)
    try:
        sim.spawn_urdf("cam", camera, (0.0, 0.0, 0.5, 0.0, 0.0, 0.0))
    except CLEAN_REFUSALS:
        event("refused")
        return
    event("rendered")
    config = sim.plugins["cam"].cameras[0]
    fast = CameraSensor(sim.physics, sim.models["cam"], config)
    frame = fast.render(sim.scene)
    assert frame.rgb.shape == (config.height, config.width, 3) and frame.rgb.dtype == np.uint8
    hit = ~np.isnan(frame.depth)
    assert ((frame.depth[hit] > config.near) & (frame.depth[hit] <= config.far)).all()
    depth, cloud, _ = fast.organised_cloud(frame)
    kept = ~np.isnan(depth)
    assert ((depth[kept] > config.cutoff) & (depth[kept] < config.cutoff_max)).all()
    assert np.isfinite(cloud.view(np.float32)[:, :, :3][kept]).all()
    if config.width * config.height <= NUMPY_PIXELS:
        slow = CameraSensor(sim.physics, sim.models["cam"], config, ray_kernel=False).render(sim.scene)
        same = np.isnan(slow.depth) == ~hit
        both = hit & ~np.isnan(slow.depth)
        same[both] = np.isclose(frame.depth[both], slow.depth[both], rtol=1e-5, atol=1e-6)
        assert same.mean() >= AGREEING_PIXELS
    for message in templates(fast).values():
        message.serialize(BytesIO())
    start = sim.sim_time
    for _ in range(10):
        sim.step()
    assert sim.sim_time > start
