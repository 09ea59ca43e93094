"""The plugin reference (doc/*.md) stays true to the code: every plugin in the registry tables has a section, each
section's XML example is read without error by the plugin's reader, and every tag or sensor element a section's
tables document is one the reader reads.

"Reads" is tested from the outside, whatever way a reader looks its tags up: the tag, set to a value no reader
accepts as it is ("not_a_value_9"), changes what the reader returns (its config, or the error it raises) against the
example without the tag. A tag the reader ignores leaves the result as it was."""
from __future__ import annotations

import re
from pathlib import Path
from typing import Dict, List, NamedTuple, Optional, Tuple
from xml.etree.ElementTree import Element, SubElement, fromstring

import pytest
from conftest import PACKAGE_ROOT

from turtle_sim_ode.control.plugin import RosControlConfig
from turtle_sim_ode.models.text import plugin_params
from turtle_sim_ode.models.urdf import GazeboPlugin
from turtle_sim_ode.sensors.plugins import SENSOR_PLUGINS
from turtle_sim_ode.world.plugins import MODEL_PLUGINS
from turtle_sim_ode.world.plugins.ros_control import RosControlPluginConfig

DOC = Path(PACKAGE_ROOT) / "doc"
README = Path(PACKAGE_ROOT) / "README.md"
PROBE = "not_a_value_9"
# A tag table's first column: plugin tags (children of <plugin>) or sensor elements (paths below <sensor>).
TAG_TABLE, ELEMENT_TABLE = "tag", "element"


class Section(NamedTuple):
    page: str
    heading: str
    anchor: str
    example: Optional[str]  # the first ```xml block
    tags: Tuple[str, ...]  # first column of the `| tag |` tables
    elements: Tuple[str, ...]  # first column of the `| element |` tables, as paths below <sensor>


def _anchor(heading: str) -> str:
    """GitHub's heading anchor: lower case, punctuation but - and _ dropped, spaces to -."""
    return re.sub(r"[^\w\- ]", "", heading.lower()).replace(" ", "-")


def _table_column(lines: List[str], kind: str) -> List[List[str]]:
    """The backticked names of each first cell of the ``kind`` tables, a list a row."""
    found: List[List[str]] = []
    inside = False
    for line in lines:
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")] if line.startswith("|") else []
        if not cells:
            inside = False
        elif cells[0] in (TAG_TABLE, ELEMENT_TABLE) and not inside:
            inside, current = True, cells[0]
        elif inside and current == kind and not set(cells[0]) <= set("-: "):
            found.append(re.findall(r"`([^`]+)`", cells[0]))
    return found


def _element_paths(names: List[str]) -> List[str]:
    """``<ray><range><min>``, ``<max>`` -> ``ray/range/min``, ``ray/range/max``: a name after the first is its
    sibling."""
    paths = [re.findall(r"<([\w:]+)>", name) for name in names]
    return ["/".join(paths[0][:-1] + path if len(path) == 1 else path) for path in paths]


def sections() -> List[Section]:
    found = []
    for page in sorted(DOC.glob("*.md")):
        parts = re.split(r"^## (.+)$", page.read_text(), flags=re.M)
        for heading, body in zip(parts[1::2], parts[2::2]):
            example = re.search(r"```xml\n(.*?)```", body, re.S)
            lines = body.splitlines()
            found.append(
                Section(
                    page.name,
                    heading.strip(),
                    _anchor(heading.strip()),
                    example.group(1) if example else None,
                    tuple(tag for row in _table_column(lines, TAG_TABLE) for tag in row),
                    tuple(path for row in _table_column(lines, ELEMENT_TABLE) for path in _element_paths(row)),
                )
            )
    return found


SECTIONS = sections()
PLUGIN_SECTIONS = [section for section in SECTIONS if section.example]


def _example_plugin(section: Section) -> Tuple[Element, Optional[Element]]:
    """The example's <plugin> of a file name the heading names, and the <sensor> it is in (None: a model plugin)."""
    root = fromstring(f"<example>{section.example}</example>")
    parents = {child: parent for parent in root.iter() for child in parent}
    named = re.findall(r"`(lib[\w.]+\.so)`", section.heading)
    for plugin in root.iter("plugin"):
        if plugin.get("filename") in named:
            parent = parents[plugin]
            return plugin, parent if parent.tag == "sensor" else None
    raise AssertionError(f"{section.page} '{section.heading}': no <plugin> of {named} in its XML example")


def _read(plugin: Element, sensor: Optional[Element]) -> str:
    """What the plugin's reader makes of it, as text: its config, or its error."""
    filename = plugin.get("filename", "")
    try:
        if sensor is not None:
            config = SENSOR_PLUGINS[filename].read("base_link", sensor, plugin, [])
        else:
            config = MODEL_PLUGINS[filename]("robot", GazeboPlugin(filename, "p", plugin_params(plugin)), {})
            if isinstance(config, RosControlPluginConfig):  # its tags are read by its ROS side's RosControlConfig
                config = RosControlConfig.read(config.params, "robot", 0.001)
    except Exception as error:  # noqa: BLE001 - a refusal is an answer too
        return f"error {type(error).__name__}: {error}"
    return repr(config)


def _without(section: Section, path: str, in_sensor: bool) -> Tuple[Element, Optional[Element], Element]:
    """A fresh copy of the example's plugin and sensor, with ``path`` removed below the plugin (or the sensor)."""
    plugin, sensor = _example_plugin(section)
    holder = sensor if in_sensor else plugin
    assert holder is not None
    *parents, leaf = path.split("/")
    parent = holder
    for name in parents:
        parent = parent.find(name) if parent.find(name) is not None else SubElement(parent, name)
    for old in parent.findall(leaf):
        parent.remove(old)
    return plugin, sensor, parent


def _probe_changes(section: Section, path: str, in_sensor: bool) -> bool:
    plugin, sensor, parent = _without(section, path, in_sensor)
    before = _read(plugin, sensor)
    SubElement(parent, path.split("/")[-1]).text = PROBE
    return _read(plugin, sensor) != before


def test_every_registered_plugin_has_a_section() -> None:
    headings = " ".join(section.heading for section in SECTIONS)
    missing = [name for name in list(MODEL_PLUGINS) + list(SENSOR_PLUGINS) if f"`{name}`" not in headings]
    assert not missing, f"no section in doc/*.md names {missing} in its heading"


@pytest.mark.parametrize("section", PLUGIN_SECTIONS, ids=[s.anchor for s in PLUGIN_SECTIONS])
def test_the_example_reads_cleanly(section: Section) -> None:
    plugin, sensor = _example_plugin(section)
    assert not _read(plugin, sensor).startswith("error"), _read(plugin, sensor)


@pytest.mark.parametrize("section", PLUGIN_SECTIONS, ids=[s.anchor for s in PLUGIN_SECTIONS])
def test_every_documented_tag_is_read(section: Section) -> None:
    assert section.tags, f"{section.page} '{section.heading}' documents no tags"
    ignored = [tag for tag in section.tags if not _probe_changes(section, tag, in_sensor=False)]
    assert not ignored, f"{section.page} '{section.heading}': the reader ignores tags {ignored}"


@pytest.mark.parametrize("section", PLUGIN_SECTIONS, ids=[s.anchor for s in PLUGIN_SECTIONS])
def test_every_documented_sensor_element_is_read(section: Section) -> None:
    if not section.elements:
        return
    assert _example_plugin(section)[1] is not None, f"'{section.heading}' documents sensor elements of no sensor"
    ignored = [path for path in section.elements if not _probe_changes(section, path, in_sensor=True)]
    assert not ignored, f"{section.page} '{section.heading}': the reader ignores elements {ignored}"


def test_an_ignored_tag_is_found() -> None:
    """The probe itself: a tag no reader knows changes nothing; a tag the reader knows changes its result."""
    section = next(s for s in PLUGIN_SECTIONS if "`libgazebo_ros_diff_drive.so`" in s.heading)
    assert not _probe_changes(section, "noSuchTag", in_sensor=False)
    assert _probe_changes(section, "commandTopic", in_sensor=False)


def test_the_readme_index_links_every_section() -> None:
    readme = README.read_text()
    links = set(re.findall(r"\(doc/([\w.]+\.md)#([\w-]+)\)", readme))
    unlinked = [f"{s.page}#{s.anchor}" for s in PLUGIN_SECTIONS if (s.page, s.anchor) not in links]
    assert not unlinked, f"README.md's plugin index does not link {unlinked}"
    anchors = {(s.page, s.anchor) for s in SECTIONS}
    dangling = sorted(link for link in links if link not in anchors)
    assert not dangling, f"README.md links sections that do not exist: {dangling}"


def test_tables_found() -> None:
    """The parser sees the tables (a changed header would otherwise pass every test above vacuously)."""
    counts: Dict[str, int] = {}
    for section in PLUGIN_SECTIONS:
        counts[section.page] = counts.get(section.page, 0) + len(section.tags)
    assert all(count > 0 for count in counts.values()) and len(counts) >= 5, counts
