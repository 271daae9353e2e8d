#!/usr/bin/env python3
"""scripts/doc_references.py on synthetic trees: a link to a missing page or heading, a path that
names no file (in a page or in a scene's comment) and a table without a section of input.md are
each reported with file and line (exit 1), while links, headings, paths, patterns and tables
that exist pass (exit 0); a folder without a README exits 2.
usage: check_doc_references.py PROJECT_SOURCE_DIR WORK_DIR"""
import pathlib
import shutil
import subprocess
import sys

project, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
script = project / "scripts" / "doc_references.py"

INPUT_MD = "# Input\n\n## `[output]`\n\n## `[[mesh]]` (any number)\n\n## `[decomposition]`\n"
GOOD = {
    "README.md": "See [the input](docs/input.md#decomposition) and `scripts/demo.sh`, the\n"
                 "`[output]` table, `[mesh.motion]` and [[mesh]]; files `inputs/x/{a,b}.toml`,\n"
                 "`src/core/*.hpp`, `<output.dir>/checkpoint.h5`, `scripts/<name>.py`.\n"
                 "```\n# not a heading\n```\n[web](https://example.org/x)\n",
    "docs/input.md": INPUT_MD,
    "docs/other.md": "# Other\n\nBack to [the start](../README.md) and [this](#other).\n",
    "scripts/demo.sh": "",
    "src/core/A.hpp": "",
    "inputs/x/a.toml": "# Run: scripts/demo.sh\nfile = \"scripts/not_checked.stl\"\n",
    "inputs/x/b.toml": "",
}


def run(files):
    shutil.rmtree(work, ignore_errors=True)
    for name, text in files.items():
        (work / name).parent.mkdir(parents=True, exist_ok=True)
        (work / name).write_text(text)
    result = subprocess.run([sys.executable, str(script), str(work)], capture_output=True,
                            text=True)
    return result.returncode, result.stdout


failures = []


def expect(what, got, wanted):
    if got != wanted:
        failures.append(f"{what}: got {got!r}, wanted {wanted!r}")


code, out = run(GOOD)
expect("good tree: exit", code, 0)
expect("good tree: report", out.strip().splitlines()[-1:],
       ["doc_references: 0 problem(s) in 5 files"])

offences = {
    "missing page": ("README.md", "[x](docs/gone.md)\n", "README.md:1: link to missing 'docs/gone.md'"),
    "missing heading": ("docs/other.md", "[x](input.md#checkpoint)\n",
                        "docs/other.md:1: no heading '#checkpoint' in input.md"),
    "missing heading, bracketed text": ("docs/other.md", "see [`[x]`](#x).\n",
                                        "docs/other.md:1: no heading '#x' in other.md"),
    "missing script": ("README.md", "Run scripts/tillage_quickstart.sh.\n",
                       "README.md:1: no file 'scripts/tillage_quickstart.sh'"),
    "missing file in a scene comment": ("inputs/x/b.toml", "dt = 1  # see scripts/gone.py\n",
                                        "inputs/x/b.toml:1: no file 'scripts/gone.py'"),
    "pattern matching nothing": ("README.md", "`src/core/*.cu`\n", "README.md:1: no file 'src/core/*.cu'"),
    "brace naming a missing file": ("README.md", "`inputs/x/{a,c}.toml`\n",
                                    "README.md:1: no file 'inputs/x/{a,c}.toml'"),
    "table without a section": ("docs/other.md", "the `[checkpoint]` table\n",
                                "docs/other.md:1: no section of docs/input.md for the table "
                                "[checkpoint]"),
}
for what, (name, text, wanted) in offences.items():
    code, out = run({**GOOD, name: text})
    expect(f"{what}: exit", code, 1)
    if wanted not in out:
        failures.append(f"{what}: '{wanted}' not in {out!r}")

shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
code, _ = run({"docs/input.md": INPUT_MD})
expect("no README: exit", code, 2)

for failure in failures:
    print(failure)
print(f"check_doc_references: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
