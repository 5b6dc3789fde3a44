#!/usr/bin/env python3
"""Counts the test cases in JUnit XML result files (gtest, rostest) and prints
"<passed> <failed> <skipped>". A result file that cannot be parsed counts as one failure.
rostest writes a wrapper file (rostest-*.xml) with one case that fails when the launch or the test
process fails, beside the test's own cases (rosunit-*.xml): a wrapper counts only when it failed.
(catkin_test_results double-counts gtest 1.12 files, which carry totals at two levels.)"""
import pathlib
import sys
import xml.etree.ElementTree as ET

passed = failed = skipped = 0
for path in sorted(pathlib.Path(sys.argv[1]).rglob("*.xml")):
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as error:
        print(f"{path}: unreadable ({error})", file=sys.stderr)
        failed += 1
        continue
    wrapper = path.name.startswith("rostest-")
    for case in root.iter("testcase"):
        if case.find("failure") is not None or case.find("error") is not None:
            failed += 1
            print(f"FAILED: {path.name}: {case.get('classname')}.{case.get('name')}", file=sys.stderr)
        elif wrapper:
            continue
        elif case.find("skipped") is not None or case.get("status") == "notrun":
            skipped += 1
        else:
            passed += 1
print(passed, failed, skipped)
