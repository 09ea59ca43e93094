"""Calls that may block (a node's services) run in threads of their own; each answer, or a time-out, reaches its
callback in the Qt thread. A call that never returns costs one idle daemon thread, never the window."""
from __future__ import annotations

import itertools
import threading
from typing import Any, Callable, Dict, Optional

from python_qt_binding.QtCore import QObject, QTimer, Signal

Callback = Callable[[Any, Optional[BaseException]], None]


class BackgroundCalls(QObject):
    _finished = Signal(int, object, object)

    def __init__(self, timeout: float, parent: Optional[QObject] = None):
        super().__init__(parent)
        self.timeout = timeout
        self._pending: Dict[int, Callback] = {}
        self._ids = itertools.count()
        self._finished.connect(self._deliver)

    def call(self, function: Callable[[], Any], callback: Callback) -> None:
        """``callback(result, None)`` or ``callback(None, error)`` in the Qt thread; TimeoutError after timeout."""
        call_id = next(self._ids)
        self._pending[call_id] = callback

        def work() -> None:
            try:
                result, error = function(), None
            except Exception as failure:  # handed to the callback, which says what failed
                result, error = None, failure
            try:
                self._finished.emit(call_id, result, error)
            except RuntimeError:  # the window was closed meanwhile
                pass

        threading.Thread(target=work, name="rqt_logger_level call", daemon=True).start()
        timeout_error = TimeoutError("no answer within %g s" % self.timeout)
        QTimer.singleShot(int(self.timeout * 1000), lambda: self._deliver(call_id, None, timeout_error))

    def busy(self) -> bool:
        return bool(self._pending)

    def _deliver(self, call_id: int, result: Any, error: Optional[BaseException]) -> None:
        callback = self._pending.pop(call_id, None)
        if callback is not None:  # the first of answer and time-out wins
            callback(result, error)

    def shutdown(self) -> None:
        self._pending.clear()
