#!/usr/bin/env python3
"""Top functions of `rayview render` by self time, as a Markdown table (docs/PERFORMANCE.md, "How to measure").

Records `perf record -F FREQ rayview render SCENE -o OUT.png --threads 1` and prints the top --top entries
of `perf report --no-children --sort sym,dso`. Debian's libembree3 has no symbols: its addresses are summed
into one row per library ("(no symbols)"), so Embree's traversal is one line rather than scattered.

    bench/perf_top.py --rayview build/release/app/rayview [--top 15] [--freq 4000] SCENE.xml...
"""
import argparse
import collections
import os
import re
import subprocess
import tempfile

ROW = re.compile(r"^\s*([\d.]+)%\s+\[([.k])\]\s+(.*?)\s{2,}(\S+)\s*$")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rayview", default="build/release/app/rayview")
    parser.add_argument("--top", type=int, default=15)
    parser.add_argument("--freq", type=int, default=4000)
    parser.add_argument("scenes", nargs="+")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        for scene in args.scenes:
            data = os.path.join(tmp, "perf.data")
            run = subprocess.run(["perf", "record", "-q", "-F", str(args.freq), "-o", data, args.rayview, "render",
                                  scene, "-o", os.path.join(tmp, "out.png"), "--threads", "1"],
                                 capture_output=True, text=True, check=True)
            summary = next((l for l in run.stdout.splitlines() if l.startswith("time")), "")
            report = subprocess.run(["perf", "report", "-i", data, "--stdio", "--no-children", "-g", "none",
                                     "--sort", "sym,dso", "--percent-limit", "0"],
                                    capture_output=True, text=True, check=True).stdout
            totals = collections.OrderedDict()
            for line in report.splitlines():
                m = ROW.match(line)
                if not m:
                    continue
                share, kind, symbol, dso = float(m.group(1)), m.group(2), m.group(3).strip(), m.group(4)
                if symbol.startswith("0x"):
                    symbol = "(no symbols)"
                key = (symbol, dso, "kernel" if kind == "k" else "user")
                totals[key] = totals.get(key, 0.0) + share
            rows = sorted(totals.items(), key=lambda kv: -kv[1])[:args.top]
            print(f"#### {os.path.basename(scene)}, 1 thread: {summary.replace('time', '').strip()}")
            print()
            print("| # | self % | function | library |")
            print("|---:|---:|---|---|")
            for i, ((symbol, dso, kind), share) in enumerate(rows, 1):
                symbol = symbol.replace("|", "\\|")
                print(f"| {i} | {share:.1f} | `{symbol}` | {dso}{' (kernel)' if kind == 'kernel' else ''} |")
            print()


if __name__ == "__main__":
    main()
