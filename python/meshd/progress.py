"""Showing a job's progress: a bar on stderr, tqdm's bar when tqdm is installed, or a live plot
of the snapshots in Jupyter when matplotlib is (meshd.live_plot). None of them is required.

`progress=` of Client.generate() and Client.result() takes:
    False     nothing (the default)
    True      the best available: the live plot in Jupyter, else tqdm, else the text bar
    "text", "tqdm" or "plot"   that one
    a callable  called with every event (meshd.Progress, meshd.Snapshot, ...)
"""

import math
import sys
import time

from meshd.events import Done, Progress, Queued, Started

DEFAULT_DPTOL = 0.001
# The loop stops when the largest move is under 10 dptol (and the mean under dptol).
STOP_MOVE_FACTOR = 10.0


def settled_fraction(first_move, move, target):
    """How far the largest move has come down from first_move to target, on a log scale, in
    [0, 1]."""
    if first_move <= target or move <= 0:
        return 1.0
    done = math.log(first_move / max(move, target)) / math.log(first_move / target)
    return min(1.0, max(0.0, done))


class SettlingEstimate:
    """An estimate of how much of a run is behind, for a bar without a known length: the
    settled fraction of the largest move, never going back within one level (the move is
    noisy), starting again when a multilevel run refines (its nodes grow several times)."""

    REFINED_GROWTH = 1.5

    def __init__(self, request):
        self.target = _target_move(request)
        self.first_move, self.nodes, self.fraction = None, 0, 0.0

    def update(self, progress):
        if self.first_move is None or progress.nodes > self.REFINED_GROWTH * self.nodes:
            self.first_move, self.fraction = progress.max_move, 0.0
        self.nodes = progress.nodes
        self.fraction = max(self.fraction,
                            settled_fraction(self.first_move, progress.max_move, self.target))
        return self.fraction


def _target_move(request):
    has_dptol = request is not None and request.params.HasField("dptol")
    return STOP_MOVE_FACTOR * (request.params.dptol if has_dptol else DEFAULT_DPTOL)


def summary(mesh):
    q = f", q_min {mesh.quality.q_min:.3f} q_mean {mesh.quality.q_mean:.4f}" if mesh.quality else ""
    its = f", {mesh.stats.iterations} iterations" if mesh.stats else ""
    cells = (f"{len(mesh.tetrahedra)} tetrahedra" if hasattr(mesh, "tetrahedra")
             else f"{len(mesh.triangles)} triangles")
    return f"{len(mesh.points)} nodes, {cells}{its}{q} on {mesh.device or mesh.backend}"


class TextBar:
    """A one-line bar redrawn in place on a terminal; on anything else, a plain line a second."""

    WIDTH = 24

    def __init__(self, request=None, stream=None):
        self.stream = stream or sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.interval = 0.1 if self.tty else 1.0
        self.estimate = SettlingEstimate(request)
        self.last_draw = -math.inf

    def __call__(self, event):
        if isinstance(event, Queued):
            self._line(f"job {event.job_id} queued (position {event.position})")
        elif isinstance(event, Started):
            self._line(f"started on {event.device}")
        elif isinstance(event, Progress):
            fraction = self.estimate.update(event)
            now = time.monotonic()
            if now - self.last_draw >= self.interval:
                self.last_draw = now
                self._draw(event, fraction)
        elif isinstance(event, Done):
            self._line(f"done: {summary(event.mesh)}")

    def _draw(self, p, fraction):
        filled = round(self.WIDTH * fraction)
        bar = "#" * filled + "." * (self.WIDTH - filled)
        text = (f"[{bar}] iteration {p.iteration}  max move {p.max_move:.1e} h0  "
                f"{p.nodes} nodes  {p.elapsed_s:.2f} s")
        if self.tty:
            self.stream.write("\r" + text + "\x1b[K")
            self.stream.flush()
        else:
            print(text, file=self.stream, flush=True)

    def _line(self, text):
        if self.tty and self.last_draw > -math.inf:
            self.stream.write("\r\x1b[K")
        print(text, file=self.stream, flush=True)

    def close(self):
        pass


class TqdmBar:
    """tqdm's bar over the same estimate, in percent."""

    def __init__(self, request=None):
        from tqdm.auto import tqdm
        self.bar = tqdm(total=100, unit="%", bar_format="{l_bar}{bar}| {elapsed}{postfix}")
        self.estimate = SettlingEstimate(request)

    def __call__(self, event):
        if isinstance(event, Progress):
            percent = round(100 * self.estimate.update(event))
            self.bar.update(percent - self.bar.n)
            self.bar.set_postfix_str(f"iteration {event.iteration}, {event.nodes} nodes",
                                     refresh=False)
        elif isinstance(event, Started):
            self.bar.set_description(event.device)
        elif isinstance(event, Done):
            self.bar.update(100 - self.bar.n)
            self.bar.set_postfix_str(summary(event.mesh))

    def close(self):
        self.bar.close()


def in_jupyter():
    try:
        from IPython import get_ipython
    except ImportError:
        return False
    shell = get_ipython()
    return shell is not None and type(shell).__name__ == "ZMQInteractiveShell"


def _importable(name):
    try:
        __import__(name)
        return True
    except ImportError:
        return False


def make_reporter(progress, request=None):
    """A callable taking each event (with close()), or None; see the module's docstring."""
    if not progress:
        return None
    if progress is True:
        if in_jupyter() and _importable("matplotlib"):
            progress = "plot"
        else:
            progress = "tqdm" if _importable("tqdm") else "text"
    if progress == "text":
        return TextBar(request)
    if progress == "tqdm":
        return TqdmBar(request)
    if progress == "plot":
        from meshd.live_plot import LivePlot
        return LivePlot(request)
    if callable(progress):
        return progress
    raise ValueError(f"progress: True, False, 'text', 'tqdm', 'plot' or a callable, "
                     f"not {progress!r}")


def close_reporter(reporter):
    close = getattr(reporter, "close", None)
    if close is not None:
        close()
