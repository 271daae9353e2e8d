#!/usr/bin/env python3
"""Checks that what the README, docs/ and the shipped scenes name exists:
- every Markdown link [text](target) in README.md and docs/*.md: the file or folder, relative to
  the page (web links aside), and its #anchor among the target page's headings;
- every path of the project named in their text or comments (scripts/, docs/, inputs/, src/,
  tests/, bench/, .ci/ and on; a * matches as in a shell, a <placeholder> is not checked);
- every scene table named in backticks (`[output]`, `[[mesh]]`, `[mesh.motion]`): a heading of
  docs/input.md for its top-level table.
Prints each problem as file:line: what, and exits 1 when there is one; 2 on a bad call.
usage: doc_references.py PROJECT_DIR"""
import glob
import pathlib
import re
import sys

ROOTS = ("scripts", "docs", "inputs", "src", "tests", "bench", ".ci", "cmake")
PATH = re.compile(r"(?<![\w./$-])((?:%s)/(?:[\w./*<>-]|\{[\w.,-]*\})*)" %
                  "|".join(re.escape(r) for r in ROOTS))
LINK = re.compile(r"\[(?:[^\[\]]|\[[^\]]*\])*\]\(([^)\s]+)\)")
TABLE = re.compile(r"`\[\[?([a-z_]+)(?:\.[a-z_.]+)?\]\]?`|\[\[([a-z_]+)\]\]")
HEADING = re.compile(r"^#+\s+(.*?)\s*$")


def slug(heading):
    """The anchor GitHub gives a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"[^\w\- ]", "", heading.lower())
    return text.replace(" ", "-")


def anchors(page):
    seen, out = {}, set()
    in_code = False
    for line in page.read_text().splitlines():
        if line.startswith("```"):
            in_code = not in_code
        match = None if in_code else HEADING.match(line)
        if not match:
            continue
        base = slug(match.group(1))
        count = seen.get(base, 0)
        seen[base] = count + 1
        out.add(base if count == 0 else f"{base}-{count}")
    return out


def table_headings(input_md):
    names = set()
    for line in input_md.read_text().splitlines():
        match = HEADING.match(line)
        if match:
            names.update(re.findall(r"\[\[?([a-z_]+)\]\]?", match.group(1)))
    return names


def expand_braces(token):
    """The paths a shell makes of `a{b,c}d`: abd and acd."""
    match = re.search(r"\{([^{}]*)\}", token)
    if not match:
        return [token]
    return [path for part in match.group(1).split(",")
            for path in expand_braces(token[:match.start()] + part + token[match.end():])]


def path_exists(project, token):
    if not token or "<" in token or ">" in token:
        return True
    for path in expand_braces(token):
        if not (glob.glob(str(project / path)) if "*" in path else (project / path).exists()):
            return False
    return True


def check_links(project, page, number, line, problems):
    for target in LINK.findall(line):
        if re.match(r"[a-z]+:", target):
            continue
        path, _, anchor = target.partition("#")
        where = page if not path else (page.parent / path)
        if not where.exists():
            problems.append(f"{page.relative_to(project)}:{number}: link to missing '{path}'")
        elif anchor and where.suffix == ".md" and anchor not in anchors(where):
            problems.append(
                f"{page.relative_to(project)}:{number}: no heading '#{anchor}' in {where.name}")


def check_file(project, page, tables, problems):
    is_markdown = page.suffix == ".md"
    for number, line in enumerate(page.read_text().splitlines(), 1):
        if is_markdown:
            check_links(project, page, number, line, problems)
            for quoted, bare in TABLE.findall(line):
                name = quoted or bare
                if name not in tables:
                    problems.append(f"{page.relative_to(project)}:{number}: no section of "
                                    f"docs/input.md for the table [{name}]")
        text = line if is_markdown else line.partition("#")[2]  # a scene's comments only
        for token in PATH.findall(text):
            token = token.rstrip(".,:;")
            if not path_exists(project, token):
                problems.append(f"{page.relative_to(project)}:{number}: no file '{token}'")


def main():
    if len(sys.argv) != 2 or not pathlib.Path(sys.argv[1], "README.md").is_file():
        print(__doc__.splitlines()[-1], file=sys.stderr)
        return 2
    project = pathlib.Path(sys.argv[1]).resolve()
    pages = [project / "README.md", *sorted((project / "docs").glob("*.md")),
             *sorted((project / "inputs").rglob("*.toml"))]
    tables = table_headings(project / "docs" / "input.md")
    problems = []
    for page in pages:
        check_file(project, page, tables, problems)
    for problem in problems:
        print(problem)
    print(f"doc_references: {len(problems)} problem(s) in {len(pages)} files")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
