"""bevel (see mechanism.py)."""

from .mechanism import MECHANISM

__all__ = ["MECHANISM"]
