"""Imports every experiment module beyond Fig. 5 so that each registers itself.

Add one line per module (e.g. ``from . import fig6``).
"""

from __future__ import annotations
from . import fig1b  # noqa: F401  (illustrative 3-D manipulator, workspace map)
from . import fig8  # noqa: F401  (blocked-tip force, Section V-C)
from . import fig6  # noqa: F401  (bending radius vs temperature, Section V-B)
from . import table1  # noqa: F401  (grip temperatures, Section V-D)
from . import buckling  # noqa: F401  (self-weight buckling and loss of stability, issue 16)
