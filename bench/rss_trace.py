#!/usr/bin/env python3
"""Resident memory of one process over its life: runs COMMAND, samples its VmRSS every 20 ms, prints the
samples (about 40 of them) and the largest, in MiB. Where in a run the peak is (docs/PERFORMANCE.md, "Memory per
triangle"), which ru_maxrss alone does not say.

    bench/rss_trace.py build/release/app/rayview render build/scale/soup_1000000.xml -o /tmp/s.png --threads 2
"""
import subprocess
import sys
import time


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    child = subprocess.Popen(sys.argv[1:], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    start = time.time()
    samples = []
    while child.poll() is None:
        try:
            with open(f"/proc/{child.pid}/status") as status:
                for line in status:
                    if line.startswith("VmRSS"):
                        samples.append((time.time() - start, int(line.split()[1]) // 1024))
        except OSError:
            pass
        time.sleep(0.02)
    print(child.stdout.read(), end="")
    for t, rss in samples[::max(1, len(samples) // 40)]:
        print(f"{t * 1000:7.0f} ms {rss:6d} MiB")
    print("largest sample", max((rss for _, rss in samples), default=0), "MiB")
    sys.exit(child.returncode)


if __name__ == "__main__":
    main()
