#!/usr/bin/env python3
"""scripts/source_shape.py on synthetic trees: a file one line over the limit and a function one
line over are reported (exit 1); the same at the limits pass (exit 0); a missing directory exits 2.
usage: check_source_shape.py PROJECT_SOURCE_DIR WORK_DIR"""
import pathlib
import shutil
import subprocess
import sys

project, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
script = project / "scripts" / "source_shape.py"


def function(name, body_lines):
    body = "".join(f"  int v{k} = {k};\n" for k in range(body_lines))
    return f"int {name}(int a) const {{\n{body}}}\n"


def run(files):
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    for name, text in files.items():
        (work / name).write_text(text)
    result = subprocess.run([sys.executable, str(script), str(work), "--max-file", "100",
                             "--max-function", "10"], capture_output=True, text=True)
    return result.returncode, result.stdout


failures = []
def expect(what, got, wanted):
    if got != wanted:
        failures.append(f"{what}: got {got!r}, wanted {wanted!r}")

code, out = run({"a.cpp": function("fine", 10) + "\n" * 50, "b.hpp": "x\n" * 100})
expect("at the limits: exit", code, 0)
code, out = run({"a.cpp": function("too_long", 11)})
expect("function of 11 lines: exit", code, 1)
expect("function named", "too_long has 11 lines" in out, True)
code, out = run({"b.hpp": "x\n" * 101})
expect("file of 101 lines: exit", code, 1)
expect("file named", "b.hpp: 101 lines" in out, True)
code, out = run({"c.cpp": "void f() {\n  if (x) {\n" + "    y();\n" * 20 + "  }\n}\n"})
expect("control block counted in its function: exit", code, 1)
code, out = run({"d.cpp": "void g() {\n  call(A{\n" + "    1,\n" * 20 + "  });\n}\n"})
expect("brace initializer is not a function; its function is too long: exit", code, 1)
expect("the function is g", "function g has" in out, True)
result = subprocess.run([sys.executable, str(script), str(work / "missing")],
                        capture_output=True, text=True)
expect("missing directory: exit", result.returncode, 2)
shutil.rmtree(work, ignore_errors=True)
for f in failures:
    print("FAIL", f)
print(f"check_source_shape: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
