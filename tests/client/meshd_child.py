"""A meshd child process for the client tests: started on a free port, killed on exit.

    with MeshdChild(meshd_binary, "--queue-capacity", "2") as meshd:
        run_client("--server", meshd.address, ...)

Reads the port from meshd's log ("meshd listening on ... (port N)") and waits for "serving:
warm-up took", which meshd logs once its health status is SERVING, so that the tests need no
health client of their own.
"""

import re
import subprocess
import threading
import time


class MeshdChild:
    def __init__(self, binary, *extra, timeout=60):
        args = [binary, "--listen", "127.0.0.1:0", "--backend", "cpu", *extra]
        self.proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     text=True, errors="replace")
        self.lines = []
        # A thread drains the log so that the pipe never fills and blocks meshd.
        threading.Thread(target=lambda: self.lines.extend(l.rstrip("\n") for l in self.proc.stdout),
                         daemon=True).start()
        try:
            deadline = time.monotonic() + timeout
            while not any("serving: warm-up took" in l for l in list(self.lines)):
                if self.proc.poll() is not None:
                    raise RuntimeError(f"meshd exited with {self.proc.returncode} while starting")
                if time.monotonic() > deadline:
                    raise RuntimeError(f"meshd not serving after {timeout} s")
                time.sleep(0.05)
            port = next(m.group(1) for m in map(re.compile(r"\(port (\d+)\)").search,
                                                list(self.lines)) if m)
            self.address = f"127.0.0.1:{port}"
        except BaseException:
            self.stop()
            print("meshd's log:\n  " + "\n  ".join(self.lines))
            raise

    def stop(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()

    def log(self):
        return "\n  ".join(self.lines)

    def __enter__(self):
        return self

    def __exit__(self, kind, value, traceback):
        self.stop()
