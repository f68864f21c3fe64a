"""A live plot of a job's snapshots in Jupyter (matplotlib and IPython; both optional).

The request must ask for snapshots (meshd.request(..., snapshot_every=10)); without them the
plot shows the progress in its title and the final mesh. Redrawn at most five times a second, so
that a fast stream of snapshots does not slow the notebook down.
"""

import time

from meshd.events import Done, Progress, Snapshot

REDRAW_INTERVAL_S = 0.2


class LivePlot:
    def __init__(self, request=None, size_inches=(5, 5)):
        import matplotlib.pyplot as plt
        from IPython.display import DisplayHandle

        self.plt = plt
        self.fig, self.ax = plt.subplots(figsize=size_inches)
        plt.close(self.fig)  # shown through the display handle only, not again at cell end
        self.handle = DisplayHandle()
        self.handle.display(self.fig)
        self.title = "queued"
        self.last_draw = 0.0

    def __call__(self, event):
        if isinstance(event, Progress):
            self.title = f"iteration {event.iteration}, {event.nodes} nodes"
            if time.monotonic() - self.last_draw >= REDRAW_INTERVAL_S:
                self.ax.set_title(self.title)
                self._show()
        elif isinstance(event, Snapshot) and event.triangles is not None:
            if time.monotonic() - self.last_draw >= REDRAW_INTERVAL_S:
                self._draw(event.points, event.triangles, f"iteration {event.iteration}")
        elif isinstance(event, Done) and hasattr(event.mesh, "triangles"):  # not a volume
            m = event.mesh
            q = f", q_min {m.quality.q_min:.3f}" if m.quality else ""
            self._draw(m.points, m.triangles, f"{len(m.points)} nodes{q}")

    def _draw(self, points, triangles, title):
        # Snapshot triangles can lag behind a density change; draw only consistent ones.
        if len(triangles) and triangles.max() >= len(points):
            return
        self.ax.clear()
        # Thinner lines for more triangles, so that a large mesh is not a black blot.
        width = min(0.5, 40.0 / max(1.0, len(triangles)) ** 0.5)
        self.ax.triplot(points[:, 0], points[:, 1], triangles, linewidth=width, color="k")
        self.ax.set_aspect("equal")
        self.ax.set_title(title)
        self._show()

    def _show(self):
        self.last_draw = time.monotonic()
        self.handle.update(self.fig)

    def close(self):
        pass
