#!/usr/bin/env python3
"""Mutation testing of the C++ tests: does a test fail when the code is wrong?

For each mutation of a JSON list (default docs/mutations.json: name, file,
old, new), replaces the one occurrence of `old` in `file` by `new`, rebuilds
asm_tests in the build directory, runs it, and prints KILLED (a test failed:
good) or SURVIVED (no test noticed). The file is restored after each
mutation, whatever happens (an interrupted run restores the file it was on;
`git status` shows anything left). About a minute per mutation on 2 cores.

A mutation with a "ctest" label (e.g. "mpi", for the code that only
multi-process runs reach) that survives asm_tests is then tried on that
CTest label too: the whole build is rebuilt (the module, its Python
wrapping, the plugin) and `ctest -L LABEL` run; a failing test kills it.
About three more minutes.

  python3 scripts/mutation-test.py                     # every mutation of docs/mutations.json
  python3 scripts/mutation-test.py --only covering     # those whose name contains "covering"
  python3 scripts/mutation-test.py --build build other.json

A survivor is either a missing test or an equivalent mutant (a change that
cannot alter any result); docs/mutation-testing.md says which is which.
"""
import argparse
import json
import os
import signal
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mutations", nargs="?", default=os.path.join(root, "docs", "mutations.json"))
    parser.add_argument("--build", default=os.path.join(root, "build"))
    parser.add_argument("--only", default="", help="run the mutations whose name contains this")
    args = parser.parse_args()
    # (A terminated run restores the file it was on, as an interrupted one.)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit("terminated"))
    mutations = [m for m in json.load(open(args.mutations)) if args.only in m["name"]]
    tests = os.path.join(args.build, "bin", "asm_tests")
    survivors = 0
    rebuilt_all = False
    for m in mutations:
        path = os.path.join(root, m["file"])
        source = open(path).read()
        if source.count(m["old"]) != 1:
            print("NOT-APPLIED %s (%d occurrences of the text)" % (m["name"], source.count(m["old"])), flush=True)
            continue
        try:
            open(path, "w").write(source.replace(m["old"], m["new"]))
            build = subprocess.run(["ninja", "-C", args.build, "asm_tests"], capture_output=True, text=True)
            if build.returncode != 0:
                print("BUILD-FAILED %s" % m["name"], flush=True)
                continue
            run = subprocess.run([tests, "--gtest_brief=1"], capture_output=True, text=True, timeout=1800)
            failed = sorted({line.split()[3] for line in run.stdout.splitlines()
                             if line.startswith("[  FAILED  ]") and len(line.split()) > 4 and "." in line.split()[3]})
            if run.returncode == 0 and m.get("ctest"):
                rebuilt_all = True
                if subprocess.run(["ninja", "-C", args.build], capture_output=True).returncode != 0:
                    print("BUILD-FAILED %s (the whole build)" % m["name"], flush=True)
                    continue
                # (A hang fails by the tests' own timeouts.)
                run = subprocess.run(["ctest", "--test-dir", args.build, "-j2", "-L", m["ctest"]],
                                     capture_output=True, text=True, timeout=3600)
                listed = run.stdout.split("The following tests FAILED:")[-1].splitlines()
                failed = [line.split()[2] for line in listed if " - " in line and len(line.split()) > 2]
                failed = failed or ["ctest -L " + m["ctest"]]
            if run.returncode != 0:
                print("KILLED %s (%s)" % (m["name"], ", ".join(failed[:3]) or "the run failed"), flush=True)
            else:
                survivors += 1
                print("SURVIVED %s" % m["name"], flush=True)
        except subprocess.TimeoutExpired:
            print("KILLED %s (timeout)" % m["name"], flush=True)
        finally:
            open(path, "w").write(source)
    # The real code again.
    subprocess.run(["ninja", "-C", args.build] + ([] if rebuilt_all else ["asm_tests"]), capture_output=True)
    print("%d of %d mutations survived" % (survivors, len(mutations)))


if __name__ == "__main__":
    sys.exit(main())
