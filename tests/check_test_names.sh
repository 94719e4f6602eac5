#!/bin/sh
# CTest registers each Catch2 test case by its name (catch_discover_tests) and runs the case by
# passing that name to the test program. A name holding a semicolon is split as a CMake list,
# so CTest runs a filter that matches nothing and the case never runs while the test "passes";
# a name beginning with '-' is read as a command-line option and the case fails without
# running. This check fails on any such name.
status=0
if grep -n 'TEST_CASE("[^"]*;' "$1"/test_*.cpp; then
  echo "test case names above contain ';' and would never run under CTest" >&2
  status=1
fi
if grep -n 'TEST_CASE("-' "$1"/test_*.cpp; then
  echo "test case names above begin with '-' and would be read as an option under CTest" >&2
  status=1
fi
exit $status
