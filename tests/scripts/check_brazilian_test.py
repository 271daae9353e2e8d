#!/usr/bin/python3
"""Checks scripts/brazilian_test.py end to end on one small realisation, its resume and its
refusals.

    check_brazilian_test.py SOURCE_DIR SOLVER WORK_DIR

One realisation (D = 24 mm, about 470 spheres in the disc and 200 in the bar) must show what
strength tests of a brittle bonded specimen show:
- the bar is elastic, then breaks: its strength lies between 5 % and 100 % of the cement's
  (a section cannot hold more than its bonds, whose areas cover about the section once at this
  packing), it breaks at a strain of at most 2 sigma_c / E_b (a bond that takes the bar's
  strain breaks at sigma_c / E_b), and afterwards it holds less than 10 % of its peak pull;
- the disc splits: after the peak the platens' load falls by more than half, and more than
  60 % of the broken bonds lie within D/6 of the loaded diameter (a third of the disc's width);
- pressed instead, the same bar holds more than it does pulled (cement and grains both carry
  compression, only the cement tension);
- the Brazilian strength lies within a factor of 3 of the direct one (the same cemented
  packing, measured two ways).
A second call finds the realisation done and runs nothing; the same folder with another grain
modulus is refused; bad options are refused with exit status 2 before any run. Exit 0 when all
holds, 1 otherwise.
"""
import csv
import pathlib
import shutil
import subprocess
import sys

CEMENT_STRENGTH, CEMENT_YOUNG = 2.0e4, 2.0e6


def run(script, solver, out, *extra):
    return subprocess.run([sys.executable, str(script), "--out", str(out), "--solver", solver,
                           "--realisations", "1", "--size", "24", "--rate", "0.02", *extra],
                          capture_output=True, text=True)


def check_row(row, problems):
    direct, ratio = float(row["tensile_direct_pa"]), float(row["ratio"])
    if not 0.05 * CEMENT_STRENGTH <= direct <= CEMENT_STRENGTH:
        problems.append(f"direct strength {direct} Pa outside 5-100 % of the cement's")
    if float(row["bar_strain_at_peak"]) > 2 * CEMENT_STRENGTH / CEMENT_YOUNG:
        problems.append(f"the bar broke late, at strain {row['bar_strain_at_peak']}")
    if float(row["bar_pull_left"]) >= 0.1:
        problems.append(f"the broken bar still holds {row['bar_pull_left']} of its peak pull")
    if float(row["disc_load_drop"]) <= 0.5:
        problems.append(f"the disc's load fell by only {row['disc_load_drop']} after its peak")
    if float(row["broken_central_share"]) <= 0.6:
        problems.append(f"only {row['broken_central_share']} of the broken bonds lie near the "
                        "loaded diameter")
    if float(row["compressive_over_direct"]) <= 1:
        problems.append(f"the pressed bar held only {row['compressive_over_direct']} of its pull")
    if not 1 / 3 <= ratio <= 3:
        problems.append(f"Brazilian over direct strength {ratio} is not within a factor of 3")


def main():
    source, solver, work = pathlib.Path(sys.argv[1]), sys.argv[2], pathlib.Path(sys.argv[3])
    script = source / "scripts" / "brazilian_test.py"
    shutil.rmtree(work, ignore_errors=True)
    problems = []
    out = work / "study"
    first = run(script, solver, out)
    if first.returncode != 0:
        print(first.stdout, first.stderr)
        sys.exit(1)
    with open(out / "strength.csv") as f:
        rows = list(csv.DictReader(f))
    if len(rows) != 1:
        problems.append(f"strength.csv holds {len(rows)} rows, not 1")
    else:
        check_row(rows[0], problems)
    if not (out / "strength.png").is_file():
        problems.append("no strength.png")
    log = out / "1-disc" / "solver.log"
    stamp = log.stat().st_mtime_ns
    again = run(script, solver, out)
    if again.returncode != 0 or log.stat().st_mtime_ns != stamp:
        problems.append("the second call ran the finished realisation again")
    for bad, option in ((["--size", "5"], "--size"), (["--rate", "0"], "--rate"),
                        (["--realisations", "0"], "--realisations"), (["--seed", "-1"], "--seed"),
                        (["--np", "0"], "--np")):
        refused = run(script, solver, work / "refused", *bad)
        if refused.returncode != 2 or option not in refused.stderr:
            problems.append(f"{bad} was not refused naming {option}: {refused.stderr.strip()}")
        if (work / "refused").exists():
            problems.append(f"{bad} wrote output before refusing")
    other = run(script, solver, out, "--grain-young", "2e8")
    if other.returncode != 2 or "--grain-young" not in other.stderr:
        problems.append(f"a study folder of other settings was not refused: {other.stderr.strip()}")
    print(first.stdout)
    for p in problems:
        print("FAIL:", p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
