#!/usr/bin/env python3
"""scripts/layers.py on synthetic trees: each kind of offence is reported with its file and line
(exit 1) — an include of a layer above, MPI outside comm, a CUDA header in a .cpp, a folder
outside the layers — while the same text in a comment or string, or in the allowed place, passes
(exit 0); a missing directory exits 2.
usage: check_layers.py PROJECT_SOURCE_DIR WORK_DIR"""
import pathlib
import shutil
import subprocess
import sys

project, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
script = project / "scripts" / "layers.py"


def run(files):
    shutil.rmtree(work, ignore_errors=True)
    for layer in ("core", "engine", "comm", "app"):
        (work / layer).mkdir(parents=True)
    for name, text in files.items():
        (work / name).parent.mkdir(parents=True, exist_ok=True)
        (work / name).write_text(text)
    result = subprocess.run([sys.executable, str(script), str(work)], capture_output=True, text=True)
    return result.returncode, result.stdout


failures = []
def expect(what, got, wanted):
    if got != wanted:
        failures.append(f"{what}: got {got!r}, wanted {wanted!r}")

allowed = {
    "core/a.hpp": '#include "core/b.hpp"\n// MPI_Allreduce in a comment\nconst char* s = "MPI_x";\n',
    "engine/e.hpp": '#include "core/a.hpp"\n#include "engine/f.hpp"\n',
    "engine/k.cu": '#include <cuda_runtime.h>\n#include "engine/p.cuh"\n',
    "comm/m.cpp": '#include <mpi.h>\n#include "engine/e.hpp"\nvoid f() { MPI_Barrier(MPI_COMM_WORLD); }\n',
    "app/main.cpp": '#include "comm/m.hpp"\n#include "engine/e.hpp"\n/* MPI_Init\n spans lines */\n',
}
code, out = run(allowed)
expect("allowed tree: exit", code, 0)

code, out = run({"core/a.hpp": '// header\n#include "engine/e.hpp"\n'})
expect("core including engine: exit", code, 1)
expect("core including engine: named", "core/a.hpp:2: core includes engine/" in out, True)
code, out = run({"engine/e.hpp": '#include "comm/m.hpp"\n'})
expect("engine including comm: named", "engine/e.hpp:1: engine includes comm/" in out, True)
code, out = run({"app/r.cpp": '/* a\n comment */\nvoid f() { MPI_Allreduce(); }\n'})
expect("MPI in app: exit", code, 1)
expect("MPI in app: line after a two-line comment", "app/r.cpp:3: MPI outside src/comm" in out, True)
code, out = run({"engine/d.hpp": "#include <mpi.h>\n"})
expect("mpi.h in engine: named", "engine/d.hpp:1: MPI outside src/comm" in out, True)
code, out = run({"engine/h.cpp": "#include <thrust/sort.h>\n"})
expect("thrust in a .cpp: named", "engine/h.cpp:1: a CUDA header outside .cu/.cuh files" in out, True)
code, out = run({"kernels/x.hpp": "\n"})
expect("a folder outside the layers: exit", code, 1)
expect("a folder outside the layers: named", "kernels: a folder outside the layers" in out, True)
result = subprocess.run([sys.executable, str(script), str(work / "missing")],
                        capture_output=True, text=True)
expect("missing directory: exit", result.returncode, 2)
shutil.rmtree(work, ignore_errors=True)

for failure in failures:
    print(failure)
print(f"check_layers: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
