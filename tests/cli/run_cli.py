#!/usr/bin/env python3
"""Runs spring-motion once in a fresh working directory and checks the outcome.

usage: run_cli.py --workdir DIR [--setup CMD]... [--exit N] [--stdout REGEX]
                  [--stderr REGEX] [--stderr-empty] [--check CMD]... -- PROGRAM ARGS...

DIR is emptied, the --setup commands run in it (to make inputs), then the
program. Checks, in order:
  * the exit status is N (default 0) -- never a crash (a signal);
  * stdout / stderr match the regular expressions (re.search, multiline);
  * with a non-zero status other than 3, stderr is exactly one line and the
    working directory holds only what the setup made: no partial output, no
    temporary file;
  * every argument naming an existing file is unchanged (same SHA-256):
    the input is never modified;
  * each --check command (run by the shell in DIR) exits with 0.
"""
import argparse
import hashlib
import os
import re
import shutil
import subprocess
import sys


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--workdir", required=True)
    p.add_argument("--exit", type=int, default=0)
    p.add_argument("--stdout")
    p.add_argument("--stderr")
    p.add_argument("--stderr-empty", action="store_true")
    p.add_argument("--setup", action="append", default=[])
    p.add_argument("--check", action="append", default=[])
    p.add_argument("command", nargs=argparse.REMAINDER)
    a = p.parse_args()
    command = a.command[1:] if a.command and a.command[0] == "--" else a.command
    if not command:
        sys.exit("run_cli.py: no command")

    shutil.rmtree(a.workdir, ignore_errors=True)
    os.makedirs(a.workdir)
    for setup in a.setup:
        c = subprocess.run(setup, cwd=a.workdir, shell=True, capture_output=True, text=True, timeout=300)
        print("$ " + setup + "\n" + c.stdout + c.stderr)
        if c.returncode != 0:
            sys.exit("run_cli.py: setup failed (exit %d): %s" % (c.returncode, setup))
    before = set(os.listdir(a.workdir))
    inputs = {}
    for arg in command[1:]:
        path = os.path.join(a.workdir, arg)  # an absolute arg stays as it is
        if os.path.isfile(path):
            inputs[path] = digest(path)

    r = subprocess.run(command, cwd=a.workdir, capture_output=True, text=True, timeout=120)
    print("$ " + " ".join(command))
    print("exit status:", r.returncode)
    print("stdout:\n" + r.stdout)
    print("stderr:\n" + r.stderr)
    failures = []
    if r.returncode < 0:
        failures.append("killed by signal %d (a crash)" % -r.returncode)
    elif r.returncode != a.exit:
        failures.append("exit status %d, expected %d" % (r.returncode, a.exit))
    if a.stdout and not re.search(a.stdout, r.stdout, re.M):
        failures.append("stdout does not match %r" % a.stdout)
    if a.stderr and not re.search(a.stderr, r.stderr, re.M):
        failures.append("stderr does not match %r" % a.stderr)
    if a.stderr_empty and r.stderr:
        failures.append("stderr is not empty")
    if r.returncode not in (0, 3):
        if r.stderr.count("\n") != 1 or not r.stderr.endswith("\n"):
            failures.append("the error is not exactly one line")
        left = sorted(set(os.listdir(a.workdir)) - before)
        if left:
            failures.append("a failed run left files behind: %s" % left)
    for path, before in inputs.items():
        if not os.path.isfile(path) or digest(path) != before:
            failures.append("input %s was modified" % path)
    for check in a.check:
        c = subprocess.run(check, cwd=a.workdir, shell=True, capture_output=True, text=True, timeout=300)
        print("$ " + check + "\n" + c.stdout + c.stderr)
        if c.returncode != 0:
            failures.append("check failed (exit %d): %s" % (c.returncode, check))
    for f in failures:
        print("FAIL: " + f)
    print("PASS" if not failures else "FAILED")
    sys.exit(1 if failures else 0)


main()
