#!/usr/bin/env python3
"""cmake/stack_report.py on a hand-written image (fixture/): call graphs (.ci), frames (.su) and
link maps in the formats GCC 12 and GNU ld write them, the C sources the call graphs point into,
and the depths worked out by hand.

The image (frames in bytes; library functions count 512, mem* 64):
  Reset_Handler 8 -> main 100 -> parse 200 -> solve 300 -> sinf (512)
                              -> h.job(1): cb_small 16 -> h.job(): cb_big 1200 -> memset (64)
                              -> h.never(1, 2, 3): no function of that shape
                              -> memcpy (64)
  cb_small, cb_big (void, one int) and cb_pair 3000 (int, two ints): nothing calls them
  directly, so they are the indirect-call targets; a job_fn call reaches only the first two,
  and a chain does not enter cb_small twice.
  TIM2_IRQHandler 24 (level 0) -> isr_hook(3): cb_small or cb_big
  CAN1_RX0_IRQHandler 40 (level 2) -> can_rx 60 -> memcpy, and an indirect call with no
  position in the call graph: any of the three
  HardFault_Handler 16 (level -1);  Default_Handler 8, also NMI_Handler (level -2) and SVC_Handler (0)
  dropped_fn 5000: in the call graph, but the map lists its section as discarded.
recursion.map links rec.c too: TIM3_IRQHandler -> ping <-> pong -> walk_tree -> walk_tree.
Usage: test_stack_report.py [path/to/stack_report.py]
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "..", "..", "cmake", "stack_report.py")
FRAME = 104 + 4  # exception frame with the FPU context, plus alignment

CB_BIG = 1200 + 64  # cb_big -> memset
CB_SMALL = 16 + CB_BIG  # cb_small -> (job_fn) cb_big
CB_PAIR = 3000
THREAD = 8 + 100 + max(200 + 300 + 512, CB_SMALL, CB_BIG, 64)
TIM2 = 24 + max(CB_SMALL, CB_BIG)
CAN = 40 + 60 + max(64, CB_PAIR, CB_SMALL, CB_BIG)
TOTAL = THREAD + (CAN + FRAME) + (TIM2 + FRAME) + (16 + FRAME) + (8 + FRAME)
# Without narrowing by pointer type: every indirect call may reach any of the three.
CB_SMALL_ALL = 16 + max(CB_PAIR, CB_BIG)
THREAD_ALL = 8 + 100 + max(200 + 300 + 512, CB_SMALL_ALL, CB_PAIR, CB_BIG, 64)
TIM2_ALL = 24 + max(CB_SMALL_ALL, CB_PAIR, CB_BIG)
CAN_ALL = 40 + 60 + max(64, CB_SMALL_ALL, CB_PAIR, CB_BIG)
TOTAL_ALL = THREAD_ALL + (CAN_ALL + FRAME) + (TIM2_ALL + FRAME) + (16 + FRAME) + (8 + FRAME)

failures = []


def check(what, cond, detail=""):
    print("%s: %s%s" % ("ok" if cond else "FAIL", what, (" (" + detail + ")") if detail and not cond else ""))
    if not cond:
        failures.append(what)


def run(work, mapname, *extra):
    js = os.path.join(work, mapname + ".json")
    if os.path.exists(js):
        os.remove(js)
    p = subprocess.run([sys.executable, SCRIPT, "--map", os.path.join(work, mapname), "--build-dir", work,
                        "--source-root", work, "--prio-header", os.path.join(work, "src", "prio.h"),
                        "--json", js, "--quiet"] + list(extra),
                       capture_output=True, text=True)
    sys.stdout.write(p.stdout + p.stderr)
    data = None
    if os.path.exists(js):
        with open(js) as f:
            data = json.load(f)
    return p.returncode, p.stdout + p.stderr, data


def main():
    work = tempfile.mkdtemp(prefix="stack_report_")
    try:
        shutil.copytree(os.path.join(HERE, "fixture"), work, dirs_exist_ok=True)
        # As after a build: the call graphs newer than the sources they point into.
        for dirpath, _dirs, files in os.walk(work):
            for f in files:
                t = 2000000000 if f.endswith((".ci", ".su")) else 1900000000
                os.utime(os.path.join(dirpath, f), (t, t))

        rc, out, d = run(work, "ok.map")
        check("within the budget: exit 0", rc == 0, out)
        check("thread depth is the hand sum %d" % THREAD, d["thread"]["bytes"] == THREAD, str(d["thread"]))
        check("thread chain goes through both job_fn targets, each once",
              d["thread"]["chain"] == ["Reset_Handler", "main", "cb_small", "cb_big", "memset"], str(d["thread"]))
        check("TIM2 handler depth %d" % TIM2, d["handlers"]["TIM2_IRQHandler"]["bytes"] == TIM2)
        check("CAN handler depth %d: its unplaced indirect call reaches cb_pair" % CAN,
              d["handlers"]["CAN1_RX0_IRQHandler"]["bytes"] == CAN, str(d["handlers"]["CAN1_RX0_IRQHandler"]))
        check("indirect-call targets are the functions nobody calls",
              sorted(d["indirect_targets"]) == ["cb_big", "cb_pair", "cb_small"], str(d["indirect_targets"]))
        sites = {(x["in"], x["at"].replace(work + "/", "")): (x["how"], sorted(x["targets"])) for x in d["sites"]}
        check("sites narrowed by the pointer's type", sites == {
            ("main", "src/app.c:29:5"): ("type", ["cb_big", "cb_small"]),
            ("main", "src/app.c:30:5"): ("no-target", []),
            ("cb_small", "src/app.c:47:5"): ("type", ["cb_big", "cb_small"]),
            ("TIM2_IRQHandler", "src/isr.c:11:5"): ("type", ["cb_big", "cb_small"]),
            ("can_rx", ""): ("unread", ["cb_big", "cb_pair", "cb_small"])}, str(sites))
        levels = {lv["level"]: (lv["handler"], lv["bytes"]) for lv in d["levels"]}
        check("levels: NMI (alias of Default_Handler) -2, HardFault -1, TIM2 0, CAN 2",
              levels == {-2: ("NMI_Handler", 8), -1: ("HardFault_Handler", 16), 0: ("TIM2_IRQHandler", TIM2),
                         2: ("CAN1_RX0_IRQHandler", CAN)}, str(levels))
        check("total is the hand sum %d" % TOTAL, d["total"] == TOTAL, str(d["total"]))
        check("total without the type narrowing is the hand sum %d" % TOTAL_ALL, d["total_every_target"] == TOTAL_ALL,
              str(d["total_every_target"]))
        check("stack size read from the map", d["stack_size"] == 8192)
        check("no recursion", d["cycles"] == [])
        check("library functions reached are listed", d["unknown_reached"] == ["memcpy", "memset", "sinf"],
              str(d["unknown_reached"]))
        check("the discarded function is not counted", "dropped_fn" not in out and
              all("dropped_fn" not in h["chain"] for h in d["handlers"].values()))
        with open(os.path.join(work, "ok.stack.txt")) as f:
            report = f.read()
        check("report written beside the image", "Deepest chain from the thread root" in report and
              "-> (indirect) cb_big" in report)

        rc, out, d = run(work, "ok.map", "--no-type-match")
        check("--no-type-match: every target at every site, total %d" % TOTAL_ALL, d["total"] == TOTAL_ALL and
              d["thread"]["bytes"] == THREAD_ALL and d["handlers"]["TIM2_IRQHandler"]["bytes"] == TIM2_ALL, str(d))
        check("--no-type-match: over the budget, exit 1", rc == 1 and "exceeds the reserved stack" in out, out)

        # app.c edited after the build: its positions are not trusted.  Its call sites keep every
        # target, and its functions' shapes are unknown, so they fit any pointer (TIM2's too).
        os.utime(os.path.join(work, "src", "app.c"), (2100000000, 2100000000))
        rc, out, d = run(work, "ok.map")
        check("source newer than its call graph: not narrowed",
              d["thread"]["bytes"] == THREAD_ALL and d["handlers"]["TIM2_IRQHandler"]["bytes"] == TIM2_ALL, str(d))
        os.utime(os.path.join(work, "src", "app.c"), (1900000000, 1900000000))

        # Over the budget: the same image with 1 byte less stack than it needs.
        with open(os.path.join(work, "ok.map")) as f:
            text = f.read()
        tight = text.replace("0x00002000                        _stack_size = 0x2000",
                             "0x%08x                        _stack_size = 0x%x" % (TOTAL - 1, TOTAL - 1))
        check("tight.map differs from ok.map", tight != text)
        with open(os.path.join(work, "tight.map"), "w") as f:
            f.write(tight)
        rc, out, d = run(work, "tight.map")
        check("one byte over the budget: exit 1", rc == 1, out)
        check("...with a message", "exceeds the reserved stack by 1 bytes" in out, out)
        check("...and the reservation from the map", d["stack_size"] == TOTAL - 1)
        rc, out, d = run(work, "tight.map", "--stack-size", str(TOTAL))
        check("exactly at the budget: exit 0", rc == 0, out)

        # Recursion: unbounded, reported, exit 1.
        rc, out, d = run(work, "recursion.map")
        check("recursion: exit 1", rc == 1, out)
        check("recursion: both cycles found", sorted(d["cycles"]) == [["ping", "pong"], ["walk_tree"]], str(d["cycles"]))
        check("recursion: the handler reaching it is unbounded", d["handlers"]["TIM3_IRQHandler"]["bounded"] is False)
        check("recursion: the others stay bounded", d["handlers"]["TIM2_IRQHandler"]["bounded"] is True)
        check("recursion: TIM3 without a priority gets a level of its own",
              any(lv["handler"] == "TIM3_IRQHandler" and str(lv["level"]).startswith("own") for lv in d["levels"]))
        check("recursion: message", "recursion, no bound: walk_tree -> walk_tree; ping -> pong -> ping" in out, out)

        # An object of the build without its call graph (a build configured without the flags).
        os.remove(os.path.join(work, "CMakeFiles", "drv.dir", "src", "isr.c.ci"))
        rc, out, d = run(work, "ok.map")
        check("missing call graph: exit 1", rc == 1, out)
        check("missing call graph: says how to fix it", "libdrv.a(isr.c.obj)" in out and "--fresh" in out, out)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("%d failed" % len(failures) if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
