"""Imports every experiment module beyond Fig. 5 so that each registers itself.

Add one line per module (e.g. ``from . import fig6``).
"""

from __future__ import annotations
