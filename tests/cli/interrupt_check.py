#!/usr/bin/env python3
"""Interrupts a long spring-motion run once it has written frames, and checks
that it exits with 130, says so in one line, and leaves no file behind.

usage: interrupt_check.py WORKDIR SPRING_MOTION MESH
"""
import os
import shutil
import signal
import subprocess
import sys
import time

work, program, mesh = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
p = subprocess.Popen([program, "deform", mesh, "--moving", "2", "--pitch", "10", "--center", "1.5,1",
                      "--steps", "1000000", "--output", "out.pvd", "--report", "r.json"],
                     cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
deadline = time.time() + 60
while time.time() < deadline and not any(f.endswith(".vtu") for f in os.listdir(work)):
    time.sleep(0.01)
frames = [f for f in os.listdir(work) if f.endswith(".vtu")]
p.send_signal(signal.SIGINT)
out, err = p.communicate(timeout=60)
left = os.listdir(work)
print("frames before the signal:", len(frames), "| exit status:", p.returncode, "| stderr:", err.strip(),
      "| left:", left)
ok = frames and p.returncode == 130 and err.count("\n") == 1 and "interrupted" in err and not left
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
