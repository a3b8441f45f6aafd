"""crossed_helical (see mechanism.py)."""

from .mechanism import MECHANISM

__all__ = ["MECHANISM"]
