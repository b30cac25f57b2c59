#!/usr/bin/env python3
"""Every case test/sanitizers/normal_build_only.txt keeps out of the sanitizer stage is a core gtest case that
exists: a case renamed or removed would otherwise leave a stale name behind, and its new name would run there
unnoticed or the list would hide nothing it says it does."""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1])
defined = set()
for source in (root / "test" / "core").glob("*.cpp"):
    for suite, case in re.findall(r"\bTEST(?:_F)?\(\s*(\w+)\s*,\s*(\w+)\s*\)", source.read_text()):
        defined.add(f"{suite}.{case}")
listed = root / "test" / "sanitizers" / "normal_build_only.txt"
missing = []
for number, line in enumerate(listed.read_text().splitlines(), 1):
    name = line.split("#", 1)[0].strip()
    if name and name not in defined:
        missing.append(f"{listed}:{number}: {name} is not a TEST or TEST_F case of test/core")
print("\n".join(missing) if missing else f"every listed case exists ({len(defined)} cases in test/core)")
sys.exit(1 if missing else 0)
