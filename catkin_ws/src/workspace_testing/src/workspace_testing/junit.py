"""A rostest test node's unittest cases run with their skips kept: rostest.rosrun writes its JUnit file with
rosunit's runner, which has no skipped outcome, so a skipped case reads as passed. ``run_node`` writes each case as
passed, failure, error or <skipped message="reason"> (which rostest's reader passes over and
scripts/lib/summarize_results.py counts as skipped) to the file rostest names with --gtest_output=xml:PATH."""
from __future__ import annotations

import os
import sys
import time
import unittest
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass
from typing import List, Optional, Sequence

XML_OUTPUT_FLAG = "--gtest_output=xml:"  # what rostest passes its test nodes


@dataclass(frozen=True)
class CaseOutcome:
    classname: str
    name: str
    seconds: float
    kind: str  # "" passed, "failure", "error" or "skipped"
    message: str = ""
    text: str = ""


class JUnitResult(unittest.TextTestResult):
    """unittest's text result that also keeps each case's outcome for the JUnit file."""

    def __init__(self, stream, descriptions, verbosity) -> None:
        super().__init__(stream, descriptions, verbosity)
        self.outcomes: List[CaseOutcome] = []
        self._started = time.monotonic()

    def startTest(self, test: unittest.TestCase) -> None:
        super().startTest(test)
        self._started = time.monotonic()

    def _keep(self, test: unittest.TestCase, kind: str, message: str = "", text: str = "") -> None:
        classname, _, name = test.id().rpartition(".")
        self.outcomes.append(CaseOutcome(classname, name, time.monotonic() - self._started, kind, message, text))

    def addSuccess(self, test: unittest.TestCase) -> None:
        super().addSuccess(test)
        self._keep(test, "")

    def addFailure(self, test: unittest.TestCase, err) -> None:
        super().addFailure(test, err)
        self._keep(test, "failure", str(err[1]), self.failures[-1][1])

    def addError(self, test: unittest.TestCase, err) -> None:
        super().addError(test, err)
        self._keep(test, "error", str(err[1]), self.errors[-1][1])

    def addSkip(self, test: unittest.TestCase, reason: str) -> None:
        super().addSkip(test, reason)
        self._keep(test, "skipped", reason)

    def addExpectedFailure(self, test: unittest.TestCase, err) -> None:
        super().addExpectedFailure(test, err)
        self._keep(test, "")

    def addUnexpectedSuccess(self, test: unittest.TestCase) -> None:
        super().addUnexpectedSuccess(test)
        self._keep(test, "failure", "unexpected success")


def junit_xml(suite_name: str, outcomes: Sequence[CaseOutcome], seconds: float) -> ElementTree.ElementTree:
    counts = {kind: sum(1 for outcome in outcomes if outcome.kind == kind) for kind in ("failure", "error", "skipped")}
    suite = ElementTree.Element(
        "testsuite",
        name=suite_name,
        tests=str(len(outcomes)),
        failures=str(counts["failure"]),
        errors=str(counts["error"]),
        skipped=str(counts["skipped"]),
        time="%.3f" % seconds,
    )
    for outcome in outcomes:
        case = ElementTree.SubElement(
            suite, "testcase", classname=outcome.classname, name=outcome.name, time="%.3f" % outcome.seconds
        )
        if outcome.kind:
            ElementTree.SubElement(case, outcome.kind, message=outcome.message).text = outcome.text or None
    return ElementTree.ElementTree(suite)


def results_file(argv: Sequence[str]) -> Optional[str]:
    """The JUnit file rostest asks for in ``argv``, None without one."""
    for argument in argv:
        if argument.startswith(XML_OUTPUT_FLAG):
            return argument[len(XML_OUTPUT_FLAG) :]
    return None


def run_node(test_case: type, suite_name: str, argv: Sequence[str]) -> int:
    """Run ``test_case``'s tests (text on stdout), write the JUnit file ``argv`` names, if any; the exit status:
    0 when every case passed or was skipped."""
    began = time.monotonic()
    suite = unittest.TestLoader().loadTestsFromTestCase(test_case)
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2, resultclass=JUnitResult).run(suite)
    path = results_file(argv)
    if path:
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
        junit_xml(suite_name, result.outcomes, time.monotonic() - began).write(path, encoding="utf-8")
    return 0 if result.wasSuccessful() else 1
