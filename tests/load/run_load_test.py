#!/usr/bin/env python3
"""load_test: a short load run on a meshd of its own, then SIGTERM.

    run_load_test.py --meshd BIN --python-stubs DIR [--clients 6] [--duration 20] [--seed 1]
                     [--json] [meshd flags after --, e.g. -- --cpu-workers 2]

Starts BIN on free loopback ports with a small queue (so that bursts meet UNAVAILABLE) and a
retention long enough that ListJobs still holds every job of the run, runs load_generator.py
against it (its audit: zero jobs unaccounted for), then stops meshd with SIGTERM and requires a
clean exit (0) within the drain. Exit status: 0 when all of that holds, 1 otherwise, 77 when
grpcio is missing.
"""

import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import meshd_launcher as ml  # noqa: E402

# Small queue and workers: two jobs run, eight wait, the rest is refused. Every finished job of
# the run is kept (the audit looks each one up), for an hour.
DEFAULT_MESHD_FLAGS = ["--queue-capacity", "8", "--cpu-workers", "2", "--cpu-threads", "1",
                       "--retention", "3600", "--max-retained", "1000000"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--meshd", required=True, help="the meshd executable")
    parser.add_argument("--python-stubs", required=True, help="<build>/python (meshd.v1 stubs)")
    parser.add_argument("--clients", default="6")
    parser.add_argument("--duration", default="20")
    parser.add_argument("--seed", default="1")
    parser.add_argument("--json", action="store_true")
    parser.add_argument("meshd_flags", nargs="*", help="replace the default meshd flags")
    args = parser.parse_args()
    if ml.import_grpc(args.python_stubs) is None:
        return ml.SKIP

    meshd = ml.Meshd(args.meshd, *(args.meshd_flags or DEFAULT_MESHD_FLAGS))
    try:
        print(f"meshd on port {meshd.port}, metrics on port {meshd.metrics_port}, "
              f"flags {' '.join(args.meshd_flags or DEFAULT_MESHD_FLAGS)}", flush=True)
        generator = [sys.executable, os.path.join(HERE, "load_generator.py"),
                     "--server", meshd.address, "--metrics-port", str(meshd.metrics_port),
                     "--python-stubs", args.python_stubs, "--clients", args.clients,
                     "--duration", args.duration, "--seed", args.seed] + \
                    (["--json"] if args.json else [])
        status = subprocess.run(generator, timeout=float(args.duration) + 240).returncode
        print(f"RSS of meshd after the run: {meshd.rss_mb():.0f} MB")
        code = meshd.stop()
        print(f"meshd exited {code} after SIGTERM")
        if status != 0 or code != 0:
            print("  meshd's log (tail):\n    " + meshd.log_tail())
            print("FAIL: " + ("the audit failed" if status else f"meshd exited {code}"))
            return 1
        print("PASS")
        return 0
    finally:
        meshd.kill()


if __name__ == "__main__":
    sys.exit(main())
