"""The `progress=` argument of long constructions (Delaunay, ConvexHull, Voronoi, the interpolators).

    progress=None or False    nothing (the default)
    progress=True             a bar on sys.stderr, redrawn in place, ended by a newline
    progress=callable         called as callable(fraction), fraction a float in [0, 1], as the
                              work goes on (at most every few hundredths of a second, from the
                              calling thread, with the GIL) and with 1.0 at the end

An exception the callable raises stops the work and is raised by the call, as Ctrl-C
(KeyboardInterrupt) does: the compiled module polls a flag in the library's loops
(python/src/watched.hpp).
"""

import sys
import time


class ProgressBar:
    """A one-line bar on a stream (sys.stderr by default): `label [#####.....]  42%  1.3 s`."""

    def __init__(self, label="dewall", stream=None, width=30):
        self.label, self.stream, self.width = label, stream, width
        self._start = time.perf_counter()
        self._done = False

    def __call__(self, fraction):
        if self._done:
            return
        stream = self.stream if self.stream is not None else sys.stderr
        fraction = min(max(float(fraction), 0.0), 1.0)
        filled = int(fraction * self.width)
        bar = "#" * filled + "." * (self.width - filled)
        elapsed = time.perf_counter() - self._start
        # "\r\033[K" on a terminal: back to the line's start and clear it; elsewhere one line a call.
        start = "\r\033[K" if getattr(stream, "isatty", lambda: False)() else ""
        end = "\n" if fraction >= 1.0 or not start else ""
        stream.write(f"{start}{self.label} [{bar}] {int(fraction * 100):3d}%  {elapsed:.1f} s{end}")
        stream.flush()
        self._done = fraction >= 1.0


def progress_callback(progress, label="dewall"):
    """`progress` as the compiled module takes it: None, or a callable of one float."""
    if progress is None or progress is False:
        return None
    if progress is True:
        return ProgressBar(label)
    if callable(progress):
        return progress
    raise TypeError(f"progress must be True, False, None or a callable of one float, not {type(progress).__name__}")
