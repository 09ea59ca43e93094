"""The xacro drop-in's expression sandbox (issue #26): what xacro's documented language allows is evaluated as
upstream evaluates it, the usual files expand to the same URDF with and without the sandbox, and code that PyPI's
xacro would run (a lambda, a comprehension, a property's value, `$(eval)` with Python's builtins) is refused with a
message naming the file and the expression, without running."""
from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
if (PACKAGE_ROOT / "CATKIN_IGNORE").exists():  # scripts/lib/dropins.py: the system's xacro is used here
    pytest.skip("the drop-in is ignored", allow_module_level=True)
sys.path.insert(0, str(PACKAGE_ROOT / "src"))

from xacro_dropin import sandbox  # noqa: E402

WORKSPACE_SRC = PACKAGE_ROOT.parent
FIXTURE_PACKAGES = [
    PACKAGE_ROOT / "test" / "fixture_packages",
    WORKSPACE_SRC / "gazebo_ros" / "test" / "fixture_packages",
]
# Expands a file with PyPI's xacro as it is ("upstream") or with the sandbox ("sandbox"); prints the URDF.
EXPAND = textwrap.dedent(
    """\
    import sys, rospkg, xacro_dropin
    from xacro_dropin.sandbox import sandbox_xacro
    xacro = xacro_dropin.import_pypi_xacro()
    from xacro import substitution_args
    import xml.parsers.expat
    xacro_dropin.use_ros_package_path(substitution_args, xacro_dropin.ros_package_finder(rospkg.RosPack()))
    if sys.argv[1] == "sandbox":
        sandbox_xacro(xacro, substitution_args)
    mappings = dict(arg.split(":=", 1) for arg in sys.argv[3:])
    print(xacro.process_file(sys.argv[2], mappings=mappings).toprettyxml(indent="  "))
    """
)


def python(argv: list, cwd: Path, **environ: str) -> subprocess.CompletedProcess:
    """/usr/bin/python3 with ``argv``, the drop-in's src on PYTHONPATH and ``environ`` added."""
    env = dict(os.environ, PYTHONPATH=str(PACKAGE_ROOT / "src"), **environ)
    return subprocess.run(
        ["/usr/bin/python3"] + argv,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        universal_newlines=True,
        env=env,
        cwd=str(cwd),
        timeout=60,
    )


def expand(mode: str, path: Path, *args: str) -> subprocess.CompletedProcess:
    packages = os.pathsep.join(str(p) for p in FIXTURE_PACKAGES)
    return python(["-c", EXPAND, mode, str(path)] + list(args), PACKAGE_ROOT, ROS_PACKAGE_PATH=packages)


def run_command(path: Path, cwd: Path) -> subprocess.CompletedProcess:
    return python([str(PACKAGE_ROOT / "xacro"), str(path)], cwd)


@pytest.mark.parametrize(
    "path, args",
    [
        (PACKAGE_ROOT / "test" / "turtlebot3_style.urdf.xacro", []),
        (PACKAGE_ROOT / "test" / "turtlebot3_style.urdf.xacro", ["prefix:=tb3_", "laser_visual:=true"]),
        (PACKAGE_ROOT / "test" / "two_wheels.urdf.xacro", ["wheel_radius:=0.05"]),
        (WORKSPACE_SRC / "gazebo_ros/test/fixture_packages/sim_fixture_description/urdf/robot.urdf.xacro", []),
    ],
    ids=["tb3_style", "tb3_style_args", "two_wheels", "sim_fixture"],
)
def test_the_usual_files_expand_to_the_same_urdf_as_upstream(path: Path, args: list) -> None:
    upstream, sandboxed = expand("upstream", path, *args), expand("sandbox", path, *args)
    assert upstream.returncode == 0, upstream.stderr
    assert sandboxed.returncode == 0, sandboxed.stderr
    assert sandboxed.stdout == upstream.stdout
    assert sandboxed.stderr == upstream.stderr  # the same warnings too (deprecated names and the like)


HOSTILE = {
    "lambda": "${(lambda: MARK)()}",
    "list comprehension": "${[c for c in ().__class__.__base__.__subclasses__()]}",
    "comprehension without dunders": "${[open('MARK', 'w') for _ in [1]]}",
    "property value": '<xacro:property name="p" value="${(lambda: open(\'MARK\', \'w\'))()}"/><link name="${p}"/>',
    "eval with builtins": "$(eval open('MARK', 'w').close() or 'x')",
    "eval through map": '$(eval list(map(exec, [\'open("MARK", "w")\'])))',
    "huge power": "${10**10**10}",
    "huge format": "${'%0999999999d' % 1}",
}


@pytest.mark.parametrize("expression", list(HOSTILE.values()), ids=list(HOSTILE))
def test_hostile_expressions_are_refused_naming_file_and_expression_and_never_run(tmp_path: Path, expression: str):
    body = expression if expression.startswith("<") else '<link name="%s"/>' % expression.replace('"', "&quot;")
    robot = tmp_path / "hostile.urdf.xacro"
    robot.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">%s</robot>' % body)
    result = run_command(robot, tmp_path)
    assert result.returncode == 2, (result.stdout, result.stderr)
    assert "hostile.urdf.xacro" in result.stderr and ("refused" in result.stderr or "too large" in result.stderr)
    assert sorted(os.listdir(tmp_path)) == ["hostile.urdf.xacro"]  # MARK never written


@pytest.mark.parametrize(
    "expression, why",
    [
        ("(lambda: 1)()", "a lambda"),
        ("[x for x in range(3)]", "a list comprehension"),
        ("{x: 1 for x in 'ab'}", "a dict comprehension"),
        ("sum(x for x in [1])", "a generator expression"),
        ("().__class__", "the attribute '__class__'"),
        ("_private", "the name '_private'"),
        ("open('f')", "a call of 'open'"),
        ("python.type(1)", "a call of method 'type'"),
        ("'{0.x}'.format(1)", "the attribute 'format'"),
        ("f'{1}'", "an f-string"),
        ("(x := 1)", "an assignment expression"),
        ("print(*[1])", "a starred argument"),
    ],
)
def test_the_sandbox_names_what_it_refuses(expression: str, why: str) -> None:
    assert why in sandbox.refusal(expression)
    with pytest.raises(sandbox.SandboxError, match="in file f.xacro: expression"):
        sandbox.check(expression, "f.xacro")


@pytest.mark.parametrize(
    "expression, value",
    [
        ("2 * pi / 4", 1.5707963267948966),
        ("radians(180) == pi", True),
        ("'a' + 'b' if 1 < 2 else 'c'", "ab"),
        ("[1, 2][-1]", 2),
        ("dict(a=1)['a']", 1),
        ("math.sqrt(4)", 2.0),
        ("max(1, 2) ** 2", 4),
        ("'base_link'.split('_')[0].upper()", "BASE"),
        ("'%s_%d' % ('wheel', 2)", "wheel_2"),
        ("'x' * 3", "xxx"),
        ("not True or None is None", True),
    ],
)
def test_the_documented_language_is_evaluated(expression: str, value: object) -> None:
    symbols = {name: getattr(__import__("math"), name) for name in ("pi", "radians", "sqrt")}
    symbols.update(dict=dict, max=max, math=__import__("math"))
    assert sandbox.sandboxed_eval(expression, symbols) == value
