#!/usr/bin/env python3
"""Checks the shape of the sources under a directory: no file over MAX_FILE lines and no function
over MAX_FUNCTION lines (a function: a definition whose body opens with '{' at the end of its
signature and closes with '}' at the signature's indentation; lambdas and control blocks are
part of their function). Prints each offender; exit 1 if any, 0 otherwise.
usage: source_shape.py SRC_DIR [--max-file N] [--max-function N]"""
import argparse
import pathlib
import re
import sys

SOURCE_SUFFIXES = {".hpp", ".cpp", ".cu", ".cuh", ".in"}
NOT_FUNCTIONS = re.compile(
    r"^\s*(if|else|for|while|switch|do|try|catch|namespace|struct|class|union|enum|extern)\b"
    r"|^\s*(template\s*<.*>\s*)?(struct|class|union)\b|=\s*\{$|=\s*\[|^\s*return\b|\)\s*->.*\{$|\]\s*\(.*\)\s*(mutable\s*)?\{$")


FUNCTION_BODY = re.compile(r"\)\s*((const|override|final|noexcept|mutable)\s*)*\{$")


def signature_start(lines, i):
    """Index of the first line of the statement that ends at line i (a '{' line)."""
    j = i
    while j > 0:
        previous = lines[j - 1].rstrip()
        if not previous or previous.endswith((";", "{", "}", ":")) or previous.lstrip().startswith(("//", "#", "///")):
            break
        j -= 1
    return j


def long_functions(path, limit):
    lines = path.read_text(encoding="utf-8").split("\n")
    found = []
    for i, line in enumerate(lines):
        stripped = line.rstrip()
        if not stripped.endswith("{") or "(" not in "".join(lines[signature_start(lines, i):i + 1]):
            continue
        start = signature_start(lines, i)
        head = " ".join(l.strip() for l in lines[start:i + 1])
        if NOT_FUNCTIONS.search(head) or not FUNCTION_BODY.search(head):
            continue
        indent = len(lines[start]) - len(lines[start].lstrip())
        end = i + 1
        while end < len(lines):
            candidate = lines[end]
            if candidate.strip().startswith("}") and len(candidate) - len(candidate.lstrip()) == indent:
                break
            end += 1
        body = end - i - 1
        if body > limit:
            name = re.search(r"([~A-Za-z_][A-Za-z0-9_:]*)\s*\(", head)
            found.append((i + 1, name.group(1) if name else head[:40], body))
    return found


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("src")
    parser.add_argument("--max-file", type=int, default=500)
    parser.add_argument("--max-function", type=int, default=60)
    args = parser.parse_args()
    root = pathlib.Path(args.src)
    if not root.is_dir():
        print(f"source_shape: {root} is not a directory", file=sys.stderr)
        return 2
    problems = 0
    for path in sorted(p for p in root.rglob("*") if p.suffix in SOURCE_SUFFIXES):
        count = len(path.read_text(encoding="utf-8").split("\n")) - 1
        if count > args.max_file:
            print(f"{path}: {count} lines (at most {args.max_file})")
            problems += 1
        for line, name, body in long_functions(path, args.max_function):
            print(f"{path}:{line}: function {name} has {body} lines (at most {args.max_function})")
            problems += 1
    print(f"source_shape: {problems} problem(s) in {root}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
