"""scripts/lib/summarize_results.py: JUnit XML files as pytest, gtest, rostest and workspace_testing.junit's rostest
nodes write them, counted into "N passed, N failed, N skipped" (CI reads words 1 and 3: scripts/check_container.sh);
each skip reason printed once; a skip never a pass. Generated result folders (Hypothesis) beside hand-picked ones."""
import os
import re
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

from hypothesis import given, settings
from hypothesis import strategies as st

import summarize_results  # scripts/lib, put on the path by conftest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "lib", "summarize_results.py")
sys.path.insert(0, os.path.join(HERE, "..", "..", "catkin_ws", "src", "workspace_testing", "src"))

from workspace_testing.junit import run_node  # noqa: E402

CLOSING_LINE = re.compile(r"^(\d+) passed, (\d+) failed, (\d+) skipped$")
OUTCOMES = ("passed", "failure", "error", "skipped")
# How each writer marks its cases: attributes of every <testcase>, those a skipped one has instead, and the attributes
# of its <skipped> element (None: it writes none).
WRITERS = {
    # pytest --junitxml: <skipped type="pytest.skip" message="reason">file:line: reason</skipped>
    "pytest": ({}, {}, {"type": "pytest.skip"}),
    # gtest >= 1.11 (Debian 12's 1.12): result="skipped" and <skipped message="...">
    "gtest": ({"status": "run", "result": "completed"}, {"result": "skipped"}, {}),
    # gtest 1.10 (Ubuntu 20.04): GTEST_SKIP only as result="skipped", no element, no reason
    "gtest_1_10": ({"status": "run", "result": "completed"}, {"result": "skipped"}, None),
    "junit_node": ({}, {}, {}),
}


def write_suite(path, writer, cases):
    """A result file of ``writer``'s kind with ``cases``: (name, outcome, reason)."""
    every, skipped, element = WRITERS[writer]
    suite = ET.Element("testsuite", name="suite", tests=str(len(cases)))
    for name, outcome, reason in cases:
        attributes = dict(every, classname="pkg.Case", name=name, **(skipped if outcome == "skipped" else {}))
        case = ET.SubElement(suite, "testcase", attributes)
        if outcome in ("failure", "error"):
            ET.SubElement(case, outcome, message="it broke").text = "trace"
        elif outcome == "skipped" and element is not None:
            ET.SubElement(case, "skipped", dict(element, message=reason)).text = "file.py:1: " + reason
    ET.ElementTree(suite).write(path)


def summarize(folder):
    ran = subprocess.run(
        [sys.executable, SCRIPT, folder], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True
    )
    return ran.returncode, ran.stdout.splitlines()


def closing_counts(lines):
    match = CLOSING_LINE.match(lines[-1])
    assert match, lines[-1]
    passed, failed, skipped = (int(group) for group in match.groups())
    words = lines[-1].split()
    assert (words[0], words[2]) == (str(passed), str(failed))  # what check_container.sh's awk '{ print $1, $3 }' reads
    return passed, failed, skipped


reasons = st.sampled_from(["no network", "needs black >= 23", "$X is not set: set X to a mirror", "  spaced\n out "])
cases = st.lists(st.tuples(st.sampled_from(OUTCOMES), reasons), max_size=8)
files = st.lists(
    st.tuples(st.sampled_from(sorted(WRITERS) + ["rostest"]), cases, st.sampled_from(["a", "b", "sub/c"])),
    max_size=6,
)


@settings(max_examples=60, deadline=None)
@given(files=files)
def test_the_counts_add_up_and_each_reason_is_printed_once(files):
    expected = {"passed": 0, "failed": 0, "skipped": 0}
    expected_reasons = set()
    total = 0
    with tempfile.TemporaryDirectory() as folder:
        for index, (writer, outcomes, subfolder) in enumerate(files):
            directory = os.path.join(folder, subfolder)
            os.makedirs(directory, exist_ok=True)
            rostest = writer == "rostest"  # rostest-*.xml: only its failures count
            name = ("rostest-%d.xml" if rostest else "rosunit-%d.xml") % index
            listed = [("t%d" % number, outcome, reason) for number, (outcome, reason) in enumerate(outcomes)]
            write_suite(os.path.join(directory, name), "junit_node" if rostest else writer, listed)
            for _, outcome, reason in listed:
                if outcome in ("failure", "error"):
                    expected["failed"] += 1
                elif rostest:
                    continue
                elif outcome == "skipped":
                    expected["skipped"] += 1
                    expected_reasons.add(
                        "gtest: skipped" if writer == "gtest_1_10" else " ".join(reason.split()) or "no reason given"
                    )
                else:
                    expected["passed"] += 1
                total += 1
        status, lines = summarize(folder)
    passed, failed, skipped = closing_counts(lines)
    assert (passed, failed, skipped) == (expected["passed"], expected["failed"], expected["skipped"])
    assert passed + failed + skipped == total  # every case counted once, a skip never as a pass
    assert status == (1 if failed or not passed else 0)
    assert sum(line.startswith("FAILED: ") for line in lines) == failed
    skip_lines = [line for line in lines if line.startswith("SKIPPED (")]
    shown = [re.match(r"SKIPPED \((\d+)\): (.*)$", line) for line in skip_lines]
    assert sorted(match.group(2) for match in shown) == sorted(expected_reasons)  # each reason once
    assert sum(int(match.group(1)) for match in shown) == skipped


class UpstreamLike(unittest.TestCase):
    """A rostest node whose upstream source is missing, as gazebo_ros's test_upstream_plugins.py has it."""

    __test__ = False  # run by run_node below, not collected by pytest

    def test_upstream_test_passes(self):
        self.skipTest("no upstream source of https://example.org/repo: $REPO is not set; set REPO to a mirror")


class Mixed(unittest.TestCase):
    __test__ = False

    def test_passes(self):
        pass

    def test_fails(self):
        self.fail("wrong")

    def test_errs(self):
        raise RuntimeError("broken")

    def test_skips(self):
        self.skipTest("not here")


def test_six_skipped_rostest_nodes_are_counted_skipped_with_their_reason_once(tmp_path):
    """The six upstream gazebo_plugins tests skip alike where the source is missing: one line says why."""
    for index in range(6):
        assert run_node(UpstreamLike, "upstream", ["--gtest_output=xml:%s/rosunit-up%d.xml" % (tmp_path, index)]) == 0
    write_suite(str(tmp_path / "pytest.xml"), "pytest", [("t", "passed", "")])
    status, lines = summarize(str(tmp_path))
    assert closing_counts(lines) == (1, 0, 6)
    assert status == 0
    reason_lines = [line for line in lines if line.startswith("SKIPPED")]
    assert reason_lines == [
        "SKIPPED (6): no upstream source of https://example.org/repo: $REPO is not set; set REPO to a mirror"
    ]


def test_only_skips_is_not_a_success(tmp_path):
    run_node(UpstreamLike, "upstream", ["--gtest_output=xml:%s/rosunit-up.xml" % tmp_path])
    status, lines = summarize(str(tmp_path))
    assert closing_counts(lines) == (0, 0, 1) and status == 1


def test_a_rostest_nodes_file_keeps_each_outcome_and_rostest_reads_it(tmp_path):
    """workspace_testing.junit: pass, failure, error and skip each as JUnit has them, and rosunit's reader (which
    rostest runs on the node's file) counts the failure and the error."""
    path = tmp_path / "rosunit-mixed.xml"
    assert run_node(Mixed, "mixed", ["__name:=x", "--gtest_output=xml:%s" % path]) == 1
    status, lines = summarize(str(tmp_path))
    assert closing_counts(lines) == (1, 2, 1) and status == 1
    assert "SKIPPED (1): not here" in lines
    suite = ET.parse(str(path)).getroot()
    assert (suite.get("tests"), suite.get("failures"), suite.get("errors"), suite.get("skipped")) == (
        "4",
        "1",
        "1",
        "1",
    )
    try:
        from rosunit import junitxml
    except ImportError:
        return  # no ROS here: the file's own counts were checked
    read = junitxml.read(str(path), "mixed")
    assert (read.num_tests, read.num_failures, read.num_errors) == (4, 1, 1)


def test_a_gtest_disabled_or_1_10_skip_is_a_skip(tmp_path):
    """gtest's XML (googletest src/gtest.cc, OutputXmlTestInfo): a DISABLED_ test has status="notrun" (1.10) or
    result="suppressed"; GTEST_SKIP result="skipped"."""
    (tmp_path / "gtest.xml").write_text(
        '<testsuites><testsuite name="s" tests="4">'
        '<testcase name="a" classname="s" status="run" result="completed"/>'
        '<testcase name="DISABLED_b" classname="s" status="notrun"/>'
        '<testcase name="DISABLED_c" classname="s" status="run" result="suppressed"/>'
        '<testcase name="d" classname="s" status="run" result="skipped"/>'
        "</testsuite></testsuites>"
    )
    status, lines = summarize(str(tmp_path))
    assert closing_counts(lines) == (1, 0, 3) and status == 0


def test_a_failed_launch_without_cases_and_an_unreadable_file_fail(tmp_path):
    (tmp_path / "rostest-x.xml").write_text('<testsuite name="x" tests="1" errors="1" failures="0"/>')
    (tmp_path / "broken.xml").write_text("<testsuite")
    status, lines = summarize(str(tmp_path))
    assert closing_counts(lines) == (0, 2, 0) and status == 1


def test_the_module_counts_as_the_script_prints(tmp_path):
    write_suite(str(tmp_path / "a.xml"), "gtest", [("x", "skipped", "why"), ("y", "passed", "")])
    counts = summarize_results.summarize([str(tmp_path)])
    assert (counts.passed, counts.failed, counts.skipped) == (1, 0, 1)
    assert summarize_results.report(counts)[-1] == "1 passed, 0 failed, 1 skipped"
