#!/usr/bin/env python3
"""Writes BUILD's compile commands one entry per source file, for tools that read one file at a
time (clang-tidy, clang -fsyntax-only): a unity batch's entry becomes one entry per file it
includes, and GCC's precompiled-header flags go (clang cannot read GCC's precompiled headers;
every file includes what it uses).

Usage: scripts/per_file_compile_db.py BUILD_DIR OUT_DIR  (writes OUT_DIR/compile_commands.json)
"""
import json
import os
import re
import sys

UNITY_INCLUDE = re.compile(r'^#include "(.+)"$')
PCH_FLAGS = re.compile(r" -Winvalid-pch| -include \S*cmake_pch\.hxx")


def per_file(entry):
    command = PCH_FLAGS.sub("", entry["command"])
    unity = entry["file"]
    if "/Unity/unity_" not in unity:
        return [dict(entry, command=command)]
    with open(unity, encoding="utf-8") as f:
        sources = [m.group(1) for m in map(UNITY_INCLUDE.match, f.read().splitlines()) if m]
    return [dict(entry, file=src, command=command.replace(unity, src)) for src in sources]


def main():
    build, out = sys.argv[1], sys.argv[2]
    with open(os.path.join(build, "compile_commands.json"), encoding="utf-8") as f:
        db = json.load(f)
    entries = [e for entry in db for e in per_file(entry)]
    with open(os.path.join(out, "compile_commands.json"), "w", encoding="utf-8") as f:
        json.dump(entries, f, indent=1)


if __name__ == "__main__":
    main()
