#!/usr/bin/env python3
"""The read-back streams: `camgen verify` of a 200,000-hole grbl program (3.2 million lines)
must stay within the job's size plus 50 MB of peak memory, with and without --job, with
--plot F.svg and with --plot F.html (whose page shows the program's text, copied into it a line
at a time). A read-back that keeps the whole program's events or steps needs gigabytes and
fails here (the HTML page of 100,000 holes took 888 MB when it kept the trace). The page is
made of the program with 700,000 comment lines more (66 MB of text that costs little to read):
a page that keeps the text needs 104 MB for it, within the limit 22 MB. And posting: a job of 1,000,000 holes posted longhand for grbl into a file (16
million lines, 100 MB) within issue 13's bound for reading a job, 3 x the job file + 50 MB: the
program goes into the file's temporary as it is made (it took 161 MB when it was held whole). Each run's peak comes from wait4's rusage of that child alone.
The same 1,000,000 holes canned for fanuc into a file, as issue 25 measures them, within the same
bound. Both posts fill each page of memory about once: at most 1.5 x their peak's pages in minor
page faults, + 1,000 for starting the program. Buffers grown by doubling and copied, or freed and
allocated again, fault twice as often (33,475 faults at a peak of 65 MB before issue 25, 18,700
after where the kernel gives no huge pages, 2,800 where it does).

Usage: check_readback_memory.py CAMGEN SOURCE_DIR [CXX_FLAGS]
Skipped (exit 77) in a sanitizer build, whose shadow memory is no measure of camgen's."""
import os
import subprocess
import sys
import tempfile

HOLES = 200_000
POSTED_HOLES = 1_000_000
SLACK_MB = 50
PADDING_LINES = 700_000


def usage_of(args, out_path):
    """Runs args with stdout to out_path; returns (exit status, peak resident KB, minor page
    faults). Through /usr/bin/time where there is one: a child forked from Python starts with
    Python's pages."""
    with open(out_path, "wb") as out:
        if os.path.exists("/usr/bin/time"):
            report = out_path + ".time"
            code = subprocess.run(["/usr/bin/time", "-f", "%M %R", "-o", report, *args], stdout=out,
                                  stderr=subprocess.STDOUT).returncode
            kb, faults = open(report).read().split()[-2:]
            return code, int(kb), int(faults)
        child = subprocess.Popen(args, stdout=out, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(child.pid, 0)
    return os.waitstatus_to_exitcode(status), usage.ru_maxrss, usage.ru_minflt


def peak_kb(args, out_path):
    """usage_of without the faults."""
    code, kb, _ = usage_of(args, out_path)
    return code, kb


def fault_limit(kb):
    """Minor page faults allowed for a run of peak `kb`: each page filled about once."""
    return 3 * kb // 8 + 1000  # 1.5 x the peak's 4 KiB pages


def main():
    camgen, source = sys.argv[1], sys.argv[2]
    if "sanitize" in (sys.argv[3] if len(sys.argv) > 3 else ""):
        print("skipped: a sanitizer build")
        return 77
    with tempfile.TemporaryDirectory() as work:
        job, program = os.path.join(work, "job.json"), os.path.join(work, "grbl.nc")
        with open(job, "w") as f:
            subprocess.run([sys.executable, os.path.join(source, "bench", "gen_holes.py"), str(HOLES)], stdout=f, check=True)
        subprocess.run([camgen, job, "--machine", "grbl", "-o", program], check=True)
        lines = sum(1 for _ in open(program, "rb"))
        padded = os.path.join(work, "padded.nc")
        with open(program) as f, open(padded, "w") as out:
            head = [f.readline(), f.readline()]
            out.writelines(head)
            for i in range(PADDING_LINES):
                out.write(f"(padding: a comment line of the program text, which the page shows and need not keep {i:07d})\n")
            for line in f:
                out.write(line)
        failed = False
        runs = {
            "verify": [],
            "verify --job": ["--job", job],
            "verify --plot F.svg": ["--plot", os.path.join(work, "plot.svg")],
            "verify --plot F.html": ["--plot", os.path.join(work, "plot.html")],
        }
        for name, extra in runs.items():
            out = os.path.join(work, "out.txt")
            read = padded if name.endswith(".html") else program
            code, kb = peak_kb([camgen, "verify", read, "--machine", "grbl", *extra], out)
            text = open(out, encoding="utf-8", errors="replace").read()
            limit_kb = os.path.getsize(job) // 1024 + SLACK_MB * 1024
            ok = code == 0 and kb <= limit_kb and (name != "verify --job" or "matches job" in text)
            failed |= not ok
            described = f"{lines} lines" + (f" and {PADDING_LINES} of comments" if read == padded else "")
            print(f"{name} of {HOLES} holes ({described}): exit {code}, peak {kb // 1024} MB, limit {limit_kb // 1024} MB: "
                  f"{'ok' if ok else 'FAILED'}")
            if code != 0:
                print(text[-2000:])
        # Posting a large job longhand into a file.
        big_job, big_program = os.path.join(work, "big.json"), os.path.join(work, "big.nc")
        with open(big_job, "w") as f:
            subprocess.run([sys.executable, os.path.join(source, "bench", "gen_holes.py"), str(POSTED_HOLES)], stdout=f, check=True)
        out = os.path.join(work, "out.txt")
        limit_kb = 3 * os.path.getsize(big_job) // 1024 + SLACK_MB * 1024
        # Longhand on grbl (16 lines a hole) and canned on fanuc (one line a hole).
        for machine, lines_per_hole in (("grbl", 16), ("fanuc", 1)):
            code, kb, faults = usage_of([camgen, big_job, "--machine", machine, "-o", big_program], out)
            big_lines = sum(1 for _ in open(big_program, "rb")) if code == 0 else 0
            ok = (code == 0 and kb <= limit_kb and faults <= fault_limit(kb)
                  and lines_per_hole * POSTED_HOLES < big_lines < (lines_per_hole + 1) * POSTED_HOLES)
            failed |= not ok
            print(f"post of {POSTED_HOLES} holes for {machine} into a file ({big_lines} lines): exit {code}, "
                  f"peak {kb // 1024} MB, limit {limit_kb // 1024} MB; {faults} minor page faults, "
                  f"limit {fault_limit(kb)}: {'ok' if ok else 'FAILED'}")
            if code != 0:
                print(open(out, encoding="utf-8", errors="replace").read()[-2000:])
            if os.path.exists(big_program):
                os.remove(big_program)
        return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
