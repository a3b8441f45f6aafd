"""gear_train (see mechanism.py)."""

from .mechanism import MECHANISM

__all__ = ["MECHANISM"]
