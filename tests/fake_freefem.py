#!/usr/bin/env python3
"""A stand-in for FreeFem++ that misbehaves on purpose (FAKE_MODE), for the driver's fault tests.

It answers -options and -columns, and runs the real solver where a fault needs
real output, through the FreeFem++ named in REAL_FREEFEM.
"""
import os
import signal
import subprocess
import sys
import time

args = sys.argv[1:]
real = os.environ["REAL_FREEFEM"]
mode = os.environ.get("FAKE_MODE", "")


def run_real() -> int:
    return subprocess.run([real, *args]).returncode


if mode == "exits_shifted":
    # hertz.edp with every exit code moved by 10: the driver must follow its -exits table
    if "-exits" in args:
        out = subprocess.run([real, *args], capture_output=True, text=True).stdout
        for line in out.splitlines():
            fields = line.split(",", 2)
            if len(fields) == 3 and fields[1].isdigit():
                line = ",".join([fields[0], str(int(fields[1]) + 10), fields[2]])
            print(line)
        sys.exit(0)
    code = run_real()
    sys.exit(code + 10 if any(flag in args for flag in ("-options", "-columns")) is False else code)

if mode == "grown":
    # a later hertz.edp with one more word option (-finish) and two more summary columns
    if "-options" in args or "-columns" in args:
        out = subprocess.run([real, *args], capture_output=True, text=True).stdout
        for line in out.splitlines():
            if line.startswith("-check,"):
                print('-finish,word,"polished","polished, rough","indenter finish"')
            print(line + (",finish,Z_fe" if line.startswith("model,") else ""))
        sys.exit(0)
    if "-exits" in args:
        sys.exit(run_real())
    finish = "polished"
    if "-finish" in args:
        k = args.index("-finish")
        finish = args[k + 1]
        del args[k:k + 2]
    code = run_real()
    out = args[args.index("-out") + 1]
    summary = os.path.join(out, "summary.csv")
    with open(summary) as f:
        head, row = f.read().splitlines()[:2]
    with open(summary, "w") as f:
        f.write(f"{head},finish,Z_fe\n{row},{finish},1.5\n")
    sys.exit(code)

if any(flag in args for flag in ("-options", "-columns", "-exits")) or not mode:
    sys.exit(run_real())

out = args[args.index("-out") + 1] if "-out" in args else "."
summary = os.path.join(out, "summary.csv")
columns = subprocess.run([real, "-nw", "-v", "0", args[args.index("-v") + 2], "-columns"],
                         capture_output=True, text=True).stdout
header = next(ln for ln in columns.splitlines() if ln.startswith("model,"))

if mode == "crash_after_summary":
    run_real()
    os.kill(os.getpid(), signal.SIGSEGV)
elif mode == "exit4_after_summary":
    run_real()
    sys.exit(4)
elif mode == "holds_stdout":
    code = run_real()
    subprocess.Popen(["sleep", "30"])  # inherits stdout and stays
    sys.exit(code)
elif mode == "detached_child":
    subprocess.Popen(["sleep", "30"], start_new_session=True, stdout=subprocess.DEVNULL,
                     stderr=subprocess.DEVNULL)
    sys.exit(run_real())
elif mode == "hang":
    time.sleep(600)
elif mode == "slow":
    time.sleep(float(os.environ.get("FAKE_DELAY", "3")))
    sys.exit(run_real())
elif mode == "orphan_exits":
    # a helper in a session of its own, without the case's marker, that outlives the case
    # briefly: an orphan that exits on its own after the case is over
    env = {k: v for k, v in os.environ.items() if k != "HERTZ_CASE_TOKEN"}
    subprocess.Popen(["sleep", "1"], start_new_session=True, env=env, stdout=subprocess.DEVNULL,
                     stderr=subprocess.DEVNULL)
    sys.exit(run_real())
elif mode == "unknown_columns":
    run_real()
    with open(summary) as f:
        lines = f.read().splitlines()
    with open(summary, "w") as f:
        f.write(lines[0] + ",surprise\n" + lines[1] + ",1\n")
elif mode == "empty_summary":
    open(summary, "w").close()
elif mode == "header_only":
    with open(summary, "w") as f:
        f.write(header + "\n")
elif mode == "binary_summary":
    with open(summary, "wb") as f:
        f.write(b"\x00\xff\xfe garbage \x81\x82\n\x00")
elif mode == "dir_summary":
    os.mkdir(summary)
elif mode == "non_numeric":
    run_real()
    with open(summary) as f:
        head, row = f.read().splitlines()[:2]
    fields = row.split(",")
    fields[head.split(",").index("p0_fe")] = "abc"
    with open(summary, "w") as f:
        f.write(head + "\n" + ",".join(fields) + "\n")
sys.exit(0)
