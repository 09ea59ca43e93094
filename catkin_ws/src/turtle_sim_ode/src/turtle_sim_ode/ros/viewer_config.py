"""The viewer's rviz configuration, written at its start: the world as Gazebo's client draws it (the scene markers on
/gazebo/scene_markers, in frame `world`), what turtlebot.rviz showed beside (tf, laser, depth point cloud; the robot
model, which the scene draws already, off; camera images: add an Image display, or rqt_image_view), seen first from the world's user camera (world.viewer_scene.orbit_view)
with rviz's orbit controls (left drag orbits, middle drag pans, wheel or right drag zooms)."""
from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence

from turtle_sim_ode.world.user_camera import DEFAULT_USER_CAMERA, OrbitView, orbit_view

SCENE_TOPIC = "/gazebo/scene_markers"
FIXED_FRAME = "world"
# Gazebo's <scene><background> default, light grey; its ground plane is Gazebo/Grey.
BACKGROUND = "178; 178; 178"
WINDOW = {"Width": 760, "Height": 600, "X": 0, "Y": 0}  # the control window beside it fits a 1024 px screen
GRID_HEIGHT = 0.002  # just above the ground plane's top, which would hide it


def _display(kind: str, name: str, enabled: bool = True, **properties: Any) -> Dict[str, Any]:
    return dict({"Class": "rviz/" + kind, "Name": name, "Enabled": enabled, "Value": enabled}, **properties)


def displays(scene_topic: str = SCENE_TOPIC) -> List[Dict[str, Any]]:
    return [
        _display(
            "Grid",
            "Grid",
            **{
                "Cell Size": 1,
                "Plane Cell Count": 20,
                "Color": "160; 160; 164",
                "Alpha": 0.5,
                "Reference Frame": "<Fixed Frame>",
                "Offset": {"X": 0, "Y": 0, "Z": GRID_HEIGHT},
            },
        ),
        _display("MarkerArray", "World", **{"Marker Topic": scene_topic, "Queue Size": 100, "Namespaces": {}}),
        _display("RobotModel", "RobotModel", False, **{"Robot Description": "robot_description", "Alpha": 1}),
        _display("TF", "TF", **{"Show Names": False, "Show Arrows": False, "Marker Scale": 0.3}),
        _display(
            "LaserScan",
            "LaserScan",
            # Magenta: no model's colour is taken for the laser's (Gazebo draws rays in a translucent blue).
            **{"Topic": "/scan", "Color Transformer": "FlatColor", "Color": "255; 0; 255", "Size (m)": 0.03},
        ),
        _display("PointCloud2", "PointCloud2", **{"Topic": "/camera/depth/points", "Size (m)": 0.02}),
    ]


def view_of(orbit: OrbitView) -> Dict[str, Any]:
    x, y, z = orbit.focal_point
    return {
        "Class": "rviz/Orbit",
        "Name": "Current View",
        "Distance": orbit.distance,
        "Focal Point": {"X": x, "Y": y, "Z": z},
        "Yaw": orbit.yaw,
        "Pitch": orbit.pitch,
        "Field of View": 0.785,
        "Near Clip Distance": 0.01,
        "Target Frame": "<Fixed Frame>",
        "Focal Shape Fixed Size": True,
        "Focal Shape Size": 0.05,
    }


def rviz_config(user_camera: Optional[Sequence[float]] = None, scene_topic: str = SCENE_TOPIC) -> Dict[str, Any]:
    """The rviz configuration (as rviz's YAML holds it) for a world whose <gui><camera><pose> is ``user_camera``
    (x y z roll pitch yaw; None: Gazebo's default view)."""
    camera = tuple(user_camera) if user_camera is not None else DEFAULT_USER_CAMERA
    return {
        "Panels": [],  # the 3D view fills the window, as Gazebo's; Panels > Displays opens the display list
        "Visualization Manager": {
            "Class": "",
            "Name": "root",
            "Enabled": True,
            "Value": True,
            "Displays": displays(scene_topic),
            "Global Options": {
                "Background Color": BACKGROUND,
                "Default Light": True,
                "Fixed Frame": FIXED_FRAME,
                "Frame Rate": 30,
            },
            "Tools": [
                {"Class": "rviz/Interact", "Hide Inactive Objects": True},
                {"Class": "rviz/MoveCamera"},
                {"Class": "rviz/Select"},
                {"Class": "rviz/FocusCamera"},
            ],
            "Views": {"Current": view_of(orbit_view(camera)), "Saved": None},  # type: ignore[arg-type]
        },
        "Window Geometry": dict(WINDOW, **{"Hide Left Dock": True, "Hide Right Dock": True}),
    }
