"""SDF text for the SDF tests, written in the style of Gazebo's own models: a document around a body, and models,
links, inertials and box collisions to put in it."""


def sdf(body, version="1.6"):
    return f'<?xml version="1.0"?>\n<sdf version="{version}">\n{body}\n</sdf>'


def inertial(mass=1.0, inertia=0.1):
    return (
        f"<inertial><mass>{mass}</mass><inertia><ixx>{inertia}</ixx><iyy>{inertia}</iyy>"
        f"<izz>{inertia}</izz></inertia></inertial>"
    )


def link(name, pose="0 0 0 0 0 0", extra=inertial()):
    return f'<link name="{name}"><pose>{pose}</pose>{extra}</link>'


def box_collision(size, surface=""):
    return f'<collision name="c"><geometry><box><size>{size}</size></box></geometry>' f"{surface}</collision>"


def model(name, *parts, static=False):
    return f'<model name="{name}"><static>{str(static).lower()}</static>{"".join(parts)}</model>'
