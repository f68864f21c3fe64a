#!/usr/bin/env python3
"""The Python package installed as its README says, then used against a real meshd.

    python_package_test.py --meshd BIN --source-dir REPO --work-dir DIR

Copies REPO's python/ and proto/ to DIR/src (so that the in-tree build writes nothing into the
source tree), makes DIR/venv with `python3 -m venv --system-site-packages`, installs the package
with `pip install --no-build-isolation --no-deps --no-index` (offline, Debian's setuptools, the
stubs generated from proto/ by the build), then runs with the venv's interpreter:
  builder_checks.py  geometry builders, requests, error parsing and the event decoder, offline
  client_checks.py   the sync and asyncio clients against `BIN --backend cpu`
  failure_checks.py  each kind of failure, the bearer token and TLS, against the same

Exit status: 0 when all pass, 1 on a failure, 77 (ctest's skip) when this interpreter lacks
grpcio, protobuf, numpy or venv/ensurepip, or protoc and grpc_python_plugin are missing.
"""

import argparse
import os
import shutil
import subprocess
import sys
import time

SKIP = 77
HERE = os.path.dirname(os.path.abspath(__file__))


def missing_prerequisite():
    """What this machine lacks to build and use the package, or None."""
    for module, package in (("grpc", "python3-grpcio"), ("google.protobuf", "python3-protobuf"),
                            ("numpy", "python3-numpy"), ("venv", "python3-venv"),
                            ("ensurepip", "python3-venv"), ("setuptools", "python3-setuptools")):
        try:
            __import__(module)
        except ImportError:
            return f"{sys.executable} has no {module} (needs {package})"
    if not (shutil.which("protoc") and shutil.which("grpc_python_plugin")):
        return "protoc or grpc_python_plugin not found (needs protobuf-compiler-grpc)"
    return None


def ignore_build_outputs(folder, names):
    """What a developer's in-tree build or editable install may have left in python/."""
    return [n for n in names if n in ("build", "__pycache__", ".venv") or n.endswith(".egg-info")
            or (os.path.basename(folder) == "meshd" and n == "v1")]


def run(what, command, env):
    t = time.monotonic()
    r = subprocess.run(command, env=env, capture_output=True, text=True, timeout=240)
    print(f"{what} ({time.monotonic() - t:.1f} s): exit {r.returncode}")
    if r.returncode != 0:
        print(f"  $ {' '.join(command)}\n{r.stdout}{r.stderr}")
    return r


def main():
    parser = argparse.ArgumentParser()
    for flag in ("--meshd", "--source-dir", "--work-dir"):
        parser.add_argument(flag, required=True)
    args = parser.parse_args()
    reason = missing_prerequisite()
    if reason:
        print(f"SKIP: {reason}")
        return SKIP

    work = os.path.abspath(args.work_dir)
    shutil.rmtree(work, ignore_errors=True)
    src = os.path.join(work, "src")
    shutil.copytree(os.path.join(args.source_dir, "python"), os.path.join(src, "python"),
                    ignore=ignore_build_outputs)
    shutil.copytree(os.path.join(args.source_dir, "proto"), os.path.join(src, "proto"))

    env = dict(os.environ, PIP_DISABLE_PIP_VERSION_CHECK="1", PIP_NO_CACHE_DIR="1",
               PIP_CONFIG_FILE=os.devnull, PYTHONDONTWRITEBYTECODE="1")
    env.pop("MESHD_PROTO_DIR", None)  # the default, ../proto, is what is tested
    env.pop("MESHD_TOKEN", None)
    venv = os.path.join(work, "venv")
    if run("python3 -m venv --system-site-packages",
           [sys.executable, "-m", "venv", "--system-site-packages", venv], env).returncode:
        return 1
    python = os.path.join(venv, "bin", "python")
    pip = [python, "-m", "pip", "install", "--no-build-isolation", "--no-deps", "--no-index",
           os.path.join(src, "python")]
    if run("pip install --no-build-isolation ./python", pip, env).returncode:
        return 1

    failures = 0
    server = ["--meshd", args.meshd, "--tmp", work]
    plate = os.path.join(args.source_dir, "examples", "python", "plate.py")
    scripts = (("builder_checks.py", ["--examples", os.path.join(args.source_dir, "examples")]),
               ("client_checks.py", server + ["--plate", plate]),
               ("failure_checks.py", server))
    for script, extra in scripts:
        r = subprocess.run([python, os.path.join(HERE, script), *extra], env=env, timeout=240)
        failures += r.returncode != 0
    print(f"{failures} of {len(scripts)} check scripts failed" if failures
          else f"all {len(scripts)} check scripts passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
