#!/usr/bin/env python3
"""Issue 22 item 2: a signal that ends `rodnet` leaves no temporary file behind.

Usage: check_signal_cleanup.py RODNET SCRATCH_DIR

1. `rodnet generate` of a large lattice is sent SIGINT, then (another run)
   SIGTERM, while it writes FILE.tmp.PID: the process ends by that signal
   (the exit status reports it), no *.tmp.* file remains, FILE is not created.
2. `rodnet homogenize --plot` is sent SIGTERM while its plotting script runs
   (a stand-in that writes part of its output and sleeps): the script is killed
   with it (no orphan left writing), no *.tmp.* file and no PNG remain.
"""
import os
import shutil
import signal
import subprocess
import sys
import time

FAILURES = []


def fail(msg):
    FAILURES.append(msg)
    print("FAIL: " + msg)


def temps(d):
    return sorted(f for f in os.listdir(d) if ".tmp." in f)


def wait_for(pred, timeout):
    t0 = time.time()
    while time.time() - t0 < timeout:
        if pred():
            return True
        time.sleep(0.002)
    return False


def fresh(path):
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


def generate_case(rodnet, root, sig):
    d = fresh(os.path.join(root, "generate_%s" % signal.Signals(sig).name))
    out = os.path.join(d, "big.json")
    # about 150 MB of JSON: written for a second or more
    p = subprocess.Popen([rodnet, "generate", "octet", "--cells", "22", "--edges-per-rod",
                          "8", "-o", out], stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE)
    try:
        seen = wait_for(lambda: temps(d) or p.poll() is not None, 300)
        if not seen or p.poll() is not None or not temps(d):
            fail("generate: the temporary file was never seen before the end (rc %s): "
                 "the test cannot interrupt the write" % p.poll())
            return
        name = temps(d)[0]
        p.send_signal(sig)
        rc = p.wait(120)
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    what = "generate, %s while writing %s" % (signal.Signals(sig).name, name)
    if rc != -sig:
        fail("%s: exit status %s, expected death by the signal (%d)" % (what, rc, -sig))
    if temps(d):
        fail("%s: temporary files left: %s" % (what, temps(d)))
    if os.path.exists(out):
        fail("%s: %s exists (a partial or complete write after the signal)" % (what, out))
    if not FAILURES:
        print("ok: %s: status %d, no temporary file, no output" % (what, rc))


FAKE_PLOT = r'''
import os, sys, time
open(os.environ["RN_FAKE_PID"] + ".part", "w").write(str(os.getpid()))
os.replace(os.environ["RN_FAKE_PID"] + ".part", os.environ["RN_FAKE_PID"])
with open(sys.argv[2], "w") as f:
    f.write("partial png")
    f.flush()
    time.sleep(120)
'''


def alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    # a zombie is dead: read its state
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().split(")")[-1].split()[0] != "Z"
    except OSError:
        return False


def plot_case(rodnet, root):
    d = fresh(os.path.join(root, "plot"))
    cell = os.path.join(root, "cell.json")
    subprocess.run([rodnet, "generate", "honeycomb", "--periodic", "--edges-per-rod", "4",
                    "-q", "-o", cell], check=True)
    fake = os.path.join(root, "fake_plot.py")
    with open(fake, "w") as f:
        f.write(FAKE_PLOT)
    pidfile = os.path.join(root, "fake.pid")
    if os.path.exists(pidfile):
        os.remove(pidfile)
    env = dict(os.environ, RODNET_PYTHON=sys.executable, RODNET_PLOT_STIFFNESS=fake,
               RN_FAKE_PID=pidfile)
    png = os.path.join(d, "plot.png")
    p = subprocess.Popen([rodnet, "homogenize", cell, "-o", os.path.join(d, "r.json"),
                          "--plot", png, "-q"], env=env, stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE)
    pid = None
    try:
        if not wait_for(lambda: os.path.exists(pidfile) or p.poll() is not None, 120) \
                or not os.path.exists(pidfile):
            fail("plot: the plotting script never started (rc %s)" % p.poll())
            return
        pid = int(open(pidfile).read())
        time.sleep(0.2)  # the script has opened its output
        p.send_signal(signal.SIGTERM)
        rc = p.wait(60)
        wait_for(lambda: not alive(pid), 5)
        if rc != -signal.SIGTERM:
            fail("plot: exit status %s, expected death by SIGTERM" % rc)
        if alive(pid):
            fail("plot: the plotting script %d still runs after rodnet ended" % pid)
        left = [f for f in os.listdir(d) if f.endswith(".png") or ".tmp." in f]
        if left:
            fail("plot: files left by the interrupted plot: %s" % left)
        if not FAILURES:
            print("ok: plot: status %d, the script killed, no PNG, no temporary file" % rc)
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
        if pid and alive(pid):
            os.kill(pid, signal.SIGKILL)


def main():
    if len(sys.argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    rodnet, root = sys.argv[1], sys.argv[2]
    os.makedirs(root, exist_ok=True)
    generate_case(rodnet, root, signal.SIGINT)
    generate_case(rodnet, root, signal.SIGTERM)
    plot_case(rodnet, root)
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
