#!/usr/bin/env python3
"""Count the JUnit XML results below a folder (pytest, gtest and rostest all write them) and print one closing line:
"N passed, N failed, N skipped" (CI reads its first and third words). Before it: a FAILED: line for each failure and
a SKIPPED: line for each distinct skip reason (once, however many tests it skipped, with their count and names).
Exit 1 on any failure or error, or when no test passed; a skipped test is never counted as passed.

A test case is skipped where it holds <skipped> (pytest, gtest >= 1.11, workspace_testing.junit's rostest nodes),
or gtest says so in its attributes (result="skipped"/"suppressed", status="notrun": GTEST_SKIP in gtest 1.10, a
DISABLED_ test).

rostest writes two files a launch: rosunit-<test-name>.xml with each test case, and rostest-<file>.xml with one
entry per test node. The second only adds what the first cannot say (a test node that crashed or timed out), so
only its failures count.
"""
import os
import sys
import xml.etree.ElementTree as ET
from collections import OrderedDict

GTEST_NOT_RUN = {("result", "skipped"), ("result", "suppressed"), ("status", "notrun")}
NAMES_SHOWN = 10  # skipped tests named under their reason; the rest counted


class Counts:
    """The outcome of the test cases read so far; ``skips``: names of the skipped cases by reason, in order met."""

    def __init__(self):
        self.passed = 0
        self.failed = 0
        self.failures = []
        self.skips = OrderedDict()

    @property
    def skipped(self):
        return sum(len(names) for names in self.skips.values())

    def skip(self, reason, name):
        self.skips.setdefault(reason, []).append(name)

    def fail(self, description):
        self.failed += 1
        self.failures.append(description)


def skip_reason(case):
    """Why the test case was skipped, "" when it was not (a skip without a reason: "no reason given")."""
    element = case.find("skipped")
    if element is not None:
        reason = element.get("message") or (element.text or "").strip()
    elif any(case.get(attribute) == value for attribute, value in GTEST_NOT_RUN):
        reason = "gtest: %s" % (case.get("result") or case.get("status"))
    else:
        return ""
    return " ".join(reason.split()) or "no reason given"


def count_file(path, counts, failures_only=False):
    """Add the test cases of one result file to ``counts``; an unreadable file is a failure. ``failures_only``: a
    rostest-*.xml file, whose passes and skips the rosunit-*.xml files count."""
    shown = os.path.relpath(path)
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as error:
        counts.fail("%s: unreadable result file (%s)" % (shown, error))
        return
    for case in root.iter("testcase"):
        name = "%s.%s" % (case.get("classname"), case.get("name"))
        if case.find("failure") is not None or case.find("error") is not None:
            counts.fail("%s (%s)" % (name, shown))
            continue
        if failures_only:
            continue
        reason = skip_reason(case)
        if reason:
            counts.skip(reason, "%s (%s)" % (name, shown))
        else:
            counts.passed += 1
    # rostest writes a suite-level failure with no test case when the launch itself failed.
    for suite in root.iter("testsuite"):
        if not list(suite.iter("testcase")):
            for _ in range(int(suite.get("errors", 0)) + int(suite.get("failures", 0))):
                counts.fail("%s: suite failed without test cases" % shown)


def summarize(folders):
    """The counts of every *.xml file below ``folders``, files in name order."""
    counts = Counts()
    for folder in folders:
        for root, dirs, files in os.walk(folder):
            dirs.sort()
            for name in sorted(files):
                if name.endswith(".xml"):
                    count_file(os.path.join(root, name), counts, failures_only=name.startswith("rostest-"))
    return counts


def report(counts):
    """The lines to print: failures, skip reasons (each once), and the closing count line."""
    lines = ["FAILED: " + name for name in counts.failures]
    for reason, names in counts.skips.items():
        lines.append("SKIPPED (%d): %s" % (len(names), reason))
        lines += ["  " + name for name in names[:NAMES_SHOWN]]
        if len(names) > NAMES_SHOWN:
            lines.append("  and %d more" % (len(names) - NAMES_SHOWN))
    lines.append("%d passed, %d failed, %d skipped" % (counts.passed, counts.failed, counts.skipped))
    return lines


def main():
    counts = summarize(sys.argv[1:])
    print("\n".join(report(counts)))
    sys.exit(1 if counts.failed or counts.passed == 0 else 0)


if __name__ == "__main__":
    main()
