"""Runs a script's sub-tests in order: PASS or FAIL with the reason for each, then a summary.
A sub-test that raises Skip is reported and not counted as a failure.

    sys.exit(run_checks([test_a, test_b], *arguments))
"""

import sys
import time
import traceback


class Skip(Exception):
    pass


def run_checks(tests, *arguments, on_failure=None):
    """Calls each test(*arguments); returns the exit status (1 if any failed)."""
    failures = 0
    for test in tests:
        t = time.monotonic()
        try:
            test(*arguments)
            print(f"PASS {test.__name__} ({time.monotonic() - t:.1f} s)", flush=True)
        except Skip as e:
            print(f"SKIP {test.__name__}: {e}", flush=True)
        except Exception as e:  # noqa: BLE001 (any error fails the sub-test, not the run)
            failures += 1
            print(f"FAIL {test.__name__}: {type(e).__name__}", flush=True)
            traceback.print_exc(file=sys.stdout)
            if on_failure is not None:
                on_failure()
    print(f"{failures} of {len(tests)} sub-tests failed" if failures
          else f"all {len(tests)} sub-tests passed", flush=True)
    return 1 if failures else 0
