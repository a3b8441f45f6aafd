"""The gear train (``kind: gear_train``) as three sub-slices, ``stages/`` (a row of stages),
``planetary/`` and ``rack/``, each with the house layout's roles and sharing ``common/``, behind one
``mechanism.py`` that dispatches to the one the design selects (``schema.py``: one YAML for the three)."""

from .mechanism import MECHANISM

__all__ = ["MECHANISM"]
