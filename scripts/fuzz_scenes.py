#!/usr/bin/python3
"""Fuzzes the scene reader and the checks before a solve: mutates the example scenes and
runs `perinom check` on each mutant.

A mutant passes when perinom ends with exit code 0, 1, 2 or 3 within the time limit and
prints no sanitizer report. Exit code 4 (internal error), a signal (a crash, or the kernel's
out-of-memory kill) or a sanitizer report is a find: the mutant is saved under --finds and
the script exits with 1. A mutant that runs past --timeout is reported and saved too (a
check that does not end is a find as well).

Mutations are textual (the YAML parser is fuzzed too) and seeded, so a run is repeatable:
deleting, duplicating or swapping lines, a stray document separator, a value replaced by a
huge, tiny, negative, NaN or infinite number, by text, a list or a mapping, odd keys
(lists and mappings as keys, empty, unicode), unbalanced quotes and brackets, tabs, a cut
file.

  scripts/fuzz_scenes.py --seconds 60                  # CI: a fixed budget
  scripts/fuzz_scenes.py --seconds 3600 --seed 7       # by hand, longer
  scripts/fuzz_scenes.py --replay finds/case_12.yaml   # run one saved mutant again

Every find becomes a regression test in tests/cli (test_fuzz_finds.cpp).
"""
import argparse
import glob
import os
import random
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

NUMBERS = ["0", "-0.0", "-1", "1", "1e308", "-1e308", "1e-308", "1e-300", "4.9e-324", "1e309", ".nan", ".inf",
           "-.inf", "nan", "inf", "NaN", "99999999999999999999", "-99999999999999999999", "2147483648",
           "4294967297", "9223372036854775808", "1e6", "1e9", "0x10", "0o17", "1_000", "3.", ".5", "+2", "1e-5",
           "1e-4", "0.5", "2", "3", "1000000"]
TEXTS = ["", "~", "null", "\"\"", "''", "abc", "true", "false", "yes", "[]", "{}", "[1, 2]", "[1, 2, 3, 4]",
         "{a: 1}", "[[1, 2], [3, 4]]", "\"1e9\"", "'x'", "\"\\0\"", "\"a\\nb\"", "..", ".", "/tmp/x", "left",
         "top", "all", "strain", "stress", "improved", "classical", "strong", "adr", "verlet", "newton", "lbc",
         "drucker_prager", "thin_plate", "clamped", "x", "[x, y, z]", "[x, x]", "é", "\u2028", "*a", "&a 1",
         "!!binary AAAA", "!!str 1", "|\n  block", ">\n  folded"]
KEYS = ["[a, b]", "? [a, b]", "{x: 1}", "\"\"", "''", "é", "a.b", "0", "1", "-", "?", "<<", "name", "dimension",
        "geometry", "dx", "box", "min", "max", "horizon", "ratio", "neighbors", "plane", "type", "stages",
        "boundary", "probes", "output", "solver", "model", "holes", "thickness"]
LINES = ["---", "...", "%YAML 1.2", "\t", "  - ", "-", ":", "? x", "'unterminated", "\"unterminated", "[", "{", "]",
         "}", "# comment", "&anchor", "*alias", "<<: *a", "key: value", "\x00", "\ufeff"]

VALUE = re.compile(r"^(\s*(?:- )?[^:#\n]+:\s+)(.+)$")
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?)")


def mutate(text, rng):
    lines = text.split("\n")
    for _ in range(rng.choice([1, 1, 1, 2, 2, 3, 5])):
        kind = rng.randrange(12)
        k = rng.randrange(len(lines)) if lines else 0
        if not lines:
            lines = [rng.choice(LINES)]
        elif kind == 0:  # delete a line
            del lines[k]
        elif kind == 1:  # duplicate a line
            lines.insert(k, lines[k])
        elif kind == 2:  # swap two lines
            j = rng.randrange(len(lines))
            lines[k], lines[j] = lines[j], lines[k]
        elif kind == 3:  # insert an odd line
            lines.insert(k, rng.choice(LINES))
        elif kind in (4, 5, 6):  # replace a number
            found = list(NUMBER.finditer(lines[k]))
            if found:
                m = rng.choice(found)
                lines[k] = lines[k][:m.start()] + rng.choice(NUMBERS) + lines[k][m.end():]
        elif kind == 7:  # replace a value by another type
            m = VALUE.match(lines[k])
            if m:
                lines[k] = m.group(1) + rng.choice(TEXTS + NUMBERS)
        elif kind == 8:  # an odd key
            indent = re.match(r"\s*", lines[k]).group(0)
            lines.insert(k, indent + rng.choice(KEYS) + ": " + rng.choice(TEXTS + NUMBERS))
        elif kind == 9:  # change the indentation
            lines[k] = (" " * rng.choice([0, 1, 2, 4])) + lines[k].lstrip() if rng.random() < 0.5 else "  " + lines[k]
        elif kind == 10:  # cut the file
            lines = lines[:k]
        else:  # a character inserted or deleted
            line = lines[k]
            at = rng.randrange(len(line) + 1)
            if rng.random() < 0.5 and line:
                lines[k] = line[:at] + line[at + 1:]
            else:
                lines[k] = line[:at] + rng.choice("\"'[]{}:,-#&*!|>%@`\t ") + line[at:]
    return "\n".join(lines)


def limit_resources(memory_bytes):
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


SANITIZER = re.compile(r"ERROR: AddressSanitizer|runtime error:|ERROR: LeakSanitizer|UndefinedBehaviorSanitizer")


def run_check(perinom, scene_path, timeout, memory):
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="PASSIVE")
    try:
        p = subprocess.run([perinom, "check", os.path.basename(scene_path)], cwd=os.path.dirname(scene_path),
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=timeout, env=env,
                           preexec_fn=limit_resources(memory))
    except subprocess.TimeoutExpired:
        return "timeout", ""
    err = p.stderr.decode("utf-8", "replace")
    if SANITIZER.search(err):
        return "sanitizer report", err
    if p.returncode < 0:
        return "signal %d" % -p.returncode, err
    if p.returncode not in (0, 1, 2, 3):
        return "exit %d" % p.returncode, err
    return None, "exit %d" % p.returncode if not err else err


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--perinom", default=os.path.join(ROOT, "build", "drivers", "perinom"))
    ap.add_argument("--seconds", type=float, default=60.0, help="time budget (default 60)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds allowed per mutant (default 20)")
    ap.add_argument("--memory", type=float, default=4.0, help="address-space limit per run in GB (default 4)")
    ap.add_argument("--finds", default=os.path.join(ROOT, "fuzz_finds"), help="where finds are saved")
    ap.add_argument("--replay", help="run one scene file and report its outcome")
    args = ap.parse_args()
    args.perinom = os.path.abspath(args.perinom)  # each mutant runs in a scratch folder
    memory = int(args.memory * 2**30)
    if os.environ.get("ASAN_OPTIONS") is not None or "sanitize" in args.perinom:
        memory = resource.RLIM_INFINITY  # ASan reserves terabytes of address space
    if args.replay:
        work = tempfile.mkdtemp(prefix="perinom_fuzz_")
        path = os.path.join(work, "scene.yaml")
        shutil.copy(args.replay, path)
        find, err = run_check(args.perinom, path, args.timeout, memory)
        print("%s: %s\n%s" % (args.replay, find or "ok", err.strip()))
        shutil.rmtree(work, ignore_errors=True)
        return 1 if find else 0

    seeds = sorted(glob.glob(os.path.join(ROOT, "examples", "*.yaml")))
    texts = [open(s, encoding="utf-8").read() for s in seeds]
    rng = random.Random(args.seed)
    work = tempfile.mkdtemp(prefix="perinom_fuzz_")
    path = os.path.join(work, "scene.yaml")
    start, cases, finds = time.time(), 0, 0
    outcomes = {}
    while time.time() - start < args.seconds:
        k = rng.randrange(len(texts))
        mutant = mutate(texts[k], rng)
        with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(mutant)
        find, err = run_check(args.perinom, path, args.timeout, memory)
        cases += 1
        first = err.strip().split("\n")[0]
        outcome = find or ("exit 0" if first == "exit 0" else "exit 2" if "perinom: error:" in first else "ok, other")
        outcomes[outcome] = outcomes.get(outcome, 0) + 1
        if find:
            finds += 1
            os.makedirs(args.finds, exist_ok=True)
            saved = os.path.join(args.finds, "seed%d_case%d.yaml" % (args.seed, cases))
            shutil.copy(path, saved)
            print("FIND (%s) from %s: %s\n  %s" % (find, os.path.basename(seeds[k]), saved, first[:300]))
            sys.stdout.flush()
    shutil.rmtree(work, ignore_errors=True)
    print("fuzz_scenes: seed %d, %d mutants in %.0f s, %d finds; outcomes: %s" %
          (args.seed, cases, time.time() - start, finds, ", ".join("%s %d" % kv for kv in sorted(outcomes.items()))))
    return 1 if finds else 0


if __name__ == "__main__":
    sys.exit(main())
