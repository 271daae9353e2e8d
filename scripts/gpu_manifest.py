"""Writes the test suite of a build as a bash file for the GPU machine (scripts/gpu_check.sh):
one `run_test NAME TIMEOUT SKIP_CODE [VAR=VALUE...] -- COMMAND...` line per ctest test, in
ctest's order, with the build's paths replaced by the bundle's: test executables and gpudem-mpi
by ${BUNDLE}/bin/..., the source tree by ${SRC}, the build's test folder (work and fixture
folders) by ${WORK}, mpirun and mpiexec by the name on the PATH there and python3 by ${PYTHON}.
Usage: python3 gpu_manifest.py BUILD_DIR SOURCE_DIR OUT.sh"""
import json
import os
import subprocess
import sys

# Tests that need what the GPU machine lacks, with the reason.
LEFT_OUT = {"paraview_opens_snapshots": "ParaView is not installed there"}
LAUNCHERS = {"mpirun": "mpirun", "mpiexec": "mpirun", "python3": "${PYTHON}"}


def shell_word(text):
    """`text` in double quotes, with ${BUNDLE}, ${SRC}, ${WORK} and ${PYTHON} left to expand."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"').replace("`", "\\`")
    escaped = escaped.replace("$", "\\$")
    for var in ("BUNDLE", "SRC", "WORK", "PYTHON"):
        escaped = escaped.replace("\\${" + var + "}", "${" + var + "}")
    return '"' + escaped + '"'


class PathMap:
    def __init__(self, build, source):
        self.build = os.path.realpath(build)
        self.tests = os.path.join(self.build, "tests")
        self.source = os.path.realpath(source)
        self.executables = set()

    def word(self, arg):
        if os.path.isabs(arg) and os.path.basename(arg) in LAUNCHERS and "/bin/" in arg:
            return LAUNCHERS[os.path.basename(arg)]
        path = os.path.normpath(arg) if os.path.isabs(arg) else arg
        if path == os.path.join(self.build, "gpudem-mpi"):
            return "${BUNDLE}/bin/gpudem-mpi"
        if os.path.dirname(path) == self.tests and os.path.isfile(path) and os.access(path, os.X_OK):
            self.executables.add(path)
            return "${BUNDLE}/bin/" + os.path.basename(path)
        if path.startswith(self.tests + "/"):
            return "${WORK}/" + path[len(self.tests) + 1:]
        if path.startswith(self.source + "/"):
            return "${SRC}/" + path[len(self.source) + 1:]
        if path.startswith(self.build + "/"):
            sys.exit(f"gpu_manifest: {arg} is in the build but not in the bundle")
        return arg


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    build, source, out = sys.argv[1:]
    listing = subprocess.run(["ctest", "--show-only=json-v1"], cwd=build, check=True,
                             capture_output=True, text=True).stdout
    paths = PathMap(build, source)
    lines = ["# The test suite of " + paths.build + ", written by scripts/gpu_manifest.py."]
    for test in json.loads(listing)["tests"]:
        name = test["name"]
        if name in LEFT_OUT:
            lines.append(f"# {name}: left out, {LEFT_OUT[name]}")
            continue
        props = {p["name"]: p["value"] for p in test.get("properties", [])}
        env = props.get("ENVIRONMENT", [])
        words = [name, str(int(props.get("TIMEOUT", 1500))), str(props.get("SKIP_RETURN_CODE", -1))]
        words += [shell_word(e) for e in env] + ["--"]
        words += [shell_word(paths.word(a)) for a in test["command"]]
        lines.append("run_test " + " ".join(words))
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(out + ".executables", "w") as f:
        f.write("\n".join(sorted(paths.executables)) + "\n")


if __name__ == "__main__":
    main()
