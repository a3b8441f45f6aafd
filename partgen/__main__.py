"""``python -m partgen``: the command line."""

from .cli.main import entry

entry()
