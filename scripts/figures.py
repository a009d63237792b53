#!/usr/bin/env python3
"""The figures README.md and docs/*.md quote, measured in one place (issue 39).

  scripts/figures.py write HEXCAL   # run the commands, write docs/figures.json (a few minutes)
  scripts/figures.py check HEXCAL   # the docs quote docs/figures.json; the fast figures are still hexcal's (seconds)

Each figure has a kind:
  exact     deterministic output (a count, a seeded ratio or RMS). A doc quotes it
            to its own precision: |quoted - recorded| <= half a unit of the
            quote's last digit ("about 25 times" for 25.2).
  timing    wall seconds, the median of a few runs on the machine that wrote
            the file. A doc's figure (or range) must lie within TIMING_FACTOR of
            the record; `check` times the fast ones again, within RERUN_FACTOR
            (a shared machine's hour can be twice as slow as another's).
  recorded  from a long benchmark or the LinuxCNC loop (bench/, tests/cli/
            readme_machine_loop.sh): the value is written below, with where it
            came from; `write` copies it, `check` compares the docs with it only.
`fast` figures are measured again by `check` (the CTest case docs/figures),
the others only by `write`: their record is what the docs are checked against.
"""
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

TIMING_FACTOR = 3.0  # a doc's timing against the record (a loaded hour is 2-3 times slower)
RERUN_FACTOR = 4.0  # the record against a timing taken now, on a shared machine
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RECORD = os.path.join(ROOT, "docs", "figures.json")


def run(hexcal, *args, cwd=None):
    """stdout of hexcal ARGS; fails on a non-zero exit."""
    done = subprocess.run([hexcal, *args], cwd=cwd, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError("hexcal %s: exit %d: %s" % (" ".join(args), done.returncode, done.stderr[-500:]))
    return done.stdout


def seconds(hexcal, *args, runs=3, cwd=None):
    """Median wall time of `runs` runs of hexcal ARGS."""
    times = []
    for _ in range(runs):
        start = time.monotonic()
        run(hexcal, *args, cwd=cwd)
        times.append(time.monotonic() - start)
    return round(statistics.median(times), 3)


def grab(pattern, text):
    found = re.search(pattern, text, re.M)
    if not found:
        raise RuntimeError("no /%s/ in:\n%s" % (pattern, text[-2000:]))
    return float(found.group(1))


class Work:
    """One scratch folder per run, and the outputs several figures share."""

    def __init__(self, hexcal):
        self.hexcal = hexcal
        self.dir = tempfile.mkdtemp(prefix="hexcal-figures-")
        self.cache = {}

    def once(self, key, make):
        if key not in self.cache:
            self.cache[key] = make()
        return self.cache[key]

    def candidates_json(self):
        return self.once("candidates", lambda: json.loads(run(
            self.hexcal, "candidates", "--robot", "inria-left-hand", "--kind", "random", "--count", "1000",
            "--out", os.path.join(self.dir, "random.csv"), "--force", "--json")))

    def demo(self):
        """The README's first command; its output and wall time."""
        def make():
            start = time.monotonic()
            out = run(self.hexcal, "demo", "--out", "example", cwd=self.dir)
            return out, round(time.monotonic() - start, 2)
        return self.once("demo", make)

    def validate_nominal(self):
        self.demo()
        return self.once("validate", lambda: run(
            self.hexcal, "validate", "--robot", "inria-left-hand", "--measurements",
            "example/results/calibration_measurements.csv", cwd=self.dir))

    def random_demo(self):
        return self.once("random", lambda: run(
            self.hexcal, "demo", "--poses", "64", "--holdout", "0", "--random-poses", "--out", "run64", cwd=self.dir))


TIMING_OF_DEMO = r"in about ([0-9.]+) s, and leaves"
FIGURES = [
    # (id, kind, fast, measure(work) or recorded value, what, [(file, regex with one group)])
    ("candidates_random_draws", "exact", True, lambda w: w.candidates_json()["draws"],
     "draws for 1000 random INRIA candidates (seed 1)",
     [("docs/performance.md", r"1000 of ([0-9  ]+) draws accepted")]),
    ("candidates_random_acceptance_percent", "exact", True,
     lambda w: round(100.0 * 1000 / w.candidates_json()["draws"], 3), "their acceptance, %",
     [("docs/performance.md", r"draws accepted \(([0-9.]+) %")]),
    ("candidates_random_seconds", "timing", True,
     lambda w: seconds(w.hexcal, "candidates", "--robot", "inria-left-hand", "--kind", "random", "--count",
                       "1000", "--out", os.path.join(w.dir, "r.csv"), "--force"),
     "`candidates --kind random --count 1000`, whole process",
     [("docs/performance.md", r"--count 1000`: ([0-9.]+) s,")]),
    ("candidates_boundary_count", "exact", True,
     lambda w: json.loads(run(w.hexcal, "candidates", "--robot", "inria-left-hand", "--kind", "boundary", "--out",
                              os.path.join(w.dir, "b.csv"), "--force", "--json"))["count"],
     "INRIA's boundary poses",
     [("README.md", r"the ([0-9]+) boundary\s+poses"), ("docs/performance.md", r"same\s+([0-9]+) poses to")]),
    ("candidates_boundary_seconds", "timing", True,
     lambda w: seconds(w.hexcal, "candidates", "--robot", "inria-left-hand", "--kind", "boundary", "--out",
                       os.path.join(w.dir, "b.csv"), "--force"),
     "`candidates --kind boundary`, whole process",
     [("docs/performance.md", r"\*\*([0-9.]+–[0-9.]+) s\*\* per process")]),
    ("fk_all_dietmaier_seconds", "timing", True,
     lambda w: seconds(w.hexcal, "fk", "--robot", os.path.join(ROOT, "tests/data/dietmaier-40-real.yaml"),
                       "--legs", "1,0.645275,1.086284,1.503439,1.281933,0.771071", "--all", runs=5),
     "`fk --all` on Dietmaier's platform, whole process",
     [("docs/performance.md", r"medians of 5 runs, [0-9-]+\): \*\*([0-9.]+–[0-9.]+) s\*\*")]),
    ("version_seconds", "timing", True, lambda w: seconds(w.hexcal, "--version", runs=5),
     "`hexcal --version`: the process start",
     [("docs/performance.md", r"`hexcal --version` takes\s+([0-9.]+) s")]),
    ("demo_seconds", "timing", False, lambda w: w.demo()[1], "`hexcal demo --out example`",
     [("README.md", TIMING_OF_DEMO)]),
    ("demo_from_pixels_corners", "exact", False,
     lambda w: grab(r"from pixels: 24 images, ([0-9]+) corners", w.demo()[0]), "corners of the demo's 24 images",
     [("docs/cli.md", r"from pixels: 24 images, ([0-9]+) corners")]),
    ("demo_from_pixels_rms_px", "exact", False,
     lambda w: grab(r"from pixels: .* reprojection RMS ([0-9.]+) px", w.demo()[0]), "their reprojection RMS, px",
     [("docs/cli.md", r"from pixels: .* reprojection RMS ([0-9.]+) px")]),
    ("demo_parameter_error_mean_cm", "exact", False,
     lambda w: grab(r"parameter error against the truth \(cm\): mean ([0-9.]+)", w.demo()[0]),
     "the demo's mean parameter error against the hidden truth, cm",
     [("docs/cli.md", r"parameter error against the truth \(cm\): mean ([0-9.]+)")]),
    ("demo_heldout_after_position_cm", "exact", False,
     lambda w: grab(r"after calibration:  position ([0-9.]+) cm", w.demo()[0]),
     "the demo's held-out position RMS after calibration, cm",
     [("docs/cli.md", r"after calibration:  position ([0-9.]+) cm")]),
    ("validate_nominal_position_ratio", "exact", False,
     lambda w: grab(r"FK error: position RMS [0-9.]+ cm = ([0-9.]+)× expected", w.validate_nominal()),
     "the nominal robot's FK error on the example, times the noise-predicted error",
     [("README.md", r"FK error is about ([0-9]+) times what the noise explains")]),
    ("random64_largest_sigma_ratio", "exact", False,
     lambda w: grab(r"largest σ [0-9.e-]+ cm \(.*?\) = ([0-9.]+)× the noise-predicted", w.random_demo()),
     "`demo --poses 64 --random-poses`: the largest parameter σ, times the noise-predicted error",
     [("README.md", r"the largest σ about ([0-9]+) times the"), ("docs/calibration.md", r"with σ ([0-9.]+) times\s+the"),
      ("docs/cli.md", r"a_z with σ ([0-9.]+) times\s+the")]),
    ("study_position_beats_percent", "exact", False,
     lambda w: w.random_demo() and grab(r"validates better than ([0-9.]+) % of the random subsets",
                                        run(w.hexcal, "study", "--session", "run64", "--select", "13", cwd=w.dir)),
     "`study --session run64 --select 13`: the share of the 6000 random subsets the selected one beats, held-out position",
     [("docs/cli.md", r"validates better than ([0-9.]+) % of the random subsets"),
      ("docs/calibration.md", r"\| inria-left-hand, 1 \| [^|]+\| [^|]+\| ([0-9.]+) \(")]),
    ("fk_all_modes_bench_ms", "recorded", False, 28.5,
     "BM_ForwardKinematicsAllModes (build/bench/hexcal_bench_kinematics, 2026-12-03)",
     [("docs/performance.md", r"`BM_ForwardKinematicsAllModes` \| \*\*([0-9.]+) ms\*\*")]),
    ("machine_loop_verify_before_cm", "recorded", False, 0.095,
     "the README's machine loop: verify's position RMS before export --push (readme_machine_loop.sh, 2026-12-05)",
     [("README.md", r"\(([0-9.]+) → [0-9.]+ cm\)"), ("docs/acquisition.md", r"LinuxCNC sees ([0-9.]+) cm RMS")]),
    ("machine_loop_verify_after_cm", "recorded", False, 0.00258,
     "the same after export --push",
     [("README.md", r"\([0-9.]+ → ([0-9.]+) cm\)"), ("docs/acquisition.md", r"`export --push` ([0-9.]+) cm \(")]),
    ("machine_loop_verify_ratio", "recorded", False, 36.9, "before / after",
     [("README.md", r"about ([0-9]+) times closer"), ("docs/acquisition.md", r"\(([0-9.]+) times closer")]),
]


def number(text):
    return float(text.replace(" ", "").replace(" ", ""))


def quoted_agrees(kind, quoted, value):
    """Whether a doc's `quoted` text stands for the recorded `value`."""
    if kind == "timing":
        low, high = ([number(x) for x in quoted.split("–")] + [None])[:2]
        high = high if high is not None else low
        return low / TIMING_FACTOR <= value <= high * TIMING_FACTOR
    digits = quoted.replace(" ", "").replace(" ", "")
    decimals = len(digits.split(".")[1]) if "." in digits else 0
    return abs(number(quoted) - value) <= 0.5 * 10 ** -decimals + 1e-12


def write(hexcal):
    work = Work(hexcal)
    figures = {}
    for ident, kind, fast, measure, what, quotes in FIGURES:
        value = measure if kind == "recorded" else measure(work)
        figures[ident] = {"value": value, "kind": kind, "fast": fast, "what": what,
                          "quoted_in": sorted({q[0] for q in quotes})}
        print("%-40s %-8s %s" % (ident, kind, value))
    record = {"written": time.strftime("%Y-%m-%d"), "timing_factor": TIMING_FACTOR, "rerun_factor": RERUN_FACTOR,
              "figures": figures}
    fd, temporary = tempfile.mkstemp(dir=os.path.dirname(RECORD), prefix=".figures.")
    with os.fdopen(fd, "w") as out:
        json.dump(record, out, indent=2, ensure_ascii=False)
        out.write("\n")
        out.flush()
        os.fsync(out.fileno())
    os.replace(temporary, RECORD)  # atomic: a reader sees the old file or the new one
    print("wrote", RECORD)


def check(hexcal):
    record = json.load(open(RECORD))["figures"]
    work = Work(hexcal)
    problems = []
    for ident, kind, fast, measure, what, quotes in FIGURES:
        if ident not in record:
            problems.append("%s: not in docs/figures.json; run scripts/figures.py write" % ident)
            continue
        value = record[ident]["value"]
        if kind == "recorded" and value != measure:
            problems.append("%s: figures.json has %s, figures.py %s" % (ident, value, measure))
        for path, pattern in quotes:
            text = open(os.path.join(ROOT, path)).read()
            found = re.search(pattern, text)
            if not found:
                problems.append("%s: %s no longer quotes it (/%s/)" % (ident, path, pattern))
            elif not quoted_agrees(kind, found.group(1), value):
                problems.append("%s: %s quotes %s, the record is %s" % (ident, path, found.group(1), value))
        if fast:
            now = measure(work)
            agrees = (value / RERUN_FACTOR <= now <= value * RERUN_FACTOR) if kind == "timing" else now == value
            print("%-40s %-8s recorded %s, now %s" % (ident, kind, value, now))
            if not agrees:
                problems.append("%s: recorded %s, hexcal now gives %s" % (ident, value, now))
    for problem in problems:
        print("FAIL:", problem)
    print("%d figures, %d quotes, %d problems" % (len(FIGURES), sum(len(f[5]) for f in FIGURES), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("write", "check"):
        sys.exit(__doc__)
    hexcal = os.path.abspath(sys.argv[2])
    sys.exit(write(hexcal) if sys.argv[1] == "write" else check(hexcal))
