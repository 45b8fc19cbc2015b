"""Guard for the PySide6 pin: void Qt calls must not take references away from None."""

import sys

from PySide6.QtCore import QPointF
from PySide6.QtGui import QPainterPath


def test_void_calls_keep_none_refcount():
    path = QPainterPath()
    before = sys.getrefcount(None)
    for i in range(1000):
        path.lineTo(QPointF(i, i))
    # A little slack for unrelated references; the 6.12.0 bug loses exactly one per call.
    assert sys.getrefcount(None) - before > -50
