"""The plugin reference (doc/*.md) stays true to the code: every plugin in the registry tables has a section, each
section's XML example is read without error by the plugin's reader, every tag or sensor element a section's tables
document is one the reader reads, and every documented default that is a value (not "the link") is the reader's.

"Reads" is tested from the outside, whatever way a reader looks its tags up: the tag, set to a value no reader
accepts as it is ("not_a_value_9"), changes what the reader returns (its config, or the error it raises) against the
example without the tag. A tag the reader ignores leaves the result as it was; a tag set to its default does too."""
from __future__ import annotations

import re
from pathlib import Path
from typing import Dict, List, NamedTuple, Optional, Tuple
from xml.etree.ElementTree import Element, SubElement, fromstring

import pytest
from conftest import PACKAGE_ROOT

from turtle_sim_ode.control.plugin import RosControlConfig
from turtle_sim_ode.models.text import plugin_params
from turtle_sim_ode.models.description import GazeboPlugin
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
    tags: Tuple[Tuple[str, Optional[str]], ...]  # (tag, its documented default as text, None where not literal)
    elements: Tuple[Tuple[str, Optional[str]], ...]  # (path below <sensor>, default)


def _anchor(heading: str) -> str:
    """GitHub's heading anchor: lower case, punctuation but - and _ dropped, spaces to -."""
    return re.sub(r"[^\w\- ]", "", heading.lower()).replace(" ", "-")


def _table_rows(lines: List[str], kind: str) -> List[Tuple[List[str], str]]:
    """Of each row of the ``kind`` tables: the backticked names of its first cell, and its default cell (the third:
    | name | type | default | meaning |)."""
    found: List[Tuple[List[str], str]] = []
    inside, current = False, ""
    for line in lines:
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")] if line.startswith("|") else []
        if not cells:
            inside = False
        elif cells[0] in (TAG_TABLE, ELEMENT_TABLE) and not inside:
            inside, current = True, cells[0]
        elif inside and current == kind and not set(cells[0]) <= set("-: "):
            found.append((re.findall(r"`([^`]+)`", cells[0]), cells[2]))
    return found


def _literal(default: str) -> Optional[str]:
    """A documented default as the tag's text, where it is one a user could write: a number (−, a/b, inf), true or
    false, "" or one backticked word; None for words ("the link", "required") and references to other tags."""
    text = default.replace("−", "-").strip()
    if re.fullmatch(r"-?\d+(\.\d+)?(e-?\d+)?|-?inf|true|false", text):
        return text
    if re.fullmatch(r"\d+/\d+", text):
        numerator, denominator = text.split("/")
        return repr(int(numerator) / int(denominator))
    if text == '""':
        return ""
    word = re.fullmatch(r"`([^`<>]+)`", text)
    return word.group(1) if word else None


def _with_defaults(names: List[str], default: str) -> List[Tuple[str, Optional[str]]]:
    """Pairs a row's names with its defaults: one default for all, or one each ("0.12, 3.5")."""
    defaults = [part.strip() for part in default.split(", ")]
    if len(defaults) != len(names):
        defaults = [default] * len(names)
    return [(name, _literal(value)) for name, value in zip(names, defaults)]


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
            tags = [pair for names, default in _table_rows(lines, TAG_TABLE) for pair in _with_defaults(names, default)]
            elements = [
                pair
                for names, default in _table_rows(lines, ELEMENT_TABLE)
                for pair in _with_defaults(_element_paths(names), default)
            ]
            named = {name for name, _ in tags + elements}
            found.append(  # a default naming another tag ("publishTf" defaults to publishOdomTF) is not literal
                Section(
                    page.name,
                    heading.strip(),
                    _anchor(heading.strip()),
                    example.group(1) if example else None,
                    tuple((name, None if default in named else default) for name, default in tags),
                    tuple((name, None if default in named else default) for name, default in elements),
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


def _changes(section: Section, path: str, in_sensor: bool, value: str = PROBE) -> bool:
    """Whether giving ``path`` the text ``value`` changes what the reader makes of the example without it."""
    plugin, sensor, parent = _without(section, path, in_sensor)
    before = _read(plugin, sensor)
    SubElement(parent, path.split("/")[-1]).text = value
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
    ignored = [tag for tag, _ in section.tags if not _changes(section, tag, in_sensor=False)]
    assert not ignored, f"{section.page} '{section.heading}': the reader ignores tags {ignored}"


@pytest.mark.parametrize("section", PLUGIN_SECTIONS, ids=[s.anchor for s in PLUGIN_SECTIONS])
def test_every_documented_sensor_element_is_read(section: Section) -> None:
    if not section.elements:
        return
    assert _example_plugin(section)[1] is not None, f"'{section.heading}' documents sensor elements of no sensor"
    ignored = [path for path, _ in section.elements if not _changes(section, path, in_sensor=True)]
    assert not ignored, f"{section.page} '{section.heading}': the reader ignores elements {ignored}"


@pytest.mark.parametrize("section", PLUGIN_SECTIONS, ids=[s.anchor for s in PLUGIN_SECTIONS])
def test_every_documented_default_is_the_readers(section: Section) -> None:
    """A tag or element given its documented default reads as if it were not there (defaults that are words, such
    as "the link", are not checked)."""
    wrong = [
        f"{name} = {default!r}"
        for in_sensor, rows in ((False, section.tags), (True, section.elements))
        for name, default in rows
        if default is not None and _changes(section, name, in_sensor, default)
    ]
    assert not wrong, f"{section.page} '{section.heading}': defaults the reader does not have: {wrong}"


def test_an_ignored_tag_is_found() -> None:
    """The probe itself: a tag no reader knows changes nothing; a tag the reader knows changes its result."""
    section = next(s for s in PLUGIN_SECTIONS if "`libgazebo_ros_diff_drive.so`" in s.heading)
    assert not _changes(section, "noSuchTag", in_sensor=False)
    assert _changes(section, "commandTopic", in_sensor=False)
    assert not _changes(section, "commandTopic", in_sensor=False, value="cmd_vel")  # its default
    assert _changes(section, "commandTopic", in_sensor=False, value="cmd_vel_2")


def test_the_readme_index_links_every_section() -> None:
    readme = README.read_text()
    links = set(re.findall(r"\(doc/([\w.]+\.md)#([\w-]+)\)", readme))
    unlinked = [f"{s.page}#{s.anchor}" for s in PLUGIN_SECTIONS if (s.page, s.anchor) not in links]
    assert not unlinked, f"README.md's plugin index does not link {unlinked}"
    anchors = {(s.page, s.anchor) for s in SECTIONS}
    dangling = sorted(link for link in links if link not in anchors)
    assert not dangling, f"README.md links sections that do not exist: {dangling}"


def test_tables_found() -> None:
    """The parser sees the tables and their literal defaults (a changed header would otherwise pass every test above
    vacuously)."""
    counts: Dict[str, int] = {}
    for section in PLUGIN_SECTIONS:
        counts[section.page] = counts.get(section.page, 0) + sum(default is not None for _, default in section.tags)
    assert all(count > 0 for count in counts.values()) and len(counts) >= 5, counts
