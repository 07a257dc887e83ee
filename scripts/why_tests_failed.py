#!/usr/bin/env python3
"""Why the failed tests of a ctest run failed, in a few lines each, for the end of a long log.

CI keeps only parts of a 600-test log; ctest's --output-on-failure puts each failure's output
where the test ended, in the middle. This prints, after the run, each failed test's assertion
messages and retry notes from every attempt (Testing/Temporary/LastTest.log), at most
MAX_LINES per test, each line cut to MAX_WIDTH characters.
"""
import pathlib
import re
import sys

MAX_LINES = 14
MAX_WIDTH = 240
# Lines that say why: GoogleTest's failure header and what follows it, the tests' retry notes,
# a script test's own error lines.
INTERESTING = re.compile(
    r"Failure|Expected|Which is|actual|Value of|tried again|lost to the machine|FAIL|error|"
    r"Error|not |never|no ")


def runs(log: str):
    """(test name, output) of every run in LastTest.log, in order."""
    pattern = re.compile(
        r"^\d+/\d+ Test: (?P<name>.+?)\n.*?^Output:\n-+\n(?P<out>.*?)^<end of output>",
        re.S | re.M)
    for m in pattern.finditer(log):
        yield m.group("name").strip(), m.group("out")


def main() -> int:
    build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "build")
    failed_log = build / "Testing" / "Temporary" / "LastTestsFailed.log"
    if not failed_log.exists():
        return 0
    failed = [line.split(":", 1)[1].split("  #")[0].strip()
              for line in failed_log.read_text().splitlines() if ":" in line]
    log = (build / "Testing" / "Temporary" / "LastTest.log").read_text(errors="replace")
    print("== why the failed tests failed (every attempt; full output above)")
    for name in failed:
        print(f"-- {name}")
        lines = []
        for run_name, out in runs(log):
            if run_name != name:
                continue
            lines.append("   (attempt)")
            lines += ["   " + l.strip()[:MAX_WIDTH] for l in out.splitlines()
                      if INTERESTING.search(l) and not l.startswith("[")]
        for line in lines[:MAX_LINES]:
            print(line)
        if len(lines) > MAX_LINES:
            print(f"   ... {len(lines) - MAX_LINES} more lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
