#!/usr/bin/env python3
"""Checks the layers of the sources under SRC_DIR (docs/architecture.md, "Layers"): a file in
src/<layer>/ includes only headers of its own layer or those below it (core, then engine, then
comm, then app); MPI (<mpi.h> or an MPI_ name outside comments and strings) appears only in comm;
CUDA headers (<cuda...>, <thrust/...>, <cub/...>, a .cuh) only in .cu and .cuh files. Prints each
offence; exit 1 if any, 0 otherwise, 2 when SRC_DIR is not a directory.
usage: layers.py SRC_DIR"""
import pathlib
import re
import sys

LAYERS = ["core", "engine", "comm", "app"]
SOURCE_SUFFIXES = {".hpp", ".cpp", ".cu", ".cuh", ".in"}
OWN_INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z]+)/')
MPI = re.compile(r"\bMPI_\w+|#\s*include\s*<mpi\.h>")
CUDA_INCLUDE = re.compile(r'#\s*include\s*(<(cuda|thrust/|cub/)[^>]*>|"[^"]*\.cuh")')
COMMENT_OR_STRING = re.compile(r'//[^\n]*|/\*.*?\*/|"(\\.|[^"\\\n])*"', re.S)


def code_only(text):
    """`text` with each comment and string literal blanked (its line breaks kept)."""
    def blank(match):
        token = match.group(0)
        return " " + "\n" * token.count("\n")
    return COMMENT_OR_STRING.sub(blank, text)


def offences(path, layer):
    text = path.read_text(encoding="utf-8")
    found = []
    for number, line in enumerate(text.split("\n"), start=1):
        match = OWN_INCLUDE.match(line)
        if match and match.group(1) in LAYERS and LAYERS.index(match.group(1)) > LAYERS.index(layer):
            found.append(f"{path}:{number}: {layer} includes {match.group(1)}/ (a layer above it)")
        if CUDA_INCLUDE.search(line) and path.suffix not in {".cu", ".cuh"}:
            found.append(f"{path}:{number}: a CUDA header outside .cu/.cuh files")
    if layer != "comm":
        for number, line in enumerate(code_only(text).split("\n"), start=1):
            if MPI.search(line):
                found.append(f"{path}:{number}: MPI outside src/comm")
    return found


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[1])
    if not root.is_dir():
        print(f"layers: {root} is not a directory", file=sys.stderr)
        return 2
    problems = []
    for layer in LAYERS:
        for path in sorted(p for p in (root / layer).rglob("*") if p.suffix in SOURCE_SUFFIXES):
            problems += offences(path, layer)
    unknown = sorted(d.name for d in root.iterdir() if d.is_dir() and d.name not in LAYERS)
    problems += [f"{root / name}: a folder outside the layers {', '.join(LAYERS)}" for name in unknown]
    for problem in problems:
        print(problem)
    print(f"layers: {len(problems)} problem(s) in {root}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
