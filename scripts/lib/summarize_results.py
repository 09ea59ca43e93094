#!/usr/bin/env python3
"""Count the JUnit XML results below a folder (pytest, gtest and rostest all write them) and print one line:
"N passed, N failed, N skipped". Exit 1 on any failure or error, or when no test ran at all.

rostest writes two files a launch: rosunit-<test-name>.xml with each test case, and rostest-<file>.xml with one
entry per test node. The second only adds what the first cannot say (a test node that crashed or timed out), so
only its failures count.
"""
import os
import sys
import xml.etree.ElementTree as ET


def count_cases(path):
    """Return (passed, failed, skipped, names of failures) of one result file; an unreadable file is a failure."""
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as error:
        return 0, 1, 0, ["%s: unreadable result file (%s)" % (path, error)]
    passed = failed = skipped = 0
    failures = []
    for case in root.iter("testcase"):
        outcome = {child.tag for child in case}
        name = "%s.%s" % (case.get("classname"), case.get("name"))
        if outcome & {"failure", "error"}:
            failed += 1
            failures.append("%s (%s)" % (name, os.path.relpath(path)))
        elif "skipped" in outcome:
            skipped += 1
        else:
            passed += 1
    # rostest writes a suite-level failure with no test case when the launch itself failed.
    suite_errors = sum(
        int(s.get("errors", 0)) + int(s.get("failures", 0))
        for s in root.iter("testsuite")
        if not list(s.iter("testcase"))
    )
    if suite_errors:
        failed += suite_errors
        failures.append("%s: suite failed without test cases" % os.path.relpath(path))
    return passed, failed, skipped, failures


def main():
    totals = [0, 0, 0]
    failures = []
    for folder in sys.argv[1:]:
        for root, _, files in os.walk(folder):
            for name in sorted(files):
                if name.endswith(".xml"):
                    passed, failed, skipped, names = count_cases(os.path.join(root, name))
                    if name.startswith("rostest-"):
                        passed = skipped = 0
                    totals = [totals[0] + passed, totals[1] + failed, totals[2] + skipped]
                    failures += names
    for name in failures:
        print("FAILED: " + name)
    passed, failed, skipped = totals
    print("%d passed, %d failed, %d skipped" % (passed, failed, skipped))
    sys.exit(1 if failed or passed == 0 else 0)


if __name__ == "__main__":
    main()
