"""Long work off Blender's main thread.

A job is two steps: `work`, which calls the gmg module and touches no Blender data (the module
releases the GIL while the engine runs, so the interface stays responsive), and `apply`, which
puts its result into Blender in the main thread. A cancelled job's work runs to its end in the
background (the engine cannot be stopped halfway) and its result is dropped: nothing is applied.
"""
import threading
import time


class Job:
    def __init__(self, label, work, apply):
        self.label = label
        self.work = work
        self.apply = apply
        self.result = None
        self.error = None
        self.cancelled = False
        self.thread = None
        self.started = time.monotonic()

    def _run(self):
        try:
            self.result = self.work()
        except Exception as e:  # handed to the main thread, which reports it
            self.error = e

    def start(self):
        """Runs the work in a thread; poll done(), then call finish() in the main thread."""
        self.started = time.monotonic()
        self.thread = threading.Thread(target=self._run, name=f"gmg {self.label}", daemon=True)
        self.thread.start()

    def done(self):
        return self.thread is not None and not self.thread.is_alive()

    def elapsed(self):
        return time.monotonic() - self.started

    def cancel(self):
        self.cancelled = True

    def finish(self):
        """Applies the finished work's result and returns apply's message; None when cancelled
        (nothing applied); raises the work's error."""
        if self.cancelled:
            return None
        if self.error is not None:
            raise self.error
        return self.apply(self.result)

    def run_here(self):
        """Work and apply in this thread, to the end (background mode, scripts)."""
        self._run()
        return self.finish()
